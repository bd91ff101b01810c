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

mod readback;

use super::fft::{Direction, GpuFft};
use super::gerstner::{Wave, G_SEED};
use super::params::{OceanSettings, Waves};
use super::spectrum::{h0, omega_steps_grid, time_ticks, Cascade};
use crate::gpu::compute::ComputeQueue;
use crate::gpu::descriptors::{self, Write};
use crate::gpu::oneshot::upload_on;
use crate::gpu::{
    Buffer, Context, DescriptorPool, DescriptorSetLayout, FormatUse, Frame, GpuResult, Image,
    ImageDesc, MemoryLocation, Pipeline, PipelineLayout, Profiler, Recorder, Tracked, Use,
    FRAMES_IN_FLIGHT,
};
use crate::shaders;

/// A named compute pass: timestamps when a profiler is given, a debug label always.
fn scope(
    timer: &mut Option<(&mut Profiler, &Frame)>,
    rec: &Recorder,
    name: &'static str,
    body: impl FnOnce(),
) {
    match timer {
        Some((profiler, _)) => profiler.pass(rec, name, body),
        None => {
            rec.begin_label(name);
            body();
            rec.end_label();
        }
    }
}

/// Moves the simulation images into GENERAL, where they stay for good, and zeroes them (no foam
/// before the first frame). Recorded at the start of the first compute submission, on the queue
/// that writes them, so the graphics queue first sees them through the compute timeline.
fn record_images_init(rec: &Recorder, images: &[&Image]) {
    let clears: Vec<(&dyn Tracked, Use)> = images
        .iter()
        .map(|&img| (img as &dyn Tracked, Use::Clear))
        .collect();
    rec.uses(&clears);
    for img in images {
        rec.clear_image(img);
    }
}

/// Patch sizes padded to four (for shaders).
fn patch_sizes(cascades: &[Cascade]) -> [f32; 4] {
    let mut out = [1.0; 4];
    for (o, c) in out.iter_mut().zip(cascades) {
        *o = c.patch_m as f32;
    }
    out
}

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
/// Format of the simulation images: fp32, as displacement and slopes need it. Linear filtering
/// of it is optional in Vulkan: where the device lacks it, the water shaders filter by hand
/// (`OCEAN_MANUAL_FILTER` in shaders/common/water.glsl).
pub const IMAGE_FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct EvolveParams {
    patch_m: [f32; 4],
    /// `spectrum::time_ticks` of the frame's time.
    ticks: u32,
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

/// The model-specific GPU resources.
enum Model {
    Fft {
        /// h0 of every cascade, (K, N, N) complex.
        h0: Buffer,
        /// Every element's quantized frequency ω/ω0 (`spectrum::omega_steps`), (K, N, N) u32.
        omega_steps: Box<Buffer>,
        /// Boxed: it dwarfs the Gerstner variant.
        fft: Box<GpuFft>,
        evolve: Kernel,
        assemble: Kernel,
        evolve_set: vk::DescriptorSet,
        /// Per slot: writes that slot's images, reads the other slot's normals (foam).
        assemble_sets: Vec<vk::DescriptorSet>,
    },
    Gerstner {
        /// The waves; per slot, as θ at the window origin changes every frame.
        waves: Vec<Wave>,
        buffers: Vec<Buffer>,
        kernel: Kernel,
        /// Per slot, like `assemble_sets`.
        sets: Vec<vk::DescriptorSet>,
    },
}

/// One wave as gerstner.comp reads it.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuWave {
    wave: [f32; 4],
    extra: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GerstnerParams {
    window_m: f32,
    dt_s: f32,
    foam_threshold: f32,
    foam_decay_s: f32,
    foam_gain: f32,
    n: u32,
    count: u32,
}

pub struct Simulation {
    pub settings: OceanSettings,
    pub cascades: Vec<Cascade>,
    model: Model,
    _pool: DescriptorPool,
    /// World position of texel (0, 0) of the images: 0 for the periodic FFT cascades, the
    /// camera-following (grid-snapped) window corner for Gerstner waves.
    origin_m: [f64; 2],
    /// Per slot: (dx, h, dz, 0), one layer per cascade.
    pub displacement: Vec<Image>,
    /// Per slot: (∂h/∂x, ∂h/∂z, J, foam), one layer per cascade.
    pub normals: Vec<Image>,
    queue: ComputeQueue,
    /// The images were initialized (the first submission does it).
    initialized: bool,
    /// Simulation time of the previous submission (s; f64: a long run keeps its frame steps).
    last_time_s: Option<f64>,
    /// Bound on how far the surface moves from its rest position (m): culling margin.
    pub max_displacement_m: f64,
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
        let layers = cascades.len() as u32;
        ctx.require_formats(&[FormatUse {
            format: IMAGE_FORMAT,
            // Written by the kernels, sampled by the water, cleared, read back (--dump, --stats).
            features: vk::FormatFeatureFlags::STORAGE_IMAGE
                | vk::FormatFeatureFlags::SAMPLED_IMAGE
                | vk::FormatFeatureFlags::TRANSFER_SRC
                | vk::FormatFeatureFlags::TRANSFER_DST,
            what: "the ocean simulation images",
        }])?;
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
                    layers,
                    array_view: true,
                    shared: true,
                    cube: false,
                },
            )
        };
        let mut displacement = Vec::new();
        let mut normals = Vec::new();
        for slot in 0..FRAMES_IN_FLIGHT {
            displacement.push(image(format!("ocean displacement slot {slot}"))?);
            normals.push(image(format!("ocean normals+foam slot {slot}"))?);
        }
        let storage = vk::DescriptorType::STORAGE_BUFFER;
        let storage_image = vk::DescriptorType::STORAGE_IMAGE;
        let slots = FRAMES_IN_FLIGHT as u32;
        let pool = DescriptorPool::new(
            ctx,
            "ocean descriptors",
            1 + slots,
            &[(storage, 3 + slots), (storage_image, 3 * slots)],
        )?;
        // Per slot: write this slot's images, read the other slot's normals (foam).
        let image_writes = |slot: usize| {
            let previous = (slot + FRAMES_IN_FLIGHT - 1) % FRAMES_IN_FLIGHT;
            [
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
            ]
        };
        let max_displacement_m;
        let model = match &settings.waves {
            Waves::Fft => {
                let fft = GpuFft::new(ctx, n, 4 * k)?;
                let h0_values: Vec<[f32; 2]> = cascades
                    .iter()
                    .enumerate()
                    .flat_map(|(c, cascade)| h0(&settings.sea, n, cascade, c as u32, settings.seed))
                    .collect();
                // Parseval: the height variance is Σ_k E|h(k,t)|² = 2 Σ_k |h0(k)|² (item 3's two
                // terms); crests rarely pass 4σ, and choppiness moves points sideways by about
                // λ times the height's scale.
                let variance: f64 = h0_values
                    .iter()
                    .map(|[re, im]| 2.0 * (*re as f64 * *re as f64 + *im as f64 * *im as f64))
                    .sum();
                max_displacement_m = 4.0 * variance.sqrt() * (1.0 + settings.choppiness) + 0.5;
                let h0_bytes: &[u8] = bytemuck::cast_slice(&h0_values);
                // Uploaded, read and (--dump) downloaded on the compute queue only: it never
                // crosses queue families.
                let h0_buffer = Buffer::new(
                    ctx,
                    "h0 (all cascades)",
                    h0_bytes.len() as u64,
                    vk::BufferUsageFlags::STORAGE_BUFFER
                        | vk::BufferUsageFlags::TRANSFER_DST
                        | vk::BufferUsageFlags::TRANSFER_SRC,
                    MemoryLocation::GpuOnly,
                )?;
                upload_on(ctx, ctx.compute, &h0_buffer, h0_bytes)?;
                let steps: Vec<u32> = cascades
                    .iter()
                    .flat_map(|c| omega_steps_grid(n, c.patch_m, settings.sea.depth_m))
                    .collect();
                let steps_buffer = Buffer::new(
                    ctx,
                    "omega steps (all cascades)",
                    (steps.len() * 4) as u64,
                    vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST,
                    MemoryLocation::GpuOnly,
                )?;
                upload_on(
                    ctx,
                    ctx.compute,
                    &steps_buffer,
                    bytemuck::cast_slice(&steps),
                )?;
                let evolve = Kernel::new(
                    ctx,
                    "ocean evolve",
                    shaders::OCEAN_EVOLVE_COMP,
                    &[storage, storage, storage],
                    std::mem::size_of::<EvolveParams>(),
                )?;
                let assemble = Kernel::new(
                    ctx,
                    "ocean assemble",
                    shaders::OCEAN_ASSEMBLE_COMP,
                    &[storage, storage_image, storage_image, storage_image],
                    std::mem::size_of::<AssembleParams>(),
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
                        Write::StorageBuffer {
                            binding: 2,
                            buffer: steps_buffer.raw,
                        },
                    ],
                );
                let mut assemble_sets = Vec::new();
                for slot in 0..FRAMES_IN_FLIGHT {
                    let set = pool.allocate(
                        &assemble.set_layout,
                        &format!("ocean assemble set slot {slot}"),
                    )?;
                    let mut writes = vec![Write::StorageBuffer {
                        binding: 0,
                        buffer: fft.data.raw,
                    }];
                    writes.extend(image_writes(slot));
                    descriptors::update(ctx, set, &writes);
                    assemble_sets.push(set);
                }
                Model::Fft {
                    h0: h0_buffer,
                    omega_steps: Box::new(steps_buffer),
                    fft: Box::new(fft),
                    evolve,
                    assemble,
                    evolve_set,
                    assemble_sets,
                }
            }
            Waves::Gerstner(waves) => {
                anyhow::ensure!(!waves.is_empty(), "Gerstner mode needs at least one wave");
                let kernel = Kernel::new(
                    ctx,
                    "ocean gerstner",
                    shaders::OCEAN_GERSTNER_COMP,
                    &[storage, storage_image, storage_image, storage_image],
                    std::mem::size_of::<GerstnerParams>(),
                )?;
                let mut buffers = Vec::new();
                let mut sets = Vec::new();
                for slot in 0..FRAMES_IN_FLIGHT {
                    let buffer = Buffer::new(
                        ctx,
                        &format!("gerstner waves slot {slot}"),
                        (waves.len() * std::mem::size_of::<GpuWave>()) as u64,
                        vk::BufferUsageFlags::STORAGE_BUFFER,
                        MemoryLocation::CpuToGpu,
                    )?;
                    let set = pool.allocate(
                        &kernel.set_layout,
                        &format!("ocean gerstner set slot {slot}"),
                    )?;
                    let mut writes = vec![Write::StorageBuffer {
                        binding: 0,
                        buffer: buffer.raw,
                    }];
                    writes.extend(image_writes(slot));
                    descriptors::update(ctx, set, &writes);
                    buffers.push(buffer);
                    sets.push(set);
                }
                // Each wave moves a point by at most a vertically and Q·a sideways.
                max_displacement_m = waves
                    .iter()
                    .map(|w| w.amplitude.abs() * (1.0 + w.steepness.abs()))
                    .sum::<f64>()
                    + 0.5;
                Model::Gerstner {
                    waves: waves.clone(),
                    buffers,
                    kernel,
                    sets,
                }
            }
        };
        Ok(Simulation {
            max_displacement_m,
            settings: settings.clone(),
            cascades,
            model,
            _pool: pool,
            origin_m: [0.0, 0.0],
            displacement,
            normals,
            queue: ComputeQueue::new(ctx)?,
            initialized: false,
            last_time_s: None,
        })
    }

    /// World position of the images' texel (0, 0) for the frame being recorded (set by
    /// [`Simulation::place_window`]).
    pub fn origin_m(&self) -> [f64; 2] {
        self.origin_m
    }

    /// Places the Gerstner window for the next submission around the camera (the periodic FFT
    /// cascades need no placement): it follows the camera in whole grid steps, so texels stay on
    /// a fixed world lattice (no swimming) and the camera sits at its centre. Called before the
    /// frame's uniforms are written, which carry the origin.
    pub fn place_window(&mut self, camera_xz: [f64; 2]) {
        if self.is_window() {
            let window = self.settings.patch_size_m;
            let step = window / self.settings.fft_size as f64;
            self.origin_m = camera_xz.map(|c| ((c - window / 2.0) / step).floor() * step);
        }
    }

    /// True for a bounded window (Gerstner), false for periodic cascades (FFT).
    pub fn is_window(&self) -> bool {
        matches!(self.model, Model::Gerstner { .. })
    }

    /// Patch sizes of the cascades, padded to four (for shaders).
    pub fn patch_sizes(&self) -> [f32; 4] {
        patch_sizes(&self.cascades)
    }

    /// Submits frame `value`'s simulation at time `time_s` into `slot` on the compute queue,
    /// with the Gerstner window where [`Simulation::place_window`] last put it, after the
    /// graphics timeline reached `wait_graphics` (the slot's previous user, `Frame::
    /// previous_user`); `timing` times the passes with a compute-queue profiler
    /// (`Profiler::for_compute`) for `frame`.
    pub fn submit(
        &mut self,
        slot: usize,
        value: u64,
        wait_graphics: Option<u64>,
        time_s: f64,
        timing: Option<(&mut Profiler, &Frame)>,
    ) -> GpuResult<()> {
        let dt_s = self
            .last_time_s
            .map(|t| (time_s - t).max(0.0) as f32)
            .unwrap_or(0.0);
        self.last_time_s = Some(time_s);
        let n = self.settings.fft_size as u32;
        let groups = n.div_ceil(8);
        let layers = self.cascades.len() as u32;
        let init: Vec<&Image> = if self.initialized {
            Vec::new()
        } else {
            self.displacement.iter().chain(&self.normals).collect()
        };
        self.initialized = true;
        // The kernel that writes the slot's images reads the previous frame's normals (foam
        // decays and is advected from there). The graphics queue samples the images through the
        // compute timeline and declares nothing (`gpu::track`).
        let previous = &self.normals[(slot + FRAMES_IN_FLIGHT - 1) % FRAMES_IN_FLIGHT];
        let images: [(&dyn Tracked, Use); 3] = [
            (previous, Use::ComputeRead),
            (&self.displacement[slot], Use::ComputeWrite),
            (&self.normals[slot], Use::ComputeWrite),
        ];
        match &mut self.model {
            Model::Fft {
                h0,
                omega_steps,
                fft,
                evolve,
                assemble,
                evolve_set,
                assemble_sets,
            } => {
                let evolve_params = EvolveParams {
                    patch_m: patch_sizes(&self.cascades),
                    ticks: time_ticks(time_s),
                    n,
                };
                let assemble_params = AssembleParams {
                    choppiness: self.settings.choppiness as f32,
                    dt_s,
                    foam_threshold: FOAM_THRESHOLD,
                    foam_decay_s: FOAM_DECAY_S,
                    foam_gain: FOAM_GAIN,
                    n,
                };
                let (h0, omega_steps) = (&*h0, &**omega_steps);
                let (fft, evolve, assemble) = (&*fft, &*evolve, &*assemble);
                let (evolve_set, assemble_set) = (*evolve_set, assemble_sets[slot]);
                self.queue.submit(slot, value, wait_graphics, |rec| {
                    let mut timer = timing;
                    if let Some((profiler, frame)) = timer.as_mut() {
                        profiler.begin_frame(rec, frame)?;
                    }
                    if !init.is_empty() {
                        record_images_init(rec, &init);
                    }
                    scope(&mut timer, rec, "ocean evolve", || {
                        // h(k, t) from h0 into the FFT data (the previous frame's FFT and
                        // assemble used it).
                        rec.uses(&[
                            (h0, Use::ComputeRead),
                            (omega_steps, Use::ComputeRead),
                            (&fft.data, Use::ComputeWrite),
                        ]);
                        rec.bind_pipeline(&evolve.pipeline);
                        rec.bind_sets(&evolve.pipeline, &evolve.layout, &[evolve_set]);
                        rec.push_constants(&evolve.layout, &evolve_params);
                        rec.dispatch(groups, groups, layers);
                    });
                    scope(&mut timer, rec, "ocean fft", || {
                        fft.record(rec, Direction::Inverse)
                    });
                    scope(&mut timer, rec, "ocean assemble", || {
                        let mut uses = images.to_vec();
                        uses.push((&fft.data, Use::ComputeRead));
                        rec.uses(&uses);
                        rec.bind_pipeline(&assemble.pipeline);
                        rec.bind_sets(&assemble.pipeline, &assemble.layout, &[assemble_set]);
                        rec.push_constants(&assemble.layout, &assemble_params);
                        rec.dispatch(groups, groups, layers);
                    });
                    if let Some((profiler, _)) = timer.as_mut() {
                        profiler.end_frame(rec);
                    }
                    Ok(())
                })
            }
            Model::Gerstner {
                waves,
                buffers,
                kernel,
                sets,
            } => {
                let window = self.settings.patch_size_m;
                let origin = self.origin_m;
                let gpu_waves: Vec<GpuWave> = waves
                    .iter()
                    .map(|w| {
                        let k = (w.kx * w.kx + w.kz * w.kz).sqrt();
                        let omega = (G_SEED * k).sqrt();
                        // θ at the origin, reduced in f64 so the shader's float phase stays exact.
                        let theta0 =
                            (w.kx * origin[0] + w.kz * origin[1] - omega * time_s - w.phase)
                                .rem_euclid(2.0 * std::f64::consts::PI);
                        GpuWave {
                            wave: [w.kx as f32, w.kz as f32, w.amplitude as f32, theta0 as f32],
                            extra: [w.steepness as f32, omega as f32, k as f32, 0.0],
                        }
                    })
                    .collect();
                // The slot's previous compute work (two frames ago) must be done before the
                // host rewrites its wave buffer.
                self.queue.wait_for_slot(value)?;
                buffers[slot].write(bytemuck::cast_slice(&gpu_waves));
                let params = GerstnerParams {
                    window_m: window as f32,
                    dt_s,
                    foam_threshold: FOAM_THRESHOLD,
                    foam_decay_s: FOAM_DECAY_S,
                    foam_gain: FOAM_GAIN,
                    n,
                    count: waves.len() as u32,
                };
                let (kernel, set) = (&*kernel, sets[slot]);
                self.queue.submit(slot, value, wait_graphics, |rec| {
                    let mut timer = timing;
                    if let Some((profiler, frame)) = timer.as_mut() {
                        profiler.begin_frame(rec, frame)?;
                    }
                    if !init.is_empty() {
                        record_images_init(rec, &init);
                    }
                    scope(&mut timer, rec, "ocean gerstner", || {
                        rec.uses(&images);
                        rec.bind_pipeline(&kernel.pipeline);
                        rec.bind_sets(&kernel.pipeline, &kernel.layout, &[set]);
                        rec.push_constants(&kernel.layout, &params);
                        rec.dispatch(groups, groups, 1);
                    });
                    if let Some((profiler, _)) = timer.as_mut() {
                        profiler.end_frame(rec);
                    }
                    Ok(())
                })
            }
        }
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

    /// The Gerstner waves (Gerstner mode).
    pub fn gerstner_waves(&self) -> Option<&[Wave]> {
        match &self.model {
            Model::Fft { .. } => None,
            Model::Gerstner { waves, .. } => Some(waves),
        }
    }
}
