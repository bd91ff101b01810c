//! The wake on the compute queue (`--boat`; the model is `ocean::wake`): its state z = h + iφ
//! lives in a [`GpuFft`]'s data buffer as a spectrum between steps. A step: the exact rotation of
//! every mode and the grid's move (shaders/ocean/wake_spectrum.comp), the inverse FFT, the
//! boat's pressure and the absorbing edge in space (wake_space.comp), the forward FFT. The
//! frame's last step also writes the wake's height and slopes into the slot's wake image
//! (wake_output.comp) before that forward FFT, for the water and the height queries.

use std::sync::Arc;

use ash::vk;

use super::{scope, Kernel, Timer, FRAMES_IN_FLIGHT};
use crate::gpu::{Bind, Bindings, BoundSet, Context, GpuResult, Image, Order, Recorder};
use crate::ocean::fft::{Direction, GpuFft};
use crate::ocean::params::OceanSettings;
use crate::ocean::wake::{self, Boat};
use crate::pass_names as names;
use crate::shaders;

// Each step's output carries the foam of the image written before it, the previous slot's; the
// warm-up alternates between this slot and that one. With more than two slots in flight the
// steps would need to alternate over all of them.
const _: () = assert!(
    FRAMES_IN_FLIGHT == 2,
    "the wake alternates between two slots"
);

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SpectrumParams {
    shift: [i32; 2],
    dt: f32,
    dk: f32,
    depth: f32,
    scale: f32,
    n: u32,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct SpaceParams {
    boat: [f32; 2],
    course: [f32; 2],
    shift: [i32; 2],
    dt: f32,
    pressure: f32,
    sigma_length: f32,
    sigma_beam: f32,
    spacing: f32,
    sponge_rate: f32,
    sponge_texels: u32,
    n: u32,
    reset: u32,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct OutputParams {
    boat: [f32; 2],
    course: [f32; 2],
    shift: [i32; 2],
    spacing: f32,
    dt: f32,
    decay_s: f32,
    spread: f32,
    churn: f32,
    sigma_length: f32,
    sigma_beam: f32,
    n: u32,
}

/// A step's image: the slot it writes (the other slot's image, written before it, has the foam it
/// carries on), the time since then (s) and the grid's move since then (texels).
#[derive(Clone, Copy, Debug)]
pub(super) struct WakeOutput {
    pub slot: usize,
    pub dt_s: f64,
    pub shift: [i32; 2],
}

/// One step as recorded: its length, the grid's move before it (texels), the boat's place
/// (from the grid's texel (0, 0), m) and pressure, and the image it writes, if any.
#[derive(Clone, Copy, Debug)]
pub(super) struct WakeStep {
    pub dt_s: f64,
    pub shift: [i32; 2],
    pub boat_m: [f64; 2],
    /// The boat's pressure over its full (`Boat::strength`).
    pub strength: f64,
    pub output: Option<WakeOutput>,
}

/// The wake as the simulation holds it: the model on the GPU with `--boat`, where its grid lies,
/// and the per-slot images the water and the queries read.
pub struct Wake {
    sim: Option<WakeSim>,
    /// The grid's texel (0, 0) this frame (world x, z; m).
    origin_m: [f64; 2],
    /// The grid's texel (0, 0) and the time at the last submission.
    last: Option<([f64; 2], f64)>,
    /// Per slot: the grid's texel (0, 0) when its image was written.
    slot_origins: [Option<[f64; 2]>; FRAMES_IN_FLIGHT],
    /// Per slot: (h, ∂h/∂x, ∂h/∂z, foam) on the grid (a 1×1 image without a boat).
    pub images: Vec<Image>,
    /// The steps `plan` made last are a warm-up: the state is zeroed before them.
    reset: bool,
}

impl Wake {
    /// The images (made by `image(name, side)`) and, with `--boat`, the model.
    pub(super) fn new(
        ctx: &Arc<Context>,
        settings: &OceanSettings,
        mut image: impl FnMut(String, usize) -> GpuResult<Image>,
    ) -> anyhow::Result<Wake> {
        let side = if settings.boat.is_some() {
            wake::GRID_N
        } else {
            1
        };
        let images = (0..FRAMES_IN_FLIGHT)
            .map(|slot| image(format!("wake slot {slot}"), side))
            .collect::<GpuResult<Vec<_>>>()?;
        let sim = settings
            .boat
            .map(|[speed_m_s, heading_deg]| {
                let boat = Boat {
                    speed_m_s,
                    heading_deg,
                    anchor: [0.0; 2],
                    anchor_time_s: 0.0,
                };
                WakeSim::new(ctx, boat, settings.sea.depth_m, &images)
            })
            .transpose()?;
        Ok(Wake {
            sim,
            origin_m: [0.0; 2],
            last: None,
            slot_origins: [None; FRAMES_IN_FLIGHT],
            images,
            reset: false,
        })
    }

    /// Puts the grid in front of the camera for the next submission (`wake::grid_origin`): a
    /// camera at `camera_xz` whose unit view direction's horizontal part is `forward_xz`.
    pub fn place(&mut self, camera_xz: [f64; 2], forward_xz: [f64; 2]) {
        self.origin_m = wake::grid_origin(camera_xz, forward_xz);
    }

    /// The boat, once the first submission placed it (`None` without `--boat`).
    pub fn boat(&self) -> Option<&Boat> {
        self.sim
            .as_ref()
            .map(|s| &s.boat)
            .filter(|_| self.last.is_some())
    }

    /// The boat as placed, or before the first submission as a first submission at `t_s` with
    /// the grid where `place` last put it will place it (`None` without `--boat`).
    pub fn boat_for(&self, t_s: f64) -> Option<Boat> {
        let sim = self.sim.as_ref()?;
        if self.last.is_some() {
            return Some(sim.boat);
        }
        let half = wake::GRID_SIDE_M / 2.0;
        Some(Boat {
            anchor: [self.origin_m[0] + half, self.origin_m[1] + half],
            anchor_time_s: t_s,
            ..sim.boat
        })
    }

    /// Where slot `slot`'s image lies (its texel (0, 0)); this frame's place if not written yet.
    pub(super) fn slot_origin(&self, slot: usize) -> [f64; 2] {
        self.slot_origins[slot].unwrap_or(self.origin_m)
    }

    /// Where the grid lies this frame: its texel (0, 0) (world x, z; m) and its texel size (m);
    /// `None` without a boat.
    pub fn place_of(&self) -> Option<([f64; 2], f64)> {
        self.sim.as_ref().map(|_| (self.origin_m, wake::SPACING_M))
    }

    /// The steps of the submission at `time_s` into `slot`: the first (`first`) places the boat
    /// at the grid's centre and runs its way there (`Boat::warmup`); later ones cut the time
    /// since the last into steps (`wake::steps_since`). The last step writes the slot's image.
    /// None without a boat.
    pub(super) fn plan(&mut self, first: bool, slot: usize, time_s: f64) -> Vec<WakeStep> {
        let Some(sim) = &mut self.sim else {
            return Vec::new();
        };
        let origin = self.origin_m;
        // The run's first frame, and after a jump in time longer than the warm-up (a window
        // minimised for minutes, `--dt 1000`): the warm-up from still water again, the boat
        // anchored in front of the camera, rather than that many steps in one frame.
        let jumped = self
            .last
            .is_some_and(|(_, last_s)| time_s - last_s > sim.boat.warmup_span_s());
        let warmup = first || self.last.is_none() || jumped;
        self.reset = warmup;
        let (mut previous, steps) = match self.last {
            Some((previous, last_s)) if !warmup => (
                previous,
                wake::steps_since(last_s, time_s, origin, sim.boat.speed_m_s),
            ),
            _ => {
                let half = wake::GRID_SIDE_M / 2.0;
                sim.boat.anchor = [origin[0] + half, origin[1] + half];
                sim.boat.anchor_time_s = time_s;
                let steps = sim.boat.warmup(time_s, origin);
                (steps[0].origin, steps)
            }
        };
        let frame_shift =
            [0, 1].map(|k| ((origin[k] - previous[k]) / wake::SPACING_M).round() as i32);
        let frame_dt = self
            .last
            .map_or(0.0, |(_, last_s)| (time_s - last_s).max(0.0));
        self.last = Some((origin, time_s));
        self.slot_origins[slot] = Some(origin);
        let count = steps.len();
        let other = (slot + FRAMES_IN_FLIGHT - 1) % FRAMES_IN_FLIGHT;
        steps
            .iter()
            .enumerate()
            .map(|(i, s)| {
                let shift =
                    [0, 1].map(|k| ((s.origin[k] - previous[k]) / wake::SPACING_M).round() as i32);
                previous = s.origin;
                let mid = 0.5 * (s.from_s + s.to_s);
                let at = sim.boat.position(mid);
                let last = i + 1 == count;
                // The warm-up writes every step's image, slots alternating and ending in
                // `slot`, so the foam of the boat's way there is already on the water.
                let to = if (count - 1 - i) % 2 == 0 {
                    slot
                } else {
                    other
                };
                let output = if warmup {
                    Some(WakeOutput {
                        slot: to,
                        dt_s: s.to_s - s.from_s,
                        shift,
                    })
                } else {
                    last.then_some(WakeOutput {
                        slot,
                        dt_s: frame_dt,
                        shift: frame_shift,
                    })
                };
                WakeStep {
                    dt_s: s.to_s - s.from_s,
                    shift,
                    boat_m: [at[0] - s.origin[0], at[1] - s.origin[1]],
                    strength: sim.boat.strength(mid),
                    output,
                }
            })
            .collect()
    }

    /// Records `steps` (`plan`), zeroing the state first when they are a warm-up.
    pub(super) fn record(&self, rec: &Recorder, timer: &mut Timer, steps: &[WakeStep]) {
        if let Some(sim) = &self.sim {
            sim.record(rec, timer, steps, self.reset);
        }
    }
}

pub(super) struct WakeSim {
    pub boat: Boat,
    depth_m: Option<f64>,
    fft: GpuFft,
    spectrum: Kernel,
    space: Kernel,
    output: Kernel,
    spectrum_set: BoundSet,
    space_set: BoundSet,
    /// Per slot: the state into that slot's wake image.
    output_sets: Vec<BoundSet>,
}

impl WakeSim {
    /// The kernels, the FFT plan and the sets writing the per-slot images `images`.
    pub(super) fn new(
        ctx: &Arc<Context>,
        boat: Boat,
        depth_m: Option<f64>,
        images: &[Image],
    ) -> anyhow::Result<WakeSim> {
        let fft = GpuFft::new(ctx, wake::GRID_N, 1)?;
        let storage = vk::DescriptorType::STORAGE_BUFFER;
        let image = vk::DescriptorType::STORAGE_IMAGE;
        let spectrum = Kernel::new(
            ctx,
            names::OCEAN_WAKE,
            shaders::OCEAN_WAKE_SPECTRUM_COMP,
            &[storage],
            std::mem::size_of::<SpectrumParams>(),
        )?;
        let space = Kernel::new(
            ctx,
            "wake space",
            shaders::OCEAN_WAKE_SPACE_COMP,
            &[storage],
            std::mem::size_of::<SpaceParams>(),
        )?;
        let output = Kernel::new(
            ctx,
            "wake output",
            shaders::OCEAN_WAKE_OUTPUT_COMP,
            &[storage, image, image],
            std::mem::size_of::<OutputParams>(),
        )?;
        let t = Order::Tracked;
        let state = |kernel: &Kernel, name: &str| {
            BoundSet::new(
                ctx,
                &kernel.set_layout,
                name,
                &[(0, Bind::Storage(&fft.data, t))],
            )
        };
        let spectrum_set = state(&spectrum, "wake spectrum set")?;
        let space_set = state(&space, "wake space set")?;
        let output_sets = images
            .iter()
            .enumerate()
            .map(|(slot, img)| {
                BoundSet::new(
                    ctx,
                    &output.set_layout,
                    &format!("wake output set slot {slot}"),
                    &[
                        (0, Bind::Storage(&fft.data, t)),
                        (1, Bind::StorageImage(img, t)),
                        (
                            2,
                            Bind::StorageImage(
                                &images[(slot + images.len() - 1) % images.len()],
                                t,
                            ),
                        ),
                    ],
                )
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(WakeSim {
            boat,
            depth_m,
            fft,
            spectrum,
            space,
            output,
            spectrum_set,
            space_set,
            output_sets,
        })
    }

    fn space_params(&self, step: &WakeStep, reset: bool) -> SpaceParams {
        let u = self.boat.course();
        SpaceParams {
            boat: step.boat_m.map(|v| v as f32),
            course: u.map(|v| v as f32),
            shift: step.shift,
            dt: step.dt_s as f32,
            pressure: (step.strength * crate::ocean::spectrum::G * wake::DRAFT_M) as f32,
            sigma_length: wake::HULL_SIGMA_M[0] as f32,
            sigma_beam: wake::HULL_SIGMA_M[1] as f32,
            spacing: wake::SPACING_M as f32,
            sponge_rate: wake::SPONGE_RATE_PER_S as f32,
            sponge_texels: wake::SPONGE_TEXELS,
            n: wake::GRID_N as u32,
            reset: u32::from(reset),
        }
    }

    /// Records `steps`, zeroing the state first when `reset` (the run's first submission).
    pub(super) fn record(
        &self,
        rec: &Recorder,
        timer: &mut Timer,
        steps: &[WakeStep],
        reset: bool,
    ) {
        let n = wake::GRID_N as u32;
        let groups = [n.div_ceil(8), n.div_ceil(8), 1];
        let dispatch = |kernel: &Kernel, set: &BoundSet| {
            let b = Bindings {
                pipeline: &kernel.pipeline,
                sets: &[set],
            };
            rec.dispatch_with(&b, groups);
        };
        scope(timer, rec, names::OCEAN_WAKE, || {
            if reset {
                let zero = WakeStep {
                    dt_s: 0.0,
                    shift: [0, 0],
                    boat_m: [0.0; 2],
                    strength: 0.0,
                    output: None,
                };
                rec.push_constants(&self.space.pipeline, &self.space_params(&zero, true));
                dispatch(&self.space, &self.space_set);
            }
            for step in steps {
                let params = SpectrumParams {
                    shift: step.shift,
                    dt: step.dt_s as f32,
                    dk: (2.0 * std::f64::consts::PI / wake::GRID_SIDE_M) as f32,
                    depth: self.depth_m.unwrap_or(0.0) as f32,
                    scale: 1.0 / (n * n) as f32,
                    n,
                };
                rec.push_constants(&self.spectrum.pipeline, &params);
                dispatch(&self.spectrum, &self.spectrum_set);
                self.fft.record(rec, Direction::Inverse);
                rec.push_constants(&self.space.pipeline, &self.space_params(step, false));
                dispatch(&self.space, &self.space_set);
                if let Some(out) = step.output {
                    let params = OutputParams {
                        boat: step.boat_m.map(|v| v as f32),
                        course: self.boat.course().map(|v| v as f32),
                        shift: out.shift,
                        spacing: wake::SPACING_M as f32,
                        dt: out.dt_s as f32,
                        decay_s: wake::FOAM_DECAY_S as f32,
                        // An explicit step is stable up to a quarter (a long frame spreads
                        // less than it should, never unstably).
                        spread: (wake::FOAM_SPREAD_M2_S * out.dt_s / wake::SPACING_M.powi(2))
                            .min(0.25) as f32,
                        churn: (step.strength * wake::churn(self.boat.speed_m_s)) as f32,
                        sigma_length: wake::HULL_SIGMA_M[0] as f32,
                        sigma_beam: wake::HULL_SIGMA_M[1] as f32,
                        n,
                    };
                    rec.push_constants(&self.output.pipeline, &params);
                    dispatch(&self.output, &self.output_sets[out.slot]);
                }
                self.fft.record(rec, Direction::Forward);
            }
        });
    }
}
