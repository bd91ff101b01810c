//! Water pass: the ocean surface as a camera-centred grid displaced by the simulation's images
//! (shaders/surface/water.*), depth-tested into the HDR and depth targets. The rendering issue
//! replaces it with tessellated tiles.

use std::sync::Arc;

use ash::vk;

use crate::gpu::{
    Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Pipeline, PipelineLayout, Recorder,
};
use crate::render::targets::{DEPTH_FORMAT, HDR_FORMAT};
use crate::shaders;

/// Quads per side of the ocean grid (`GRID` in shaders/surface/water.vert).
pub const GRID_QUADS: u32 = 192;

pub struct WaterPass {
    layout: PipelineLayout,
    pipeline: Pipeline,
}

impl WaterPass {
    pub fn new(ctx: &Arc<Context>, frame_layout: &DescriptorSetLayout) -> GpuResult<WaterPass> {
        let layout = PipelineLayout::new(ctx, "water layout", &[frame_layout], None)?;
        let pipeline = Pipeline::graphics(
            ctx,
            &layout,
            &GraphicsDesc {
                name: "water",
                stages: &[
                    (vk::ShaderStageFlags::VERTEX, shaders::SURFACE_WATER_VERT),
                    (vk::ShaderStageFlags::FRAGMENT, shaders::SURFACE_WATER_FRAG),
                ],
                colour_formats: &[HDR_FORMAT],
                depth_format: Some(DEPTH_FORMAT),
                depth_compare: Some(vk::CompareOp::GREATER), // reversed-Z
                depth_write: true,
                ..Default::default()
            },
        )?;
        Ok(WaterPass { layout, pipeline })
    }

    /// Draws inside a rendering scope on the HDR + depth targets.
    pub fn record(&self, rec: &Recorder, frame_set: vk::DescriptorSet) {
        rec.bind_pipeline(&self.pipeline);
        rec.bind_sets(&self.pipeline, &self.layout, &[frame_set]);
        rec.draw(GRID_QUADS * GRID_QUADS * 6, 1);
    }
}
