//! Light shafts under the water (issue 34; shaders/underwater/shafts.frag,
//! common/caustics.glsl): the sun's light the water scatters toward the eye, focused into
//! shafts by the waves. Marching the caustics along every pixel's ray costs lavapipe about
//! 190 ms a frame at `--quality low` (12 area ratios a pixel, each 24 slope samples), so this
//! pass marches the main camera's rays at a fixed `SHAFTS_EXTENT` before the scene is drawn and
//! keeps, per texel, the caustics' mean along four lengths of the ray; the scene's shaders
//! under the water sample it (linearly: the shafts are soft) and take the mean up to their own
//! distance: 21 ms at low. It runs only with the camera under the water (or half in it:
//! `WaterSide`) and the caustics on; the image is cleared to 1 (a level sea's ratio) when it is
//! made, so what samples it is never undefined.

use std::sync::Arc;

use ash::vk;

use super::water::WaterKind;
use super::FrameSetImage;
use crate::gpu::{Context, DescriptorSetLayout, GpuResult};
use crate::shaders;

/// The shaft image's size (texels), whatever the window's: the shafts are soft, and at
/// `--quality low`'s 640x360 main target this is a texel per 2.5x2.5 pixels.
pub const SHAFTS_EXTENT: vk::Extent2D = vk::Extent2D {
    width: 256,
    height: 144,
};

/// The pass: its image holds, per texel, the caustics' mean area ratio over the first quarter,
/// half, three quarters and all of the march (RGBA16F; the frame set's binding 5).
pub type ShaftsPass = FrameSetImage;

/// `ocean`: how the shader samples the ocean images (as the terrain's caustics do).
pub fn shafts_pass(
    ctx: &Arc<Context>,
    frame_layout: &DescriptorSetLayout,
    ocean: WaterKind,
) -> GpuResult<ShaftsPass> {
    // common/shadow.glsl's SHADOWS (id 4) besides the caustics' constants.
    FrameSetImage::new(
        ctx,
        frame_layout,
        "light shafts",
        SHAFTS_EXTENT,
        shaders::UNDERWATER_SHAFTS_FRAG,
        &[
            ocean.cascades,
            ocean.manual_filter as u32,
            0,
            0,
            ocean.shadows as u32,
            0,
            ocean.slope_mips as u32,
        ],
    )
}
