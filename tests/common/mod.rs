//! Helpers shared by the integration tests: run the `vkocean` binary, make scratch directories,
//! read the exit summary lines.
#![allow(dead_code)] // each test binary uses a different subset

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The binary under test.
pub fn bin() -> &'static str {
    env!("CARGO_BIN_EXE_vkocean")
}

/// `vkocean ARGS` with the given extra environment; DISPLAY removed unless `keep_display`.
pub fn run_with_env(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(bin());
    cmd.args(args)
        .env_remove("RUST_LOG")
        .env_remove("VK_INSTANCE_LAYERS");
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.output().expect("the vkocean binary runs")
}

pub fn run(args: &[&str]) -> Output {
    run_with_env(args, &[])
}

pub fn stderr(out: &Output) -> String {
    String::from_utf8_lossy(&out.stderr).into_owned()
}

/// A fresh, empty scratch directory for one test.
pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("vkocean-test-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("temp dir is writable");
    dir
}

/// File names in `dir` (hidden ones included).
pub fn entries(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .expect("dir exists")
        .map(|e| e.expect("entry").file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Asserts a `--validation` run exited 0 with `validation: 0 warnings, 0 errors`; returns its
/// stderr. `what` names the run in failure messages.
pub fn clean_run(out: &Output, what: &str) -> String {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(0), "{what}: {err}");
    assert_eq!(validation_counts(&err), Some((0, 0)), "{what}: {err}");
    err
}

/// The pass names of a `--profile` run of 7 frames of `size` with `args` (validation on,
/// asserted clean); `name` names the scratch directory.
pub fn profiled_passes(name: &str, size: &str, args: &[&str]) -> Vec<String> {
    let dir = scratch(&format!("profile-{name}"));
    let profile = dir.join("p.json");
    let mut all = vec![
        "--headless",
        "--validation",
        "--size",
        size,
        "--frames",
        "7",
        "--profile",
        profile.to_str().expect("temp paths are UTF-8"),
    ];
    all.extend_from_slice(args);
    clean_run(&run(&all), &format!("{all:?}"));
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&profile).expect("profile written"))
            .expect("profile is JSON");
    let _ = std::fs::remove_dir_all(&dir);
    json["passes"]
        .as_array()
        .expect("passes")
        .iter()
        .map(|p| p["name"].as_str().expect("name").to_string())
        .collect()
}

/// Parses `validation: N warnings, M errors` from stderr.
pub fn validation_counts(stderr: &str) -> Option<(u32, u32)> {
    let line = stderr.lines().find(|l| l.starts_with("validation: "))?;
    let nums: Vec<u32> = line
        .split(|c: char| !c.is_ascii_digit())
        .filter(|s| !s.is_empty())
        .map(|s| s.parse().expect("digits"))
        .collect();
    match nums.as_slice() {
        [w, e] => Some((*w, *e)),
        _ => None,
    }
}

/// Parses the frame count from the exit summary `vkocean: N frames at WxH ...`.
pub fn frames_rendered(stderr: &str) -> Option<u64> {
    let line = stderr
        .lines()
        .find(|l| l.starts_with("vkocean: ") && l.contains(" frames at "))?;
    line.trim_start_matches("vkocean: ")
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}

/// Decodes a PNG into (width, height, RGBA8 pixels).
pub fn read_png(path: &Path) -> (u32, u32, Vec<u8>) {
    let img = image::open(path)
        .unwrap_or_else(|e| panic!("{} is a PNG: {e}", path.display()))
        .to_rgba8();
    (img.width(), img.height(), img.into_raw())
}

/// One in-process Vulkan device at a time: Debian 13's Vulkan loader (1.4.309) walks its device
/// list without the writers' lock (Vulkan-Loader issue 2018), so a test naming an object while
/// another test thread destroys its device crashes (SIGSEGV in libvulkan.so.1). vkocean itself
/// has one device per process; tests that make their own hold this from [`gpu_context`] until
/// [`assert_validation_clean`] (or the test's end).
static DEVICE_LOCK: std::sync::Mutex<()> = std::sync::Mutex::new(());

/// A test thread's hold on [`DEVICE_LOCK`], with how many of its contexts are not yet checked.
type DeviceHold = (std::sync::MutexGuard<'static, ()>, usize);

std::thread_local! {
    /// This test thread's hold on [`DEVICE_LOCK`] (released when the count returns to zero, or
    /// when the test's thread ends).
    static DEVICE_HELD: std::cell::RefCell<Option<DeviceHold>> =
        const { std::cell::RefCell::new(None) };
}

/// A validation-enabled Vulkan context; its messages go to the log, shown when a test fails.
/// The thread holds the device lock ([`DEVICE_LOCK`]) until [`assert_validation_clean`].
pub fn gpu_context() -> std::sync::Arc<vkocean::gpu::Context> {
    DEVICE_HELD.with(|held| {
        let mut held = held.borrow_mut();
        match held.as_mut() {
            Some((_, contexts)) => *contexts += 1,
            None => {
                let guard = DEVICE_LOCK.lock().unwrap_or_else(|p| p.into_inner());
                *held = Some((guard, 1));
            }
        }
    });
    let _ = env_logger::builder()
        .is_test(true)
        .filter_level(log::LevelFilter::Warn)
        .try_init();
    vkocean::gpu::Context::new(&vkocean::gpu::ContextDesc {
        validation: true,
        validation_extras: Default::default(),
        gpu_index: None,
        needs: vkocean::gpu::Needs::RENDERING,
        window: None,
    })
    .expect("a Vulkan device (tools/setup installs lavapipe)")
}

/// A 16x16 RGBA8 (UNORM) image with `usage`, one layer (the GPU-layer tests' texture or target).
pub fn test_image(
    ctx: &std::sync::Arc<vkocean::gpu::Context>,
    name: &str,
    usage: vkocean::gpu::vk::ImageUsageFlags,
) -> vkocean::gpu::Image {
    use vkocean::gpu::vk;
    vkocean::gpu::Image::new(
        ctx,
        &vkocean::gpu::ImageDesc::new(
            name,
            vk::Extent2D {
                width: 16,
                height: 16,
            },
            vk::Format::R8G8B8A8_UNORM,
            usage,
        ),
    )
    .expect("a 16x16 test image")
}

/// Destroys the context (so destruction is validated too) and asserts that validation reported
/// nothing. Drop every object created from it first.
pub fn assert_validation_clean(ctx: std::sync::Arc<vkocean::gpu::Context>) {
    let counters = ctx.counters();
    drop(ctx);
    DEVICE_HELD.with(|held| {
        let mut held = held.borrow_mut();
        if let Some((_, contexts)) = held.as_mut() {
            *contexts -= 1;
            if *contexts == 0 {
                *held = None;
            }
        }
    });
    assert_eq!(
        (counters.warnings(), counters.errors()),
        (0, 0),
        "validation messages"
    );
}

/// A validation-clean headless run of `size` with `args` (and `env`) whose `--screenshot` is a
/// file in a fresh scratch directory named `name`: the RGBA pixels of every PNG it wrote, in
/// file-name order (the one, or `--screenshot-every`'s numbered frames).
fn pictures(name: &str, size: (u32, u32), args: &[&str], env: &[(&str, &str)]) -> Vec<Vec<u8>> {
    let dir = scratch(name);
    let png = dir.join("s.png");
    let size_arg = format!("{}x{}", size.0, size.1);
    let mut all = vec![
        "--headless",
        "--validation",
        "--size",
        &size_arg,
        "--screenshot",
        png.to_str().expect("temp paths are UTF-8"),
    ];
    all.extend_from_slice(args);
    let out = run_with_env(&all, env);
    clean_run(&out, &format!("{all:?}"));
    let pictures = entries(&dir)
        .iter()
        .map(|file| {
            let (w, h, pixels) = read_png(&dir.join(file));
            assert_eq!((w, h), size, "{file}");
            pixels
        })
        .collect();
    let _ = std::fs::remove_dir_all(&dir);
    pictures
}

/// One validation-clean headless frame of `size` with `args` (and `env`): its RGBA pixels.
/// `name` names the scratch directory.
pub fn shot(name: &str, size: (u32, u32), args: &[&str], env: &[(&str, &str)]) -> Vec<u8> {
    let mut one = pictures(&format!("shot-{name}"), size, args, env);
    assert_eq!(one.len(), 1, "one picture");
    one.pop().expect("one picture")
}

/// One validation-clean headless run of `size` with `args` that saves every `every`-th frame
/// (`--screenshot-every`): the RGBA pixels of frames 1, every + 1, … in order. `name` names the
/// scratch directory.
pub fn shots(name: &str, size: (u32, u32), every: u64, args: &[&str]) -> Vec<Vec<u8>> {
    let every = every.to_string();
    let mut all = vec!["--screenshot-every", &every];
    all.extend_from_slice(args);
    pictures(&format!("shots-{name}"), size, &all, &[])
}

/// An sRGB byte's linear value (IEC 61966-2-1).
pub fn linear(v: u8) -> f64 {
    let v = f64::from(v) / 255.0;
    if v <= 0.04045 {
        v / 12.92
    } else {
        ((v + 0.055) / 1.055).powf(2.4)
    }
}

/// Linear Rec. 709 luminance of each RGBA pixel (its sRGB bytes decoded, 0..1).
pub fn linear_luminance(p: &[u8]) -> Vec<f64> {
    p.chunks(4)
        .map(|c| 0.2126 * linear(c[0]) + 0.7152 * linear(c[1]) + 0.0722 * linear(c[2]))
        .collect()
}

/// The exposed radiance (linear, per channel) a display colour (its sRGB bytes decoded, 0..1)
/// was tone mapped from: the inverse of `tone_map` in shaders/common/display.glsl (the ACES
/// fit per channel, blended toward the brightest channel's curve as that rises), or `None`
/// where the curve cannot be undone: a channel at 255 (clipped) or an exposed peak past 3
/// (TONE_WHITE_FROM there: the colour turns white). The brightest channel p maps on its own
/// curve in both halves of the blend, so p comes from the fit's quadratic; the others solve
/// the blend, which rises with them, by bisection. tests/shared.rs checks it against the
/// shader's own tone map. Ratios of radiance are what energy is conserved in: the curve's toe
/// is convex, so light moved around (the caustics) raises the display colour's mean.
pub fn untone(display: [f64; 3]) -> Option<[f64; 3]> {
    // display.glsl's constants: the fit (Narkowicz 2015), TONE_HUE_MID4, TONE_WHITE_FROM.
    const A: f64 = 2.51;
    const B: f64 = 0.03;
    const C: f64 = 2.43;
    const D: f64 = 0.59;
    const E: f64 = 0.14;
    const HUE_MID4: f64 = 0.0625;
    const WHITE_FROM: f64 = 3.0;
    let aces = |x: f64| (x * (A * x + B) / (x * (C * x + D) + E)).min(1.0);
    let top = display.iter().cloned().fold(0.0, f64::max);
    if top >= 254.5 / 255.0 {
        return None;
    }
    // (A − C·y)x² + (B − D·y)x − E·y = 0, its positive root.
    let (qa, qb, qc) = (A - C * top, B - D * top, -E * top);
    let peak = (-qb + (qb * qb - 4.0 * qa * qc).sqrt()) / (2.0 * qa);
    if peak >= WHITE_FROM {
        return None;
    }
    if peak <= 0.0 {
        return Some([0.0; 3]);
    }
    let p4 = peak.powi(4);
    let w = p4 / (p4 + HUE_MID4);
    let shown = |x: f64| (1.0 - w) * aces(x) + w * x * top / peak;
    Some(display.map(|y| {
        let (mut lo, mut hi) = (0.0, peak);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if shown(mid) < y {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }))
}

/// Rec. 709 luminance of each RGBA pixel's exposed radiance (`untone`), `None` where the tone
/// map cannot be undone.
pub fn radiance_luminance(p: &[u8]) -> Vec<Option<f64>> {
    p.chunks(4)
        .map(|c| {
            untone([linear(c[0]), linear(c[1]), linear(c[2])])
                .map(|[r, g, b]| 0.2126 * r + 0.7152 * g + 0.0722 * b)
        })
        .collect()
}

/// Mean of `values` (a `w`-wide picture's, row by row) over `rows` and `columns`.
pub fn mean_over(
    values: &[f64],
    w: usize,
    rows: std::ops::Range<usize>,
    columns: std::ops::Range<usize>,
) -> f64 {
    let n = (rows.len() * columns.len()) as f64;
    rows.map(|y| {
        values[y * w + columns.start..y * w + columns.end]
            .iter()
            .sum::<f64>()
    })
    .sum::<f64>()
        / n
}

/// Rec. 709 luma of each RGBA pixel (0..255).
pub fn luma(p: &[u8]) -> Vec<f64> {
    p.chunks(4)
        .map(|c| 0.2126 * c[0] as f64 + 0.7152 * c[1] as f64 + 0.0722 * c[2] as f64)
        .collect()
}

/// Mean absolute difference of two pictures' bytes (0..255).
pub fn mean_abs_diff(a: &[u8], b: &[u8]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (*x as f64 - *y as f64).abs())
        .sum::<f64>()
        / a.len() as f64
}

/// Relative L2 error ‖ours − reference‖ / ‖reference‖ of (ours, reference) pairs.
pub fn relative_l2(pairs: impl IntoIterator<Item = (f64, f64)>) -> f64 {
    let (err, norm) = pairs.into_iter().fold((0.0, 0.0), |(e, n), (o, r)| {
        (e + (o - r).powi(2), n + r * r)
    });
    (err / norm).sqrt()
}

/// Standard deviation of `v` (population).
pub fn std_dev(v: &[f64]) -> f64 {
    let mean = v.iter().sum::<f64>() / v.len() as f64;
    (v.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / v.len() as f64).sqrt()
}

/// Header and little-endian f32 payload of an .npy file's bytes (format 1.0).
pub fn npy_f32(bytes: &[u8]) -> (String, Vec<f32>) {
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00", "an .npy 1.0 file");
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let header = String::from_utf8(bytes[10..10 + len].to_vec()).unwrap();
    let data = bytes[10 + len..]
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]))
        .collect();
    (header, data)
}

/// [`npy_f32`] of the file at `path`.
pub fn read_npy_f32(path: &Path) -> (String, Vec<f32>) {
    let bytes = std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    npy_f32(&bytes)
}

/// CRC-32 (IEEE) of PNG chunks.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= b as u32;
        for _ in 0..8 {
            crc = if crc & 1 != 0 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

/// A PNG chunk: length, type, data, CRC.
pub fn png_chunk(kind: &[u8; 4], data: &[u8]) -> Vec<u8> {
    let mut out = (data.len() as u32).to_be_bytes().to_vec();
    let mut typed = kind.to_vec();
    typed.extend_from_slice(data);
    out.extend_from_slice(&typed);
    out.extend_from_slice(&crc32(&typed).to_be_bytes());
    out
}

/// A PNG file whose header claims `w`x`h` 8-bit RGBA and whose picture data is missing (IHDR,
/// an IDAT with a bare zlib header, IEND): a hostile input that costs nothing to make.
pub fn png_header_only(w: u32, h: u32) -> Vec<u8> {
    let mut ihdr = w.to_be_bytes().to_vec();
    ihdr.extend_from_slice(&h.to_be_bytes());
    ihdr.extend_from_slice(&[8, 6, 0, 0, 0]);
    let mut png = b"\x89PNG\r\n\x1a\n".to_vec();
    png.extend(png_chunk(b"IHDR", &ihdr));
    png.extend(png_chunk(b"IDAT", &[0x78, 0x9c]));
    png.extend(png_chunk(b"IEND", &[]));
    png
}

/// Whether `line` is a long run's progress line, `vkocean: frame N/M (T s)` (every 5 s: a
/// loaded machine prints one even in short runs).
pub fn is_progress(line: &str) -> bool {
    line.strip_prefix("vkocean: frame ")
        .and_then(|rest| rest.split_once(' '))
        .is_some_and(|(count, time)| {
            count.split('/').all(|n| n.parse::<u64>().is_ok())
                && time.starts_with('(')
                && time.ends_with(" s)")
        })
}

/// Asserts a failed run: exit `code`, exactly one stderr line starting `vkocean: ` that contains
/// `needle` (besides progress lines), no panic or backtrace hint.
pub fn assert_one_line(out: &Output, code: i32, needle: &str, what: &str) {
    let err = stderr(out);
    assert_eq!(
        out.status.code(),
        Some(code),
        "{what}: exit code; stderr:\n{err}"
    );
    let lines: Vec<&str> = err.lines().filter(|l| !is_progress(l)).collect();
    assert_eq!(
        lines.len(),
        1,
        "{what}: expected one stderr line, got:\n{err}"
    );
    assert!(lines[0].starts_with("vkocean: "), "{what}: {err}");
    assert!(
        lines[0].contains(needle),
        "{what}: {err:?} lacks {needle:?}"
    );
    assert!(
        !err.contains("panicked") && !err.contains("RUST_BACKTRACE"),
        "{what}: {err}"
    );
}

/// Seed 000's Gerstner waves (steepness-limited) over a 200 m window of 128² texels.
pub fn gerstner_window_settings() -> vkocean::ocean::OceanSettings {
    let mut waves = vkocean::ocean::gerstner::default_waves();
    vkocean::ocean::gerstner::limit_steepness(&mut waves);
    vkocean::ocean::OceanSettings {
        fft_size: 128,
        patch_size_m: 200.0,
        waves: vkocean::ocean::Waves::Gerstner(waves),
        ..vkocean::ocean::OceanSettings::default()
    }
}

/// Simulation images read back or dumped, as a lattice: texel (i, j) of cascade c is node
/// (i, j), periodic (FFT) or offset by the window's origin (Gerstner).
pub struct ImageLattice {
    /// RGBA texels, cascade after cascade, `[m][n]`.
    pub texels: Vec<[f32; 4]>,
    pub n: usize,
    pub steps: Vec<f64>,
    /// The window's origin in nodes (Gerstner), None for periodic cascades.
    pub origin: Option<[i64; 2]>,
}

impl vkocean::ocean::surface::Lattice for ImageLattice {
    fn steps(&self) -> Vec<f64> {
        self.steps.clone()
    }
    fn set_time(&mut self, _t: f64) {}
    fn node(&self, c: usize, i: i64, j: i64) -> [f64; 3] {
        let n = self.n as i64;
        let (col, row) = match self.origin {
            None => (i.rem_euclid(n), j.rem_euclid(n)),
            Some([oi, oj]) => {
                let (col, row) = (i - oi, j - oj);
                assert!(
                    (0..n).contains(&col) && (0..n).contains(&row),
                    "node ({i},{j}) outside the window"
                );
                (col, row)
            }
        };
        let d = self.texels[c * self.n * self.n + (row * n + col) as usize];
        [d[0] as f64, d[1] as f64, d[2] as f64]
    }
}

/// Runs the test kernel `spirv` (shaders/test/*.comp: one storage buffer at set 0, binding 0,
/// written; its inputs in push constants) once for each of `pushes`, over `groups`
/// workgroups, and returns each run's first `bytes` of the buffer as f32s. Validation-clean.
pub fn run_test_kernel<P: bytemuck::Pod>(
    name: &str,
    spirv: &[u8],
    pushes: &[P],
    bytes: usize,
    groups: [u32; 3],
) -> Vec<Vec<f32>> {
    use vkocean::gpu::oneshot::{download, run_once};
    use vkocean::gpu::{
        vk, Bind, Bindings, BoundSet, Buffer, DescriptorSetLayout, MemoryLocation, Order, Pipeline,
        PipelineLayout,
    };
    let ctx = gpu_context();
    let usage = vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_SRC;
    let stage = vk::ShaderStageFlags::COMPUTE;
    let ty = vk::DescriptorType::STORAGE_BUFFER;
    let set_layout =
        DescriptorSetLayout::new(&ctx, &format!("{name} set layout"), &[(0, ty, stage)]).unwrap();
    let layout = PipelineLayout::new(
        &ctx,
        &format!("{name} layout"),
        &[&set_layout],
        Some((stage, std::mem::size_of::<P>() as u32)),
    )
    .unwrap();
    let pipeline = Pipeline::compute(&ctx, &layout, name, spirv, &[]).unwrap();
    let mut out = Vec::new();
    for push in pushes {
        let buffer = Buffer::new(
            &ctx,
            &format!("{name} output"),
            bytes as u64,
            usage,
            MemoryLocation::GpuOnly,
        )
        .unwrap();
        let set = BoundSet::new(
            &ctx,
            &set_layout,
            &format!("{name} set"),
            &[(0, Bind::Storage(&buffer, Order::Tracked))],
        )
        .unwrap();
        run_once(&ctx, name, |rec| {
            rec.push_constants(&pipeline, push);
            let b = Bindings {
                pipeline: &pipeline,
                sets: &[&set],
            };
            rec.dispatch_with(&b, groups);
        })
        .unwrap();
        let raw = download(&ctx, &buffer, bytes).unwrap();
        out.push(bytemuck::cast_slice(&raw).to_vec());
    }
    drop(pipeline);
    assert_validation_clean(ctx);
    out
}
