//! Drawing the charts with plotters' bitmap backend into an RGB buffer (text through ab_glyph
//! with a font read at run time) and writing the PNG (`image`), all or nothing.

use std::fmt::Display;
use std::path::Path;

use image::codecs::png::{CompressionType, FilterType, PngEncoder};
use image::{ExtendedColorType, ImageEncoder};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::input::file_name;
use crate::input::{FrameSeries, Run};
use crate::{runtime, Error, CPU_COLOUR, DEFAULT_SIZE, FPS30_MS, GPU_COLOUR, PALETTE};

/// The 30 FPS line and its label.
const REFERENCE: RGBColor = RGBColor(90, 90, 90);
const GRID: RGBColor = RGBColor(225, 225, 225);
/// The family name `load_font` registers the `--font` file under.
const FONT: &str = "sans-serif";

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
// Long: one chart: axes, stacked bars, labels, legend and the 30 FPS line, in drawing order.
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
    use crate::input::Run;

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
