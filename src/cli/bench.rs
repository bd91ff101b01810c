//! `vkocean bench fft|frames|gerstner`: the subcommands' own options and their settings.

use std::path::PathBuf;

use clap::{Args, CommandFactory, Subcommand};

use super::values::*;
use super::{Cli, UsageError, WavesArg, MAX_SIDE};

#[derive(Subcommand, Debug, Clone)]
pub enum Command {
    /// Benchmarks (GPU timestamps, medians, a reference run in the same process).
    #[command(subcommand)]
    Bench(BenchCommand),
}

#[derive(Subcommand, Debug, Clone)]
pub enum BenchCommand {
    /// Time our GPU FFT against rustfft (one CPU thread) on the same 2D transforms.
    Fft(BenchFftArgs),
    /// Render the sample headless and report GPU ms per pass (min/median/p95/max), frame GPU
    /// and wall ms, FPS and the settings (every Ocean and Scene flag applies).
    Frames(BenchFramesArgs),
    /// Seed 004's experiment: FPS against Gerstner wave count (grid width 200) and grid width
    /// (10 waves), beside the paper's figures.
    Gerstner(BenchGerstnerArgs),
}

#[derive(Args, Debug, Clone)]
pub struct BenchFramesArgs {
    /// Warm-up before measuring (s; at least one frame).
    #[arg(long, value_name = "S", default_value = "2", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 0.0, 600.0))]
    pub warmup: f64,
    /// Measured frames.
    #[arg(long, value_name = "N", default_value = "60", value_parser = parse_frames, allow_hyphen_values = true)]
    pub frames: u64,
    /// Render size in pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "1280x720")]
    pub size: (u32, u32),
    /// Write the report as JSON (the --profile schema plus "fps", "wall_s" and "settings").
    #[arg(long, value_name = "PATH")]
    pub json: Option<PathBuf>,
    /// Write one CSV row per measured frame: frame, cpu_ms, gpu_ms, compute_gpu_ms,
    /// graphics_gpu_ms, then each pass.
    #[arg(long, value_name = "PATH")]
    pub csv: Option<PathBuf>,
}

#[derive(Args, Debug, Clone)]
pub struct BenchGerstnerArgs {
    /// Wave counts of the first table (grid width 200), 1 to 13 (seed 000's table).
    #[arg(long, value_name = "M,...", value_delimiter = ',', default_value = "1,3,6,10",
          value_parser = |s: &str| parse_whole(s, 1, 13).map(|n| n as usize))]
    pub wave_counts: Vec<usize>,
    /// Grid widths of the second table (10 waves), 8 to 16384.
    #[arg(long, value_name = "W,...", value_delimiter = ',', default_value = "200,600,1200,3000",
          value_parser = |s: &str| parse_whole(s, 8, MAX_SIDE as u64).map(|n| n as usize))]
    pub grid_widths: Vec<usize>,
    /// Warm-up before measuring each configuration (s; at least one frame).
    #[arg(long, value_name = "S", default_value = "1", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 0.0, 600.0))]
    pub warmup: f64,
    /// Measured frames per configuration.
    #[arg(long, value_name = "N", default_value = "20", value_parser = parse_frames, allow_hyphen_values = true)]
    pub frames: u64,
    /// Render size in pixels.
    #[arg(long, value_name = "WxH", value_parser = parse_size, default_value = "1280x720")]
    pub size: (u32, u32),
    /// Write both tables as JSON: {"wave_count": [...], "grid_width": [...], ...}.
    #[arg(long, value_name = "PATH")]
    pub json: Option<PathBuf>,
}

impl BenchFramesArgs {
    pub fn settings(
        &self,
        cli: &Cli,
    ) -> Result<crate::bench::frames::FramesBenchSettings, UsageError> {
        require_extension("--json", self.json.as_deref(), "json")?;
        require_extension("--csv", self.csv.as_deref(), "csv")?;
        Ok(crate::bench::frames::FramesBenchSettings {
            run: cli.bench_run("frames", self.size)?,
            warmup_s: self.warmup,
            frames: self.frames,
            json: self.json.clone(),
            csv: self.csv.clone(),
        })
    }
}

impl BenchGerstnerArgs {
    pub fn settings(
        &self,
        cli: &Cli,
    ) -> Result<crate::bench::gerstner::GerstnerBenchSettings, UsageError> {
        require_extension("--json", self.json.as_deref(), "json")?;
        if cli.waves != WavesArg::Fft
            || cli.gerstner_waves.is_some()
            || cli.gerstner_count.is_some()
        {
            return Err(UsageError(
                "bench gerstner sets the waves itself (seed 000's table); drop --waves, --gerstner-waves and --gerstner-count".to_string(),
            ));
        }
        Ok(crate::bench::gerstner::GerstnerBenchSettings {
            run: cli.bench_run("gerstner", self.size)?,
            wave_counts: self.wave_counts.clone(),
            grid_widths: self.grid_widths.clone(),
            warmup_s: self.warmup,
            frames: self.frames,
            json: self.json.clone(),
        })
    }
}

#[derive(Args, Debug, Clone)]
pub struct BenchFftArgs {
    /// FFT sizes, comma-separated powers of two from 64 to 1024.
    #[arg(long, value_name = "N,...", value_delimiter = ',', value_parser = parse_fft_size,
          default_value = "128,256,512,1024")]
    pub sizes: Vec<usize>,
    /// 2D transforms per batch.
    #[arg(long, value_name = "B", value_parser = parse_batch, allow_hyphen_values = true, default_value = "4")]
    pub batch: usize,
    /// Measured runs per size, after 5 warm-up runs on the GPU and 3 on the CPU [default: at
    /// least 30, and more until the size has been measured for 3 s (at most 2000), so that a
    /// median spans the drift of a shared machine]
    #[arg(long, value_name = "R", value_parser = parse_runs, allow_hyphen_values = true)]
    pub runs: Option<usize>,
    /// Also write the table as JSON: [{"n","batch","gpu_ms","rustfft_ms","ratio","rustfft_2d_ms","kernel","runs","steal_pct"}, ...].
    #[arg(long, value_name = "PATH")]
    pub json: Option<PathBuf>,
}

impl BenchFftArgs {
    pub fn settings(&self, cli: &Cli) -> Result<crate::bench::FftBenchSettings, UsageError> {
        require_extension("--json", self.json.as_deref(), "json")?;
        Ok(crate::bench::FftBenchSettings {
            sizes: self.sizes.clone(),
            batch: self.batch,
            runs: self.runs,
            json: self.json.clone(),
            validation: cli.validation_on(),
            validation_extras: cli.validation_extra.unwrap_or_default(),
            gpu: cli.gpu,
        })
    }
}

/// The flags `bench fft` takes besides its own (`--config` may set them too), as written.
const FFT_GLOBALS: [&str; 4] = ["gpu", "validation", "validation-extra", "config"];

/// The command line's clap command, with `bench fft`'s help listing only the flags that apply
/// there (clap would list every global scene and sea flag, which `bench fft` rejects).
pub fn command() -> clap::Command {
    let cli = Cli::command();
    let mut fft = BenchFftArgs::augment_args(
        clap::Command::new("fft")
            .bin_name("vkocean bench fft")
            .about("Time our GPU FFT against rustfft (one CPU thread) on the same 2D transforms."),
    );
    for id in FFT_GLOBALS {
        let id = id.replace('-', "_"); // clap's id is the field's name
        if let Some(arg) = cli.get_arguments().find(|a| a.get_id() == id.as_str()) {
            fft = fft.arg(arg.clone().global(false));
        }
    }
    let help = fft.render_help().to_string();
    cli.mut_subcommand("bench", |b| {
        b.mut_subcommand("fft", |f| f.override_help(help))
    })
}

/// `bench fft` times the FFT alone: a scene or sea flag on its command line is an error, not
/// silently ignored. (Settings from a `--config` file it does not use are ignored, so one file
/// serves every command.)
pub fn check_bench_fft_flags(user_args: &[std::ffi::OsString]) -> Result<(), UsageError> {
    let own = ["sizes", "batch", "runs", "json", "help"];
    for arg in user_args.iter().skip(1) {
        let arg = arg.to_string_lossy();
        if arg == "--" {
            break;
        }
        let Some(name) = arg.strip_prefix("--") else {
            continue;
        };
        let name = name.split('=').next().unwrap_or(name);
        if !own.contains(&name) && !FFT_GLOBALS.contains(&name) {
            return Err(UsageError(format!(
                "--{name} does not apply to bench fft (it times the FFT alone; it takes --sizes, --batch, --runs, --json, --gpu, --validation, --validation-extra and --config)"
            )));
        }
    }
    Ok(())
}
