//! Render targets the scene passes draw into: HDR colour and depth at the output's size, and the
//! reflection and refraction textures (colour + depth) at a scale of it (seed 001 §3.1: the
//! frame-buffer objects). All are recreated on resize.

use std::sync::Arc;

use ash::vk;

use crate::gpu::{Context, GpuResult, Image, ImageDesc};

/// HDR scene colour (linear radiance, tone-mapped by the composite pass).
pub const HDR_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;
/// Scene depth (reversed-Z).
pub const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;

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
            Image::new(
                ctx,
                &ImageDesc {
                    name: &format!("{name} {suffix}"),
                    extent,
                    format,
                    usage,
                    layers: 1,
                    array_view: false,
                    shared: false,
                    cube: false,
                },
            )
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

pub struct Targets {
    /// Scene radiance and depth at the output size; the colour is sampled by composite.
    pub main: ColourDepth,
    /// What the water reflects (mirrored camera, clipped below the water).
    pub reflection: ColourDepth,
    /// What lies under the water (clipped above it); its depth gives the water's thickness.
    pub refraction: ColourDepth,
    /// Scale of the reflection and refraction targets relative to the output.
    pub scale: f32,
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
    pub fn new(ctx: &Arc<Context>, extent: vk::Extent2D, scale: f32) -> GpuResult<Targets> {
        let rtt = scaled(extent, scale);
        Ok(Targets {
            main: ColourDepth::new(ctx, "main", extent, false)?,
            reflection: ColourDepth::new(ctx, "reflection", rtt, false)?,
            refraction: ColourDepth::new(ctx, "refraction", rtt, true)?,
            scale,
        })
    }

    pub fn extent(&self) -> vk::Extent2D {
        self.main.extent()
    }
}
