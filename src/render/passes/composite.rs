//! Composite pass, in compute (shaders/post/composite.comp): tone-maps the HDR target (scaling
//! it up from `--render-scale`) into the display image, sRGB-encoded by the shader, then copies
//! that bit for bit into the output image (swapchain image or the headless target).
//!
//! Why compute and a copy rather than a full-screen triangle into the output: on lavapipe the
//! compute pass costs the same as the fragment one or less (about 25 ms at 1280x720 either way,
//! README "Measured on lavapipe"), lets each invocation shade a run of pixels, and the copy
//! (0.5 ms) frees the output from needing STORAGE usage, which 8-bit sRGB swapchain formats
//! rarely offer.

use std::sync::Arc;

use ash::vk;

use crate::gpu::descriptors::{self, Write};
use crate::gpu::image::{full_range, is_bgra};
use crate::gpu::{
    Access, Context, DescriptorPool, DescriptorSetLayout, GpuResult, Image, ImageBarrier, Pipeline,
    PipelineLayout, Recorder, Sampler,
};
use crate::render::targets::Targets;
use crate::render::{OutputTarget, ViewMode};
use crate::shaders;

/// Workgroup side of composite.comp (`local_size_x`, `local_size_y`).
const GROUP: u32 = 8;
/// Pixels per invocation along x (`RUN` in composite.comp).
const RUN: u32 = 8;

/// Push constants of composite.comp.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct CompositeParams {
    exposure: f32,
    /// `ViewMode` as u32: which texture to show.
    view: u32,
    /// 1: store BGRA (the output is a B8G8R8A8 image).
    bgra: u32,
}

pub struct CompositePass {
    ctx: Arc<Context>,
    /// Layout of `set` (kept with the pass that owns the set).
    _set_layout: DescriptorSetLayout,
    layout: PipelineLayout,
    pipeline: Pipeline,
    /// Format of the output image (decides the byte order).
    pub output_format: vk::Format,
    _pool: DescriptorPool,
    /// Binds the targets (rewritten on resize, with the device idle).
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
        let compute = vk::ShaderStageFlags::COMPUTE;
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        let set_layout = DescriptorSetLayout::new(
            ctx,
            "composite set layout",
            &[
                (0, sampled, compute),
                (1, sampled, compute),
                (2, sampled, compute),
                (3, sampled, compute),
                (4, vk::DescriptorType::STORAGE_IMAGE, compute),
            ],
        )?;
        let layout = PipelineLayout::new(
            ctx,
            "composite layout",
            &[&set_layout],
            Some((compute, std::mem::size_of::<CompositeParams>() as u32)),
        )?;
        let pipeline =
            Pipeline::compute(ctx, &layout, "composite", shaders::POST_COMPOSITE_COMP, &[])?;
        let pool = DescriptorPool::new(
            ctx,
            "composite descriptors",
            1,
            &[(sampled, 4), (vk::DescriptorType::STORAGE_IMAGE, 1)],
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
        let mut writes: Vec<_> = views
            .iter()
            .enumerate()
            .map(|(binding, &(view, sampler))| Write::SampledImage {
                binding: binding as u32,
                view,
                sampler,
                layout: read,
            })
            .collect();
        writes.push(Write::StorageImage {
            binding: 4,
            view: targets.display.view,
        });
        descriptors::update(&self.ctx, self.set, &writes);
    }

    /// Records the dispatch into `display` and its copy into `output`, outside any rendering
    /// scope. The sampled targets must be readable by compute; `output` ends in
    /// [`OutputTarget::FINAL_LAYOUT`] after a copy write.
    pub fn record(&self, rec: &Recorder, display: &Image, output: &OutputTarget, view: ViewMode) {
        let range = full_range(vk::ImageAspectFlags::COLOR, 1);
        // The previous frame's copy read the display image; its contents are rewritten whole.
        rec.barrier(
            &[ImageBarrier {
                image: display.raw,
                range,
                old_layout: vk::ImageLayout::UNDEFINED,
                new_layout: vk::ImageLayout::GENERAL,
                src: Access::COPY_READ,
                dst: Access::COMPUTE_WRITE,
            }],
            &[],
        );
        rec.bind_pipeline(&self.pipeline);
        rec.bind_sets(&self.pipeline, &self.layout, &[self.set]);
        rec.push_constants(
            &self.layout,
            &CompositeParams {
                exposure: self.exposure,
                view: view as u32,
                bgra: is_bgra(self.output_format) as u32,
            },
        );
        let extent = display.extent;
        debug_assert_eq!(extent, output.extent);
        rec.dispatch(
            extent.width.div_ceil(GROUP * RUN),
            extent.height.div_ceil(GROUP),
            1,
        );
        rec.barrier(
            &[
                ImageBarrier {
                    image: display.raw,
                    range,
                    old_layout: vk::ImageLayout::GENERAL,
                    new_layout: vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                    src: Access::COMPUTE_WRITE,
                    dst: Access::COPY_READ,
                },
                ImageBarrier {
                    image: output.image,
                    range,
                    old_layout: vk::ImageLayout::UNDEFINED,
                    new_layout: OutputTarget::FINAL_LAYOUT,
                    src: output.prior,
                    dst: Access::COPY_WRITE,
                },
            ],
            &[],
        );
        rec.copy_image(display.raw, output.image, extent);
    }
}
