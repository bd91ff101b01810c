//! The foam near the camera (shaders/ocean/foam.comp, `foam::FoamLevels`): after the FFT
//! model's assemble, a clipmap of world-space levels at rest positions, fine near the camera
//! (0.25 m a texel), where the whitecaps form from the whole surface's Jacobian, drift
//! downwind, fade, and leave residual foam that Langmuir circulation gathers into windrows.
//! The lattice's foam (assemble.comp, layer 0 of the normal images) stays the far field and
//! what `--stats` counts.

use std::sync::Arc;

use ash::vk;

use super::{scope, Kernel, ModelFrame, SlotUniforms, Timer};
use crate::gpu::{
    Bind, Bindings, BoundSet, Buffer, Context, Image, MemoryLocation, Order, Recorder,
};
use crate::ocean::foam::{self, MAX_LEVELS};
use crate::ocean::shore;
use crate::pass_names as names;
use crate::shaders;
use crate::shared::FOAM_WINDROW_PERIOD;

/// Format of the foam images: (whitecap foam A, residual foam S, 0, 0). RGBA16F is a storage
/// format every Vulkan device has, and filters linearly.
pub const FOAM_FORMAT: vk::Format = vk::Format::R16G16B16A16_SFLOAT;

/// One level as foam.comp reads it (`Level`, std140).
#[repr(C)]
#[derive(Clone, Copy, Default, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuLevel {
    base: [[f32; 4]; 2],
    steps: [f32; 4],
    previous: [f32; 4],
    place: [f32; 4],
    anchor: [f32; 4],
}

/// foam.comp's uniform block: the levels, then the scene (`FoamScene`'s fields in order).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuLevels {
    levels: [GpuLevel; MAX_LEVELS],
    scene: [[f32; 4]; 7],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FoamParams {
    wind: [f32; 2],
    drift_m_s: f32,
    converge_m_s: f32,
    windrow_m: f32,
    dt_s: f32,
    threshold: f32,
    gain: f32,
    decay_s: f32,
    residual_decay_s: f32,
    residual: f32,
    spread_m2_s: f32,
    choppiness: f32,
    n: u32,
    cascades: u32,
    size: u32,
    levels: u32,
    jet_m_s: f32,
    step: u32,
    surf_clock: f32,
}

/// The wind a foam step needs: its unit direction (x, z) and speed U10 (m/s).
#[derive(Clone, Copy, Debug)]
pub(super) struct Wind {
    pub dir: [f64; 2],
    pub u10: f64,
}

pub(super) struct FoamSim {
    kernel: Kernel,
    /// Per slot: the levels' placement, written by the host.
    buffers: SlotUniforms,
    /// Per slot: reads the cascades' derivatives and the other slot's foam, writes this slot's.
    sets: Vec<BoundSet>,
    wind: Wind,
    /// Steps recorded so far (the spreading alternates its diagonal with them).
    steps: std::cell::Cell<u32>,
}

impl FoamSim {
    /// The kernel and its sets over `derivatives` (the cascades' derivatives, from assemble)
    /// and the per-slot foam images `foam`.
    pub(super) fn new(
        ctx: &Arc<Context>,
        derivatives: &Image,
        foam: &[Image],
        wind: Wind,
    ) -> anyhow::Result<FoamSim> {
        let (uniform, image) = (
            vk::DescriptorType::UNIFORM_BUFFER,
            vk::DescriptorType::STORAGE_IMAGE,
        );
        let kernel = Kernel::new(
            ctx,
            names::OCEAN_FOAM,
            shaders::OCEAN_FOAM_COMP,
            &[image, uniform, image, image],
            std::mem::size_of::<FoamParams>(),
        )?;
        let slots = foam.len();
        let buffers = (0..slots)
            .map(|slot| {
                Buffer::new(
                    ctx,
                    &format!("foam levels slot {slot}"),
                    std::mem::size_of::<GpuLevels>() as u64,
                    vk::BufferUsageFlags::UNIFORM_BUFFER,
                    MemoryLocation::CpuToGpu,
                )
            })
            .collect::<Result<Vec<_>, _>>()?;
        let t = Order::Tracked;
        let sets = (0..slots)
            .map(|slot| {
                let previous = (slot + slots - 1) % slots;
                BoundSet::new(
                    ctx,
                    &kernel.set_layout,
                    &format!("{} set slot {slot}", names::OCEAN_FOAM),
                    &[
                        (0, Bind::StorageImage(derivatives, t)),
                        (1, Bind::Uniform(&buffers[slot])),
                        (2, Bind::StorageImage(&foam[slot], t)),
                        (3, Bind::StorageImage(&foam[previous], t)),
                    ],
                )
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(FoamSim {
            kernel,
            buffers: SlotUniforms::new(buffers),
            sets,
            wind,
            steps: std::cell::Cell::new(0),
        })
    }

    /// Writes the frame's placement into its slot's buffer (into every slot's the first time),
    /// once the slot's previous compute work is done.
    pub(super) fn prepare(&mut self, f: &ModelFrame) {
        let sc = &f.scene;
        let o = sc.objects;
        let block = GpuLevels {
            levels: gpu_levels(f, self.wind.dir),
            scene: [sc.terrain, sc.shore, sc.open_sea, o[0], o[1], o[2], o[3]],
        };
        self.buffers.write(f.slot, bytemuck::bytes_of(&block));
    }

    /// Records the foam step of frame `f` (after assemble: it reads the derivatives assemble
    /// wrote).
    pub(super) fn record(&self, rec: &Recorder, timer: &mut Timer, f: &ModelFrame) {
        let levels = f.foam.count as u32;
        if levels == 0 {
            return;
        }
        let step = self.steps.get();
        self.steps.set(step.wrapping_add(1));
        let lateral = foam::windrow_velocity(self.wind.u10);
        let params = FoamParams {
            wind: self.wind.dir.map(|v| v as f32),
            drift_m_s: (foam::DRIFT_SHARE * self.wind.u10) as f32,
            converge_m_s: lateral as f32,
            windrow_m: foam::WINDROW_SPACING_M as f32,
            dt_s: f.dt_s,
            threshold: f.foam_threshold,
            gain: foam::GAIN,
            decay_s: foam::DECAY_S,
            residual_decay_s: foam::RESIDUAL_DECAY_S,
            residual: foam::RESIDUAL_SHARE,
            spread_m2_s: foam::SPREAD_M2_S,
            choppiness: f.choppiness,
            n: f.n,
            cascades: f.layers,
            size: f.foam.size,
            levels,
            jet_m_s: (foam::WINDROW_JET_SHARE * lateral) as f32,
            step,
            // The step's own time: each warm-up step's bores are where they were then.
            surf_clock: shore::surf_clock(f.time_s, f64::from(f.scene.shore[1])),
        };
        let kernel = &self.kernel;
        scope(timer, rec, names::OCEAN_FOAM, || {
            rec.push_constants(&kernel.pipeline, &params);
            let b = Bindings {
                pipeline: &kernel.pipeline,
                sets: &[&self.sets[f.slot]],
            };
            let groups = f.foam.size.div_ceil(8);
            rec.dispatch_with(&b, [groups, groups, levels]);
        });
    }
}

/// Each level's placement for foam.comp: positions reduced in f64 on the CPU (the cascades'
/// lattice mod N, the windrows' pattern mod its period), offsets to the previous frame's
/// levels in their texels.
fn gpu_levels(f: &ModelFrame, wind: [f64; 2]) -> [GpuLevel; MAX_LEVELS] {
    let n = f.n as f64;
    let period = foam::WINDROW_SPACING_M * FOAM_WINDROW_PERIOD as f64;
    let across = [-wind[1], wind[0]];
    let mut out = [GpuLevel::default(); MAX_LEVELS];
    for (l, level) in out.iter_mut().enumerate().take(f.foam.count) {
        let h = f.foam.texel_m(l);
        // Texel (0, 0)'s centre.
        let centre = f.foam.origin_m[l].map(|o| o + 0.5 * h);
        let lattice = |c: usize| {
            let l_c = f.patch_m[c] as f64;
            centre.map(|x| ((x * n / l_c).rem_euclid(n)) as f32)
        };
        let (b0, b1, b2, b3) = (lattice(0), lattice(1), lattice(2), lattice(3));
        level.base = [[b0[0], b0[1], b1[0], b1[1]], [b2[0], b2[1], b3[0], b3[1]]];
        level.steps = std::array::from_fn(|c| (h * n / f.patch_m[c] as f64) as f32);
        let in_previous = |m: usize| {
            let hm = f.previous_foam.texel_m(m);
            let o = f.previous_foam.origin_m[m];
            [0, 1].map(|i| ((centre[i] - o[i]) / hm - 0.5) as f32)
        };
        let here = in_previous(l);
        let coarser = if l + 1 < f.foam.count {
            in_previous(l + 1)
        } else {
            [0.0; 2]
        };
        level.previous = [here[0], here[1], coarser[0], coarser[1]];
        let dot = |a: [f64; 2]| centre[0] * a[0] + centre[1] * a[1];
        level.place = [
            dot(wind).rem_euclid(period) as f32,
            dot(across).rem_euclid(period) as f32,
            h as f32,
            (1.0 / foam::LEVEL_RATIO) as f32,
        ];
        level.anchor = [centre[0] as f32, centre[1] as f32, 0.0, 0.0];
    }
    out
}
