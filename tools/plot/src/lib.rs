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

use std::fmt::Display;
use std::path::{Path, PathBuf};

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use serde_json::Value;

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
/// The 30 FPS line and its label.
const REFERENCE: RGBColor = RGBColor(90, 90, 90);
const GRID: RGBColor = RGBColor(225, 225, 225);
const FONT: &str = "sans-serif";

/// Names of whole-submission totals (the bench table's total rows): never stacked as passes.
const TOTAL_NAMES: [&str; 6] = [
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

fn runtime(message: impl Into<String>) -> Error {
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

/// `None`: `--help`.
pub fn parse_args(args: &[String]) -> Result<Option<Options>, Error> {
    let mut positional = Vec::new();
    let (mut labels, mut size, mut font, mut title) = (None, None, None, None);
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        if arg == "-h" || arg == "--help" {
            return Ok(None);
        }
        if arg == "--" {
            positional.extend(it.by_ref().cloned());
            break;
        }
        if let Some(option) = arg.strip_prefix("--") {
            let (name, inline) = match option.split_once('=') {
                Some((n, v)) => (n, Some(v.to_string())),
                None => (option, None),
            };
            let slot = match name {
                "labels" => &mut labels,
                "size" => &mut size,
                "font" => &mut font,
                "title" => &mut title,
                _ => return Err(usage(format!("unknown option --{name} (see --help)"))),
            };
            let value = match inline {
                Some(v) => v,
                None => it
                    .next()
                    .cloned()
                    .ok_or_else(|| usage(format!("--{name} needs a value (see --help)")))?,
            };
            *slot = Some(value);
        } else if arg.starts_with('-') && arg.len() > 1 {
            return Err(usage(format!("unknown option {arg} (see --help)")));
        } else {
            positional.push(arg.clone());
        }
    }

    let mut positional = positional.into_iter();
    let Some(command) = positional.next() else {
        return Err(usage("missing subcommand: passes or frames (see --help)"));
    };
    if command != "passes" && command != "frames" {
        return Err(usage(format!(
            "unknown subcommand {command:?}: expected passes or frames (see --help)"
        )));
    }
    let out = PathBuf::from(
        positional
            .next()
            .ok_or_else(|| usage(format!("{command}: missing OUT.png (see --help)")))?,
    );
    if out.file_name().is_none() {
        return Err(usage(format!(
            "{command}: OUT.png {:?} is not a file name",
            out.display().to_string()
        )));
    }
    let inputs: Vec<PathBuf> = positional.map(PathBuf::from).collect();
    let chart = if command == "passes" {
        if inputs.is_empty() {
            return Err(usage("passes: missing RUN.json (see --help)"));
        }
        let labels: Option<Vec<String>> = labels.map(|l: String| {
            l.split(',')
                .map(|s| s.trim().to_string())
                .collect::<Vec<_>>()
        });
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
        if labels.is_some() {
            return Err(usage("frames: --labels applies to passes only"));
        }
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
    let size = match size {
        Some(s) => parse_size(&s)?,
        None => DEFAULT_SIZE,
    };
    Ok(Some(Options {
        chart,
        out,
        size,
        font: font.map_or_else(|| PathBuf::from(DEFAULT_FONT), PathBuf::from),
        title,
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

fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    )
}

fn read_text(path: &Path) -> Result<String, Error> {
    std::fs::read_to_string(path)
        .map_err(|e| runtime(format!("cannot read {}: {e}", path.display())))
}

/// One `passes` bar: the run's timed passes in report order.
#[derive(Debug, Clone, PartialEq)]
pub struct Run {
    pub label: String,
    pub device: Option<String>,
    /// (pass name, median GPU ms > 0).
    pub passes: Vec<(String, f64)>,
}

/// Reads a bench frames / `--profile` JSON report.
pub fn read_run(path: &Path) -> Result<Run, Error> {
    let shown = path.display();
    let value: Value = serde_json::from_str(&read_text(path)?)
        .map_err(|e| runtime(format!("{shown}: not valid JSON: {e}")))?;
    let entries = value.get("passes").and_then(Value::as_array).ok_or_else(|| {
        runtime(format!(
            "{shown}: no \"passes\" array (expected the --json of vkocean bench frames or --profile)"
        ))
    })?;
    let mut passes = Vec::new();
    for (i, entry) in entries.iter().enumerate() {
        let name = entry
            .get("name")
            .and_then(Value::as_str)
            .ok_or_else(|| runtime(format!("{shown}: passes[{i}] has no \"name\" string")))?;
        let median = match entry.get("gpu_ms").and_then(|g| g.get("median")) {
            None | Some(Value::Null) => continue,
            Some(m) => m
                .as_f64()
                .filter(|m| m.is_finite() && *m >= 0.0)
                .ok_or_else(|| {
                    runtime(format!(
                        "{shown}: passes[{i}] ({name}): gpu_ms.median {m} is not a number >= 0"
                    ))
                })?,
        };
        if median > 0.0 && !TOTAL_NAMES.contains(&name) {
            passes.push((name.to_string(), median));
        }
    }
    if passes.is_empty() {
        return Err(runtime(format!(
            "{shown}: no pass has a GPU median above 0 (no timestamps?)"
        )));
    }
    let setting = |key: &str| {
        value
            .get("settings")
            .and_then(|s| s.get(key))
            .and_then(Value::as_str)
    };
    let label = match (setting("quality"), setting("size")) {
        (Some(q), Some(s)) => format!("{q} {s}"),
        (Some(one), None) | (None, Some(one)) => one.to_string(),
        (None, None) => path
            .file_stem()
            .map_or_else(|| file_name(path), |s| s.to_string_lossy().into_owned()),
    };
    Ok(Run {
        label,
        device: value
            .get("device")
            .and_then(Value::as_str)
            .map(str::to_string),
        passes,
    })
}

/// The `frames` chart's data: per CSV row the frame index and its GPU and CPU ms (`None`: an
/// empty cell).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct FrameSeries {
    pub frame: Vec<f64>,
    pub gpu_ms: Vec<Option<f64>>,
    pub cpu_ms: Vec<Option<f64>>,
}

/// Reads a bench frames `--csv`.
pub fn read_frames(path: &Path) -> Result<FrameSeries, Error> {
    let shown = path.display();
    let text = read_text(path)?;
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty());
    let Some((_, header)) = lines.next() else {
        return Err(runtime(format!(
            "{shown}: empty CSV (expected the --csv of vkocean bench frames)"
        )));
    };
    let header: Vec<&str> = header.split(',').map(str::trim).collect();
    let column = |name: &str| {
        header.iter().position(|h| *h == name).ok_or_else(|| {
            runtime(format!(
                "{shown}: the header has no {name} column (expected the --csv of vkocean bench frames)"
            ))
        })
    };
    let (frame_col, gpu_col, cpu_col) = (column("frame")?, column("gpu_ms")?, column("cpu_ms")?);
    let mut series = FrameSeries::default();
    for (line, row) in lines {
        let cells: Vec<&str> = row.split(',').map(str::trim).collect();
        if cells.len() != header.len() {
            return Err(runtime(format!(
                "{shown}:{line}: {} cells, the header has {}",
                cells.len(),
                header.len()
            )));
        }
        let number = |col: usize| -> Result<Option<f64>, Error> {
            let cell = cells[col];
            if cell.is_empty() {
                return Ok(None);
            }
            cell.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && *v >= 0.0)
                .map(Some)
                .ok_or_else(|| {
                    runtime(format!(
                        "{shown}:{line}: {} {cell:?} is not a number >= 0",
                        header[col]
                    ))
                })
        };
        let frame = number(frame_col)?
            .ok_or_else(|| runtime(format!("{shown}:{line}: empty frame cell")))?;
        series.frame.push(frame);
        series.gpu_ms.push(number(gpu_col)?);
        series.cpu_ms.push(number(cpu_col)?);
    }
    if series.frame.is_empty() {
        return Err(runtime(format!("{shown}: no frames, only a header")));
    }
    if series
        .gpu_ms
        .iter()
        .chain(&series.cpu_ms)
        .all(Option::is_none)
    {
        return Err(runtime(format!("{shown}: no gpu_ms or cpu_ms values")));
    }
    Ok(series)
}

/// Registers the font file for plotters' ab_glyph text (once per process).
pub fn load_font(path: &Path) -> Result<(), Error> {
    let bytes = std::fs::read(path).map_err(|e| {
        runtime(format!(
            "cannot read font {}: {e} (install fonts-dejavu-core or pass --font PATH)",
            path.display()
        ))
    })?;
    // plotters keeps registered fonts for the life of the process.
    let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
    plotters::style::register_font(FONT, FontStyle::Normal, bytes).map_err(|_| {
        runtime(format!(
            "font {}: not a TrueType/OpenType font",
            path.display()
        ))
    })
}

fn draw_error(e: impl Display) -> Error {
    runtime(format!("drawing failed: {e}"))
}

fn rgb((r, g, b): (u8, u8, u8)) -> RGBColor {
    RGBColor(r, g, b)
}

/// Sizes scale with the image (1 at the default 1200x700).
fn scale((w, h): (u32, u32)) -> f64 {
    (w as f64 / DEFAULT_SIZE.0 as f64)
        .min(h as f64 / DEFAULT_SIZE.1 as f64)
        .clamp(0.5, 4.0)
}

fn px(v: f64) -> u32 {
    v.round().max(1.0) as u32
}

/// Pass names across runs in report order (a name first seen in a later run goes after the
/// name before it in that run).
fn pass_order(runs: &[Run]) -> Vec<String> {
    let mut order: Vec<String> = Vec::new();
    for run in runs {
        let mut at = 0;
        for (name, _) in &run.passes {
            match order.iter().position(|n| n == name) {
                Some(i) => at = i + 1,
                None => {
                    order.insert(at, name.clone());
                    at += 1;
                }
            }
        }
    }
    order
}

/// Space at the right end of the x range for the "30 FPS" label, in x units, for a plot of
/// about `plot_w` pixels showing `span` units.
fn label_room(span: f64, plot_w: f64, label_px: f64) -> f64 {
    (label_px * span / (plot_w - label_px).max(1.0)).max(0.0)
}

/// The legend beside the chart: (colour, text, swatch is a line).
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    entries: &[(RGBColor, String, bool)],
    top: i32,
    s: f64,
) -> Result<(), Error> {
    let text = (FONT, 16.0 * s).into_font().color(&BLACK);
    let x = (8.0 * s) as i32;
    let row = (26.0 * s) as i32;
    let sw = (16.0 * s) as i32;
    area.draw(&Text::new(
        title.to_string(),
        (x, top),
        text.clone().pos(Pos::new(HPos::Left, VPos::Center)),
    ))
    .map_err(draw_error)?;
    for (k, (colour, label, line)) in entries.iter().enumerate() {
        let y = top + row * (k as i32 + 1);
        if *line {
            area.draw(&PathElement::new(
                vec![(x, y), (x + sw + sw / 2, y)],
                colour.stroke_width(px(3.0 * s)),
            ))
        } else {
            area.draw(&Rectangle::new(
                [(x, y - sw / 2), (x + sw, y + sw / 2)],
                colour.filled(),
            ))
        }
        .map_err(draw_error)?;
        let label = fit(
            area,
            label,
            &text,
            area.dim_in_pixel().0 as i32 - x - sw * 2,
        )?;
        area.draw(&Text::new(
            label,
            (x + sw * 2, y),
            text.clone().pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(draw_error)?;
    }
    Ok(())
}

/// `text`, cut short with an ellipsis to fit `max_w` pixels.
fn fit<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    style: &TextStyle,
    max_w: i32,
) -> Result<String, Error> {
    let mut out = text.to_string();
    let mut chars: Vec<char> = text.chars().collect();
    while !chars.is_empty()
        && area.estimate_text_size(&out, style).map_err(draw_error)?.0 as i32 > max_w
    {
        chars.pop();
        out = chars.iter().collect::<String>() + "\u{2026}";
    }
    Ok(out)
}

/// A chart's caption, shortened to the width of `area`.
fn fit_caption<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    text: &str,
    s: f64,
) -> Result<String, Error> {
    let style = TextStyle::from((FONT, 24.0 * s).into_font());
    fit(
        area,
        text,
        &style,
        area.dim_in_pixel().0 as i32 - (16.0 * s) as i32,
    )
}

/// Splits the image into the chart and a legend column on the right.
fn legend_width(w: u32, s: f64) -> u32 {
    ((240.0 * s) as u32).min(w / 3)
}

/// The per-pass stacked bars into `buf` (RGB, `size`); `title` replaces the default caption.
pub fn draw_passes(
    buf: &mut [u8],
    size: (u32, u32),
    runs: &[Run],
    title: Option<&str>,
) -> Result<(), Error> {
    let (w, _) = size;
    let s = scale(size);
    let root = BitMapBackend::with_buffer(buf, size).into_drawing_area();
    root.fill(&WHITE).map_err(draw_error)?;
    let legend_w = legend_width(w, s);
    let (plot_area, legend_area) = root.split_horizontally(w - legend_w);

    let order = pass_order(runs);
    let colour = |name: &str| {
        let i = order.iter().position(|n| n == name).unwrap_or(0);
        rgb(PALETTE[i % PALETTE.len()])
    };
    let totals: Vec<f64> = runs
        .iter()
        .map(|r| r.passes.iter().map(|p| p.1).sum())
        .collect();
    let y_max = totals.iter().copied().fold(FPS30_MS, f64::max) * 1.15;
    let n = runs.len() as f64;
    let (margin, y_area, x_area) = (16.0 * s, 72.0 * s, 40.0 * s);
    let plot_w = (w - legend_w) as f64 - y_area - 2.0 * margin;
    let x_max = n + label_room(n, plot_w, 72.0 * s);

    let device = runs[0].device.as_deref();
    let caption = match (title, device) {
        (Some(t), _) => t.to_string(),
        (None, Some(d)) if runs.iter().all(|r| r.device.as_deref() == Some(d)) => {
            format!("GPU time per pass (median), {d}")
        }
        _ => "GPU time per pass (median)".to_string(),
    };
    let mut chart = ChartBuilder::on(&plot_area)
        .margin(px(margin))
        .x_label_area_size(px(x_area))
        .y_label_area_size(px(y_area))
        .caption(fit_caption(&plot_area, &caption, s)?, (FONT, 24.0 * s))
        .build_cartesian_2d(0.0..x_max, 0.0..y_max)
        .map_err(draw_error)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(0)
        .max_light_lines(0)
        .bold_line_style(GRID)
        .y_desc("GPU ms (median per pass)")
        .y_label_formatter(&|v| format!("{v:.0}"))
        .label_style((FONT, 15.0 * s))
        .axis_desc_style((FONT, 17.0 * s))
        .draw()
        .map_err(draw_error)?;

    let value_style = (FONT, 15.0 * s)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Center, VPos::Bottom));
    let half = 0.3 * (n / 3.0).min(1.0);
    for (i, run) in runs.iter().enumerate() {
        let cx = i as f64 + 0.5;
        let mut y = 0.0;
        for (name, ms) in &run.passes {
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(cx - half, y), (cx + half, y + ms)],
                    colour(name).filled(),
                )))
                .map_err(draw_error)?;
            y += ms;
        }
        chart
            .draw_series(std::iter::once(
                EmptyElement::at((cx, y))
                    + Text::new(
                        format!("{y:.1} ms"),
                        (0, -(4.0 * s) as i32),
                        value_style.clone(),
                    ),
            ))
            .map_err(draw_error)?;
    }
    draw_reference(&mut chart, x_max, s)?;

    let label_style = (FONT, 17.0 * s)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Center, VPos::Top));
    for (i, run) in runs.iter().enumerate() {
        let (bx, by) = chart.backend_coord(&(i as f64 + 0.5, 0.0));
        root.draw(&Text::new(
            run.label.clone(),
            (bx, by + (8.0 * s) as i32),
            label_style.clone(),
        ))
        .map_err(draw_error)?;
    }

    // Top of the stack first, as the bars read.
    let entries: Vec<(RGBColor, String, bool)> = order
        .iter()
        .rev()
        .map(|name| (colour(name), name.clone(), false))
        .collect();
    let top = chart.backend_coord(&(0.0, y_max)).1;
    draw_legend(&legend_area, "Pass (as stacked)", &entries, top, s)?;
    root.present().map_err(draw_error)?;
    Ok(())
}

/// The dashed 30 FPS line across the plot, labelled at its right end.
fn draw_reference<DB: DrawingBackend>(
    chart: &mut ChartContext<DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    x_max: f64,
    s: f64,
) -> Result<(), Error> {
    let x_min = chart.x_range().start;
    chart
        .draw_series(DashedLineSeries::new(
            [(x_min, FPS30_MS), (x_max, FPS30_MS)],
            px(10.0 * s),
            px(6.0 * s),
            REFERENCE.stroke_width(px(2.0 * s)),
        ))
        .map_err(draw_error)?;
    let style = (FONT, 15.0 * s)
        .into_font()
        .color(&REFERENCE)
        .pos(Pos::new(HPos::Right, VPos::Bottom));
    chart
        .draw_series(std::iter::once(
            EmptyElement::at((x_max, FPS30_MS))
                + Text::new("30 FPS", (-(4.0 * s) as i32, -(4.0 * s) as i32), style),
        ))
        .map_err(draw_error)?;
    Ok(())
}

/// Runs of consecutive values (gaps at empty cells).
fn segments(frame: &[f64], values: &[Option<f64>]) -> Vec<Vec<(f64, f64)>> {
    let mut out: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
    for (f, v) in frame.iter().zip(values) {
        match v {
            Some(v) => out.last_mut().expect("never empty").push((*f, *v)),
            None => out.push(Vec::new()),
        }
    }
    out.retain(|s| !s.is_empty());
    out
}

/// Frame time over frames into `buf` (RGB, `size`).
pub fn draw_frames(
    buf: &mut [u8],
    size: (u32, u32),
    series: &FrameSeries,
    title: &str,
) -> Result<(), Error> {
    let (w, _) = size;
    let s = scale(size);
    let root = BitMapBackend::with_buffer(buf, size).into_drawing_area();
    root.fill(&WHITE).map_err(draw_error)?;
    let legend_w = legend_width(w, s);
    let (plot_area, legend_area) = root.split_horizontally(w - legend_w);

    let first = series.frame.iter().copied().fold(f64::INFINITY, f64::min);
    let last = series
        .frame
        .iter()
        .copied()
        .fold(f64::NEG_INFINITY, f64::max);
    let (x_min, last) = if last > first {
        (first, last)
    } else {
        (first - 0.5, first + 0.5)
    };
    let y_top = series
        .gpu_ms
        .iter()
        .chain(&series.cpu_ms)
        .flatten()
        .copied()
        .fold(FPS30_MS, f64::max);
    let y_max = y_top * 1.15;
    let (margin, y_area, x_area) = (16.0 * s, 72.0 * s, 56.0 * s);
    let plot_w = (w - legend_w) as f64 - y_area - 2.0 * margin;
    let x_max = last + label_room(last - x_min, plot_w, 72.0 * s);

    let mut chart = ChartBuilder::on(&plot_area)
        .margin(px(margin))
        .x_label_area_size(px(x_area))
        .y_label_area_size(px(y_area))
        .caption(fit_caption(&plot_area, title, s)?, (FONT, 24.0 * s))
        .build_cartesian_2d(x_min..x_max, 0.0..y_max)
        .map_err(draw_error)?;
    chart
        .configure_mesh()
        .max_light_lines(0)
        .bold_line_style(GRID)
        // At most one label per frame: whole-frame ticks only.
        .x_labels(((x_max - x_min).floor() as usize + 1).min(11))
        .x_desc("frame")
        .y_desc("ms")
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .label_style((FONT, 15.0 * s))
        .axis_desc_style((FONT, 17.0 * s))
        .draw()
        .map_err(draw_error)?;
    draw_reference(&mut chart, x_max, s)?;

    let lines = [
        (&series.gpu_ms, rgb(GPU_COLOUR), "GPU (gpu_ms)"),
        (&series.cpu_ms, rgb(CPU_COLOUR), "CPU wall (cpu_ms)"),
    ];
    let markers = series.frame.len() <= 150;
    for (values, colour, _) in &lines {
        for segment in segments(&series.frame, values) {
            chart
                .draw_series(LineSeries::new(
                    segment.iter().copied(),
                    colour.stroke_width(px(2.0 * s)),
                ))
                .map_err(draw_error)?;
            if markers || segment.len() == 1 {
                chart
                    .draw_series(
                        segment
                            .iter()
                            .map(|p| Circle::new(*p, px(3.0 * s), colour.filled())),
                    )
                    .map_err(draw_error)?;
            }
        }
    }
    let entries: Vec<(RGBColor, String, bool)> = lines
        .iter()
        .map(|(_, colour, label)| (*colour, label.to_string(), true))
        .collect();
    let top = chart.backend_coord(&(x_min, y_max)).1;
    draw_legend(&legend_area, "Series", &entries, top, s)?;
    root.present().map_err(draw_error)?;
    Ok(())
}

/// Encodes `buf` (RGB) as a PNG and writes it to `out` through a temporary file in the same
/// directory, renamed into place (a failure leaves no partial file).
pub fn write_png(out: &Path, buf: &[u8], (w, h): (u32, u32)) -> Result<(), Error> {
    let shown = out.display();
    let mut png = Vec::new();
    PngEncoder::new_with_quality(&mut png, CompressionType::Best, FilterType::Adaptive)
        .write_image(buf, w, h, ExtendedColorType::Rgb8)
        .map_err(|e| runtime(format!("{shown}: PNG encoding failed: {e}")))?;
    let dir = match out.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let tmp = dir.join(format!(".{}.{}.tmp", file_name(out), std::process::id()));
    let result = std::fs::write(&tmp, &png).and_then(|()| std::fs::rename(&tmp, out));
    result.map_err(|e| {
        let _ = std::fs::remove_file(&tmp);
        runtime(format!("cannot write {shown}: {e}"))
    })
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

    #[test]
    fn pass_order_merges_runs() {
        let run = |names: &[&str]| Run {
            label: String::new(),
            device: None,
            passes: names.iter().map(|n| (n.to_string(), 1.0)).collect(),
        };
        let order = pass_order(&[
            run(&["evolve", "fft", "water"]),
            run(&["evolve", "sky cube", "water", "sky"]),
        ]);
        assert_eq!(order, ["evolve", "sky cube", "fft", "water", "sky"]);
    }

    #[test]
    fn segments_split_at_gaps() {
        let frames = [1.0, 2.0, 3.0, 4.0, 5.0];
        let values = [Some(1.0), None, Some(3.0), Some(4.0), None];
        assert_eq!(
            segments(&frames, &values),
            vec![vec![(1.0, 1.0)], vec![(3.0, 3.0), (4.0, 4.0)]]
        );
    }
}
