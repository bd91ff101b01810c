//! Sky pass: a fullscreen triangle writing the procedural sky (shaders/sky/sky.frag) into the
//! HDR target. Reads the frame uniforms only.

use std::sync::Arc;

use ash::vk;

use crate::gpu::{
    Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Pipeline, PipelineLayout, Recorder,
};
use crate::render::targets::HDR_FORMAT;
use crate::shaders;

pub struct SkyPass {
    layout: PipelineLayout,
    pipeline: Pipeline,
}

impl SkyPass {
    pub fn new(ctx: &Arc<Context>, frame_layout: &DescriptorSetLayout) -> GpuResult<SkyPass> {
        let layout = PipelineLayout::new(ctx, "sky layout", &[frame_layout], None)?;
        let pipeline = Pipeline::graphics(
            ctx,
            &layout,
            &GraphicsDesc {
                name: "sky",
                stages: &[
                    (
                        vk::ShaderStageFlags::VERTEX,
                        shaders::COMMON_FULLSCREEN_VERT,
                    ),
                    (vk::ShaderStageFlags::FRAGMENT, shaders::SKY_SKY_FRAG),
                ],
                colour_formats: &[HDR_FORMAT],
                ..Default::default()
            },
        )?;
        Ok(SkyPass { layout, pipeline })
    }

    /// Draws inside a rendering scope on the HDR target.
    pub fn record(&self, rec: &Recorder, frame_set: vk::DescriptorSet) {
        rec.bind_pipeline(&self.pipeline);
        rec.bind_sets(&self.pipeline, &self.layout, &[frame_set]);
        rec.draw(3, 1);
    }
}
