//! One struct per pass, each owning its pipelines and layouts, with `new` and `record`
//! (and `resize` where the pass holds size-dependent descriptors).
//!
//! The scene passes (sky, terrain, water) draw into HDR colour + depth targets and share the
//! frame set (set 0: uniforms, ocean images, sky cube) and a push constant picking the view
//! (`ViewIndex`): the same pipelines render the main view and the reflection and refraction
//! textures.

pub mod composite;
pub mod sky;
pub mod terrain;
pub mod water;

use std::sync::Arc;

use ash::vk;

pub use composite::CompositePass;
pub use sky::{SkyCube, SkyPass};
pub use terrain::TerrainPass;
pub use water::WaterPass;

use crate::gpu::{
    Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Pipeline, PipelineLayout, Recorder,
};
use crate::render::camera::ViewIndex;
use crate::render::targets::{DEPTH_FORMAT, HDR_FORMAT};

/// Push constants of the scene shaders (`Pass` in shaders/common/frame.glsl).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ViewPush {
    pub view: u32,
}

/// A pipeline layout for scene shaders: the frame set, then `extra` sets, and the view push
/// constant.
pub fn scene_layout(
    ctx: &Arc<Context>,
    name: &str,
    frame_layout: &DescriptorSetLayout,
    extra: &[&DescriptorSetLayout],
) -> GpuResult<PipelineLayout> {
    let mut sets = vec![frame_layout];
    sets.extend_from_slice(extra);
    PipelineLayout::new(
        ctx,
        name,
        &sets,
        Some((
            vk::ShaderStageFlags::ALL_GRAPHICS,
            std::mem::size_of::<ViewPush>() as u32,
        )),
    )
}

/// How a scene pipeline uses the depth buffer (reversed-Z: cleared to 0, the far plane).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Depth {
    /// Geometry: nearer wins, and writes its depth.
    TestWrite,
    /// The background (sky) at the far plane, drawn last: only where nothing was drawn, so
    /// covered pixels are never shaded.
    Background,
}

/// A scene pipeline drawing into HDR colour + depth.
pub fn scene_pipeline(
    ctx: &Arc<Context>,
    layout: &PipelineLayout,
    desc: GraphicsDesc,
    depth: Depth,
) -> GpuResult<Pipeline> {
    let (compare, write) = match depth {
        Depth::TestWrite => (vk::CompareOp::GREATER, true),
        Depth::Background => (vk::CompareOp::GREATER_OR_EQUAL, false),
    };
    Pipeline::graphics(
        ctx,
        layout,
        &GraphicsDesc {
            colour_formats: &[HDR_FORMAT],
            depth_format: Some(DEPTH_FORMAT),
            depth_compare: Some(compare),
            depth_write: write,
            ..desc
        },
    )
}

/// Binds a scene pipeline with its sets and selects the view.
pub fn bind_scene(
    rec: &Recorder,
    pipeline: &Pipeline,
    layout: &PipelineLayout,
    sets: &[vk::DescriptorSet],
    view: ViewIndex,
) {
    rec.bind_pipeline(pipeline);
    rec.bind_sets(pipeline, layout, sets);
    rec.push_constants(layout, &ViewPush { view: view as u32 });
}
