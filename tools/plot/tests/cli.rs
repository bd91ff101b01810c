//! Runs the built `vkocean-plot` on synthetic bench output (the schemas of `vkocean bench frames
//! --json/--csv`) and checks the PNGs by their pixels, and the failures by exit code and stderr.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::atomic::{AtomicUsize, Ordering};

use image::RgbImage;
use serde_json::{json, Value};
use vkocean_plot::{CPU_COLOUR, GPU_COLOUR, PALETTE};

const BIN: &str = env!("CARGO_BIN_EXE_vkocean-plot");

/// A fresh directory under the system temp dir, removed on drop.
struct TempDir(PathBuf);

impl TempDir {
    fn new(name: &str) -> TempDir {
        static COUNT: AtomicUsize = AtomicUsize::new(0);
        let dir = std::env::temp_dir().join(format!(
            "vkocean-plot-test-{}-{name}-{}",
            std::process::id(),
            COUNT.fetch_add(1, Ordering::Relaxed)
        ));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        TempDir(dir)
    }

    fn path(&self, name: &str) -> PathBuf {
        self.0.join(name)
    }

    fn write(&self, name: &str, text: &str) -> PathBuf {
        let path = self.path(name);
        std::fs::write(&path, text).unwrap();
        path
    }

    /// File names in the directory, sorted.
    fn names(&self) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(&self.0)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn run(args: &[&str]) -> Output {
    Command::new(BIN).args(args).output().unwrap()
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn ok(args: &[&str]) {
    let out = run(args);
    assert!(
        out.status.success(),
        "{args:?}: {:?}\n{}",
        out.status,
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A report in the bench frames JSON schema; `None` medians are passes without samples.
fn report(quality: &str, passes: &[(&str, Option<f64>)]) -> String {
    let stats =
        |m: f64| json!({"min": m * 0.9, "median": m, "mean": m, "p95": m * 1.2, "max": m * 1.3});
    let passes: Vec<Value> = passes
        .iter()
        .map(|(name, median)| match median {
            Some(m) => json!({"name": name, "gpu_ms": stats(*m), "samples": 20}),
            None => json!({"name": name, "gpu_ms": null, "samples": 0}),
        })
        .collect();
    let value = json!({
        "device": "llvmpipe (LLVM 15.0.6, 256 bits)",
        "driver": "llvmpipe: Mesa 22.3.6 (LLVM 15.0.6)",
        "frames": 25,
        "warmup_frames": 5,
        "size": [320, 180],
        "passes": passes,
        "frame_gpu_ms": stats(20.0),
        "compute_gpu_ms": stats(4.0),
        "gpu_total_ms": stats(24.0),
        "frame_cpu_ms": stats(28.0),
        "fps": 30.0,
        "wall_s": 0.6,
        "settings": {"size": "320x180", "quality": quality, "waves": "fft", "fft_size": 64},
    });
    serde_json::to_string_pretty(&value).unwrap()
}

fn load(path: &Path) -> RgbImage {
    image::open(path).unwrap().to_rgb8()
}

fn is(p: &image::Rgb<u8>, c: (u8, u8, u8)) -> bool {
    p.0 == [c.0, c.1, c.2]
}

fn count(img: &RgbImage, c: (u8, u8, u8)) -> usize {
    img.pixels().filter(|p| is(p, c)).count()
}

/// The bars of a `passes` chart, left to right: column ranges (at least 30 px wide, which
/// leaves out the legend's swatches) where some pixel has one of `colours`.
fn bars(img: &RgbImage, colours: &[(u8, u8, u8)]) -> Vec<(u32, u32)> {
    let hit =
        |x: u32| (0..img.height()).any(|y| colours.iter().any(|c| is(img.get_pixel(x, y), *c)));
    let mut out = Vec::new();
    let mut start = None;
    for x in 0..=img.width() {
        match (x < img.width() && hit(x), start) {
            (true, None) => start = Some(x),
            (false, Some(s)) => {
                if x - s >= 30 {
                    out.push((s, x - 1));
                }
                start = None;
            }
            _ => {}
        }
    }
    out
}

/// Pixel rows of each colour in column `x`.
fn rows(img: &RgbImage, x: u32, colours: &[(u8, u8, u8)]) -> Vec<usize> {
    colours
        .iter()
        .map(|c| {
            (0..img.height())
                .filter(|&y| is(img.get_pixel(x, y), *c))
                .count()
        })
        .collect()
}

#[test]
fn help_exits_0_on_stdout() {
    let out = run(&["--help"]);
    assert!(out.status.success());
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("vkocean-plot passes OUT.png RUN.json"),
        "{text}"
    );
    assert!(
        text.contains("vkocean-plot frames OUT.png RUN.csv"),
        "{text}"
    );
    assert!(out.stderr.is_empty());
}

#[test]
fn passes_chart_size_and_pass_colours() {
    let dir = TempDir::new("colours");
    let passes = [
        ("ocean evolve", Some(1.0)),
        ("ocean fft", Some(1.5)),
        ("water", Some(5.0)),
        ("composite", Some(3.0)),
    ];
    let run_json = dir.write("run.json", &report("low", &passes));
    let out = dir.path("passes.png");
    ok(&["passes", s(&out), s(&run_json)]);
    let img = load(&out);
    assert_eq!(img.dimensions(), (1200, 700));
    for (i, c) in PALETTE.iter().take(passes.len()).enumerate() {
        assert!(count(&img, *c) > 500, "pass {i} colour {c:?} missing");
    }
    assert_eq!(
        count(&img, PALETTE[passes.len()]),
        0,
        "a colour beyond the passes"
    );

    ok(&["passes", s(&out), s(&run_json), "--size", "800x500"]);
    assert_eq!(load(&out).dimensions(), (800, 500));
    ok(&["passes", s(&out), s(&run_json), "--size=640x480"]);
    assert_eq!(load(&out).dimensions(), (640, 480));
    assert_eq!(dir.names(), ["passes.png", "run.json"], "no temp file left");
}

#[test]
fn stacked_bar_heights_are_proportional_to_medians() {
    let dir = TempDir::new("stack");
    let medians = [2.0, 4.0, 6.0, 8.0];
    let passes: Vec<(&str, Option<f64>)> = ["a", "b", "c", "d"]
        .iter()
        .zip(medians)
        .map(|(n, m)| (*n, Some(m)))
        .collect();
    let run_json = dir.write("run.json", &report("low", &passes));
    let out = dir.path("passes.png");
    ok(&["passes", s(&out), s(&run_json)]);
    let img = load(&out);
    let colours = &PALETTE[..4];
    let found = bars(&img, colours);
    assert_eq!(found.len(), 1, "bars {found:?}");
    let (x0, x1) = found[0];
    let heights = rows(&img, (x0 + x1) / 2, colours);
    let total: usize = heights.iter().sum();
    assert!(total > 200, "bar only {total} px tall: {heights:?}");
    let sum: f64 = medians.iter().sum();
    for (h, m) in heights.iter().zip(medians) {
        let (got, want) = (*h as f64 / total as f64, m / sum);
        assert!(
            (got - want).abs() < 0.02,
            "heights {heights:?} not proportional to {medians:?}"
        );
    }
    // Bottom to top in report order: the first pass's colour is lowest.
    let x = (x0 + x1) / 2;
    let lowest = |c: (u8, u8, u8)| {
        (0..img.height())
            .rev()
            .find(|&y| is(img.get_pixel(x, y), c))
            .unwrap()
    };
    assert!(lowest(colours[0]) > lowest(colours[1]) && lowest(colours[1]) > lowest(colours[3]));
}

#[test]
fn bigger_medians_make_a_taller_bar_and_skipped_passes_get_no_colour() {
    let dir = TempDir::new("taller");
    let small = dir.write(
        "small.json",
        &report(
            "low",
            &[("a", Some(1.0)), ("b", Some(2.0)), ("c", Some(3.0))],
        ),
    );
    // Twice the medians, plus passes that must not be stacked: a zero median, no samples, and
    // a submission total.
    let big = dir.write(
        "big.json",
        &report(
            "high",
            &[
                ("a", Some(2.0)),
                ("idle", Some(0.0)),
                ("b", Some(4.0)),
                ("unused", None),
                ("c", Some(6.0)),
                ("graphics (GPU)", Some(12.0)),
            ],
        ),
    );
    let out = dir.path("passes.png");
    ok(&[
        "passes",
        s(&out),
        s(&small),
        s(&big),
        "--labels",
        "small,big",
    ]);
    let img = load(&out);
    let colours = &PALETTE[..3];
    let found = bars(&img, colours);
    assert_eq!(found.len(), 2, "bars {found:?}");
    let height =
        |(x0, x1): (u32, u32)| rows(&img, (x0 + x1) / 2, colours).iter().sum::<usize>() as f64;
    let (h_small, h_big) = (height(found[0]), height(found[1]));
    assert!(
        (h_big / h_small - 2.0).abs() < 0.06,
        "bar heights {h_small} and {h_big}: expected twice"
    );
    assert_eq!(count(&img, PALETTE[3]), 0, "a skipped pass got a colour");
}

/// A bench frames CSV: `frames` rows, GPU at `gpu` ms and CPU at `cpu` ms, with one empty CPU
/// cell.
fn frames_csv(frames: u32, gpu: f64, cpu: f64) -> String {
    let mut out =
        String::from("frame,cpu_ms,gpu_ms,compute_gpu_ms,graphics_gpu_ms,ocean_evolve,water\n");
    for f in 0..frames {
        let wobble = (f % 3) as f64 * 0.5;
        let cpu = if f == frames / 2 {
            String::new()
        } else {
            format!("{:.4}", cpu + wobble)
        };
        out += &format!(
            "{},{cpu},{:.4},{:.4},{:.4},1.0000,\n",
            17 + f,
            gpu + wobble,
            gpu * 0.2,
            gpu * 0.8
        );
    }
    out
}

#[test]
fn frames_chart_draws_both_series() {
    let dir = TempDir::new("frames");
    let csv = dir.write("run.csv", &frames_csv(40, 10.0, 40.0));
    let out = dir.path("frames.png");
    ok(&["frames", s(&out), s(&csv), "--size", "1000x600"]);
    let img = load(&out);
    assert_eq!(img.dimensions(), (1000, 600));
    // Inside the plot (left of the legend): the GPU line (10 ms) is below the CPU line (40 ms).
    let mean_y = |c: (u8, u8, u8)| {
        let ys: Vec<u32> = img
            .enumerate_pixels()
            .filter(|(x, _, p)| *x < 600 && is(p, c))
            .map(|(_, y, _)| y)
            .collect();
        assert!(ys.len() > 300, "colour {c:?}: {} pixels", ys.len());
        ys.iter().sum::<u32>() as f64 / ys.len() as f64
    };
    let (gpu, cpu) = (mean_y(GPU_COLOUR), mean_y(CPU_COLOUR));
    assert!(
        gpu > cpu + 100.0,
        "GPU line at y {gpu}, CPU line at y {cpu}"
    );
    assert_eq!(dir.names(), ["frames.png", "run.csv"]);
}

#[test]
fn real_pass_names_fit_the_legend() {
    // The legend shortens names that do not fit; long names must not fail the run.
    let dir = TempDir::new("long");
    let long = "a pass with a name far too long for the legend column of the chart";
    let run_json = dir.write(
        "run.json",
        &report("low", &[(long, Some(3.0)), ("water", Some(5.0))]),
    );
    let out = dir.path("passes.png");
    ok(&["passes", s(&out), s(&run_json), "--size", "400x300"]);
    assert_eq!(load(&out).dimensions(), (400, 300));
}

#[test]
fn bad_inputs_fail_cleanly() {
    let dir = TempDir::new("bad");
    let good_json = dir.write("good.json", &report("low", &[("water", Some(5.0))]));
    let good_csv = dir.write("good.csv", &frames_csv(5, 10.0, 20.0));
    let cases: Vec<(&str, Vec<String>, i32)> = {
        let p = |name: &str| s(&dir.path(name)).to_string();
        let w = |name: &str, text: &str| s(&dir.write(name, text)).to_string();
        let out = p("out.png");
        let good_json = s(&good_json).to_string();
        let good_csv = s(&good_csv).to_string();
        let v = |a: &[&str]| a.iter().map(|x| x.to_string()).collect::<Vec<_>>();
        vec![
            ("missing file", v(&["passes", &out, &p("nope.json")]), 1),
            (
                "malformed JSON",
                v(&["passes", &out, &w("bad.json", "{\"passes\": [")]),
                1,
            ),
            (
                "JSON without passes",
                v(&["passes", &out, &w("nopasses.json", "{\"frames\": 3}")]),
                1,
            ),
            (
                "JSON array",
                v(&["passes", &out, &w("array.json", "[1, 2]")]),
                1,
            ),
            (
                "no timed pass",
                v(&[
                    "passes",
                    &out,
                    &w(
                        "untimed.json",
                        &report("low", &[("a", None), ("b", Some(0.0))]),
                    ),
                ]),
                1,
            ),
            (
                "median not a number",
                v(&[
                    "passes",
                    &out,
                    &w(
                        "strmedian.json",
                        r#"{"passes": [{"name": "a", "gpu_ms": {"median": "x"}}]}"#,
                    ),
                ]),
                1,
            ),
            (
                "one bad run of two",
                v(&["passes", &out, &good_json, &p("nope.json")]),
                1,
            ),
            ("empty CSV", v(&["frames", &out, &w("empty.csv", "")]), 1),
            (
                "CSV header only",
                v(&["frames", &out, &w("header.csv", "frame,cpu_ms,gpu_ms\n")]),
                1,
            ),
            (
                "CSV with a non-number",
                v(&[
                    "frames",
                    &out,
                    &w("nan.csv", "frame,cpu_ms,gpu_ms\n1,2.0,abc\n"),
                ]),
                1,
            ),
            (
                "CSV without gpu_ms",
                v(&["frames", &out, &w("nogpu.csv", "frame,cpu_ms\n1,2.0\n")]),
                1,
            ),
            (
                "CSV short row",
                v(&[
                    "frames",
                    &out,
                    &w("short.csv", "frame,cpu_ms,gpu_ms\n1,2.0\n"),
                ]),
                1,
            ),
            ("missing CSV", v(&["frames", &out, &p("nope.csv")]), 1),
            (
                "missing output directory",
                v(&["passes", &p("missing/out.png"), &good_json]),
                1,
            ),
            (
                "output is a directory",
                v(&["frames", s(&dir.0), &good_csv]),
                1,
            ),
            (
                "missing font",
                v(&["passes", &out, &good_json, "--font", &p("nofont.ttf")]),
                1,
            ),
            (
                "font not a font",
                v(&["frames", &out, &good_csv, "--font", &good_json]),
                1,
            ),
            ("unknown subcommand", v(&["bars", &out, &good_json]), 2),
            ("no arguments", v(&[]), 2),
            ("no inputs", v(&["passes", &out]), 2),
            (
                "frames with two CSVs",
                v(&["frames", &out, &good_csv, &good_csv]),
                2,
            ),
            (
                "unknown option",
                v(&["passes", &out, &good_json, "--bogus"]),
                2,
            ),
            (
                "bad --size",
                v(&["passes", &out, &good_json, "--size", "big"]),
                2,
            ),
            (
                "--size too small",
                v(&["passes", &out, &good_json, "--size", "10x10"]),
                2,
            ),
            (
                "--size without H",
                v(&["frames", &out, &good_csv, "--size=1200x"]),
                2,
            ),
            (
                "--size without a value",
                v(&["frames", &out, &good_csv, "--size"]),
                2,
            ),
            (
                "--labels count",
                v(&["passes", &out, &good_json, "--labels", "a,b"]),
                2,
            ),
            (
                "--labels for frames",
                v(&["frames", &out, &good_csv, "--labels", "a"]),
                2,
            ),
        ]
    };
    let before = dir.names();
    for (what, args, code) in &cases {
        let out = Command::new(BIN).args(args).output().unwrap();
        let stderr = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(*code), "{what}: {args:?}\n{stderr}");
        assert!(
            stderr.starts_with("vkocean-plot: "),
            "{what}: stderr {stderr:?}"
        );
        assert_eq!(stderr.lines().count(), 1, "{what}: stderr {stderr:?}");
        assert!(!stderr.contains("panicked"), "{what}: {stderr}");
        assert!(
            out.stdout.is_empty(),
            "{what}: stdout {:?}",
            String::from_utf8_lossy(&out.stdout)
        );
        assert_eq!(dir.names(), before, "{what}: left a file behind");
    }
}

#[test]
fn a_failed_run_keeps_the_previous_png() {
    let dir = TempDir::new("keep");
    let good = dir.write("good.json", &report("low", &[("water", Some(5.0))]));
    let out = dir.path("passes.png");
    ok(&["passes", s(&out), s(&good)]);
    let before = std::fs::read(&out).unwrap();
    let bad = dir.write("bad.json", "{");
    let failed = run(&["passes", s(&out), s(&bad)]);
    assert_eq!(failed.status.code(), Some(1));
    assert_eq!(std::fs::read(&out).unwrap(), before);
}
