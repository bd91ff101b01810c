//! Texture debug views (`--view reflection|refraction|dudv`, shaders/post/textures.frag): the
//! reflection or refraction texture, or the DU/DV map tiled, over the whole main target. Reads
//! the water's textures set ([`WaterTextures`]).

use std::sync::Arc;

use ash::vk;

use super::water::WaterTextures;
use super::{scene_layout, FullscreenDraw, SceneTarget};
use crate::gpu::{Bindings, BoundSet, Context, DescriptorSetLayout, GpuResult, Recorder};
use crate::render::ViewMode;
use crate::shaders;

pub struct TexturesViewPass {
    fill: FullscreenDraw,
}

impl TexturesViewPass {
    /// Draws into the main target (`display_format`).
    pub fn new(
        ctx: &Arc<Context>,
        frame_layout: &DescriptorSetLayout,
        textures: &WaterTextures,
        display_format: vk::Format,
    ) -> GpuResult<TexturesViewPass> {
        let layout = scene_layout(
            ctx,
            "textures view layout",
            frame_layout,
            &[&textures.layout],
        )?;
        let fill = FullscreenDraw::new(
            ctx,
            &layout,
            "textures view",
            shaders::POST_TEXTURES_FRAG,
            &[],
            SceneTarget::Display(display_format),
        )?;
        Ok(TexturesViewPass { fill })
    }

    /// Whether `view` is one this pass draws.
    pub fn shows(view: ViewMode) -> bool {
        matches!(
            view,
            ViewMode::Reflection | ViewMode::Refraction | ViewMode::Dudv
        )
    }

    /// What `record` binds: its pipeline with `sets` (the frame set, the water's textures).
    pub fn draw<'a>(&'a self, sets: &'a [&'a BoundSet]) -> Bindings<'a> {
        self.fill.draw(sets)
    }

    /// Draws the texture `--view` names over the whole main target, inside a rendering scope
    /// with the main colour attachment only that declared `draw(sets)`.
    pub fn record(&self, rec: &Recorder, sets: &[&BoundSet]) {
        self.fill.record(rec, sets);
    }
}
