//! The part of a run both frontends share: context objects, frame pacing, profiler, renderer and
//! the frame recording sequence, plus the end-of-run profile and summary.

use std::sync::Arc;
use std::time::Instant;

use ash::vk;

use super::RunSettings;
use crate::gpu::graph::FrameGraph;
use crate::gpu::selftest::SyncHazard;
use crate::gpu::{
    Buffer, Context, FrameTimes, Frames, GpuResult, GpuTimings, MemoryLocation, Profilers,
};
use crate::ocean::bodies::{Body, BodyDesc, Fleet, Shape};
use crate::ocean::buoy::Buoy;
use crate::ocean::dump;
use crate::ocean::simulation::Simulation;
use crate::ocean::simulation::MAX_QUERIES;
use crate::ocean::stats::stats_line;
use crate::output::{PendingFile, Staged};
use crate::profile::{ProfileReport, WARMUP_FRAMES};
use crate::render::scene::shore_scale;
use crate::render::{
    record_frame, Delivery, FrameInputs, FrameParts, OceanBindings, OutputTarget, OverlayDraw,
    Renderer,
};
use crate::shared::MAX_BODIES;

pub struct Session {
    /// The device, its queues and timelines (the frontends create it).
    pub ctx: Arc<Context>,
    /// Frames in flight: slots, command buffers, the frame timeline (the frontends wait on it
    /// and read back through it).
    pub frames: Frames,
    /// GPU timestamps of the graphics and the compute passes.
    profilers: Profilers,
    /// What the frame draws with (the frontends move its camera and resize it).
    pub renderer: Renderer,
    /// The wave model (FFT or Gerstner) on the compute queue.
    simulation: Simulation,
    /// The floating buoy: its pose at each frame's time, from CPU height queries.
    buoy: Buoy,
    /// `--bodies`: the floating bodies, on the GPU's height queries; and per frame, how many
    /// frames old the answers they moved on were.
    fleet: Option<Fleet>,
    /// Frames counted at each latency 0, 1, 2, … (a histogram: memory stays flat).
    query_latency: Vec<u64>,
    /// Test-only hazard, recorded once in the first frame.
    hazard: Option<SyncHazard>,
    /// Wall time between consecutive frame starts (ms), after warm-up: (frame index, ms), the
    /// index being the frame that started the interval.
    cpu_frame_ms: Vec<(u64, f64)>,
    /// Frames below this index are warm-up (not in the statistics).
    measure_from: u64,
    last_frame_start: Option<Instant>,
    /// When the session was made (the windowed clock, the summary line).
    started: Instant,
    /// The last submitted frame: (slot, timeline value, simulation time).
    last: Option<(usize, u64, f64)>,
    /// `--frame-graph`: the frame (index) whose graph goes to the file.
    frame_graph: Option<(u64, PendingFile)>,
}

/// How far apart `--bodies` places the bodies (m).
const BODY_SPACING_M: f64 = 8.0;

/// Writes a frame graph: Graphviz for a `.dot` path, JSON otherwise.
fn write_frame_graph(file: PendingFile, graph: &FrameGraph) -> anyhow::Result<()> {
    let dot = file
        .path()
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("dot"));
    let text = if dot {
        graph.to_dot()
    } else {
        serde_json::to_string_pretty(&graph.to_json())? + "\n"
    };
    file.commit(text.as_bytes())
}

impl Session {
    /// `--frame-graph`: writes the graph of frame `index` (counted from 0) to `file` as soon
    /// as that frame is submitted.
    pub fn write_frame_graph_of(&mut self, index: u64, file: PendingFile) {
        self.frame_graph = Some((index, file));
    }

    pub fn new(
        ctx: &Arc<Context>,
        output_format: vk::Format,
        extent: vk::Extent2D,
        s: &RunSettings,
    ) -> anyhow::Result<Self> {
        let hazard = if s.inject_sync_hazard {
            Some(SyncHazard::new(ctx)?)
        } else {
            None
        };
        let mut profilers = Profilers::new(ctx, WARMUP_FRAMES, s.profile.is_some())?;
        profilers.set_ordered(s.profile.is_some());
        if s.profile.is_some() && !profilers.graphics.enabled() {
            anyhow::bail!(
                "--profile: {} has no timestamp queries on its graphics queue",
                ctx.info.name
            );
        }
        let mut simulation = Simulation::new(ctx, &s.ocean)?;
        let buoy = buoy_on(s, &simulation);
        let camera = s.camera.unwrap_or_default();
        let mut fleet = (s.bodies > 0).then(|| {
            let [bx, bz] = s.scene.layout.buoy_xz;
            Fleet::scattered(s.bodies, [bx as f64 + 30.0, bz as f64], BODY_SPACING_M)
        });
        // `--boat`: the wake's grid where the first frame will put it, and the boat there,
        // driven along its course (the first body).
        let (eye, forward) = (camera.position, camera.forward);
        simulation.wake.place(
            [eye.x as f64, eye.z as f64],
            [forward.x as f64, forward.z as f64],
        );
        if let Some(boat) = simulation.wake.boat_for(s.start_time_s) {
            let body = Body::driven_boat(&boat, s.start_time_s);
            fleet
                .get_or_insert_with(Fleet::default)
                .bodies
                .insert(0, body);
        }
        let ocean = ocean_bindings(&simulation);
        let renderer = Renderer::new(ctx, output_format, extent, ocean, &s.scene, camera)?;
        let mut session = Session {
            ctx: ctx.clone(),
            frames: Frames::new(ctx)?,
            profilers,
            renderer,
            simulation,
            buoy,
            fleet,
            query_latency: Vec::new(),
            hazard,
            cpu_frame_ms: Vec::new(),
            measure_from: WARMUP_FRAMES,
            last_frame_start: None,
            started: Instant::now(),
            last: None,
            frame_graph: None,
        };
        // Per-frame timings are kept for the whole run (medians, the CSV), so only runs that
        // report them keep any: without --profile (and until a bench starts measuring) memory
        // stays flat however long the run (tests/soak.rs).
        if s.profile.is_none() {
            session.defer_measuring();
        }
        Ok(session)
    }

    /// Records and submits one frame into `output` (`render::record_frame`, the frame top to
    /// bottom), delivered as `delivery` says; keeps the wall time between frame starts.
    /// Returns the frame's timeline value.
    pub fn frame(
        &mut self,
        output: &OutputTarget,
        inputs: &FrameInputs,
        delivery: &Delivery,
        overlay: Option<OverlayDraw>,
    ) -> GpuResult<u64> {
        let now = Instant::now();
        if let Some(last) = self.last_frame_start {
            let previous = self.frames.submitted() - 1;
            if previous >= self.measure_from {
                self.cpu_frame_ms
                    .push((previous, now.duration_since(last).as_secs_f64() * 1e3));
            }
        }
        self.last_frame_start = Some(now);
        let slot = self.frames.next_slot();
        let eye = self.renderer.camera().position;
        let inputs = &FrameInputs {
            buoy: self.buoy.pose(inputs.time_s),
            camera_surface_m: self.buoy.surface_height_at(
                eye.x as f64,
                eye.z as f64,
                inputs.time_s,
            ),
            camera_slope: self
                .buoy
                .surface_slope_at(eye.x as f64, eye.z as f64, inputs.time_s),
            ..*inputs
        };
        let newest = self.float_bodies(inputs.time_s)?;
        let index = self.frames.submitted();
        let graph = self.frame_graph.take_if(|(at, _)| *at == index);
        if graph.is_some() {
            self.ctx.capture_frame_graph();
        }
        let parts = FrameParts {
            ctx: &self.ctx,
            frames: &mut self.frames,
            renderer: &mut self.renderer,
            simulation: &mut self.simulation,
            profilers: &mut self.profilers,
            overlay,
        };
        let value = record_frame(parts, output, inputs, delivery, self.hazard.take())?;
        if let (Some((_, file)), Some(recorded)) = (graph, self.ctx.take_frame_graph()) {
            // A file error is this run's error (exit 1), reported as the GPU layer's are.
            write_frame_graph(file, &recorded)
                .map_err(|e| crate::gpu::GpuError::Unsupported(format!("{e:#}")))?;
        }
        self.last = Some((slot, value, inputs.time_s));
        if let Some(answered) = newest {
            let late = (value - answered) as usize;
            if self.query_latency.len() <= late {
                self.query_latency.resize(late + 1, 0);
            }
            self.query_latency[late] += 1;
        }
        Ok(value)
    }

    /// `--bodies`: moves the bodies to `time_s` on the newest height queries' answers, asks
    /// about their columns' new places with this frame's simulation and hands them to the
    /// renderer. Returns the frame value the answers were for (`None`: none yet).
    fn float_bodies(&mut self, time_s: f64) -> GpuResult<Option<u64>> {
        let Some(fleet) = &mut self.fleet else {
            return Ok(None);
        };
        // The wait the frame's `begin` does anyway (for the frame that last used its slot, two
        // back), done first: that frame's compute work is then done too, and its answers here.
        self.frames.wait_for_slot()?;
        if let Some(boat) = self.simulation.wake.boat_for(time_s) {
            for body in fleet.bodies.iter_mut().filter(|b| b.driven.is_some()) {
                body.driven = Some(boat);
            }
        }
        let answers = self.simulation.answers()?;
        let newest = answers.map(|a| a.value);
        fleet.advance_on(answers, time_s);
        self.simulation
            .ask(&self.ctx, &fleet.query_points())
            .map_err(|e| crate::gpu::GpuError::Unsupported(format!("{e:#}")))?;
        self.renderer
            .set_bodies(fleet.bodies.iter().map(|b| b.instance()).collect());
        Ok(newest)
    }

    /// Applies changed settings between two frames (the overlay, `--live-set`): a changed sea
    /// or grid makes a new simulation (h0 computed and uploaded anew); a changed sea, grid,
    /// scale, terrain grid or anti-aliasing a new renderer (targets, pipelines, frame sets);
    /// anything else (sun, clouds, slicks, gusts, Fresnel, view, tessellation edge) is a uniform.
    /// Nothing waits for the GPU: the replaced objects go to the deferred-deletion queue, and the
    /// frames in flight finish with them. On an error the session keeps its old state.
    pub fn retune(&mut self, s: &RunSettings) -> anyhow::Result<()> {
        let ocean_changed = s.ocean != self.simulation.settings;
        if !ocean_changed && !self.renderer.needs_rebuild(&s.scene) {
            self.renderer.set_scene(&s.scene);
            return Ok(());
        }
        let simulation = if ocean_changed {
            Some(Simulation::new(&self.ctx, &s.ocean)?)
        } else {
            None
        };
        let bindings = ocean_bindings(simulation.as_ref().unwrap_or(&self.simulation));
        self.renderer = self.renderer.remade(bindings, &s.scene)?;
        if let Some(mut simulation) = simulation {
            self.buoy = buoy_on(s, &simulation);
            // A new wake starts anew in front of the camera (the boat with it: `float_bodies`).
            let camera = self.renderer.camera();
            let (eye, forward) = (camera.position, camera.forward);
            simulation.wake.place(
                [eye.x as f64, eye.z as f64],
                [forward.x as f64, forward.z as f64],
            );
            self.simulation = simulation;
        }
        Ok(())
    }

    /// Keeps the last finished frame's pass times of both queues (the overlay shows them).
    pub fn keep_live_timings(&mut self) {
        self.profilers.graphics.live = true;
        self.profilers.compute.live = true;
    }

    /// The last finished frame's pass times: (graphics, compute), once `keep_live_timings`.
    pub fn latest_timings(&self) -> (Option<&FrameTimes>, Option<&FrameTimes>) {
        (
            self.profilers.graphics.latest(),
            self.profilers.compute.latest(),
        )
    }

    /// Seconds since the session was made.
    pub fn elapsed_s(&self) -> f64 {
        self.started.elapsed().as_secs_f64()
    }

    /// Whether the graphics queue has timestamps (`--profile`, benchmarks).
    pub fn can_profile(&self) -> bool {
        self.profilers.graphics.enabled()
    }

    /// Measures nothing until [`Session::start_measuring`] (a warm-up of unknown length).
    pub fn defer_measuring(&mut self) {
        self.measure_from = u64::MAX;
        self.profilers.set_warmup(u64::MAX);
    }

    /// Orders each pass's opening timestamp before the pass's work, as `--profile` does
    /// (`Profiler::ordered`): for `bench frames`, whose per-pass times are the point.
    pub fn order_timestamps(&mut self) {
        self.profilers.set_ordered(true);
    }

    /// Ends the warm-up now: statistics count only frames submitted from here on (instead of
    /// the first `WARMUP_FRAMES` being skipped). Returns the number of warm-up frames.
    pub fn start_measuring(&mut self) -> u64 {
        let n = self.frames.submitted();
        self.measure_from = n;
        self.profilers.set_warmup(n);
        n
    }

    /// Wall time of each measured frame: (frame index, ms from its start to the next frame's
    /// start). The last frame has none.
    pub fn cpu_frame_ms(&self) -> &[(u64, f64)] {
        &self.cpu_frame_ms
    }

    /// `--stats`: waits for the last frame (compute and graphics) and prints the height
    /// statistics and whitecap fraction of its simulation images as one JSON line on stdout.
    pub fn print_stats(&mut self) -> anyhow::Result<()> {
        let Some((slot, value, t)) = self.last else {
            return Ok(());
        };
        // Graphics sampled the images: wait for it before the readback changes their layout.
        self.frames.wait_for(value)?;
        let (displacement, normals) = self.simulation.read_back(&self.ctx, slot)?;
        let spray = self.simulation.spray_counts(&self.ctx, slot)?;
        let patches: Vec<f64> = self.simulation.cascades.iter().map(|c| c.patch_m).collect();
        let index = self.frames.submitted() - 1;
        crate::outln!(
            "{}",
            stats_line(
                index,
                t,
                (&displacement, &normals),
                self.simulation.settings.fft_size,
                &patches,
                spray
            )
        );
        Ok(())
    }

    /// `--dump`: the last frame's files, ready to be written (`ocean::dump`).
    pub fn dump_contents(&mut self) -> anyhow::Result<Vec<(&'static str, Vec<u8>)>> {
        let (slot, value, t) = self
            .last
            .ok_or_else(|| anyhow::anyhow!("--dump: no frame was rendered"))?;
        self.frames.wait_for(value)?;
        let mut files = dump::files(&self.simulation, &self.ctx, slot, t)?;
        if let Some(fleet) = &self.fleet {
            let json = serde_json::to_string_pretty(&fleet.to_json())? + "\n";
            files.push(("bodies.json", json.into_bytes()));
        }
        Ok(files)
    }

    /// Waits for every frame and builds the profile report. Nothing is written or printed:
    /// the frontend commits its output files only once the whole run has succeeded.
    pub fn finish(&mut self, size: (u32, u32)) -> anyhow::Result<Finished> {
        let (timings, compute) = self.finish_timings()?;
        let cpu: Vec<f64> = self.cpu_frame_ms.iter().map(|c| c.1).collect();
        let report = ProfileReport {
            device: &self.ctx.info,
            frames: self.frames.submitted(),
            warmup_frames: self.measure_from,
            size,
            gpu: &timings,
            compute: &compute,
            cpu_frame_ms: &cpu,
        };
        Ok(Finished {
            profile_json: report.to_json(),
            table: format!(
                "vkocean: GPU time per pass (median of {} frames):\n{}",
                timings.frames.len(),
                report.summary()
            ),
            measured_frames: timings.frames.len(),
            summary: self.summary_line(size),
        })
    }

    /// Waits for every frame and returns the (graphics, compute) timings.
    pub fn finish_timings(&mut self) -> anyhow::Result<(GpuTimings, GpuTimings)> {
        self.frames.wait_all()?;
        // The last frame's wall time runs until the GPU finished it.
        if let Some(start) = self.last_frame_start.take() {
            let last = self.frames.submitted().saturating_sub(1);
            if self.frames.submitted() > 0 && last >= self.measure_from {
                self.cpu_frame_ms
                    .push((last, start.elapsed().as_secs_f64() * 1e3));
            }
        }
        Ok(self.profilers.finish()?)
    }

    /// Drops a crate (1.2 × 0.5 × 1 m, half the water's density) a metre above the water under
    /// the pixel `ndc` (−1 to 1, y down) of a view of `aspect`, if the ray meets the water within
    /// 500 m and the bodies and their height queries have room. Returns where (world x, z).
    pub fn drop_body(&mut self, ndc: [f32; 2], aspect: f32) -> Option<[f32; 2]> {
        let at = self
            .renderer
            .camera()
            .water_point(ndc, aspect, 0.0, 500.0)?;
        let fleet = self.fleet.get_or_insert_with(Fleet::default);
        let body = Body::new(BodyDesc {
            shape: Shape::Box([0.6, 0.25, 0.5]),
            relative_density: 0.5,
            position: [at[0] as f64, 1.0, at[1] as f64],
            heading_deg: 37.0 * fleet.bodies.len() as f64,
        });
        let room = fleet.bodies.len() < MAX_BODIES as usize
            && fleet.column_count() + body.column_count() <= MAX_QUERIES;
        room.then(|| {
            fleet.bodies.push(body);
            at
        })
    }

    /// `--bodies`: how many, the height queries they ask a frame and how late the answers
    /// came (median and most, in frames), the physics steps taken; `None` without bodies.
    /// The summary line and the overlay show it.
    pub fn bodies_status(&self) -> Option<String> {
        let fleet = self.fleet.as_ref()?;
        let counts = &self.query_latency;
        let total: u64 = counts.iter().sum();
        let mut seen = 0;
        let median = counts
            .iter()
            .position(|&c| {
                seen += c;
                2 * seen > total
            })
            .unwrap_or(0);
        let max = counts.iter().rposition(|&c| c > 0).unwrap_or(0);
        Some(format!(
            "{} bodies, {} height queries a frame, answered {median} frames late (median; max \
             {max}), {} physics steps",
            fleet.bodies.len(),
            fleet.column_count(),
            fleet.steps
        ))
    }

    /// The closing line of a run: frames, size, wall time, device.
    pub fn summary_line(&self, size: (u32, u32)) -> String {
        let n = self.frames.submitted();
        let secs = self.started.elapsed().as_secs_f64();
        let mut line = format!(
            "vkocean: {n} frames at {}x{} in {secs:.2} s ({:.1} ms/frame) on {}",
            size.0,
            size.1,
            if n > 0 { secs * 1e3 / n as f64 } else { 0.0 },
            self.ctx.info.name
        );
        if let Some(status) = self.bodies_status() {
            line += &format!("\nvkocean: {status}");
        }
        line
    }
}

/// The end of a run, ready to be written.
pub struct Finished {
    pub profile_json: String,
    /// The per-pass table printed with `--profile`.
    pub table: String,
    /// Frames that contributed to the statistics (after warm-up).
    pub measured_frames: usize,
    /// The closing line (frames, size, time, device).
    pub summary: String,
}

impl Finished {
    /// The profile written to its temporary file, for [`crate::output::place_all`].
    pub fn stage_profile(&self, profile: Option<PendingFile>) -> anyhow::Result<Option<Staged>> {
        let Some(file) = profile else {
            return Ok(None);
        };
        if self.measured_frames == 0 {
            anyhow::bail!(
                "--profile: no frame was measured (the first {WARMUP_FRAMES} frames are warm-up)"
            );
        }
        Ok(Some(file.stage(self.profile_json.as_bytes())?))
    }

    /// Prints the per-pass table (`with_table`: the run wrote a profile) and the summary line.
    pub fn report(&self, with_table: bool, summary_suffix: &str) {
        if with_table {
            eprint!("{}", self.table);
        }
        eprintln!("{}{summary_suffix}", self.summary);
    }
}

/// What the renderer binds of a simulation: its images and cascade layout.
fn ocean_bindings(simulation: &Simulation) -> OceanBindings {
    OceanBindings {
        displacement: simulation.displacement.clone(),
        normals: simulation.normals.clone(),
        foam: simulation.foam.clone(),
        wake: simulation.wake.images.clone(),
        spray: simulation.spray().cloned(),
        wait_stages: simulation.wait_stages,
        patch_m: simulation.patch_sizes(),
        cascades: simulation.cascades.len() as u32,
        texels: simulation.settings.fft_size as u32,
        max_displacement_m: simulation.max_displacement_m as f32,
        sea_moments: simulation.sea_moments,
        mean_square_slope: simulation.mean_square_slope() as f32,
        slope_anisotropy: simulation.slope_anisotropy().map(|v| v as f32),
        slicks: crate::render::slicks::Slicks::of_sea(
            &simulation.settings,
            &simulation.sea_moments,
            simulation.mean_square_slope(),
        ),
        gusts: crate::render::gusts::Gusts::of_sea(&simulation.settings),
    }
}

/// The buoy where the settings put it, floating on the waves as the water draws them,
/// shallows included.
fn buoy_on(s: &RunSettings, simulation: &Simulation) -> Buoy {
    let [bx, bz] = s.scene.layout.buoy_xz;
    let shore = shore_scale(s.scene.layout, simulation.sea_moments);
    Buoy::on(&s.ocean, [bx as f64, bz as f64], shore)
}

/// A host-visible buffer for reading back a `width x height` RGBA8 image.
pub fn readback_buffer(ctx: &Arc<Context>, extent: vk::Extent2D) -> GpuResult<Buffer> {
    Buffer::new(
        ctx,
        "screenshot readback",
        extent.width as u64 * extent.height as u64 * 4,
        vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuToCpu,
    )
}

/// Checks `--size` against the device's image limits.
pub fn check_size(ctx: &Context, size: (u32, u32)) -> anyhow::Result<()> {
    let max = ctx.info.limits.max_image_dimension2_d;
    if size.0 > max || size.1 > max {
        anyhow::bail!(
            "--size {}x{} exceeds the largest image this device supports ({max}x{max})",
            size.0,
            size.1
        );
    }
    Ok(())
}
