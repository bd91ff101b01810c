//! `vkocean bench frames`: the sample rendered headless with the given settings, timed per pass
//! (GPU timestamps) and per frame (GPU and wall clock), after a warm-up measured in seconds
//! (SaschaWillems' `-bw`: the first frames compile pipelines and touch memory).
//!
//! Whole-frame figures: `gpu_total_ms` is the compute plus the graphics submission of a frame
//! (one queue on lavapipe, so they run back to back); `frame_cpu_ms` is the wall time from a
//! frame's start to the next frame's start (for the last frame: until the GPU finished it), and
//! `fps` is measured frames / wall seconds of the measured part. The JSON is the `--profile`
//! schema plus `fps`, `wall_s` and `settings`; the CSV has one row per measured frame.

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use serde_json::{json, Value};

use crate::frontend::headless::{frame_inputs, Offscreen};
use crate::frontend::session::Session;
use crate::frontend::{Outcome, RunSettings};
use crate::gpu::{Context, GpuTimings};
use crate::ocean::Waves;
use crate::output::PendingFile;
use crate::profile::{gpu_per_frame, gpu_total_ms, ProfileReport, Stats};
use crate::render::Delivery;

/// Settings of `bench frames`.
#[derive(Clone, Debug)]
pub struct FramesBenchSettings {
    /// The sample's settings (size, scene, ocean, validation, device).
    pub run: RunSettings,
    /// Warm-up time before measuring (s); at least one frame is always warm-up.
    pub warmup_s: f64,
    /// Measured frames.
    pub frames: u64,
    pub json: Option<PathBuf>,
    pub csv: Option<PathBuf>,
}

/// The timings of one measured run.
pub struct Measured {
    pub warmup_frames: u64,
    pub frames: u64,
    /// Wall time of the measured frames, until the GPU finished the last one (s).
    pub wall_s: f64,
    pub graphics: GpuTimings,
    pub compute: GpuTimings,
    /// (frame index, wall ms) per measured frame.
    pub cpu: Vec<(u64, f64)>,
}

impl Measured {
    /// Measured frames per wall-clock second.
    pub fn fps(&self) -> f64 {
        if self.wall_s > 0.0 {
            self.frames as f64 / self.wall_s
        } else {
            0.0
        }
    }

    /// Compute + graphics GPU ms per frame.
    pub fn gpu_total_ms(&self) -> Vec<f64> {
        gpu_total_ms(&self.graphics, &self.compute)
    }

    /// Pass names in report order: compute passes, then graphics passes.
    fn pass_names(&self) -> Vec<&'static str> {
        self.compute
            .passes
            .iter()
            .chain(&self.graphics.passes)
            .map(|p| p.0)
            .collect()
    }

    /// One row per measured frame: frame, cpu_ms, gpu_ms (compute + graphics), compute_gpu_ms,
    /// graphics_gpu_ms, then one column per pass (empty when the pass did not run that frame).
    pub fn csv(&self) -> String {
        let names = self.pass_names();
        let mut out = String::from("frame,cpu_ms,gpu_ms,compute_gpu_ms,graphics_gpu_ms");
        for name in &names {
            out += &format!(",{}", name.replace([' ', ','], "_"));
        }
        out.push('\n');
        let cpu: BTreeMap<u64, f64> = self.cpu.iter().copied().collect();
        let mut passes: BTreeMap<u64, Vec<(&'static str, f64)>> = BTreeMap::new();
        for f in self
            .compute
            .per_frame
            .iter()
            .chain(&self.graphics.per_frame)
        {
            passes.entry(f.index).or_default().extend(&f.passes);
        }
        let cell = |v: Option<f64>| v.map(|v| format!("{v:.4}")).unwrap_or_default();
        for (index, compute, graphics) in gpu_per_frame(&self.graphics, &self.compute) {
            out += &format!(
                "{index},{},{:.4},{compute:.4},{graphics:.4}",
                cell(cpu.get(&index).copied()),
                compute + graphics
            );
            let frame_passes = passes.get(&index);
            for name in &names {
                let value = frame_passes.and_then(|p| p.iter().find(|(n, _)| n == name));
                out += &format!(",{}", cell(value.map(|v| v.1)));
            }
            out.push('\n');
        }
        out
    }
}

/// Renders `warm-up + frames` frames of `run` headless on `ctx` and returns the timings of the
/// measured ones. `label` prefixes the progress lines on stderr (one every 2 s).
pub fn measure(
    ctx: &Arc<Context>,
    run: &RunSettings,
    warmup_s: f64,
    frames: u64,
    label: &str,
) -> anyhow::Result<Measured> {
    let offscreen = Offscreen::new(ctx, run.size)?;
    let output = offscreen.output();
    let mut session = Session::new(ctx, Offscreen::FORMAT, offscreen.extent, run)?;
    if !session.can_profile() {
        anyhow::bail!(
            "bench: {} has no timestamp queries on its graphics queue",
            ctx.info.name
        );
    }
    session.defer_measuring();
    session.order_timestamps();
    let started = Instant::now();
    let mut last_progress = Instant::now();
    let mut progress = |text: String| {
        if last_progress.elapsed() >= Duration::from_secs(2) {
            eprintln!("{label}: {text}");
            last_progress = Instant::now();
        }
    };
    let mut index = 0;
    while index == 0 || started.elapsed().as_secs_f64() < warmup_s {
        session.frame(
            &output,
            &frame_inputs(run, index),
            &Delivery::default(),
            None,
        )?;
        index += 1;
        crate::interrupt::check()?;
        progress(format!(
            "warm-up {:.1}/{warmup_s:.1} s, {index} frames",
            started.elapsed().as_secs_f64()
        ));
    }
    let warmup_frames = session.start_measuring();
    let measuring = Instant::now();
    for k in 0..frames {
        session.frame(
            &output,
            &frame_inputs(run, index),
            &Delivery::default(),
            None,
        )?;
        index += 1;
        crate::interrupt::check()?;
        let secs = measuring.elapsed().as_secs_f64();
        progress(format!(
            "frame {}/{frames}, {:.1} ms/frame",
            k + 1,
            secs * 1e3 / (k + 1) as f64
        ));
    }
    let (graphics, compute) = session.finish_timings()?;
    Ok(Measured {
        warmup_frames,
        frames,
        wall_s: measuring.elapsed().as_secs_f64(),
        graphics,
        compute,
        cpu: session.cpu_frame_ms().to_vec(),
    })
}

/// The settings that change what a frame costs, as (name, value) for reports.
pub fn cost_settings(run: &RunSettings) -> Vec<(&'static str, Value)> {
    let o = &run.ocean;
    let sc = &run.scene;
    let mut out = vec![
        ("size", json!(format!("{}x{}", run.size.0, run.size.1))),
        ("quality", json!(run.quality.0)),
        ("quality_by", json!(run.quality.1)),
    ];
    match &o.waves {
        Waves::Fft => {
            out.push(("waves", json!("fft")));
            out.push(("fft_size", json!(o.fft_size)));
            out.push(("cascades", json!(o.cascades)));
        }
        Waves::Gerstner(table) => {
            out.push(("waves", json!("gerstner")));
            out.push(("gerstner_waves", json!(table.len())));
            out.push(("grid", json!(o.fft_size)));
        }
    }
    out.extend([
        ("render_scale", json!(sc.render_scale)),
        ("rtt_scale", json!(sc.rtt_scale)),
        ("terrain_grid", json!(sc.terrain_grid)),
        ("tess_edge_px", json!(sc.tess_edge_px)),
        ("view", json!(format!("{:?}", sc.view).to_lowercase())),
        ("aa", json!(format!("{:?}", sc.aa).to_lowercase())),
        ("upscale", json!(format!("{:?}", sc.upscale).to_lowercase())),
        (
            "skybox",
            json!(if sc.skybox.is_some() {
                "files"
            } else {
                "analytic"
            }),
        ),
        ("validation", json!(run.validation)),
    ]);
    out
}

pub fn frames(s: &FramesBenchSettings) -> anyhow::Result<Outcome> {
    let json_file = PendingFile::create_if("--json", s.json.as_deref())?;
    let csv_file = PendingFile::create_if("--csv", s.csv.as_deref())?;
    let needs = s.run.scene.needs();
    let ctx = Context::headless(s.run.validation, s.run.validation_extras, s.run.gpu, needs)?;
    let counters = ctx.counters();
    let settings = cost_settings(&s.run);
    let settings_line: Vec<String> = settings
        .iter()
        .map(|(k, v)| format!("{k}={}", v.as_str().map_or(v.to_string(), str::to_string)))
        .collect();
    crate::outln!(
        "bench frames: {} ({}), {} frames after {:.1} s of warm-up",
        ctx.info.name,
        ctx.info.driver,
        s.frames,
        s.warmup_s
    );
    crate::outln!("settings: {}", settings_line.join(" "));
    let m = measure(&ctx, &s.run, s.warmup_s, s.frames, "bench frames")?;
    let coverage = water_coverage(&ctx, &s.run)?;

    let cpu: Vec<f64> = m.cpu.iter().map(|c| c.1).collect();
    let report = ProfileReport {
        device: &ctx.info,
        frames: m.warmup_frames + m.frames,
        warmup_frames: m.warmup_frames,
        size: s.run.size,
        gpu: &m.graphics,
        compute: &m.compute,
        cpu_frame_ms: &cpu,
    };
    let mut value = report.to_value();
    value["fps"] = json!(m.fps());
    value["wall_s"] = json!(m.wall_s);
    value["settings"] = Value::Object(
        settings
            .iter()
            .map(|(k, v)| (k.to_string(), v.clone()))
            .collect(),
    );
    let mut table = table(&m, &cpu);
    if let Some((json, line)) = coverage {
        value["water_coverage"] = json;
        table += &format!("water coverage: {line} ({COVERAGE_FRAMES} frames of their own)\n");
    }
    drop(ctx);
    // Outputs are written only once the whole run (stdout included) has succeeded, together.
    let mut staged = Vec::new();
    if let Some(file) = json_file {
        staged.push(file.stage((serde_json::to_string_pretty(&value)? + "\n").as_bytes())?);
    }
    if let Some(file) = csv_file {
        staged.push(file.stage(m.csv().as_bytes())?);
    }
    crate::output::write_stdout(&table);
    crate::output::stdout_status()?;
    crate::output::place_all(staged)?;
    Ok(Outcome { counters })
}

/// Frames the water's coverage is counted over, after the timed ones.
const COVERAGE_FRAMES: u64 = 3;

/// The water's coverage (`ProfileReport::water_coverage`: fragment invocations per covered
/// pixel, covered pixels) over `COVERAGE_FRAMES` frames of a run of their own with the draw
/// statistics on: they cost the water pass 5–7 % on lavapipe, so the timed frames run without.
/// Its JSON and summary line; `None` without pipeline statistics and precise occlusion queries.
fn water_coverage(
    ctx: &Arc<Context>,
    run: &RunSettings,
) -> anyhow::Result<Option<(Value, String)>> {
    if !(ctx.info.pipeline_statistics_query && ctx.info.occlusion_query_precise) {
        return Ok(None);
    }
    let mut counted = run.clone();
    // The session counts the water draw when a profile is asked for (nothing is written here).
    counted.profile = Some(PathBuf::from("(bench frames: water coverage)"));
    let m = measure(
        ctx,
        &counted,
        0.0,
        COVERAGE_FRAMES,
        "bench frames (coverage)",
    )?;
    let report = ProfileReport {
        device: &ctx.info,
        frames: m.warmup_frames + m.frames,
        warmup_frames: m.warmup_frames,
        size: run.size,
        gpu: &m.graphics,
        compute: &m.compute,
        cpu_frame_ms: &[],
    };
    Ok(report
        .water_coverage_json()
        .zip(report.water_coverage_line()))
}

/// The summary printed on stdout: per pass min/median/p95/max, whole-frame rows, FPS.
fn table(m: &Measured, cpu: &[f64]) -> String {
    let mut out = format!(
        "{:<22} {:>9} {:>9} {:>9} {:>9}   (ms; {} warm-up frames excluded)\n",
        "pass", "min", "median", "p95", "max", m.warmup_frames
    );
    let mut row = |name: &str, samples: &[f64]| {
        if let Some(st) = Stats::of(samples) {
            out += &format!(
                "{name:<22} {:>9.3} {:>9.3} {:>9.3} {:>9.3}\n",
                st.min, st.median, st.p95, st.max
            );
        }
    };
    for (name, samples) in m.compute.passes.iter().chain(&m.graphics.passes) {
        row(name, samples);
    }
    row("compute (GPU)", &m.compute.frames);
    row("graphics (GPU)", &m.graphics.frames);
    row("frame GPU total", &m.gpu_total_ms());
    row("frame CPU (wall)", cpu);
    let median = Stats::of(cpu).map_or(0.0, |s| s.median);
    out += &format!(
        "FPS {:.2} ({} frames in {:.2} s); median frame {:.1} ms ({:.1} FPS)\n",
        m.fps(),
        m.frames,
        m.wall_s,
        median,
        if median > 0.0 { 1e3 / median } else { 0.0 }
    );
    out
}
