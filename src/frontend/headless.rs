//! Headless frontend: renders `--frames` frames into an offscreen target, reads the last one back
//! and writes `--screenshot` as PNG (with `--screenshot-every N`, frames 1, N+1, … as numbered
//! PNGs). Time starts at `--time` and advances by a fixed `--dt` (default 1/60 s) per frame, so a
//! run is reproducible.

use std::time::{Duration, Instant};

use ash::vk;

use super::clock::Clock;
use super::overlay::Overlay;
use super::session::{check_size, readback_buffer, Session};
use super::{Outcome, RunSettings};
use crate::gpu::{Context, Image, ImageDesc, Output};
use crate::output::{encode_png, place_all, PendingDir, PendingFile};
use crate::render::{Delivery, FrameInputs, OutputTarget, OverlayDraw};

/// Format of the offscreen target: 8-bit sRGB, the bytes a PNG stores.
const OUTPUT_FORMAT: vk::Format = vk::Format::R8G8B8A8_SRGB;
/// The same bytes in a UNORM format (`--unorm-output`, a test of the path windows without an
/// sRGB surface format take: the shaders encode sRGB).
const UNORM_OUTPUT_FORMAT: vk::Format = vk::Format::R8G8B8A8_UNORM;
/// Simulation time step per frame (s).
pub const FIXED_DT_S: f32 = 1.0 / 60.0;

// Long: a run in the order its promises need (output paths checked before any work, frames,
// everything encoded before the first file is committed); split, that order would be hidden.
pub fn run(s: &RunSettings) -> anyhow::Result<Outcome> {
    let screenshot = PendingFile::create_if("--screenshot", s.screenshot.as_deref())?;
    let profile = PendingFile::create_if("--profile", s.profile.as_deref())?;
    let frame_graph = PendingFile::create_if("--frame-graph", s.frame_graph.as_deref())?;
    let dump = s
        .dump
        .as_deref()
        .map(|dir| PendingDir::create("--dump", dir))
        .transpose()?;
    let frames = s.frames.unwrap_or(1);
    // `--screenshot-every`: the frames saved (0-based) and their files, all checked up front.
    let sequence = match (&s.screenshot, s.screenshot_every) {
        (Some(path), Some(every)) => (0..frames)
            .step_by(every as usize)
            .map(|i| {
                Ok((
                    i,
                    PendingFile::create("--screenshot", &numbered(path, i + 1, frames))?,
                ))
            })
            .collect::<anyhow::Result<Vec<_>>>()?,
        _ => Vec::new(),
    };
    let screenshot = screenshot.filter(|_| sequence.is_empty());
    let mut sequence = sequence.into_iter().peekable();
    let mut staged = Vec::new();

    let ctx = Context::headless(s.validation, s.validation_extras, s.gpu, s.scene.needs())?;
    let counters = ctx.counters();
    let format = if s.unorm_output {
        UNORM_OUTPUT_FORMAT
    } else {
        OUTPUT_FORMAT
    };
    let offscreen = Offscreen::with_format(&ctx, s.size, format)?;
    let (extent, output) = (offscreen.extent, offscreen.output());
    let readback = if screenshot.is_some() || sequence.peek().is_some() {
        Some(readback_buffer(&ctx, extent)?)
    } else {
        None
    };
    let mut session = Session::new(&ctx, format, extent, s)?;
    if let Some(file) = frame_graph {
        session.write_frame_graph_of(frames - 1, file);
    }
    let mut overlay = if s.overlay {
        session.keep_live_timings();
        Some(Overlay::new(&ctx, format, &s.tunables, s.quality.0, true)?)
    } else {
        None
    };
    let dt = s.dt_s.unwrap_or(FIXED_DT_S as f64);
    let mut clock = Clock::new(s.start_time_s, s.time_scale);

    let mut last_progress = Instant::now();
    for i in 0..frames {
        let in_sequence = sequence.peek().is_some_and(|(k, _)| *k == i);
        let last = screenshot.is_some() && i + 1 == frames;
        let capture = readback.as_ref().filter(|_| in_sequence || last);
        if i == 1 && !s.live_set.is_empty() {
            let time_scale = apply_live_set(s, &mut session)?;
            clock.set(i as f64 * dt, time_scale, false);
        }
        let inputs = FrameInputs {
            time_s: clock.at(i as f64 * dt),
            ..FrameInputs::default()
        };
        let delivery = Delivery {
            readback: capture,
            present: None,
        };
        let draw = match overlay.as_mut() {
            Some(o) => Some(overlay_frame(o, &mut session, extent, i as f64 * dt)?),
            None => None,
        };
        session.frame(&output, &inputs, &delivery, draw)?;
        if let (true, Some(buffer)) = (in_sequence, &readback) {
            // Waits for this frame; the next capture reuses the buffer after this read.
            let pixels = session.frames.read_back(buffer)?;
            let png = encode_png(extent.width, extent.height, &pixels)?;
            let (_, file) = sequence.next().expect("peeked");
            staged.push(file.stage(&png)?);
        }
        if s.stats {
            session.print_stats()?;
            crate::output::stdout_status()?;
        }
        crate::interrupt::check()?;
        if s.log_resources.is_some_and(|n| (i + 1) % n == 0) {
            let kib = |key| proc_status_kib(key).map_or("unknown".into(), |v| format!("{v} kB"));
            eprintln!(
                "vkocean: frame {}: resident {} (peak {}), {} Vulkan objects live",
                i + 1,
                kib("VmRSS:"),
                kib("VmHWM:"),
                ctx.live_objects()
            );
        }
        if last_progress.elapsed() > Duration::from_secs(5) {
            eprintln!(
                "vkocean: frame {}/{frames} ({:.1} s)",
                i + 1,
                session.elapsed_s()
            );
            last_progress = Instant::now();
        }
    }
    let finished = session.finish(s.size)?;
    let dump_contents = match dump {
        Some(_) => session.dump_contents()?,
        None => Vec::new(),
    };
    // Encode before writing anything, so a failure leaves no file at all.
    let png = match &readback {
        Some(buffer) => {
            let pixels = session.frames.read_back(buffer)?;
            Some(encode_png(extent.width, extent.height, &pixels)?)
        }
        None => None,
    };
    // Every output staged, then all moved into place together (or none, after a signal).
    if let (Some(file), Some(png)) = (screenshot, png) {
        staged.push(file.stage(&png)?);
    }
    if let Some(dir) = dump {
        // Gerstner dumps have no h0.npy: the files are the ones the session returns.
        let files: Vec<(&str, Vec<u8>)> = dump_contents.into_iter().collect();
        staged.extend(dir.stage(&files)?);
    }
    let with_table = profile.is_some();
    staged.extend(finished.stage_profile(profile)?);
    place_all(staged)?;
    finished.report(with_table, "");
    if let Some([x, y, w, h]) = overlay.as_ref().and_then(|o| o.rect) {
        eprintln!("vkocean: overlay drawn at {x:.0},{y:.0} size {w:.0}x{h:.0}");
    }
    drop(overlay);
    Ok(Outcome { counters })
}

/// `--live-set`: the tunables changed as the overlay changes them, resolved as flags and
/// applied between frames; returns the new time scale.
fn apply_live_set(s: &RunSettings, session: &mut Session) -> anyhow::Result<f64> {
    let mut tunables = s.tunables.clone();
    for (key, value) in &s.live_set {
        tunables.set(key, value).map_err(anyhow::Error::msg)?;
    }
    let retuned = (s.retune.0)(&tunables).map_err(anyhow::Error::msg)?;
    session.retune(&retuned)?;
    Ok(retuned.time_scale)
}

/// The overlay's panel for a headless frame at `time_s` (no input: it is laid out as shown).
fn overlay_frame<'o>(
    o: &'o mut Overlay,
    session: &mut Session,
    extent: vk::Extent2D,
    time_s: f64,
) -> anyhow::Result<OverlayDraw<'o>> {
    let size = egui::vec2(extent.width as f32, extent.height as f32);
    let input = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(egui::Pos2::ZERO, size)),
        time: Some(time_s),
        ..egui::RawInput::default()
    };
    let (_, textures) = o.run(input, session);
    o.upload(textures)?;
    Ok(o.draw())
}

/// `path` with frame `number` (1-based) before its extension, zero-padded to the digits of
/// `frames`: ocean.png, 7 of 25 -> ocean-07.png.
fn numbered(path: &std::path::Path, number: u64, frames: u64) -> std::path::PathBuf {
    let stem = path.file_stem().unwrap_or_default().to_string_lossy();
    let width = frames.to_string().len();
    path.with_file_name(format!("{stem}-{number:0width$}.png"))
}

/// The offscreen colour target both the headless run and `bench frames` render into.
pub struct Offscreen {
    pub image: Image,
    pub extent: vk::Extent2D,
    pub format: vk::Format,
}

impl Offscreen {
    /// Format of the target: [`OUTPUT_FORMAT`].
    pub const FORMAT: vk::Format = OUTPUT_FORMAT;

    pub fn new(ctx: &std::sync::Arc<Context>, size: (u32, u32)) -> anyhow::Result<Offscreen> {
        Offscreen::with_format(ctx, size, OUTPUT_FORMAT)
    }

    /// A target in another 8-bit RGBA format (`UNORM_OUTPUT_FORMAT`).
    fn with_format(
        ctx: &std::sync::Arc<Context>,
        size: (u32, u32),
        format: vk::Format,
    ) -> anyhow::Result<Offscreen> {
        check_size(ctx, size)?;
        let extent = vk::Extent2D {
            width: size.0,
            height: size.1,
        };
        let image = Image::new(
            ctx,
            &ImageDesc::new(
                "headless output",
                extent,
                format,
                // Colour attachment: the overlay draws into it (--overlay).
                vk::ImageUsageFlags::TRANSFER_DST
                    | vk::ImageUsageFlags::TRANSFER_SRC
                    | vk::ImageUsageFlags::COLOR_ATTACHMENT,
            ),
        )?;
        Ok(Offscreen {
            image,
            extent,
            format,
        })
    }

    /// The target as the renderer's output (its state carries over from frame to frame).
    pub fn output(&self) -> OutputTarget<'_> {
        OutputTarget::new(Output::Image(&self.image), true)
    }
}

/// Inputs of headless frame `i`: time starts at `--time` and advances by `--dt` (default
/// [`FIXED_DT_S`]).
pub fn frame_inputs(s: &RunSettings, i: u64) -> FrameInputs {
    FrameInputs {
        time_s: Clock::new(s.start_time_s, s.time_scale)
            .at(i as f64 * s.dt_s.unwrap_or(FIXED_DT_S as f64)),
        ..FrameInputs::default()
    }
}

/// A kB figure of this process from /proc/self/status (Linux), e.g. `VmRSS:` (resident set) or
/// `VmHWM:` (its peak); `None` elsewhere.
fn proc_status_kib(key: &str) -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with(key))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

#[cfg(test)]
mod tests {
    use super::numbered;
    use std::path::{Path, PathBuf};

    #[test]
    fn sequence_files_are_numbered_from_one_to_the_width_of_the_frame_count() {
        let at = |path: &str, n, frames| numbered(Path::new(path), n, frames);
        assert_eq!(
            at("out/ocean.png", 7, 25),
            PathBuf::from("out/ocean-07.png")
        );
        assert_eq!(at("ocean.png", 1, 1), PathBuf::from("ocean-1.png"));
        assert_eq!(at("a.b.png", 100, 1000), PathBuf::from("a.b-0100.png"));
    }
}
