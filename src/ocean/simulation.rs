//! The ocean on the compute queue: a wave model (`fft_model.rs`: h0 uploaded once, then per
//! frame evolve → inverse FFT → assemble; or `gerstner_model.rs`: a sum of Gerstner waves)
//! writes the displacement and normal images of the frame's slot (slot = frame % 2, one array
//! layer per cascade).
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

mod fft_model;
mod foam_sim;
mod gerstner_model;
mod kernel;
mod queries;
mod readback;
mod slope_mips;
mod spray_sim;
mod wake_sim;

use fft_model::FftModel;
pub use foam_sim::FOAM_FORMAT;
use gerstner_model::GerstnerModel;
use kernel::{Kernel, SlotImages};
pub use queries::{Answers, SurfaceAnswer, MAX_QUERIES};
use queries::{HeightQueries, SlotPlace};
pub use slope_mips::slope_levels;
use slope_mips::SlopeMips;
pub use spray_sim::{SprayBuffers, COUNTS_BYTES, DRAW_ARGS_OFFSET, LIVE_INDEX, PARTICLE_BYTES};
pub use wake_sim::Wake;

use super::foam::{self, FoamLevels, FoamScene};
use super::gerstner::Wave;
use super::moments::{
    anisotropy_along, cox_munk_mean_square_slope, cox_munk_upwind_excess, SeaMoments,
};
use super::params::{OceanSettings, Waves};
use super::spectrum::{wind_vector, Cascade};
use crate::gpu::compute::ComputeQueue;
use crate::gpu::{
    Buffer, Context, DeviceInfo, FormatUse, Frame, GpuResult, Image, ImageDesc, Profiler, Recorder,
    SemaphoreOp, FRAMES_IN_FLIGHT,
};
use crate::pass_names as names;

/// A named compute pass: timestamps when a profiler is given, a debug label always.
fn scope(timer: &mut Timer, rec: &Recorder, name: &'static str, body: impl FnOnce()) {
    match timer {
        Some((profiler, _)) => profiler.pass(rec, name, body),
        None => {
            rec.pass(name);
            rec.begin_label(name);
            body();
            rec.end_label();
        }
    }
}

/// Per-slot uniform buffers the host rewrites each frame, once the slot's previous compute work
/// is done. The first write fills every slot: the first frame's warm-up steps use both.
pub(super) struct SlotUniforms {
    buffers: Vec<Buffer>,
    written: bool,
}

impl SlotUniforms {
    pub(super) fn new(buffers: Vec<Buffer>) -> Self {
        SlotUniforms {
            buffers,
            written: false,
        }
    }

    /// Writes `bytes` into slot `slot`'s buffer, or into every slot's the first time.
    pub(super) fn write(&mut self, slot: usize, bytes: &[u8]) {
        if self.written {
            self.buffers[slot].write(bytes);
        } else {
            for b in &mut self.buffers {
                b.write(bytes);
            }
            self.written = true;
        }
    }
}

/// Moves the simulation images into GENERAL, where they stay for good, and zeroes them (no foam
/// before the first frame). Recorded at the start of the first compute submission, on the queue
/// that writes them, so the graphics queue first sees them through the compute timeline.
fn record_images_init(rec: &Recorder, images: &[Image]) {
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
/// Format of the simulation images: fp32, as displacement and slopes need it. Linear filtering
/// of it is optional in Vulkan: where the device lacks it, the water shaders filter by hand
/// (`OCEAN_MANUAL_FILTER` in shaders/common/water.glsl).
pub const IMAGE_FORMAT: vk::Format = vk::Format::R32G32B32A32_SFLOAT;

/// The stages at which graphics waits for the compute timeline before reading what the
/// simulation wrote: every stage a water shader samples the images in (vertex: the clipmap
/// water, the floating objects and the spray's particles; tessellation evaluation: the
/// tessellated water, named only where the device has tessellation shaders, as a stage mask
/// may name only enabled stages; fragment), and the spray's indirect draw (DRAW_INDIRECT).
/// The renderer checks each pipeline that reads them against it (`Order::Wait`,
/// `gpu::check_bindings`).
pub fn graphics_wait_stages(device: &DeviceInfo) -> vk::PipelineStageFlags2 {
    let mut stages = vk::PipelineStageFlags2::DRAW_INDIRECT
        | vk::PipelineStageFlags2::VERTEX_SHADER
        | vk::PipelineStageFlags2::FRAGMENT_SHADER;
    if device.tessellation_shader {
        stages |= vk::PipelineStageFlags2::TESSELLATION_EVALUATION_SHADER;
    }
    stages
}

/// One frame as a wave model sees it.
#[derive(Clone, Copy)]
pub(super) struct ModelFrame {
    pub slot: usize,
    /// Simulation time (s).
    pub time_s: f64,
    /// Time since the previous frame (s; foam decay).
    pub dt_s: f32,
    /// J below which foam forms (`foam::threshold`).
    pub foam_threshold: f32,
    /// Whole texels the Gerstner window moved since the previous frame (the previous foam is
    /// read that far over).
    pub window_shift: [i32; 2],
    /// World position of the images' texel (0, 0) (the Gerstner window's corner).
    pub origin_m: [f64; 2],
    /// Grid size N and cascades (image layers).
    pub n: u32,
    pub layers: u32,
    pub choppiness: f32,
    pub patch_m: [f32; 4],
    /// Side of the Gerstner window (m).
    pub window_m: f64,
    /// The foam's levels this frame and the previous one (no levels: Gerstner waves).
    pub foam: FoamLevels,
    pub previous_foam: FoamLevels,
    /// The scene the foam meets (surf, objects).
    pub scene: FoamScene,
    /// The camera's world xz (m): the spray's emission grid lies around it.
    pub camera_xz: [f64; 2],
    /// The step moves the spray: every frame, and the warm-up's short steps (the spray lives
    /// seconds; the long steps would throw it metres at a time).
    pub spray: bool,
}

/// The compute-queue profiler and the frame it times, when timing.
type Timer<'a> = Option<(&'a mut Profiler, &'a Frame)>;

/// What the simulation needs of a wave model: the FFT cascades (`fft_model.rs`) or the sum of
/// Gerstner waves (`gerstner_model.rs`). Both write the same images.
trait WaveModel {
    /// Host work before the frame is recorded, once the slot's previous compute work is done.
    fn prepare(&mut self, _frame: &ModelFrame) {}
    /// Records the model's passes (their barriers come from the kernels' bindings).
    fn record(&self, rec: &Recorder, timer: &mut Timer, frame: &ModelFrame);
    /// The spectrum's h0 (FFT only; `--dump`).
    fn h0(&self) -> Option<&Buffer> {
        None
    }
    /// The waves (Gerstner only).
    fn gerstner_waves(&self) -> Option<&[Wave]> {
        None
    }
    /// The spray's buffers (FFT only, with `--spray on`).
    fn spray(&self) -> Option<&SprayBuffers> {
        None
    }
}

pub struct Simulation {
    pub settings: OceanSettings,
    pub cascades: Vec<Cascade>,
    model: Box<dyn WaveModel>,
    /// World position of texel (0, 0) of the images: 0 for the periodic FFT cascades, the
    /// camera-following (grid-snapped) window corner for Gerstner waves.
    origin_m: [f64; 2],
    /// Per slot: (dx, h, dz, 0), one layer per cascade.
    pub displacement: Vec<Image>,
    /// Per slot: (−n_x/n_y, −n_z/n_y, J, foam) of the choppy surface's exact normal, one layer
    /// per cascade; J is the cascade's own, the foam (layer 0 only) the whole surface's. With
    /// mip levels above a 64² grid (`slope_mips`, made after the model writes level 0).
    pub normals: Vec<Image>,
    slope_mips: Option<SlopeMips>,
    /// Each cascade's (∂Dx/∂x, ∂Dz/∂z, ∂Dx/∂z, 0) before choppiness, one layer per cascade:
    /// written by assemble, read by the foam step after it (FFT only; 1×1 for Gerstner waves).
    derivatives: Image,
    /// Per slot: the foam near the camera (whitecap foam, residual foam, 0, 0), one layer per
    /// level of `foam_levels` (`foam_sim.rs`; FFT only, a 1×1 image for Gerstner waves).
    pub foam: Vec<Image>,
    /// Where the foam's levels lie this frame (set by [`Simulation::place_window`]), and where
    /// they lay at the previous submission.
    pub foam_levels: FoamLevels,
    previous_foam_levels: Option<FoamLevels>,
    /// J below which foam forms (`foam::threshold`, calibrated at startup).
    pub foam_threshold: f32,
    /// The Gerstner window's origin at the previous submission (foam follows it).
    previous_origin_m: Option<[f64; 2]>,
    queue: ComputeQueue,
    /// Where graphics waits for the images ([`graphics_wait_stages`] of the device).
    pub wait_stages: vk::PipelineStageFlags2,
    /// The images were initialized (the first submission does it).
    initialized: bool,
    /// The last submission ran the warm-up, which read both slots' per-slot buffers: the next
    /// one waits for it before the host rewrites the other slot's.
    after_warmup: bool,
    /// Simulation time of the previous submission (s; f64: a long run keeps its frame steps).
    last_time_s: Option<f64>,
    /// The camera's world xz at the last `place_window` (m).
    camera_xz: [f64; 2],
    /// Height queries (`ask`), made at the first.
    queries: Option<HeightQueries>,
    /// Per slot: where its images lie and the time they are for (`None`: not written yet).
    slot_places: [Option<SlotPlace>; FRAMES_IN_FLIGHT],
    /// Bound on how far the surface moves from its rest position (m): culling margin.
    pub max_displacement_m: f64,
    /// The rendered sea's significant height and mean frequency (the shore's shoaling and
    /// breaking, `ocean::shore`).
    pub sea_moments: SeaMoments,
    /// `--boat`: the wake near the camera (`ocean::wake`), and its images.
    pub wake: Wake,
}

impl Simulation {
    /// The whole sea surface's mean-square slope: Cox & Munk (1954) at the wind for the FFT
    /// sea, and for Gerstner waves (no wind) their own plus Cox & Munk's calm 0.003; never less
    /// than what the cascades resolve.
    pub fn mean_square_slope(&self) -> f64 {
        let resolved: f64 = self.sea_moments.slope_variance.iter().sum();
        let sea = match self.settings.waves {
            Waves::Fft => cox_munk_mean_square_slope(self.settings.sea.wind_speed_m_s),
            Waves::Gerstner(_) => resolved + cox_munk_mean_square_slope(0.0),
        };
        sea.max(resolved)
    }

    /// How the whole sea surface's slopes differ by direction (`SeaMoments::slope_anisotropy`):
    /// Cox & Munk's (1954) upwind excess along the wind for the FFT sea; for Gerstner waves
    /// their own (the calm's 0.003 has no direction).
    pub fn slope_anisotropy(&self) -> [f64; 2] {
        match self.settings.waves {
            Waves::Fft => anisotropy_along(
                cox_munk_upwind_excess(self.settings.sea.wind_speed_m_s),
                wind_vector(&self.settings.sea),
            ),
            Waves::Gerstner(_) => {
                let a = &self.sea_moments.slope_anisotropy;
                [0, 1].map(|i| a.iter().map(|l| l[i]).sum())
            }
        }
    }
}

/// The foam near the camera's levels for `settings` (none for Gerstner waves or `--foam-sim
/// off`; by the grid's size by default).
fn foam_levels_for(settings: &OceanSettings) -> FoamLevels {
    let fft = matches!(settings.waves, Waves::Fft);
    match (fft, settings.foam_sim) {
        (false, _) | (true, Some(false)) => FoamLevels::none(),
        (true, None) => FoamLevels::layout(settings.fft_size),
        (true, Some(true)) => FoamLevels::levels(),
    }
}

/// A model as the simulation holds it, with its displacement bound and sea height.
fn boxed<M: WaveModel + 'static>(
    (model, bound, sea): (M, f64, SeaMoments),
) -> (Box<dyn WaveModel>, f64, SeaMoments) {
    (Box::new(model), bound, sea)
}

/// The simulation's and the foam's image formats, with the features their uses need.
fn require_image_formats(ctx: &Context) -> GpuResult<()> {
    ctx.require_formats(&[
        FormatUse {
            format: IMAGE_FORMAT,
            // Written by the kernels, sampled by the water, cleared, read back (--dump, --stats).
            features: vk::FormatFeatureFlags::STORAGE_IMAGE
                | vk::FormatFeatureFlags::SAMPLED_IMAGE
                | vk::FormatFeatureFlags::TRANSFER_SRC
                | vk::FormatFeatureFlags::TRANSFER_DST,
            what: "the ocean simulation images",
        },
        FormatUse {
            format: FOAM_FORMAT,
            features: vk::FormatFeatureFlags::STORAGE_IMAGE
                | vk::FormatFeatureFlags::SAMPLED_IMAGE
                | vk::FormatFeatureFlags::SAMPLED_IMAGE_FILTER_LINEAR
                | vk::FormatFeatureFlags::TRANSFER_DST,
            what: "the foam images",
        },
    ])
}

/// The simulation's images: storage for the compute passes, sampled by the water, and transfer
/// source and destination (as `require_image_formats` asks of their formats).
const IMAGE_USAGE: vk::ImageUsageFlags = vk::ImageUsageFlags::from_raw(
    vk::ImageUsageFlags::STORAGE.as_raw()
        | vk::ImageUsageFlags::SAMPLED.as_raw()
        | vk::ImageUsageFlags::TRANSFER_SRC.as_raw()
        | vk::ImageUsageFlags::TRANSFER_DST.as_raw(),
);

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
        require_image_formats(ctx)?;
        let foam_levels = foam_levels_for(settings);
        let mipped = |name: String, format: vk::Format, side: usize, layers: u32, levels: u32| {
            Image::new(
                ctx,
                &ImageDesc {
                    layers,
                    array_view: true,
                    shared: true,
                    levels,
                    ..ImageDesc::new(
                        &name,
                        vk::Extent2D {
                            width: side as u32,
                            height: side as u32,
                        },
                        format,
                        IMAGE_USAGE,
                    )
                },
            )
        };
        let image = |name, format, side, layers| mipped(name, format, side, layers, 1);
        // Each cascade's derivatives, written by assemble and read by the foam step in the same
        // submission (FFT waves only: 1×1 for Gerstner waves).
        let side = if settings.waves == Waves::Fft { n } else { 1 };
        let derivatives = image("ocean derivatives".into(), IMAGE_FORMAT, side, layers)?;
        let mut displacement = Vec::new();
        let mut normals = Vec::new();
        let mut foam = Vec::new();
        let (foam_side, foam_layers) = (foam_levels.size as usize, foam_levels.count.max(1) as u32);
        for slot in 0..FRAMES_IN_FLIGHT {
            let name = format!("ocean displacement slot {slot}");
            displacement.push(image(name, IMAGE_FORMAT, n, layers)?);
            let name = format!("ocean normals+foam slot {slot}");
            normals.push(mipped(name, IMAGE_FORMAT, n, layers, slope_levels(n))?);
            let name = format!("foam levels slot {slot}");
            foam.push(image(name, FOAM_FORMAT, foam_side, foam_layers)?);
        }
        let images = SlotImages {
            displacement: &displacement,
            normals: &normals,
        };
        let wake = Wake::new(ctx, settings, |name, side| {
            image(name, IMAGE_FORMAT, side, 1)
        })?;
        let (model, max_displacement_m, sea_moments) = match &settings.waves {
            Waves::Fft => boxed(FftModel::new(
                ctx,
                settings,
                &cascades,
                &images,
                &derivatives,
                &foam,
            )?),
            Waves::Gerstner(w) => boxed(GerstnerModel::new(
                ctx,
                w,
                &images,
                settings.patch_size_m / n as f64,
            )?),
        };
        Ok(Simulation {
            foam_threshold: foam::threshold(settings),
            previous_origin_m: None,
            max_displacement_m,
            sea_moments,
            settings: settings.clone(),
            cascades,
            model,
            origin_m: [0.0, 0.0],
            displacement,
            slope_mips: SlopeMips::new(ctx, &normals)?,
            normals,
            derivatives,
            foam,
            foam_levels,
            previous_foam_levels: None,
            queue: ComputeQueue::new(ctx)?,
            wait_stages: graphics_wait_stages(&ctx.info),
            initialized: false,
            after_warmup: false,
            last_time_s: None,
            camera_xz: [0.0; 2],
            queries: None,
            slot_places: [None; FRAMES_IN_FLIGHT],
            wake,
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
        self.camera_xz = camera_xz;
        self.foam_levels = self.foam_levels.around(camera_xz);
        if self.is_window() {
            let window = self.settings.patch_size_m;
            let step = window / self.settings.fft_size as f64;
            self.origin_m = camera_xz.map(|c| ((c - window / 2.0) / step).floor() * step);
        }
    }

    /// True for a bounded window (Gerstner), false for periodic cascades (FFT).
    pub fn is_window(&self) -> bool {
        self.model.gerstner_waves().is_some()
    }

    /// Patch sizes of the cascades, padded to four (for shaders).
    pub fn patch_sizes(&self) -> [f32; 4] {
        patch_sizes(&self.cascades)
    }

    /// Every image the simulation writes (the first submission initializes them).
    fn images(&self) -> Vec<Image> {
        self.displacement
            .iter()
            .chain(&self.normals)
            .chain(&self.foam)
            .chain(&self.wake.images)
            .chain([&self.derivatives])
            .cloned()
            .collect()
    }

    /// Submits frame `value`'s simulation at time `time_s` into `slot` on the compute queue,
    /// with the Gerstner window where [`Simulation::place_window`] last put it and the foam
    /// meeting `scene` (its surf and the objects in the water), after the
    /// graphics timeline reached `wait_graphics` (the slot's previous user, `Frame::
    /// previous_user`); `timing` times the passes with a compute-queue profiler
    /// (`Profiler::for_compute`) for `frame`.
    pub fn submit(
        &mut self,
        slot: usize,
        value: u64,
        wait_graphics: Option<u64>,
        time_s: f64,
        scene: &FoamScene,
        timing: Option<(&mut Profiler, &Frame)>,
    ) -> GpuResult<()> {
        let dt_s = self
            .last_time_s
            .map_or(0.0, |t| (time_s - t).max(0.0) as f32);
        self.last_time_s = Some(time_s);
        let window_shift = self.window_shift();
        let previous_foam = self.previous_foam_levels.unwrap_or(self.foam_levels);
        self.previous_foam_levels = Some(self.foam_levels);
        let frame = ModelFrame {
            foam: self.foam_levels,
            previous_foam,
            scene: *scene,
            camera_xz: self.camera_xz,
            spray: true,
            foam_threshold: self.foam_threshold,
            window_shift,
            slot,
            time_s,
            dt_s,
            origin_m: self.origin_m,
            n: self.settings.fft_size as u32,
            layers: self.cascades.len() as u32,
            choppiness: self.settings.choppiness as f32,
            patch_m: patch_sizes(&self.cascades),
            window_m: self.settings.patch_size_m,
        };
        let first = !self.initialized;
        let init = if first { self.images() } else { Vec::new() };
        self.initialized = true;
        let warmup = if first {
            self.warmup_steps(&frame)
        } else {
            Vec::new()
        };
        let frame = if warmup.is_empty() {
            frame
        } else {
            ModelFrame {
                dt_s: foam::WARMUP_STEP_S,
                ..frame
            }
        };
        // The slot's previous compute work (two frames ago) must be done before the host
        // rewrites its inputs.
        self.queue.wait_for_slot(value)?;
        if std::mem::replace(&mut self.after_warmup, !warmup.is_empty()) {
            self.queue.wait_for_last()?;
        }
        self.model.prepare(&frame);
        let wake_steps = self.wake.plan(first, slot, time_s);
        let queries = self.prepare_queries(&warmup, slot, value, time_s, scene)?;
        let wake = &self.wake;
        let (model, mips) = (&*self.model, self.slope_mips.as_ref());
        let query_pass = self.queries.as_ref().zip(queries);
        self.queue.submit(slot, value, wait_graphics, |rec| {
            let mut timer = timing;
            if let Some((profiler, frame)) = timer.as_mut() {
                profiler.begin_frame(rec, frame)?;
            }
            if !init.is_empty() {
                record_images_init(rec, &init);
            }
            if !warmup.is_empty() {
                rec.begin_label(names::OCEAN_WARMUP);
                for step in &warmup {
                    model.record(rec, &mut None, step);
                }
                rec.end_label();
            }
            model.record(rec, &mut timer, &frame);
            if let Some(mips) = mips {
                mips.record(rec, &mut timer, slot, frame.n, frame.layers);
            }
            wake.record(rec, &mut timer, &wake_steps);
            if let Some((pass, dispatch)) = &query_pass {
                scope(&mut timer, rec, names::OCEAN_QUERIES, || {
                    pass.record(rec, dispatch)
                });
            }
            if let Some((profiler, _)) = timer.as_mut() {
                profiler.end_frame(rec);
            }
            Ok(())
        })
    }

    /// Whole texels the Gerstner window moved since the previous submission (0 for the FFT
    /// cascades), and remembers where it is now.
    fn window_shift(&mut self) -> [i32; 2] {
        let step = self.settings.patch_size_m / self.settings.fft_size as f64;
        let shift = match self.previous_origin_m {
            Some(previous) if self.is_window() => {
                [0, 1].map(|i| ((self.origin_m[i] - previous[i]) / step).round() as i32)
            }
            _ => [0, 0],
        };
        self.previous_origin_m = Some(self.origin_m);
        shift
    }

    /// The steps run before the first FFT frame `frame`: foam::RESIDUAL_WARMUP_STEPS long steps
    /// (the residual foam's slow life, with the foam near the camera only) and then
    /// foam::WARMUP_STEPS short ones (the whitecaps')
    /// over the seconds before it, alternating slots and ending in the other one, so its foam is
    /// already in steady state (a single screenshot shows the foam a running sea has). Both
    /// slots are unused by graphics so far. Gerstner: none (its per-slot wave buffers are
    /// written by the host for one time each).
    fn warmup_steps(&self, frame: &ModelFrame) -> Vec<ModelFrame> {
        if self.model.h0().is_none() {
            return Vec::new();
        }
        let schedule = foam::warmup_schedule(self.foam_levels.count > 0);
        let total = schedule.len();
        schedule
            .into_iter()
            .enumerate()
            .map(|(k, (before_s, dt_s))| ModelFrame {
                slot: (frame.slot + total - k) % FRAMES_IN_FLIGHT,
                time_s: frame.time_s - before_s,
                dt_s: dt_s as f32,
                spray: dt_s <= foam::WARMUP_STEP_S as f64,
                ..*frame
            })
            .collect()
    }

    /// The wait a graphics submission adds before sampling frame `value`'s images.
    pub fn graphics_wait(&self, value: u64) -> SemaphoreOp {
        self.queue.graphics_wait(value, self.wait_stages)
    }

    /// The Gerstner waves (Gerstner mode).
    pub fn gerstner_waves(&self) -> Option<&[Wave]> {
        self.model.gerstner_waves()
    }

    /// The spray's particle and count buffers, when the run has spray (FFT waves, `--spray
    /// on`).
    pub fn spray(&self) -> Option<&SprayBuffers> {
        self.model.spray()
    }
}
