//! The benchmarks: bad values are usage errors; small runs of `bench fft`, `bench frames` and
//! `bench gerstner` print their tables and write JSON (and CSV) consistent with them.

mod common;

use common::{clean_run, run, scratch, stderr};

#[test]
fn bench_fft_rejects_bad_values() {
    for (args, needle) in [
        (vec!["bench", "fft", "--sizes", "100"], "power of two"),
        (vec!["bench", "fft", "--sizes", "2048"], "power of two"),
        (vec!["bench", "fft", "--sizes", "32"], "power of two"),
        (
            vec!["bench", "fft", "--sizes", "256,x"],
            "not a whole number",
        ),
        (vec!["bench", "fft", "--batch", "0"], "--batch"),
        (vec!["bench", "fft", "--runs", "-2"], "--runs"),
        (
            vec!["bench", "fft", "--json", "out.txt"],
            "must end in .json",
        ),
        (vec!["bench", "nothing"], "nothing"),
        (vec!["bench", "frames", "--frames", "0"], "--frames"),
        (vec!["bench", "frames", "--warmup", "-1"], "--warmup"),
        (vec!["bench", "frames", "--warmup", "nan"], "--warmup"),
        (vec!["bench", "frames", "--size", "0x5"], "--size"),
        (
            vec!["bench", "frames", "--csv", "frames.txt"],
            "must end in .csv",
        ),
        (
            vec!["--size", "64x64", "bench", "frames"],
            "--size does not apply to bench frames",
        ),
        (
            vec!["--headless", "bench", "frames"],
            "--headless does not apply",
        ),
        (vec!["bench", "frames", "--tess-edge", "1"], "--tess-edge"),
        (
            vec!["bench", "gerstner", "--wave-counts", "14"],
            "--wave-counts",
        ),
        (
            vec!["bench", "gerstner", "--grid-widths", "4"],
            "--grid-widths",
        ),
        (
            vec!["--waves", "gerstner", "bench", "gerstner"],
            "drop --waves",
        ),
    ] {
        let out = run(&args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}

#[test]
fn bench_fft_writes_rows() {
    let dir = scratch("bench-fft");
    let json = dir.join("fft.json");
    let out = run(&[
        "bench",
        "fft",
        "--sizes",
        "64,128",
        "--batch",
        "2",
        "--runs",
        "3",
        "--json",
        json.to_str().unwrap(),
        "--validation",
    ]);
    clean_run(&out, "bench");
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains("gpu_ms") && table.contains("rustfft_ms") && table.contains("ratio"),
        "{table}"
    );
    let rows: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let rows = rows.as_array().expect("an array of rows");
    assert_eq!(rows.len(), 2);
    for (row, n) in rows.iter().zip([64, 128]) {
        assert_eq!(row["n"], n);
        assert_eq!(row["batch"], 2);
        let (gpu, cpu, ratio) = (
            row["gpu_ms"].as_f64().unwrap(),
            row["rustfft_ms"].as_f64().unwrap(),
            row["ratio"].as_f64().unwrap(),
        );
        assert!(gpu > 0.0 && cpu > 0.0, "{row}");
        assert!((ratio - gpu / cpu).abs() < 1e-9 * ratio.max(1.0), "{row}");
        assert_eq!(row["runs"], 3, "--runs 3: {row}");
        let steal = row["steal_pct"].as_f64().expect("Linux has /proc/stat");
        assert!((0.0..=100.0).contains(&steal), "{row}");
    }
}

/// Reads a JSON file.
fn json(path: &std::path::Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

#[test]
fn bench_frames_reports_passes_frames_and_settings() {
    let dir = scratch("bench-frames");
    let (json_path, csv_path) = (dir.join("frames.json"), dir.join("frames.csv"));
    // Sample flags before and after the subcommand both apply.
    let out = run(&[
        "--fft-size",
        "64",
        "bench",
        "frames",
        "--frames",
        "4",
        "--warmup",
        "0",
        "--size",
        "160x90",
        "--cascades",
        "1",
        "--quality",
        "low",
        "--terrain-grid",
        "32",
        "--json",
        json_path.to_str().unwrap(),
        "--csv",
        csv_path.to_str().unwrap(),
        "--validation",
    ]);
    clean_run(&out, "bench");
    let table = String::from_utf8_lossy(&out.stdout);
    use vkocean::pass_names::{OCEAN_FFT, OUTPUT, REFLECTION, WATER};
    for row in [
        OCEAN_FFT,
        REFLECTION,
        WATER,
        OUTPUT,
        "frame GPU total",
        "FPS",
    ] {
        assert!(table.contains(row), "{row} missing from:\n{table}");
    }

    let report = json(&json_path);
    assert_eq!(report["size"], serde_json::json!([160, 90]));
    assert_eq!(report["settings"]["cascades"], 1);
    assert_eq!(report["settings"]["fft_size"], 64);
    assert_eq!(report["settings"]["size"], "160x90");
    assert_eq!(report["settings"]["validation"], true);
    // --quality low fills what was not given: its render scale, but not its terrain grid (64).
    assert_eq!(report["settings"]["quality"], "low");
    assert_eq!(report["settings"]["quality_by"], "flag");
    assert_eq!(report["settings"]["render_scale"], 0.5);
    assert_eq!(report["settings"]["terrain_grid"], 32);
    let warmup = report["warmup_frames"].as_u64().unwrap();
    assert!(warmup >= 1, "{report}");
    assert_eq!(report["frames"].as_u64().unwrap(), warmup + 4);
    assert!(report["fps"].as_f64().unwrap() > 0.0);
    // The water's coverage, counted over frames of their own (lavapipe has pipeline statistics
    // and precise occlusion queries): the water covers part of the 80x45 scene target (render
    // scale 0.5), each covered pixel shaded at least once.
    assert!(table.contains("water coverage: median"), "{table}");
    let coverage = &report["water_coverage"];
    let covered = coverage["covered_pixels"]["median"].as_f64().unwrap();
    assert!(
        (0.2..0.8).contains(&(covered / (80.0 * 45.0))),
        "{coverage}"
    );
    assert!(
        coverage["invocations_per_pixel"]["median"]
            .as_f64()
            .unwrap()
            >= 0.999,
        "{coverage}"
    );
    let passes = report["passes"].as_array().unwrap();
    let names: Vec<&str> = passes.iter().map(|p| p["name"].as_str().unwrap()).collect();
    for name in vkocean::pass_names::FFT_FRAME {
        assert!(names.contains(&name), "{name} not in {names:?}");
    }
    for p in passes {
        assert_eq!(p["samples"], 4, "{p}");
        let g = &p["gpu_ms"];
        let [min, median, p95, max] =
            ["min", "median", "p95", "max"].map(|k| g[k].as_f64().unwrap());
        assert!(
            0.0 <= min && min <= median && median <= p95 && p95 <= max,
            "{p}"
        );
    }

    // The CSV: one row per measured frame, indices after the warm-up, gpu = compute + graphics,
    // and each frame's passes fit inside its submissions.
    let csv = std::fs::read_to_string(&csv_path).unwrap();
    let mut lines = csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(
        &header[..5],
        [
            "frame",
            "cpu_ms",
            "gpu_ms",
            "compute_gpu_ms",
            "graphics_gpu_ms"
        ]
    );
    assert!(
        header.contains(&"ocean_fft") && header.contains(&"water"),
        "{header:?}"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse::<f64>().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    assert_eq!(rows.len(), 4, "{csv}");
    for (i, row) in rows.iter().enumerate() {
        assert_eq!(row.len(), header.len(), "{csv}");
        assert_eq!(row[0] as u64, warmup + i as u64, "{csv}");
        assert!(row[1] > 0.0, "{csv}");
        assert!((row[2] - row[3] - row[4]).abs() < 2e-3, "{csv}");
        let passes: f64 = row[5..].iter().filter(|v| v.is_finite()).sum();
        assert!(
            passes <= row[2] * 1.001 + 1e-3,
            "passes exceed the frame: {csv}"
        );
    }
}

/// Each pass is timed over its own work: a driver may start the commands after a timestamp
/// before writing it (Mesa 25's lavapipe does), and there the water's draws ran before its
/// opening timestamp, so it read 0.3 ms of a 24 ms frame. `bench frames` orders each opening
/// timestamp before what follows (README, Profile JSON). At `--quality low` and 1280x720 the
/// water is the frame's largest graphics pass: measured 0.42 of the graphics time on Mesa 22.3
/// and 0.43 on Mesa 25, where it was 0.01 without the ordering (CI runs this binary on both).
#[test]
fn bench_frames_times_each_pass_over_its_own_work() {
    let dir = scratch("bench-order");
    let json_path = dir.join("frames.json");
    let out = run(&[
        "--quality",
        "low",
        "bench",
        "frames",
        "--frames",
        "8",
        "--warmup",
        "1",
        "--json",
        json_path.to_str().unwrap(),
        "--validation",
    ]);
    clean_run(&out, "bench");
    let report = json(&json_path);
    let graphics = report["frame_gpu_ms"]["median"].as_f64().unwrap();
    let passes: Vec<(&str, f64)> = report["passes"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|p| p["submission"] != "compute")
        .map(|p| {
            (
                p["name"].as_str().unwrap(),
                p["gpu_ms"]["median"].as_f64().unwrap(),
            )
        })
        .collect();
    let (largest, ms) = passes
        .iter()
        .copied()
        .max_by(|a, b| a.1.total_cmp(&b.1))
        .unwrap();
    let water = passes
        .iter()
        .find(|p| p.0 == vkocean::pass_names::WATER)
        .unwrap()
        .1;
    eprintln!("graphics {graphics:.2} ms; water {water:.2}; largest {largest} {ms:.2}");
    assert_eq!(largest, vkocean::pass_names::WATER, "{passes:?}");
    assert!(
        water >= 0.25 * graphics,
        "the water {water:.2} ms of a {graphics:.2} ms graphics frame: {passes:?}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// Without `--quality` the level follows the device the run uses: low on a CPU implementation
/// (lavapipe, which `--list-gpus` calls "cpu"), high on a GPU; the report says so.
#[test]
fn the_quality_level_defaults_by_device_and_the_report_names_it() {
    let dir = scratch("bench-quality");
    let json_path = dir.join("frames.json");
    let list = run(&["--list-gpus"]);
    let devices = String::from_utf8_lossy(&list.stdout).into_owned();
    let best = devices
        .lines()
        .filter(|l| !l.contains("[unusable"))
        .max_by_key(|l| {
            // discrete > integrated > virtual > cpu; the first of a rank wins.
            let rank = ["(cpu,", "(virtual,", "(integrated,", "(discrete,"]
                .iter()
                .position(|t| l.contains(t))
                .map_or(0, |r| r + 1);
            (rank, std::cmp::Reverse(l.to_string()))
        })
        .expect("a usable device");
    let expected = if best.contains("(cpu,") {
        "low"
    } else {
        "high"
    };
    let out = run(&[
        "bench",
        "frames",
        "--frames",
        "1",
        "--warmup",
        "0",
        "--size",
        "64x36",
        "--json",
        json_path.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let report = json(&json_path);
    assert_eq!(report["settings"]["quality"], expected, "on {best}");
    assert_eq!(report["settings"]["quality_by"], "device");
    let fft_size = if expected == "low" { 64 } else { 256 };
    assert_eq!(report["settings"]["fft_size"], fft_size);
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains(&format!("quality={expected} quality_by=device")),
        "{table}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bench_gerstner_prints_both_tables() {
    let dir = scratch("bench-gerstner");
    let json_path = dir.join("gerstner.json");
    let out = run(&[
        "bench",
        "gerstner",
        "--wave-counts",
        "1,3",
        "--grid-widths",
        "24,200",
        "--frames",
        "2",
        "--warmup",
        "0",
        "--size",
        "96x54",
        "--json",
        json_path.to_str().unwrap(),
        "--validation",
    ]);
    clean_run(&out, "bench");
    let table = String::from_utf8_lossy(&out.stdout);
    assert!(
        table.contains("Table 4-1") && table.contains("Table 4-2"),
        "{table}"
    );
    // The paper's figures sit beside ours: 161 FPS for 1 wave, 2579 for width 200.
    assert!(table.contains("161") && table.contains("2579"), "{table}");
    let report = json(&json_path);
    let waves: Vec<(u64, u64)> = report["wave_count"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| (r["waves"].as_u64().unwrap(), r["grid"].as_u64().unwrap()))
        .collect();
    assert_eq!(waves, [(1, 200), (3, 200)]);
    let grids: Vec<(u64, u64)> = report["grid_width"]
        .as_array()
        .unwrap()
        .iter()
        .map(|r| (r["waves"].as_u64().unwrap(), r["grid"].as_u64().unwrap()))
        .collect();
    assert_eq!(grids, [(10, 24), (10, 200)]);
    for r in report["wave_count"]
        .as_array()
        .unwrap()
        .iter()
        .chain(report["grid_width"].as_array().unwrap())
    {
        for key in ["fps", "frame_cpu_ms", "gerstner_gpu_ms", "gpu_total_ms"] {
            let v = r[key].as_f64().unwrap_or(f64::NAN);
            assert!(v.is_finite() && v > 0.0, "{key}: {r}");
        }
    }
}
