//! The FFT ocean on the compute queue: h0 (uploaded once), then per frame
//! evolve (shaders/ocean/evolve.comp) → inverse FFT (`fft.rs`) → assemble (assemble.comp) into
//! the displacement and normal images of the frame's slot (slot = frame % 2, one array layer per
//! cascade).
//!
//! Synchronization (the design card):
//! - frame f's compute submission waits for the graphics timeline to reach frame f−2's value
//!   (the last frame that sampled slot f % 2) before overwriting the slot, and signals the compute
//!   timeline with frame f's value;
//! - frame f's graphics submission waits for the compute timeline to reach f's value at the
//!   stages that sample the images (`graphics_wait`);
//! - the images stay in GENERAL layout (storage writes, sampled reads) and are CONCURRENT when the
//!   queues differ in family; the semaphores carry the memory dependencies between queues.

use std::sync::Arc;

use ash::vk;

use super::fft::{Direction, GpuFft};
use super::params::OceanSettings;
use super::spectrum::{h0, Cascade};
use crate::gpu::compute::ComputeQueue;
use crate::gpu::descriptors::{self, Write};
use crate::gpu::oneshot::{run_once, run_once_waiting, upload};
use crate::gpu::{
    Access, Buffer, Context, DescriptorPool, DescriptorSetLayout, GpuResult, Image, ImageBarrier,
    ImageDesc, MemoryLocation, Pipeline, PipelineLayout, FRAMES_IN_FLIGHT,
};
use crate::shaders;

/// RGBA f32 texels of every cascade, cascade after cascade, `[m][n]`.
pub type Texels = Vec<[f32; 4]>;

/// Most cascades the shaders take (a vec4 of patch sizes).
pub const MAX_CASCADES: usize = 4;
/// Foam grows where J < this.
pub const FOAM_THRESHOLD: f32 = 0.4;
/// Foam fades with this time constant (s).
pub const FOAM_DECAY_S: f32 = 2.5;
/// Foam added per frame per unit of (threshold − J).
pub const FOAM_GAIN: f32 = 0.8;
/// Format of the simulation images: fp32, as displacement and slopes need it.
pub const IMAGE_FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct EvolveParams {
    patch_m: [f32; 4],
    time_s: f32,
    depth_m: f32,
    n: u32,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct AssembleParams {
    choppiness: f32,
    dt_s: f32,
    foam_threshold: f32,
    foam_decay_s: f32,
    foam_gain: f32,
    n: u32,
}

/// A compute pipeline with its layouts.
struct Kernel {
    set_layout: DescriptorSetLayout,
    layout: PipelineLayout,
    pipeline: Pipeline,
}

impl Kernel {
    fn new(
        ctx: &Arc<Context>,
        name: &str,
        spirv: &[u8],
        bindings: &[vk::DescriptorType],
        push_size: usize,
    ) -> GpuResult<Kernel> {
        let entries: Vec<_> = bindings
            .iter()
            .enumerate()
            .map(|(i, &ty)| (i as u32, ty, vk::ShaderStageFlags::COMPUTE))
            .collect();
        let set_layout = DescriptorSetLayout::new(ctx, &format!("{name} set layout"), &entries)?;
        let layout = PipelineLayout::new(
            ctx,
            &format!("{name} layout"),
            &[&set_layout],
            Some((vk::ShaderStageFlags::COMPUTE, push_size as u32)),
        )?;
        let pipeline = Pipeline::compute(ctx, &layout, name, spirv, &[])?;
        Ok(Kernel {
            set_layout,
            layout,
            pipeline,
        })
    }
}

pub struct Simulation {
    pub settings: OceanSettings,
    pub cascades: Vec<Cascade>,
    /// h0 of every cascade, (K, N, N) complex.
    h0: Buffer,
    fft: GpuFft,
    evolve: Kernel,
    assemble: Kernel,
    _pool: DescriptorPool,
    evolve_set: vk::DescriptorSet,
    /// Per slot: writes that slot's images, reads the other slot's normals (foam).
    assemble_sets: Vec<vk::DescriptorSet>,
    /// Per slot: (dx, h, dz, 0), one layer per cascade.
    pub displacement: Vec<Image>,
    /// Per slot: (∂h/∂x, ∂h/∂z, J, foam), one layer per cascade.
    pub normals: Vec<Image>,
    queue: ComputeQueue,
    last_time_s: Option<f32>,
}

impl Simulation {
    pub fn new(ctx: &Arc<Context>, settings: &OceanSettings) -> anyhow::Result<Simulation> {
        let n = settings.fft_size;
        let k = settings.cascades;
        anyhow::ensure!(
            (1..=MAX_CASCADES).contains(&k),
            "--cascades must be from 1 to {MAX_CASCADES}"
        );
        let cascades = settings.cascade_list();
        let fft = GpuFft::new(ctx, n, 4 * k)?;

        let h0_values: Vec<[f32; 2]> = cascades
            .iter()
            .enumerate()
            .flat_map(|(c, cascade)| h0(&settings.sea, n, cascade, c as u32, settings.seed))
            .collect();
        let h0_bytes: &[u8] = bytemuck::cast_slice(&h0_values);
        let h0_buffer = Buffer::new(
            ctx,
            "h0 (all cascades)",
            h0_bytes.len() as u64,
            vk::BufferUsageFlags::STORAGE_BUFFER
                | vk::BufferUsageFlags::TRANSFER_DST
                | vk::BufferUsageFlags::TRANSFER_SRC,
            MemoryLocation::GpuOnly,
        )?;
        upload(ctx, &h0_buffer, h0_bytes)?;

        let image = |name: String| {
            Image::new(
                ctx,
                &ImageDesc {
                    name: &name,
                    extent: vk::Extent2D {
                        width: n as u32,
                        height: n as u32,
                    },
                    format: IMAGE_FORMAT,
                    usage: vk::ImageUsageFlags::STORAGE
                        | vk::ImageUsageFlags::SAMPLED
                        | vk::ImageUsageFlags::TRANSFER_SRC
                        | vk::ImageUsageFlags::TRANSFER_DST,
                    layers: k as u32,
                    shared: true,
                },
            )
        };
        let mut displacement = Vec::new();
        let mut normals = Vec::new();
        for slot in 0..FRAMES_IN_FLIGHT {
            displacement.push(image(format!("ocean displacement slot {slot}"))?);
            normals.push(image(format!("ocean normals+foam slot {slot}"))?);
        }
        // GENERAL for good, and zero (no foam before the first frame).
        run_once(ctx, "ocean images init", |rec| {
            let to_general: Vec<_> = displacement
                .iter()
                .chain(&normals)
                .map(|img| ImageBarrier {
                    image: img.raw,
                    range: img.range(),
                    old_layout: vk::ImageLayout::UNDEFINED,
                    new_layout: vk::ImageLayout::GENERAL,
                    src: Access::NONE,
                    dst: Access::CLEAR_WRITE,
                })
                .collect();
            rec.barrier(&to_general, &[]);
            for img in displacement.iter().chain(&normals) {
                rec.clear_image(img);
            }
            let done: Vec<_> = displacement
                .iter()
                .chain(&normals)
                .map(|img| ImageBarrier {
                    image: img.raw,
                    range: img.range(),
                    old_layout: vk::ImageLayout::GENERAL,
                    new_layout: vk::ImageLayout::GENERAL,
                    src: Access::CLEAR_WRITE,
                    dst: Access::ALL_READ_WRITE,
                })
                .collect();
            rec.barrier(&done, &[]);
        })?;

        let storage = vk::DescriptorType::STORAGE_BUFFER;
        let storage_image = vk::DescriptorType::STORAGE_IMAGE;
        let evolve = Kernel::new(
            ctx,
            "ocean evolve",
            shaders::OCEAN_EVOLVE_COMP,
            &[storage, storage],
            std::mem::size_of::<EvolveParams>(),
        )?;
        let assemble = Kernel::new(
            ctx,
            "ocean assemble",
            shaders::OCEAN_ASSEMBLE_COMP,
            &[storage, storage_image, storage_image, storage_image],
            std::mem::size_of::<AssembleParams>(),
        )?;
        let pool = DescriptorPool::new(
            ctx,
            "ocean descriptors",
            1 + FRAMES_IN_FLIGHT as u32,
            &[
                (storage, 2 + FRAMES_IN_FLIGHT as u32),
                (storage_image, 3 * FRAMES_IN_FLIGHT as u32),
            ],
        )?;
        let evolve_set = pool.allocate(&evolve.set_layout, "ocean evolve set")?;
        descriptors::update(
            ctx,
            evolve_set,
            &[
                Write::StorageBuffer {
                    binding: 0,
                    buffer: h0_buffer.raw,
                },
                Write::StorageBuffer {
                    binding: 1,
                    buffer: fft.data.raw,
                },
            ],
        );
        let mut assemble_sets = Vec::new();
        for slot in 0..FRAMES_IN_FLIGHT {
            let previous = (slot + FRAMES_IN_FLIGHT - 1) % FRAMES_IN_FLIGHT;
            let set = pool.allocate(
                &assemble.set_layout,
                &format!("ocean assemble set slot {slot}"),
            )?;
            descriptors::update(
                ctx,
                set,
                &[
                    Write::StorageBuffer {
                        binding: 0,
                        buffer: fft.data.raw,
                    },
                    Write::StorageImage {
                        binding: 1,
                        view: displacement[slot].view,
                    },
                    Write::StorageImage {
                        binding: 2,
                        view: normals[slot].view,
                    },
                    Write::StorageImage {
                        binding: 3,
                        view: normals[previous].view,
                    },
                ],
            );
            assemble_sets.push(set);
        }
        Ok(Simulation {
            settings: settings.clone(),
            cascades,
            h0: h0_buffer,
            fft,
            evolve,
            assemble,
            _pool: pool,
            evolve_set,
            assemble_sets,
            displacement,
            normals,
            queue: ComputeQueue::new(ctx)?,
            last_time_s: None,
        })
    }

    /// Patch sizes of the cascades, padded to four (for shaders).
    pub fn patch_sizes(&self) -> [f32; 4] {
        let mut out = [1.0; 4];
        for (o, c) in out.iter_mut().zip(&self.cascades) {
            *o = c.patch_m as f32;
        }
        out
    }

    /// Submits frame `value`'s simulation at time `time_s` into `slot` on the compute queue.
    pub fn submit(&mut self, slot: usize, value: u64, time_s: f32) -> GpuResult<()> {
        let dt_s = self
            .last_time_s
            .map(|t| (time_s - t).max(0.0))
            .unwrap_or(0.0);
        self.last_time_s = Some(time_s);
        // Frame f − 2 (value − 2) was the last to sample this slot.
        let wait_graphics =
            (value > FRAMES_IN_FLIGHT as u64).then(|| value - FRAMES_IN_FLIGHT as u64);
        let evolve_params = EvolveParams {
            patch_m: self.patch_sizes(),
            time_s,
            depth_m: self.settings.sea.depth_m.map(|d| d as f32).unwrap_or(0.0),
            n: self.settings.fft_size as u32,
        };
        let assemble_params = AssembleParams {
            choppiness: self.settings.choppiness as f32,
            dt_s,
            foam_threshold: FOAM_THRESHOLD,
            foam_decay_s: FOAM_DECAY_S,
            foam_gain: FOAM_GAIN,
            n: self.settings.fft_size as u32,
        };
        let n = self.settings.fft_size as u32;
        let layers = self.cascades.len() as u32;
        let previous = &self.normals[(slot + FRAMES_IN_FLIGHT - 1) % FRAMES_IN_FLIGHT];
        let (fft, evolve, assemble) = (&self.fft, &self.evolve, &self.assemble);
        let (evolve_set, assemble_set) = (self.evolve_set, self.assemble_sets[slot]);
        // Disjoint field borrows: the queue mutably, the kernels and images shared.
        self.queue.submit(slot, value, wait_graphics, |rec| {
            let groups = n.div_ceil(8);
            // Evolve overwrites the FFT data that the previous frame's FFT and assemble used.
            rec.begin_label("ocean evolve");
            rec.barrier(
                &[],
                &[(
                    fft.data.raw,
                    Access::COMPUTE_READ.or(Access::COMPUTE_WRITE),
                    Access::COMPUTE_WRITE,
                )],
            );
            rec.bind_pipeline(&evolve.pipeline);
            rec.bind_sets(&evolve.pipeline, &evolve.layout, &[evolve_set]);
            rec.push_constants(&evolve.layout, &evolve_params);
            rec.dispatch(groups, groups, layers);
            rec.end_label();

            rec.begin_label("ocean fft");
            fft.record(rec, Direction::Inverse, Access::COMPUTE_WRITE);
            rec.end_label();

            rec.begin_label("ocean assemble");
            // FFT output → assemble; the previous frame's normals (foam) → assemble.
            rec.barrier(
                &[ImageBarrier {
                    image: previous.raw,
                    range: previous.range(),
                    old_layout: vk::ImageLayout::GENERAL,
                    new_layout: vk::ImageLayout::GENERAL,
                    src: Access::COMPUTE_WRITE,
                    dst: Access::COMPUTE_READ,
                }],
                &[(fft.data.raw, Access::COMPUTE_WRITE, Access::COMPUTE_READ)],
            );
            rec.bind_pipeline(&assemble.pipeline);
            rec.bind_sets(&assemble.pipeline, &assemble.layout, &[assemble_set]);
            rec.push_constants(&assemble.layout, &assemble_params);
            rec.dispatch(groups, groups, layers);
            rec.end_label();
        })
    }

    /// The wait a graphics submission adds before sampling frame `value`'s images.
    pub fn graphics_wait(&self, value: u64) -> vk::SemaphoreSubmitInfo<'static> {
        self.queue.graphics_wait(
            value,
            vk::PipelineStageFlags2::VERTEX_SHADER
                | vk::PipelineStageFlags2::TESSELLATION_EVALUATION_SHADER
                | vk::PipelineStageFlags2::FRAGMENT_SHADER,
        )
    }

    /// Reads both images of `slot` once the compute timeline reaches `value` (tests, dumps):
    /// (displacement, normals), each cascade after cascade, `[m][n]` RGBA f32.
    pub fn read_back(
        &self,
        ctx: &Arc<Context>,
        slot: usize,
        value: u64,
    ) -> GpuResult<(Texels, Texels)> {
        let images = [&self.displacement[slot], &self.normals[slot]];
        let n = self.settings.fft_size;
        let bytes = (self.cascades.len() * n * n * 16) as u64;
        let buffers = [
            Buffer::new(
                ctx,
                "ocean displacement readback",
                bytes,
                vk::BufferUsageFlags::TRANSFER_DST,
                MemoryLocation::GpuToCpu,
            )?,
            Buffer::new(
                ctx,
                "ocean normals readback",
                bytes,
                vk::BufferUsageFlags::TRANSFER_DST,
                MemoryLocation::GpuToCpu,
            )?,
        ];
        let wait = self
            .queue
            .graphics_wait(value, vk::PipelineStageFlags2::COPY);
        run_once_waiting(ctx, "ocean readback", &[wait], |rec| {
            let transition = |src, dst, old, new| -> Vec<ImageBarrier> {
                images
                    .iter()
                    .map(|img| ImageBarrier {
                        image: img.raw,
                        range: img.range(),
                        old_layout: old,
                        new_layout: new,
                        src,
                        dst,
                    })
                    .collect()
            };
            let (general, src_optimal) = (
                vk::ImageLayout::GENERAL,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
            );
            rec.barrier(
                &transition(
                    Access::COMPUTE_WRITE,
                    Access::COPY_READ,
                    general,
                    src_optimal,
                ),
                &[],
            );
            for (img, buffer) in images.iter().zip(&buffers) {
                rec.copy_image_layers_to_buffer(img, src_optimal, buffer);
            }
            // Back to GENERAL for the next frame's compute writes and graphics reads.
            rec.barrier(
                &transition(
                    Access::COPY_READ,
                    Access::ALL_READ_WRITE,
                    src_optimal,
                    general,
                ),
                &[],
            );
            rec.barrier(
                &[],
                &[
                    (buffers[0].raw, Access::COPY_WRITE, Access::HOST_READ),
                    (buffers[1].raw, Access::COPY_WRITE, Access::HOST_READ),
                ],
            );
        })?;
        let read = |b: &Buffer| -> Texels {
            bytemuck::cast_slice(b.mapped().expect("readback is host-visible")).to_vec()
        };
        Ok((read(&buffers[0]), read(&buffers[1])))
    }

    /// h0 as uploaded (for tests and dumps).
    pub fn h0_buffer(&self) -> &Buffer {
        &self.h0
    }
}
