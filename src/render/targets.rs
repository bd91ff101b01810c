//! Render targets the scene passes draw into: HDR colour and depth at `--render-scale` of the
//! output's size, the reflection and refraction textures (colour + depth) at `--rtt-scale` of it
//! (seed 001 §3.1: the frame-buffer objects), and the display image the composite pass writes
//! at the output's size. All are recreated on resize.

use std::sync::Arc;

use ash::vk;

use crate::gpu::{Context, GpuResult, Image, ImageDesc};

/// HDR scene colour (linear radiance, tone-mapped by the composite pass).
pub const HDR_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;
/// Scene depth (reversed-Z).
pub const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;
/// The composite pass's storage image: sRGB-encoded bytes in RGBA or BGRA order, copied
/// bit for bit into the 8-bit sRGB output (swapchain image or headless target).
pub const DISPLAY_FORMAT: vk::Format = vk::Format::R8G8B8A8_UNORM;

/// A colour + depth pair.
pub struct ColourDepth {
    pub colour: Image,
    pub depth: Image,
}

impl ColourDepth {
    fn new(
        ctx: &Arc<Context>,
        name: &str,
        extent: vk::Extent2D,
        depth_sampled: bool,
    ) -> GpuResult<ColourDepth> {
        let image = |suffix: &str, format, usage| {
            plain_image(ctx, &format!("{name} {suffix}"), extent, format, usage)
        };
        let depth_usage = if depth_sampled {
            vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT | vk::ImageUsageFlags::SAMPLED
        } else {
            vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT
        };
        Ok(ColourDepth {
            colour: image(
                "colour",
                HDR_FORMAT,
                vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::SAMPLED,
            )?,
            depth: image("depth", DEPTH_FORMAT, depth_usage)?,
        })
    }

    pub fn extent(&self) -> vk::Extent2D {
        self.colour.extent
    }
}

/// A single-layer 2D image on the graphics queue.
fn plain_image(
    ctx: &Arc<Context>,
    name: &str,
    extent: vk::Extent2D,
    format: vk::Format,
    usage: vk::ImageUsageFlags,
) -> GpuResult<Image> {
    Image::new(
        ctx,
        &ImageDesc {
            name,
            extent,
            format,
            usage,
            layers: 1,
            array_view: false,
            shared: false,
            cube: false,
        },
    )
}

pub struct Targets {
    /// Scene radiance and depth at `render_scale` of the output; the colour is sampled (and
    /// scaled up) by composite.
    pub main: ColourDepth,
    /// What the water reflects (mirrored camera, clipped below the water).
    pub reflection: ColourDepth,
    /// What lies under the water (clipped above it); its depth gives the water's thickness.
    pub refraction: ColourDepth,
    /// Composite's output at the output size (`DISPLAY_FORMAT`), copied into the output.
    pub display: Image,
}

/// `extent` scaled by `scale`, at least 1x1.
pub fn scaled(extent: vk::Extent2D, scale: f32) -> vk::Extent2D {
    let side = |v: u32| ((v as f32 * scale).round() as u32).max(1);
    vk::Extent2D {
        width: side(extent.width),
        height: side(extent.height),
    }
}

impl Targets {
    /// `output`: the output's size; `render_scale` and `rtt_scale` size the main and the
    /// reflection/refraction targets relative to it.
    pub fn new(
        ctx: &Arc<Context>,
        output: vk::Extent2D,
        render_scale: f32,
        rtt_scale: f32,
    ) -> GpuResult<Targets> {
        let rtt = scaled(output, rtt_scale);
        let display = plain_image(
            ctx,
            "display (composite output)",
            output,
            DISPLAY_FORMAT,
            vk::ImageUsageFlags::STORAGE | vk::ImageUsageFlags::TRANSFER_SRC,
        )?;
        Ok(Targets {
            main: ColourDepth::new(ctx, "main", scaled(output, render_scale), false)?,
            reflection: ColourDepth::new(ctx, "reflection", rtt, false)?,
            refraction: ColourDepth::new(ctx, "refraction", rtt, true)?,
            display,
        })
    }

    /// The output's size.
    pub fn output_extent(&self) -> vk::Extent2D {
        self.display.extent
    }
}
