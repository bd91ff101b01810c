//! Render targets the scene passes draw into: HDR colour and depth, sized to the output.

use std::sync::Arc;

use ash::vk;

use crate::gpu::{Context, GpuResult, Image, ImageDesc};

/// HDR scene colour (linear radiance, tone-mapped by the composite pass).
pub const HDR_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;
/// Scene depth (reversed-Z).
pub const DEPTH_FORMAT: vk::Format = vk::Format::D32_SFLOAT;

pub struct Targets {
    /// Scene radiance; sampled by the composite pass.
    pub hdr: Image,
    /// Scene depth.
    pub depth: Image,
}

impl Targets {
    pub fn new(ctx: &Arc<Context>, extent: vk::Extent2D) -> GpuResult<Targets> {
        Ok(Targets {
            hdr: Image::new(
                ctx,
                &ImageDesc {
                    name: "hdr colour target",
                    extent,
                    format: HDR_FORMAT,
                    usage: vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::SAMPLED,
                    layers: 1,
                    array_view: false,
                    shared: false,
                },
            )?,
            depth: Image::new(
                ctx,
                &ImageDesc {
                    name: "depth target",
                    extent,
                    format: DEPTH_FORMAT,
                    usage: vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT,
                    layers: 1,
                    array_view: false,
                    shared: false,
                },
            )?,
        })
    }

    pub fn extent(&self) -> vk::Extent2D {
        self.hdr.extent
    }
}
