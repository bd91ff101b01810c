//! `vkocean-plot`: PNG charts of `vkocean bench frames` output.
//!
//! - `passes`: per-pass stacked bars, one bar per `--json` report (the `--profile` schema:
//!   `passes: [{name, gpu_ms: {min, median, mean, p95, max} | null, samples}]`, plus `settings`
//!   and `device`). Each bar stacks the run's per-pass median GPU ms. The submission totals are
//!   top-level keys of that schema (`frame_gpu_ms`, `compute_gpu_ms`, `gpu_total_ms`), never
//!   entries of `passes`; entries named like the bench table's total rows are skipped all the
//!   same, so a total is never stacked on top of the passes it contains.
//! - `frames`: frame time over frames from the `--csv` (header
//!   `frame,cpu_ms,gpu_ms,compute_gpu_ms,graphics_gpu_ms,<one column per pass>`; empty cells
//!   are frames without a value): one line for `gpu_ms`, one for `cpu_ms`.
//!
//! Drawn with plotters' bitmap backend into an RGB buffer; text through ab_glyph with a font
//! file read at run time (`--font`); PNG encoded by `image`.

mod draw;
mod input;

use std::path::PathBuf;

use clap::{Parser, Subcommand};

pub use draw::{draw_frames, draw_passes, load_font, write_png};
use input::file_name;
pub use input::{read_frames, read_run, FrameSeries, Run};

/// `--font` default (Debian/Ubuntu package `fonts-dejavu-core`).
pub const DEFAULT_FONT: &str = "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf";
/// `--size` default.
pub const DEFAULT_SIZE: (u32, u32) = (1200, 700);
/// `--size` bounds (smaller images have no room for the axes and the legend).
pub const MIN_SIZE: (u32, u32) = (400, 300);
pub const MAX_SIZE: u32 = 10_000;
/// The dashed reference line: one frame at 30 FPS.
pub const FPS30_MS: f64 = 1000.0 / 30.0;

/// Pass colours, in order of first appearance across the runs (Tableau 10 plus two); cycles
/// after 12 passes.
pub const PALETTE: [(u8, u8, u8); 12] = [
    (0x4e, 0x79, 0xa7),
    (0xf2, 0x8e, 0x2b),
    (0xe1, 0x57, 0x59),
    (0x76, 0xb7, 0xb2),
    (0x59, 0xa1, 0x4f),
    (0xed, 0xc9, 0x48),
    (0xb0, 0x7a, 0xa1),
    (0xff, 0x9d, 0xa7),
    (0x9c, 0x75, 0x5f),
    (0xba, 0xb0, 0xac),
    (0x2f, 0x4b, 0x7c),
    (0xa0, 0xcb, 0xe8),
];
/// `frames`: the `gpu_ms` line.
pub const GPU_COLOUR: (u8, u8, u8) = PALETTE[0];
/// `frames`: the `cpu_ms` line.
pub const CPU_COLOUR: (u8, u8, u8) = PALETTE[1];
/// Names of whole-submission totals (the bench table's total rows): never stacked as passes.
pub(crate) const TOTAL_NAMES: [&str; 6] = [
    "compute (GPU)",
    "graphics (GPU)",
    "frame GPU total",
    "frame CPU (wall)",
    "frame (GPU)",
    "compute + frame",
];

pub const USAGE: &str = "\
vkocean-plot: PNG charts of `vkocean bench frames` output

Usage:
  vkocean-plot passes OUT.png RUN.json [RUN.json ...] [--labels A,B,...]
      Per-pass stacked bars, one bar per RUN.json (bench frames --json, or --profile): each
      bar stacks that run's per-pass median GPU ms (passes without a median, or with 0, are
      left out). Bars are labelled with --labels, else with settings.quality and
      settings.size from the JSON.
  vkocean-plot frames OUT.png RUN.csv
      Frame time over frames from bench frames --csv: the gpu_ms and cpu_ms columns.

Both charts draw a dashed line at 33.3 ms (30 FPS).

Options:
  --labels A,B,...  bar labels for `passes`, one per RUN.json
  --size WxH        image size in pixels (default 1200x700; at least 400x300)
  --title TEXT      the chart's title (default: what and, for passes, the device; for
                    frames, the CSV's file name)
  --font PATH       TrueType/OpenType font for the text (default
                    /usr/share/fonts/truetype/dejavu/DejaVuSans.ttf, from fonts-dejavu-core)
  -h, --help        print this help

OUT.png is written to a temporary file in its directory and renamed, so a failed run leaves
no partial PNG. Exit status: 0 done, 1 runtime error (unreadable or malformed input, missing
font, write failure), 2 usage error.

The README charts: tools/charts (runs target/release/vkocean bench frames, then this).
";

/// A failure: the message (printed after `vkocean-plot: `) and its kind.
#[derive(Debug)]
pub enum Error {
    /// Bad command line (exit 2).
    Usage(String),
    /// Bad input, missing font, failed write (exit 1).
    Runtime(String),
}

impl Error {
    pub fn message(&self) -> &str {
        match self {
            Error::Usage(m) | Error::Runtime(m) => m,
        }
    }

    pub fn exit_code(&self) -> u8 {
        match self {
            Error::Usage(_) => 2,
            Error::Runtime(_) => 1,
        }
    }
}

fn usage(message: impl Into<String>) -> Error {
    Error::Usage(message.into())
}

pub(crate) fn runtime(message: impl Into<String>) -> Error {
    Error::Runtime(message.into())
}

/// Which chart, from which inputs.
#[derive(Debug, PartialEq)]
pub enum Chart {
    Passes {
        inputs: Vec<PathBuf>,
        labels: Option<Vec<String>>,
    },
    Frames {
        input: PathBuf,
    },
}

/// A parsed command line.
#[derive(Debug, PartialEq)]
pub struct Options {
    pub chart: Chart,
    pub out: PathBuf,
    pub size: (u32, u32),
    pub font: PathBuf,
    /// `--title`: replaces the default caption.
    pub title: Option<String>,
}

/// Runs the command line `args` (without the program name).
pub fn run(args: &[String]) -> Result<(), Error> {
    let Some(options) = parse_args(args)? else {
        print!("{USAGE}");
        return Ok(());
    };
    let (w, h) = options.size;
    // Inputs first (their errors name the file), then the font, then the drawing.
    enum Data {
        Passes(Vec<Run>),
        Frames(FrameSeries, String),
    }
    let data = match &options.chart {
        Chart::Passes { inputs, labels } => {
            let mut runs = inputs
                .iter()
                .map(|p| read_run(p))
                .collect::<Result<Vec<_>, _>>()?;
            if let Some(labels) = labels {
                for (run, label) in runs.iter_mut().zip(labels) {
                    run.label = label.clone();
                }
            }
            Data::Passes(runs)
        }
        Chart::Frames { input } => Data::Frames(read_frames(input)?, file_name(input)),
    };
    load_font(&options.font)?;
    let mut buf = vec![255u8; w as usize * h as usize * 3];
    match &data {
        Data::Passes(runs) => draw_passes(&mut buf, (w, h), runs, options.title.as_deref())?,
        Data::Frames(series, name) => {
            let title = options
                .title
                .clone()
                .unwrap_or_else(|| format!("Frame time per frame, {name}"));
            draw_frames(&mut buf, (w, h), series, &title)?
        }
    }
    write_png(&options.out, &buf, (w, h))
}

/// The command line as clap reads it; `parse_args` checks what clap cannot (labels per input,
/// one CSV, the size's range) with the messages of `--help`'s terms. The help text is `USAGE`.
#[derive(Parser, Debug)]
#[command(
    name = "vkocean-plot",
    disable_help_flag = true,
    disable_help_subcommand = true,
    disable_version_flag = true
)]
struct Args {
    #[arg(short, long, global = true)]
    help: bool,
    #[arg(long, global = true, value_name = "WxH")]
    size: Option<String>,
    #[arg(long, global = true, value_name = "PATH")]
    font: Option<PathBuf>,
    #[arg(long, global = true, value_name = "TEXT")]
    title: Option<String>,
    #[command(subcommand)]
    chart: Option<Sub>,
}

#[derive(Subcommand, Debug)]
enum Sub {
    Passes {
        out: Option<PathBuf>,
        inputs: Vec<PathBuf>,
        #[arg(long, value_delimiter = ',', value_name = "A,B,...")]
        labels: Option<Vec<String>>,
    },
    Frames {
        out: Option<PathBuf>,
        inputs: Vec<PathBuf>,
    },
}

/// Parses the command line; `None`: `--help`.
pub fn parse_args(args: &[String]) -> Result<Option<Options>, Error> {
    let argv = std::iter::once("vkocean-plot".to_string()).chain(args.iter().cloned());
    let parsed = Args::try_parse_from(argv).map_err(|e| {
        // clap's first line ("error: unexpected argument '--bogus' found") is the message.
        let text = e.to_string();
        let first = text.lines().next().unwrap_or("bad arguments");
        usage(format!(
            "{} (see --help)",
            first.trim_start_matches("error: ")
        ))
    })?;
    if parsed.help {
        return Ok(None);
    }
    let (command, out, inputs, labels) = match parsed.chart {
        None => return Err(usage("missing subcommand: passes or frames (see --help)")),
        Some(Sub::Passes {
            out,
            inputs,
            labels,
        }) => ("passes", out, inputs, labels),
        Some(Sub::Frames { out, inputs }) => ("frames", out, inputs, None),
    };
    let out = out.ok_or_else(|| usage(format!("{command}: missing OUT.png (see --help)")))?;
    if out.file_name().is_none() {
        return Err(usage(format!(
            "{command}: OUT.png {:?} is not a file name",
            out.display().to_string()
        )));
    }
    let chart = if command == "passes" {
        if inputs.is_empty() {
            return Err(usage("passes: missing RUN.json (see --help)"));
        }
        let labels: Option<Vec<String>> =
            labels.map(|l| l.iter().map(|s| s.trim().to_string()).collect());
        if let Some(labels) = &labels {
            if labels.len() != inputs.len() {
                return Err(usage(format!(
                    "passes: --labels has {} labels for {} RUN.json files",
                    labels.len(),
                    inputs.len()
                )));
            }
        }
        Chart::Passes { inputs, labels }
    } else {
        match <[PathBuf; 1]>::try_from(inputs) {
            Ok([input]) => Chart::Frames { input },
            Err(inputs) => {
                return Err(usage(format!(
                    "frames: expected one RUN.csv, got {} (see --help)",
                    inputs.len()
                )))
            }
        }
    };
    let size = match parsed.size {
        Some(s) => parse_size(&s)?,
        None => DEFAULT_SIZE,
    };
    Ok(Some(Options {
        chart,
        out,
        size,
        font: parsed.font.unwrap_or_else(|| PathBuf::from(DEFAULT_FONT)),
        title: parsed.title,
    }))
}

/// `WxH`, within `MIN_SIZE`..=`MAX_SIZE`.
pub fn parse_size(s: &str) -> Result<(u32, u32), Error> {
    let bad = || {
        usage(format!(
            "--size {s:?}: expected WxH with W >= {}, H >= {}, both <= {MAX_SIZE} (e.g. 1200x700)",
            MIN_SIZE.0, MIN_SIZE.1
        ))
    };
    let (w, h) = s.split_once(['x', 'X']).ok_or_else(bad)?;
    let (w, h): (u32, u32) = (
        w.trim().parse().map_err(|_| bad())?,
        h.trim().parse().map_err(|_| bad())?,
    );
    if w < MIN_SIZE.0 || h < MIN_SIZE.1 || w > MAX_SIZE || h > MAX_SIZE {
        return Err(bad());
    }
    Ok((w, h))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn args(a: &[&str]) -> Vec<String> {
        a.iter().map(|s| s.to_string()).collect()
    }

    #[test]
    fn parses_both_subcommands_and_options_anywhere() {
        let o = parse_args(&args(&[
            "--size",
            "800x600",
            "passes",
            "o.png",
            "a.json",
            "b.json",
            "--labels=x, y",
        ]))
        .unwrap()
        .unwrap();
        assert_eq!(o.size, (800, 600));
        assert_eq!(o.out, PathBuf::from("o.png"));
        assert_eq!(o.font, PathBuf::from(DEFAULT_FONT));
        assert_eq!(
            o.chart,
            Chart::Passes {
                inputs: vec!["a.json".into(), "b.json".into()],
                labels: Some(vec!["x".into(), "y".into()]),
            }
        );
        assert_eq!(o.title, None);
        let o = parse_args(&args(&[
            "frames", "o.png", "r.csv", "--font", "f.ttf", "--title", "T",
        ]))
        .unwrap()
        .unwrap();
        assert_eq!(
            o.chart,
            Chart::Frames {
                input: "r.csv".into()
            }
        );
        assert_eq!((o.size, o.font), (DEFAULT_SIZE, PathBuf::from("f.ttf")));
        assert_eq!(o.title.as_deref(), Some("T"));
        assert!(parse_args(&args(&["frames", "--help"])).unwrap().is_none());
    }

    #[test]
    fn sizes() {
        assert_eq!(parse_size("1200x700").unwrap(), (1200, 700));
        assert_eq!(parse_size("400X300").unwrap(), (400, 300));
        for bad in [
            "",
            "x",
            "1200",
            "1200x",
            "x700",
            "-5x300",
            "399x300",
            "400x299",
            "10001x700",
            "axb",
        ] {
            assert!(matches!(parse_size(bad), Err(Error::Usage(_))), "{bad:?}");
        }
    }
}
