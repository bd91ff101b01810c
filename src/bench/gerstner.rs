//! `vkocean bench gerstner`: seed 004's experiment (section 4.2) on our renderer. The paper
//! measures FPS against the number of Gerstner waves at grid width 200 (table 4-1) and against
//! the grid width at 10 waves (table 4-2), on an RTX 3060 laptop. Here the grid width is the side
//! of the Gerstner evaluation grid (the displacement and normal images the compute pass writes,
//! width² points), the waves are the first M of seed 000's table, and each configuration is a
//! `bench frames` run of the whole sample (the other flags apply).

use std::path::PathBuf;

use serde_json::json;

use super::frames::{measure, Measured};
use crate::frontend::{Outcome, RunSettings};
use crate::gpu::Context;
use crate::ocean::{gerstner, Waves};
use crate::output::PendingFile;
use crate::profile::Stats;

/// Seed 004, table 4-1: (wave count, FPS) at grid width 200.
pub const PAPER_WAVES: [(usize, f64); 4] = [(1, 161.0), (3, 2702.0), (6, 2691.0), (10, 2530.0)];
/// Seed 004, table 4-2: (grid width, FPS) at 10 waves.
pub const PAPER_GRID: [(usize, f64); 4] =
    [(200, 2579.0), (600, 1008.0), (1200, 275.0), (3000, 49.0)];
/// Grid width of table 4-1 and wave count of table 4-2.
pub const FIXED_GRID: usize = 200;
pub const FIXED_WAVES: usize = 10;

/// Settings of `bench gerstner`.
#[derive(Clone, Debug)]
pub struct GerstnerBenchSettings {
    /// The sample's settings; waves and grid are replaced per configuration.
    pub run: RunSettings,
    pub wave_counts: Vec<usize>,
    pub grid_widths: Vec<usize>,
    pub warmup_s: f64,
    pub frames: u64,
    pub json: Option<PathBuf>,
}

/// One configuration's result.
#[derive(Clone, Debug)]
pub struct GerstnerRow {
    pub waves: usize,
    pub grid: usize,
    pub fps: f64,
    /// Median wall time per frame (ms).
    pub frame_ms: f64,
    /// Median GPU time of the Gerstner compute pass (ms).
    pub gerstner_ms: f64,
    /// Median GPU time of compute + graphics (ms).
    pub gpu_ms: f64,
}

fn row(waves: usize, grid: usize, m: &Measured) -> GerstnerRow {
    let median = |v: &[f64]| Stats::of(v).map_or(f64::NAN, |s| s.median);
    let pass = m
        .compute
        .passes
        .iter()
        .find(|p| p.0 == crate::pass_names::OCEAN_GERSTNER)
        .map_or(f64::NAN, |p| median(&p.1));
    let cpu: Vec<f64> = m.cpu.iter().map(|c| c.1).collect();
    GerstnerRow {
        waves,
        grid,
        fps: m.fps(),
        frame_ms: median(&cpu),
        gerstner_ms: pass,
        gpu_ms: median(&m.gpu_total_ms()),
    }
}

pub fn gerstner(s: &GerstnerBenchSettings) -> anyhow::Result<Outcome> {
    let json_file = PendingFile::create_if("--json", s.json.as_deref())?;
    let needs = s.run.scene.needs();
    let ctx = Context::headless(s.run.validation, s.run.validation_extras, s.run.gpu, needs)?;
    let counters = ctx.counters();
    let max = ctx.info.limits.max_image_dimension2_d as usize;
    if let Some(&too_big) = s.grid_widths.iter().find(|&&w| w > max) {
        anyhow::bail!("--grid-widths {too_big}: this device's images are at most {max} wide");
    }
    crate::outln!(
        "bench gerstner (seed 004's experiment): {} ({}), {}x{}, {} frames per configuration after {:.1} s of warm-up",
        ctx.info.name, ctx.info.driver, s.run.size.0, s.run.size.1, s.frames, s.warmup_s
    );
    let table = gerstner::default_waves();
    let configs: Vec<(usize, usize)> = s
        .wave_counts
        .iter()
        .map(|&w| (w, FIXED_GRID))
        .chain(s.grid_widths.iter().map(|&g| (FIXED_WAVES, g)))
        .collect();
    let mut rows: Vec<GerstnerRow> = Vec::new();
    for (i, &(waves, grid)) in configs.iter().enumerate() {
        // Table 4-1's last row and table 4-2's first are the same configuration: measured once.
        if rows.iter().any(|r| (r.waves, r.grid) == (waves, grid)) {
            continue;
        }
        let mut run = s.run.clone();
        run.ocean.waves = Waves::Gerstner(table[..waves].to_vec());
        run.ocean.fft_size = grid;
        let label = format!(
            "bench gerstner {}/{} ({waves} waves, grid {grid})",
            i + 1,
            configs.len()
        );
        let m = measure(&ctx, &run, s.warmup_s, s.frames, &label)?;
        rows.push(row(waves, grid, &m));
    }
    let find = |waves: usize, grid: usize| {
        rows.iter()
            .find(|r| (r.waves, r.grid) == (waves, grid))
            .expect("every configuration was measured")
    };
    let paper = |table: &[(usize, f64)], key: usize| {
        table
            .iter()
            .find(|p| p.0 == key)
            .map_or("-".to_string(), |p| format!("{:.0}", p.1))
    };
    let header = |first: &str| {
        format!(
            "{first:>8} {:>9} {:>10} {:>12} {:>10} {:>10}\n",
            "FPS", "frame_ms", "gerstner_ms", "gpu_ms", "paper_FPS"
        )
    };
    let line = |key: usize, r: &GerstnerRow, paper_fps: String| {
        format!(
            "{key:>8} {:>9.2} {:>10.1} {:>12.3} {:>10.1} {:>10}\n",
            r.fps, r.frame_ms, r.gerstner_ms, r.gpu_ms, paper_fps
        )
    };
    let mut out = String::new();
    if !s.wave_counts.is_empty() {
        out += &format!("Table 4-1: wave count at grid width {FIXED_GRID}\n");
        out += &header("waves");
        for &w in &s.wave_counts {
            out += &line(w, find(w, FIXED_GRID), paper(&PAPER_WAVES, w));
        }
    }
    if !s.grid_widths.is_empty() {
        out += &format!("Table 4-2: grid width at {FIXED_WAVES} waves\n");
        out += &header("width");
        for &g in &s.grid_widths {
            out += &line(g, find(FIXED_WAVES, g), paper(&PAPER_GRID, g));
        }
    }
    out += "paper_FPS: seed 004 on an RTX 3060 laptop GPU (OpenGL); gerstner_ms: the compute pass alone; gpu_ms: compute + graphics\n";
    let to_json = |r: &GerstnerRow| {
        json!({"waves": r.waves, "grid": r.grid, "fps": r.fps, "frame_cpu_ms": r.frame_ms,
               "gerstner_gpu_ms": r.gerstner_ms, "gpu_total_ms": r.gpu_ms})
    };
    let value = json!({
        "device": ctx.info.name,
        "driver": ctx.info.driver,
        "size": [s.run.size.0, s.run.size.1],
        "frames": s.frames,
        "warmup_s": s.warmup_s,
        "wave_count": s.wave_counts.iter().map(|&w| to_json(find(w, FIXED_GRID))).collect::<Vec<_>>(),
        "grid_width": s.grid_widths.iter().map(|&g| to_json(find(FIXED_WAVES, g))).collect::<Vec<_>>(),
    });
    drop(ctx);
    crate::output::write_stdout(&out);
    crate::output::stdout_status()?;
    if let Some(file) = json_file {
        file.commit((serde_json::to_string_pretty(&value)? + "\n").as_bytes())?;
    }
    Ok(Outcome { counters })
}
