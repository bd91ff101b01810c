//! `Renderer::record`: the frame, pass by pass, in order.
//!
//! ```text
//!  frame uniforms (slot f % 2) ──┐
//!  sky        fullscreen sky            -> hdr colour            (every pixel written)
//!  water      displaced ocean grid      -> hdr colour + depth    (depth cleared, reversed-Z)
//!             (samples the simulation images of slot f % 2, after the compute timeline wait)
//!  composite  tone map hdr colour       -> output image (swapchain image or headless target)
//! ```
//! The output is left in COLOR_ATTACHMENT_OPTIMAL; the frontend transitions it for present or copy.

use std::sync::Arc;

use ash::vk;
use glam::Vec3;

use super::camera::{Camera, FrameUniforms, OceanBindings};
use super::passes::{CompositePass, SkyPass, WaterPass};
use super::targets::Targets;
use crate::gpu::descriptors::{self, Write};
use crate::gpu::image::full_range;
use crate::gpu::{
    Access, Attachment, Buffer, Context, DescriptorPool, DescriptorSetLayout, Frame, GpuResult,
    ImageBarrier, Load, MemoryLocation, Profiler, Recorder, Sampler, FRAMES_IN_FLIGHT,
};

/// The image a frame ends in.
#[derive(Clone, Copy, Debug)]
pub struct OutputTarget {
    pub image: vk::Image,
    pub view: vk::ImageView,
    pub extent: vk::Extent2D,
    /// The last access to the image before this frame (its contents are discarded).
    pub prior: Access,
}

/// Per-frame inputs.
#[derive(Clone, Copy, Debug, Default)]
pub struct FrameInputs {
    /// Simulation time in seconds.
    pub time_s: f32,
    /// World position of the ocean images' texel (0, 0) (0 for periodic cascades).
    pub ocean_origin_m: [f32; 2],
    /// The images cover one bounded window (Gerstner) rather than repeating tiles.
    pub ocean_window: bool,
}

pub struct Renderer {
    ctx: Arc<Context>,
    pub camera: Camera,
    /// Unit vector toward the sun.
    pub sun_dir: Vec3,
    /// Radiance of the sun disc relative to the sky.
    pub sun_scale: f32,
    targets: Targets,
    /// Layout of the frame-uniform sets; kept alive with them.
    _frame_set_layout: DescriptorSetLayout,
    _pool: DescriptorPool,
    /// Per frame slot: uniform buffer and the set that binds it.
    frame_uniforms: Vec<(Buffer, vk::DescriptorSet)>,
    /// The simulation images the frame sets bind, and the cascade layout.
    ocean: OceanBindings,
    _ocean_sampler: Sampler,
    sky: SkyPass,
    water: WaterPass,
    composite: CompositePass,
}

impl Renderer {
    /// `output_format`: format of the images the frontend renders to.
    pub fn new(
        ctx: &Arc<Context>,
        output_format: vk::Format,
        extent: vk::Extent2D,
        ocean: OceanBindings,
    ) -> GpuResult<Renderer> {
        let targets = Targets::new(ctx, extent)?;
        let graphics = vk::ShaderStageFlags::ALL_GRAPHICS;
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        let frame_set_layout = DescriptorSetLayout::new(
            ctx,
            "frame set layout (uniforms, ocean images)",
            &[
                (0, vk::DescriptorType::UNIFORM_BUFFER, graphics),
                (1, sampled, graphics),
                (2, sampled, graphics),
            ],
        )?;
        let slots = FRAMES_IN_FLIGHT as u32;
        let pool = DescriptorPool::new(
            ctx,
            "renderer descriptors",
            slots,
            &[
                (vk::DescriptorType::UNIFORM_BUFFER, slots),
                (sampled, 2 * slots),
            ],
        )?;
        let ocean_sampler = Sampler::linear(
            ctx,
            "ocean sampler (repeat)",
            vk::SamplerAddressMode::REPEAT,
        )?;
        let mut frame_uniforms = Vec::new();
        for slot in 0..FRAMES_IN_FLIGHT {
            let buffer = Buffer::new(
                ctx,
                &format!("frame uniforms slot {slot}"),
                std::mem::size_of::<FrameUniforms>() as u64,
                vk::BufferUsageFlags::UNIFORM_BUFFER,
                MemoryLocation::CpuToGpu,
            )?;
            let set = pool.allocate(
                &frame_set_layout,
                &format!("frame uniforms set slot {slot}"),
            )?;
            descriptors::update(
                ctx,
                set,
                &[
                    Write::UniformBuffer {
                        binding: 0,
                        buffer: buffer.raw,
                    },
                    Write::SampledImage {
                        binding: 1,
                        view: ocean.displacement[slot],
                        sampler: ocean_sampler.raw,
                        layout: vk::ImageLayout::GENERAL,
                    },
                    Write::SampledImage {
                        binding: 2,
                        view: ocean.normals[slot],
                        sampler: ocean_sampler.raw,
                        layout: vk::ImageLayout::GENERAL,
                    },
                ],
            );
            frame_uniforms.push((buffer, set));
        }
        let sky = SkyPass::new(ctx, &frame_set_layout)?;
        let water = WaterPass::new(ctx, &frame_set_layout)?;
        let composite = CompositePass::new(ctx, output_format, &targets.hdr)?;
        Ok(Renderer {
            ctx: ctx.clone(),
            camera: Camera::default(),
            // Low sun ahead and to the right, so its glitter path lies on the water.
            sun_dir: Vec3::new(0.35, 0.22, -1.0).normalize(),
            sun_scale: 40.0,
            targets,
            _frame_set_layout: frame_set_layout,
            _pool: pool,
            frame_uniforms,
            ocean,
            _ocean_sampler: ocean_sampler,
            sky,
            water,
            composite,
        })
    }

    /// Size of the scene targets.
    pub fn extent(&self) -> vk::Extent2D {
        self.targets.extent()
    }

    /// Recreates the size-dependent targets, and the composite pipeline if the output format
    /// changed (a recreated swapchain may pick another). Waits for the device to go idle first
    /// (resizes are rare).
    pub fn resize(&mut self, extent: vk::Extent2D, output_format: vk::Format) -> GpuResult<()> {
        if extent == self.targets.extent() && output_format == self.composite.output_format {
            return Ok(());
        }
        self.ctx.wait_idle()?;
        if extent != self.targets.extent() {
            self.targets = Targets::new(&self.ctx, extent)?;
        }
        if output_format == self.composite.output_format {
            self.composite.resize(&self.targets.hdr);
        } else {
            self.composite = CompositePass::new(&self.ctx, output_format, &self.targets.hdr)?;
        }
        Ok(())
    }

    /// Records the frame into `rec`. `output` must have the extent of the scene targets.
    pub fn record(
        &mut self,
        rec: &Recorder,
        frame: &Frame,
        profiler: &mut Profiler,
        output: &OutputTarget,
        inputs: &FrameInputs,
    ) {
        debug_assert_eq!(output.extent, self.targets.extent());
        let extent = self.targets.extent();
        let uniforms = FrameUniforms::new(
            &self.camera,
            self.sun_dir,
            self.sun_scale,
            inputs.time_s,
            (extent.width, extent.height),
            &self.ocean,
            inputs,
        );
        let (buffer, frame_set) = &mut self.frame_uniforms[frame.slot];
        buffer.write(bytemuck::bytes_of(&uniforms));
        let frame_set = *frame_set;

        let hdr = &self.targets.hdr;
        let depth = &self.targets.depth;
        // The previous frame sampled hdr in composite and wrote depth; both are rewritten whole.
        rec.barrier(
            &[
                ImageBarrier {
                    image: hdr.raw,
                    range: hdr.range(),
                    old_layout: vk::ImageLayout::UNDEFINED,
                    new_layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
                    src: Access::FRAGMENT_SAMPLED.or(Access::COLOUR_WRITE),
                    dst: Access::COLOUR_RW,
                },
                ImageBarrier {
                    image: depth.raw,
                    range: depth.range(),
                    old_layout: vk::ImageLayout::UNDEFINED,
                    new_layout: vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                    src: Access::DEPTH_RW,
                    dst: Access::DEPTH_RW,
                },
            ],
            &[],
        );

        let hdr_attachment = |load: Load| Attachment {
            view: hdr.view,
            layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
            load,
        };
        profiler.pass(rec, "sky", || {
            // The fullscreen triangle writes every pixel.
            rec.begin_rendering(extent, &[hdr_attachment(Load::DontCare)], None);
            self.sky.record(rec, frame_set);
            rec.end_rendering();
        });
        // Attachment writes are only ordered within one rendering scope: water loads the sky.
        rec.barrier(
            &[ImageBarrier {
                image: hdr.raw,
                range: hdr.range(),
                old_layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
                new_layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
                src: Access::COLOUR_WRITE,
                dst: Access::COLOUR_RW,
            }],
            &[],
        );
        profiler.pass(rec, "water", || {
            let depth_clear = vk::ClearValue {
                depth_stencil: vk::ClearDepthStencilValue {
                    depth: 0.0,
                    stencil: 0,
                },
            };
            rec.begin_rendering(
                extent,
                &[hdr_attachment(Load::Keep)],
                Some(Attachment {
                    view: depth.view,
                    layout: vk::ImageLayout::DEPTH_STENCIL_ATTACHMENT_OPTIMAL,
                    load: Load::Clear(depth_clear),
                }),
            );
            self.water.record(rec, frame_set);
            rec.end_rendering();
        });

        rec.barrier(
            &[
                ImageBarrier {
                    image: hdr.raw,
                    range: hdr.range(),
                    old_layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
                    new_layout: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
                    src: Access::COLOUR_RW,
                    dst: Access::FRAGMENT_SAMPLED,
                },
                ImageBarrier {
                    image: output.image,
                    range: full_range(vk::ImageAspectFlags::COLOR, 1),
                    old_layout: vk::ImageLayout::UNDEFINED,
                    new_layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
                    src: output.prior,
                    dst: Access::COLOUR_WRITE,
                },
            ],
            &[],
        );
        profiler.pass(rec, "composite", || {
            let target = Attachment {
                view: output.view,
                layout: vk::ImageLayout::COLOR_ATTACHMENT_OPTIMAL,
                // Composite writes every pixel.
                load: Load::DontCare,
            };
            rec.begin_rendering(extent, &[target], None);
            self.composite.record(rec);
            rec.end_rendering();
        });
    }
}
