//! Height queries on the GPU (shaders/ocean/query.comp): up to [`MAX_QUERIES`] world points a
//! frame answered from the images the water draws (the surface's height, displacement and
//! normal above each point, and how fast it rises there), read by the CPU a frame or two later
//! without a stall.
//!
//! How a query travels:
//! 1. record: `Simulation::ask` keeps the points; `Simulation::submit` of frame f writes them
//!    into slot f % 2's host-visible point buffer and records the query pass after the wave
//!    model's, in the same compute submission, ending in a barrier that makes the answers
//!    available to the host (`Use::HostRead`);
//! 2. submit and signal: the submission signals the compute timeline with f's value;
//! 3. read N frames later: `Simulation::answers` asks the timeline's counter (no wait) and reads
//!    the newest slot whose value it passed. Slot f % 2 is rewritten by frame f + 2, whose
//!    submission first waits for frame f's compute work (`ComputeQueue::wait_for_slot`): its
//!    answers are read then at the latest, so the latency is at most the frames in flight.
//!
//! The answers are for the frame's simulation time; `Answers::height_at` carries a height to a
//! later time with the queried vertical velocity (the latency's compensation).

use std::sync::Arc;

use ash::vk;

use super::{Kernel, ModelFrame, Simulation, FRAMES_IN_FLIGHT};
use crate::gpu::compute::ComputeQueue;
use crate::gpu::{
    Bind, Bindings, BoundSet, Buffer, Context, GpuResult, Image, MemoryLocation, Order, Recorder,
    Use,
};
use crate::ocean::foam::FoamScene;
use crate::pass_names as names;
use crate::shaders;

/// Most points one frame may ask about.
pub const MAX_QUERIES: usize = 4096;
/// Threads per workgroup of query.comp.
const GROUP: usize = 64;

/// The surface above one asked point.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct SurfaceAnswer {
    /// The displacement (λD_x, h, λD_z) of the rest point that lands on the asked point (m):
    /// its y is the height of the surface there.
    pub displacement: [f64; 3],
    /// ∂h/∂t at the asked point (m/s): the height in the previous frame's images, differenced.
    pub vertical_velocity_m_s: f64,
    /// Unit normal of the surface there.
    pub normal: [f64; 3],
    /// How far the inverted rest point's image lies from the asked point (m): over a
    /// millimetre only where the surface folds over (J < 0).
    pub residual_m: f64,
}

impl SurfaceAnswer {
    /// Height of the surface above the point (m).
    pub fn height_m(&self) -> f64 {
        self.displacement[1]
    }
}

/// One frame's answers.
#[derive(Clone, Debug, Default)]
pub struct Answers {
    /// The timeline value of the frame that asked (frames count up by one).
    pub value: u64,
    /// The simulation time they are for (s).
    pub time_s: f64,
    /// The points asked (world x, z in m), in order.
    pub points: Vec<[f64; 2]>,
    /// The answer to each.
    pub surface: Vec<SurfaceAnswer>,
}

impl Answers {
    /// The height above point `i` carried to time `t_s` with its vertical velocity (first
    /// order: the latency is a frame or two, a few hundredths of a wave period).
    pub fn height_at(&self, i: usize, t_s: f64) -> f64 {
        let a = &self.surface[i];
        a.height_m() + a.vertical_velocity_m_s * (t_s - self.time_s)
    }
}

/// query.comp's uniform block (std140).
#[repr(C)]
#[derive(Clone, Copy, Default, bytemuck::Pod, bytemuck::Zeroable)]
struct Placement {
    base: [[f32; 4]; 4],
    texels_per_m: [f32; 4],
    place: [f32; 4],
    terrain: [f32; 4],
    shore: [f32; 4],
    open_sea: [f32; 4],
    /// The anchor's texel coordinate in this slot's wake image (xy) and the previous slot's
    /// (zw).
    wake_base: [f32; 4],
    /// x: the wake's texels per metre; y: 1 with a wake (`--boat`).
    wake: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct Params {
    count: u32,
    cascades: u32,
    periodic: u32,
    shore: u32,
    /// 1/Δt to the previous slot (0: none).
    rate: f32,
}

impl Simulation {
    /// Asks for the surface above `points` (world x, z in m; at most [`MAX_QUERIES`]) with the
    /// next submission, whose answers [`Simulation::answers`] returns a frame or two later
    /// (`queries.rs`). The query pass is made at the first call.
    pub fn ask(&mut self, ctx: &Arc<Context>, points: &[[f64; 2]]) -> anyhow::Result<()> {
        anyhow::ensure!(
            points.len() <= MAX_QUERIES,
            "{} height queries in one frame: at most {MAX_QUERIES}",
            points.len()
        );
        if self.queries.is_none() {
            self.queries = Some(HeightQueries::new(
                ctx,
                &self.displacement,
                &self.normals,
                &self.wake.images,
            )?);
        }
        self.queries.as_mut().expect("made above").ask(points);
        Ok(())
    }

    /// The newest height queries' answers the compute timeline says are done, without
    /// waiting (`None` before the first arrive).
    pub fn answers(&mut self) -> GpuResult<Option<&Answers>> {
        match &mut self.queries {
            Some(q) => q.answers(&self.queue),
            None => Ok(None),
        }
    }

    /// Notes where the slots written by this submission (`warmup`'s steps, then `slot` at
    /// `time_s`) lie, and sets up the frame's queries (`None`: none asked). The slot's previous
    /// compute work is done.
    pub(super) fn prepare_queries(
        &mut self,
        warmup: &[ModelFrame],
        slot: usize,
        value: u64,
        time_s: f64,
        scene: &FoamScene,
    ) -> GpuResult<Option<QueryDispatch>> {
        for step in warmup {
            self.slot_places[step.slot] = Some(SlotPlace {
                origin_m: step.origin_m,
                time_s: step.time_s,
            });
        }
        let here = SlotPlace {
            origin_m: self.origin_m,
            time_s,
        };
        self.slot_places[slot] = Some(here);
        let periodic = !self.is_window();
        let n = self.settings.fft_size;
        let steps_m: Vec<f64> = self.cascades.iter().map(|c| c.patch_m / n as f64).collect();
        let previous = (slot + FRAMES_IN_FLIGHT - 1) % FRAMES_IN_FLIGHT;
        let before = self.slot_places[previous];
        let wake = self.wake.place_of().map(|(_, spacing)| {
            let here = self.wake.slot_origin(slot);
            (here, self.wake.slot_origin(previous), spacing)
        });
        let Some(q) = &mut self.queries else {
            return Ok(None);
        };
        q.prepare(
            &self.queue,
            &QueryFrame {
                slot,
                value,
                time_s,
                here,
                before,
                steps_m: &steps_m,
                n,
                periodic,
                scene,
                wake,
            },
        )
    }
}

/// A frame's query pass, as `HeightQueries::prepare` sets it up.
pub(super) struct QueryDispatch {
    slot: usize,
    params: Params,
}

/// What a slot's submission asked.
struct Pending {
    value: u64,
    time_s: f64,
    points: Vec<[f64; 2]>,
}

/// Where a slot's images lie: the world position of texel (0, 0) and the time they are for.
#[derive(Clone, Copy, Debug)]
pub(super) struct SlotPlace {
    pub origin_m: [f64; 2],
    pub time_s: f64,
}

/// One frame's query as the simulation records it.
struct QueryFrame<'a> {
    pub slot: usize,
    pub value: u64,
    pub time_s: f64,
    /// Where this slot's images and the previous slot's lie (`None`: not written yet).
    pub here: SlotPlace,
    pub before: Option<SlotPlace>,
    /// Node spacing of each cascade (m) and the images' side.
    pub steps_m: &'a [f64],
    pub n: usize,
    pub periodic: bool,
    pub scene: &'a FoamScene,
    /// With a wake: its grid's texel (0, 0) for this slot and the previous one, its texel (m).
    pub wake: Option<([f64; 2], [f64; 2], f64)>,
}

/// The mean water level (m): render::uniforms::WATER_LEVEL_M, which the water draws at.
const WATER_LEVEL_M: f32 = 0.0;

pub(super) struct HeightQueries {
    kernel: Kernel,
    /// Per slot: the uniform block, the points (relative to the anchor) and the answers.
    placement: Vec<Buffer>,
    points: Vec<Buffer>,
    answers: Vec<Buffer>,
    sets: Vec<BoundSet>,
    pending: Vec<Option<Pending>>,
    /// The points the next submission asks about.
    asked: Vec<[f64; 2]>,
    newest: Option<Answers>,
}

impl HeightQueries {
    /// The pass over the per-slot images `displacement`, `normals` and `wake`.
    pub(super) fn new(
        ctx: &Arc<Context>,
        displacement: &[Image],
        normals: &[Image],
        wake: &[Image],
    ) -> GpuResult<HeightQueries> {
        let (uniform, storage, image) = (
            vk::DescriptorType::UNIFORM_BUFFER,
            vk::DescriptorType::STORAGE_BUFFER,
            vk::DescriptorType::STORAGE_IMAGE,
        );
        let kernel = Kernel::new(
            ctx,
            names::OCEAN_QUERIES,
            shaders::OCEAN_QUERY_COMP,
            &[uniform, storage, storage, image, image, image, image, image],
            std::mem::size_of::<Params>(),
        )?;
        let buffer = |name: String, size: usize, usage, location| {
            Buffer::new(ctx, &name, size as u64, usage, location)
        };
        let (mut placement, mut points, mut answers) = (Vec::new(), Vec::new(), Vec::new());
        for slot in 0..FRAMES_IN_FLIGHT {
            placement.push(buffer(
                format!("height query placement slot {slot}"),
                std::mem::size_of::<Placement>(),
                vk::BufferUsageFlags::UNIFORM_BUFFER,
                MemoryLocation::CpuToGpu,
            )?);
            points.push(buffer(
                format!("height query points slot {slot}"),
                MAX_QUERIES * 8,
                vk::BufferUsageFlags::STORAGE_BUFFER,
                MemoryLocation::CpuToGpu,
            )?);
            answers.push(buffer(
                format!("height query answers slot {slot}"),
                MAX_QUERIES * 32,
                vk::BufferUsageFlags::STORAGE_BUFFER,
                MemoryLocation::GpuToCpu,
            )?);
        }
        let t = Order::Tracked;
        let sets = (0..FRAMES_IN_FLIGHT)
            .map(|slot| {
                let previous = (slot + FRAMES_IN_FLIGHT - 1) % FRAMES_IN_FLIGHT;
                BoundSet::new(
                    ctx,
                    &kernel.set_layout,
                    &format!("{} set slot {slot}", names::OCEAN_QUERIES),
                    &[
                        (0, Bind::Uniform(&placement[slot])),
                        (1, Bind::Storage(&points[slot], Order::Host)),
                        (2, Bind::Storage(&answers[slot], t)),
                        (3, Bind::StorageImage(&displacement[slot], t)),
                        (4, Bind::StorageImage(&normals[slot], t)),
                        (5, Bind::StorageImage(&displacement[previous], t)),
                        (6, Bind::StorageImage(&wake[slot], t)),
                        (7, Bind::StorageImage(&wake[previous], t)),
                    ],
                )
            })
            .collect::<GpuResult<Vec<_>>>()?;
        Ok(HeightQueries {
            kernel,
            placement,
            points,
            answers,
            sets,
            pending: (0..FRAMES_IN_FLIGHT).map(|_| None).collect(),
            asked: Vec::new(),
            newest: None,
        })
    }

    /// The points the next submission asks about (world x, z in m).
    pub(super) fn ask(&mut self, points: &[[f64; 2]]) {
        assert!(points.len() <= MAX_QUERIES, "checked by Simulation::ask");
        self.asked = points.to_vec();
    }

    /// Reads slot `slot`'s answers if its submission is done and they are newer than the
    /// newest read.
    fn harvest(&mut self, queue: &ComputeQueue, slot: usize) -> GpuResult<()> {
        let Some(pending) = &self.pending[slot] else {
            return Ok(());
        };
        let len = pending.points.len() * 32;
        let Some(bytes) = queue.read_if_done(&self.answers[slot], pending.value, len)? else {
            return Ok(());
        };
        let pending = self.pending[slot].take().expect("checked above");
        if self
            .newest
            .as_ref()
            .is_some_and(|n| n.value > pending.value)
        {
            return Ok(());
        }
        let floats: &[f32] = bytemuck::cast_slice(&bytes);
        let surface = floats
            .chunks_exact(8)
            .map(|a| SurfaceAnswer {
                displacement: [a[0], a[1], a[2]].map(f64::from),
                vertical_velocity_m_s: f64::from(a[3]),
                normal: [a[4], a[5], a[6]].map(f64::from),
                residual_m: f64::from(a[7]),
            })
            .collect();
        self.newest = Some(Answers {
            value: pending.value,
            time_s: pending.time_s,
            points: pending.points,
            surface,
        });
        Ok(())
    }

    /// The newest answers the compute timeline says are done (no wait).
    pub(super) fn answers(&mut self, queue: &ComputeQueue) -> GpuResult<Option<&Answers>> {
        for slot in 0..FRAMES_IN_FLIGHT {
            self.harvest(queue, slot)?;
        }
        Ok(self.newest.as_ref())
    }

    /// Host work before frame `f` is recorded, once slot `f.slot`'s previous compute work is
    /// done: that work's answers are read, the new points and placement written. Returns the
    /// dispatch to record (`None`: nothing asked).
    fn prepare(
        &mut self,
        queue: &ComputeQueue,
        f: &QueryFrame,
    ) -> GpuResult<Option<QueryDispatch>> {
        self.harvest(queue, f.slot)?;
        if self.pending[f.slot].is_some() {
            // Frame values that skip (tests): the slot's last work may still run.
            queue.wait_for_last()?;
            self.harvest(queue, f.slot)?;
        }
        let count = self.asked.len();
        if count == 0 {
            return Ok(None);
        }
        // The anchor: a whole metre near the points, so their offsets keep fp32's precision.
        let anchor = self.asked[0].map(f64::floor);
        let relative: Vec<[f32; 2]> = self
            .asked
            .iter()
            .map(|p| [(p[0] - anchor[0]) as f32, (p[1] - anchor[1]) as f32])
            .collect();
        self.points[f.slot].write(bytemuck::cast_slice(&relative));
        let base = |place: &SlotPlace, step: f64| -> [f32; 2] {
            [0, 1].map(|i| {
                let u = (anchor[i] - place.origin_m[i]) / step;
                (if f.periodic {
                    u.rem_euclid(f.n as f64)
                } else {
                    u
                }) as f32
            })
        };
        let mut block = Placement::default();
        for (c, &step) in f.steps_m.iter().enumerate() {
            let here = base(&f.here, step);
            let before = f.before.map_or(here, |b| base(&b, step));
            block.base[c] = [here[0], here[1], before[0], before[1]];
            block.texels_per_m[c] = (1.0 / step) as f32;
        }
        let rate = f
            .before
            .map(|b| f.here.time_s - b.time_s)
            .filter(|dt| *dt > 0.0)
            .map_or(0.0, |dt| 1.0 / dt);
        block.place = [anchor[0] as f32, anchor[1] as f32, 0.0, WATER_LEVEL_M];
        block.terrain = f.scene.terrain;
        block.shore = f.scene.shore;
        block.open_sea = f.scene.open_sea;
        if let Some((here, before, spacing)) = f.wake {
            let at = |origin: [f64; 2]| [0, 1].map(|i| ((anchor[i] - origin[i]) / spacing) as f32);
            let (h, b) = (at(here), at(before));
            block.wake_base = [h[0], h[1], b[0], b[1]];
            block.wake = [(1.0 / spacing) as f32, 1.0, 0.0, 0.0];
        }
        self.placement[f.slot].write(bytemuck::bytes_of(&block));
        self.pending[f.slot] = Some(Pending {
            value: f.value,
            time_s: f.time_s,
            points: std::mem::take(&mut self.asked),
        });
        Ok(Some(QueryDispatch {
            slot: f.slot,
            params: Params {
                count: count as u32,
                cascades: f.steps_m.len() as u32,
                periodic: f.periodic as u32,
                // A scene without an island (tests' `FoamScene::default()`): no shore.
                shore: (f.scene.terrain[3] > 0.0 && f.scene.shore[0] > 0.0) as u32,
                rate: rate as f32,
            },
        }))
    }

    /// Records a dispatch `prepare` returned, after the wave model's passes: the answers end
    /// available to the host.
    pub(super) fn record(&self, rec: &Recorder, d: &QueryDispatch) {
        let b = Bindings {
            pipeline: &self.kernel.pipeline,
            sets: &[&self.sets[d.slot]],
        };
        rec.push_constants(&self.kernel.pipeline, &d.params);
        let groups = (d.params.count as usize).div_ceil(GROUP) as u32;
        rec.dispatch_with(&b, [groups, 1, 1]);
        rec.uses(&[(&self.answers[d.slot], Use::HostRead)]);
    }
}
