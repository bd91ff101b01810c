//! Composite pass: tone-maps the HDR target into the output image (swapchain image or the
//! headless target), shaders/post/composite.frag.

use std::sync::Arc;

use ash::vk;

use crate::gpu::descriptors::{self, Write};
use crate::gpu::{
    Context, DescriptorPool, DescriptorSetLayout, GpuResult, GraphicsDesc, Image, Pipeline,
    PipelineLayout, Recorder, Sampler,
};
use crate::render::targets::Targets;
use crate::render::ViewMode;
use crate::shaders;

/// Push constants of composite.frag.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct CompositeParams {
    exposure: f32,
    /// `ViewMode` as u32: which texture to show.
    view: u32,
}

pub struct CompositePass {
    ctx: Arc<Context>,
    /// Layout of `set` (kept with the pass that owns the set).
    _set_layout: DescriptorSetLayout,
    layout: PipelineLayout,
    pipeline: Pipeline,
    /// Output format the pipeline was built for.
    pub output_format: vk::Format,
    _pool: DescriptorPool,
    /// Binds the HDR target (rewritten on resize, with the device idle).
    set: vk::DescriptorSet,
    sampler: Sampler,
    pub exposure: f32,
}

impl CompositePass {
    pub fn new(
        ctx: &Arc<Context>,
        output_format: vk::Format,
        targets: &Targets,
        dudv: &Image,
        dudv_sampler: vk::Sampler,
    ) -> GpuResult<CompositePass> {
        let set_layout = DescriptorSetLayout::new(
            ctx,
            "composite set layout",
            &[0, 1, 2, 3].map(|binding| {
                (
                    binding,
                    vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
                    vk::ShaderStageFlags::FRAGMENT,
                )
            }),
        )?;
        let layout = PipelineLayout::new(
            ctx,
            "composite layout",
            &[&set_layout],
            Some((
                vk::ShaderStageFlags::FRAGMENT,
                std::mem::size_of::<CompositeParams>() as u32,
            )),
        )?;
        let pipeline = Pipeline::graphics(
            ctx,
            &layout,
            &GraphicsDesc {
                name: "composite",
                stages: &[
                    (
                        vk::ShaderStageFlags::VERTEX,
                        shaders::COMMON_FULLSCREEN_VERT,
                    ),
                    (vk::ShaderStageFlags::FRAGMENT, shaders::POST_COMPOSITE_FRAG),
                ],
                colour_formats: &[output_format],
                ..Default::default()
            },
        )?;
        let pool = DescriptorPool::new(
            ctx,
            "composite descriptors",
            1,
            &[(vk::DescriptorType::COMBINED_IMAGE_SAMPLER, 4)],
        )?;
        let set = pool.allocate(&set_layout, "composite set")?;
        let sampler = Sampler::linear(
            ctx,
            "hdr sampler (clamp)",
            vk::SamplerAddressMode::CLAMP_TO_EDGE,
        )?;
        let pass = CompositePass {
            ctx: ctx.clone(),
            _set_layout: set_layout,
            layout,
            pipeline,
            output_format,
            _pool: pool,
            set,
            sampler,
            exposure: 1.0,
        };
        pass.resize(targets, dudv, dudv_sampler);
        Ok(pass)
    }

    /// Points the pass at new targets. The caller makes sure no frame in flight uses the set.
    pub fn resize(&self, targets: &Targets, dudv: &Image, dudv_sampler: vk::Sampler) {
        let read = vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL;
        let views = [
            (targets.main.colour.view, self.sampler.raw),
            (targets.reflection.colour.view, self.sampler.raw),
            (targets.refraction.colour.view, self.sampler.raw),
            (dudv.view, dudv_sampler),
        ];
        let writes: Vec<_> = views
            .iter()
            .enumerate()
            .map(|(binding, &(view, sampler))| Write::SampledImage {
                binding: binding as u32,
                view,
                sampler,
                layout: read,
            })
            .collect();
        descriptors::update(&self.ctx, self.set, &writes);
    }

    /// Draws inside a rendering scope on the output image.
    pub fn record(&self, rec: &Recorder, view: ViewMode) {
        rec.bind_pipeline(&self.pipeline);
        rec.bind_sets(&self.pipeline, &self.layout, &[self.set]);
        rec.push_constants(
            &self.layout,
            &CompositeParams {
                exposure: self.exposure,
                view: view as u32,
            },
        );
        rec.draw(3, 1);
    }
}
