//! The spray (shaders/ocean/spray.comp; physics and constants in `ocean::spray`): after the
//! foam step, on the compute queue, puffs of spume drops are moved through the wind, landed
//! into the foam, and born where crests break, in per-slot particle buffers whose counts never
//! leave the GPU: the update is an indirect dispatch over the previous slot's count, the
//! renderer's spray pass an indirect draw of this slot's (`src/render/passes/spray.rs`).
//!
//! Sync: the particle and count buffers are shared by both queues (CONCURRENT where the
//! families differ) and tracked on the compute queue, like the simulation images. Frame f
//! writes slot f % 2 after the graphics timeline reached f − 1 (its previous reader, frame f −
//! 2, is done) and reads slot (f − 1) % 2, which graphics may be drawing at the same time (two
//! reads). Graphics draws slot f % 2 behind the compute timeline's wait for f, which names
//! DRAW_INDIRECT and VERTEX_SHADER (`simulation::graphics_wait_stages`).

use std::cell::Cell;
use std::sync::Arc;

use ash::vk;

use super::foam_sim::Wind;
use super::{scope, ModelFrame, SlotUniforms, Timer};
use crate::gpu::{
    Bind, Bindings, BoundSet, Buffer, Context, DescriptorSetLayout, GpuResult, Image,
    MemoryLocation, Order, Pipeline, PipelineLayout, Recorder, FRAMES_IN_FLIGHT,
};
use crate::ocean::foam::{self, MAX_LEVELS};
use crate::ocean::spray;
use crate::pass_names as names;
use crate::shaders;
use crate::shared::{SPRAY_CAPACITY, SPRAY_EMIT_GRID, SPRAY_GROUP};

/// Bytes of one particle (`Particle` in spray.comp: three vec4).
pub const PARTICLE_BYTES: u64 = 48;
/// Bytes of a slot's counts (`uint counts[16]`); the update's dispatch arguments at 0, the
/// live count at 12, the draw's arguments at [`DRAW_ARGS_OFFSET`], the puffs landed and born
/// in the frame at u32 indices 8 and 9.
pub const COUNTS_BYTES: u64 = 64;
pub const DRAW_ARGS_OFFSET: u64 = 16;
/// Where the live count lies in a slot's counts (u32 index).
pub const LIVE_INDEX: usize = 3;

/// spray.comp's uniform block (`SprayFrame`, std140).
#[repr(C)]
#[derive(Clone, Copy, Default, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuSprayFrame {
    base01: [f32; 4],
    base23: [f32; 4],
    per_m: [f32; 4],
    grid: [f32; 4],
    wind: [f32; 4],
    step: [f32; 4],
    launch: [f32; 4],
    drops: [f32; 4],
    water: [f32; 4],
    levels: [[f32; 4]; MAX_LEVELS],
}

/// spray.comp's push constants (`Counts`): what its loops run over.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Counts {
    n: u32,
    cascades: u32,
    levels: u32,
    /// Steps recorded so far (the emission's random seed).
    step: u32,
    dt_s: f32,
    /// The chance a fully breaking candidate emits in the step.
    chance: f32,
}

/// The kernels of spray.comp (its `MODE`), in the order a frame runs them.
#[derive(Clone, Copy)]
enum Mode {
    Reset = 0,
    Update = 1,
    Emit = 2,
    Finalize = 3,
}

/// The buffers the renderer draws from: per slot, the particles and their counts. A clone
/// shares them (`Buffer::share`).
pub struct SprayBuffers {
    pub particles: Vec<Buffer>,
    pub counts: Vec<Buffer>,
}

impl Clone for SprayBuffers {
    fn clone(&self) -> SprayBuffers {
        SprayBuffers {
            particles: self.particles.iter().map(Buffer::share).collect(),
            counts: self.counts.iter().map(Buffer::share).collect(),
        }
    }
}

impl std::fmt::Debug for SprayBuffers {
    fn fmt(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "SprayBuffers({} slots)", self.particles.len())
    }
}

pub(super) struct SpraySim {
    /// Kept alive with the sets and pipelines.
    _set_layout: DescriptorSetLayout,
    pipelines: [Pipeline; 4],
    /// Per slot: spray.comp's uniforms, written by the host.
    uniforms: SlotUniforms,
    buffers: SprayBuffers,
    /// Per slot: reads the previous slot's particles and counts, writes this slot's.
    sets: Vec<BoundSet>,
    wind: Wind,
    /// Steps recorded so far (the emission's random seed).
    steps: Cell<u32>,
}

/// Per slot: the particles and counts (both queues use them), and the uniforms.
fn slot_buffers(ctx: &Arc<Context>) -> GpuResult<(SprayBuffers, Vec<Buffer>)> {
    let mut buffers = SprayBuffers {
        particles: Vec::new(),
        counts: Vec::new(),
    };
    let mut uniforms = Vec::new();
    for slot in 0..FRAMES_IN_FLIGHT {
        buffers.particles.push(Buffer::shared(
            ctx,
            &format!("spray particles slot {slot}"),
            SPRAY_CAPACITY as u64 * PARTICLE_BYTES,
            // Read back by --dump.
            vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_SRC,
        )?);
        buffers.counts.push(Buffer::shared(
            ctx,
            &format!("spray counts slot {slot}"),
            COUNTS_BYTES,
            vk::BufferUsageFlags::STORAGE_BUFFER
                | vk::BufferUsageFlags::INDIRECT_BUFFER
                | vk::BufferUsageFlags::TRANSFER_SRC,
        )?);
        uniforms.push(Buffer::new(
            ctx,
            &format!("spray uniforms slot {slot}"),
            std::mem::size_of::<GpuSprayFrame>() as u64,
            vk::BufferUsageFlags::UNIFORM_BUFFER,
            MemoryLocation::CpuToGpu,
        )?);
    }
    Ok((buffers, uniforms))
}

impl SpraySim {
    /// The kernels, buffers and sets over `fields` (the inverse FFT's output) and the per-slot
    /// foam images `foam` (landing puffs add to them).
    pub(super) fn new(
        ctx: &Arc<Context>,
        fields: &Buffer,
        foam: &[Image],
        wind: Wind,
    ) -> GpuResult<SpraySim> {
        let (storage, uniform, image) = (
            vk::DescriptorType::STORAGE_BUFFER,
            vk::DescriptorType::UNIFORM_BUFFER,
            vk::DescriptorType::STORAGE_IMAGE,
        );
        let types = [storage, uniform, storage, storage, storage, storage, image];
        let entries: Vec<_> = types
            .iter()
            .enumerate()
            .map(|(i, &ty)| (i as u32, ty, vk::ShaderStageFlags::COMPUTE))
            .collect();
        let name = names::OCEAN_SPRAY;
        let set_layout = DescriptorSetLayout::new(ctx, &format!("{name} set layout"), &entries)?;
        let push = (
            vk::ShaderStageFlags::COMPUTE,
            std::mem::size_of::<Counts>() as u32,
        );
        let layout =
            PipelineLayout::new(ctx, &format!("{name} layout"), &[&set_layout], Some(push))?;
        let pipeline = |mode: Mode, what: &str| {
            let spirv = shaders::OCEAN_SPRAY_COMP;
            Pipeline::compute(
                ctx,
                &layout,
                &format!("{name} {what}"),
                spirv,
                &[mode as u32],
            )
        };
        let pipelines = [
            pipeline(Mode::Reset, "reset")?,
            pipeline(Mode::Update, "update")?,
            pipeline(Mode::Emit, "emit")?,
            pipeline(Mode::Finalize, "finalize")?,
        ];
        let (buffers, uniforms) = slot_buffers(ctx)?;
        let t = Order::Tracked;
        let sets = (0..FRAMES_IN_FLIGHT)
            .map(|slot| {
                let previous = (slot + FRAMES_IN_FLIGHT - 1) % FRAMES_IN_FLIGHT;
                BoundSet::new(
                    ctx,
                    &set_layout,
                    &format!("{name} set slot {slot}"),
                    &[
                        (0, Bind::Storage(fields, t)),
                        (1, Bind::Uniform(&uniforms[slot])),
                        (2, Bind::Storage(&buffers.particles[previous], t)),
                        (3, Bind::Storage(&buffers.particles[slot], t)),
                        (4, Bind::Storage(&buffers.counts[previous], t)),
                        (5, Bind::Storage(&buffers.counts[slot], t)),
                        (6, Bind::StorageImage(&foam[slot], t)),
                    ],
                )
            })
            .collect::<GpuResult<Vec<_>>>()?;
        Ok(SpraySim {
            _set_layout: set_layout,
            pipelines,
            uniforms: SlotUniforms::new(uniforms),
            buffers,
            sets,
            wind,
            steps: Cell::new(0),
        })
    }

    /// The particle and count buffers, for the renderer's spray pass.
    pub(super) fn buffers(&self) -> &SprayBuffers {
        &self.buffers
    }

    /// Writes frame `f`'s uniforms into its slot's buffer (into both the first time: the
    /// warm-up's steps use both), once the slot's previous compute work is done: the emission grid around the camera, reduced into each cascade's lattice
    /// in f64 here, so the kernel's f32 offsets stay small however far the camera goes.
    pub(super) fn prepare(&mut self, f: &ModelFrame) {
        let h = spray::EMIT_SPACING_M;
        let half = SPRAY_EMIT_GRID as f64 / 2.0;
        let corner = f.camera_xz.map(|c| ((c / h).floor() - half) * h);
        let n = f.n as f64;
        let lattice = |c: usize| {
            let l_c = f.patch_m[c] as f64;
            corner.map(|x| (x * n / l_c).rem_euclid(n) as f32)
        };
        let (b0, b1, b2, b3) = (lattice(0), lattice(1), lattice(2), lattice(3));
        let u10 = self.wind.u10;
        let air = spray::SEA_AIR;
        let mut levels = [[0.0; 4]; MAX_LEVELS];
        for (l, level) in levels.iter_mut().enumerate().take(f.foam.count) {
            let o = f.foam.origin_m[l];
            let texel = f.foam.texel_m(l);
            *level = [o[0] as f32, o[1] as f32, texel as f32, f.foam.size as f32];
        }
        let block = GpuSprayFrame {
            base01: [b0[0], b0[1], b1[0], b1[1]],
            base23: [b2[0], b2[1], b3[0], b3[1]],
            per_m: std::array::from_fn(|c| (n / f.patch_m[c] as f64) as f32),
            grid: [corner[0] as f32, corner[1] as f32, h as f32, 0.0],
            wind: [
                self.wind.dir[0] as f32,
                self.wind.dir[1] as f32,
                u10 as f32,
                spray::roughness_m(u10) as f32,
            ],
            step: [0.0, f.foam_threshold, foam::GAIN, f.choppiness],
            launch: [
                spray::LAUNCH_DOWNWIND_M_S as f32,
                spray::LAUNCH_UP_M_S[0] as f32,
                spray::LAUNCH_UP_M_S[1] as f32,
                spray::LANDING_FOAM as f32,
            ],
            drops: [
                spray::DROP_RADIUS_M[0] as f32,
                spray::DROP_RADIUS_M[1] as f32,
                air.density as f32,
                air.viscosity as f32,
            ],
            water: [spray::DROP_DENSITY as f32, spray::GRAVITY as f32, 0.0, 0.0],
            levels,
        };
        self.uniforms.write(f.slot, bytemuck::bytes_of(&block));
    }

    /// Records step `f`'s spray (after the foam step: landing puffs add to its field): a
    /// frame's, or one of the first frame's short warm-up steps.
    pub(super) fn record(&self, rec: &Recorder, timer: &mut Timer, f: &ModelFrame) {
        let previous = (f.slot + FRAMES_IN_FLIGHT - 1) % FRAMES_IN_FLIGHT;
        let step = self.steps.get();
        self.steps.set(step.wrapping_add(1));
        let h = spray::EMIT_SPACING_M;
        let chance = spray::EMIT_PER_M2_S * spray::intensity(self.wind.u10) * h * h;
        let dt_s = f.dt_s.min(spray::MAX_STEP_S);
        let counts = Counts {
            n: f.n,
            cascades: f.layers,
            levels: f.foam.count as u32,
            step,
            dt_s,
            chance: (chance * dt_s as f64) as f32,
        };
        let run = |mode: Mode, slot: usize, groups: u32| {
            let pipeline = &self.pipelines[mode as usize];
            rec.push_constants(pipeline, &counts);
            let b = Bindings {
                pipeline,
                sets: &[&self.sets[slot]],
            };
            rec.dispatch_with(&b, [groups, 1, 1]);
        };
        scope(timer, rec, names::OCEAN_SPRAY, || {
            if step == 0 {
                // No particles yet: the previous slot's counts say so (a dispatch of 0 groups).
                run(Mode::Reset, previous, 1);
                run(Mode::Finalize, previous, 1);
            }
            run(Mode::Reset, f.slot, 1);
            let pipeline = &self.pipelines[Mode::Update as usize];
            rec.push_constants(pipeline, &counts);
            let update = Bindings {
                pipeline,
                sets: &[&self.sets[f.slot]],
            };
            rec.dispatch_indirect(&update, &self.buffers.counts[previous], 0);
            // Below Beaufort 6 no crest makes spray: the emission is skipped.
            if spray::intensity(self.wind.u10) > 0.0 {
                let candidates = SPRAY_EMIT_GRID * SPRAY_EMIT_GRID;
                run(Mode::Emit, f.slot, candidates.div_ceil(SPRAY_GROUP));
            }
            run(Mode::Finalize, f.slot, 1);
        });
    }
}
