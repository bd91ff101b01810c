//! `--dump` and `--stats` end to end: the dump's layout is what README says (checked against the
//! CPU reference at the dumped time), the same seed gives identical files, and `--stats` prints
//! one JSON line per frame.

mod common;

use std::path::PathBuf;
use std::process::Output;

use common::{clean_run, read_npy_f32, run, scratch, stderr};
use vkocean::ocean::cpu::CpuOcean;
use vkocean::ocean::{OceanSettings, SeaState};

const ARGS: [&str; 14] = [
    "--headless",
    "--size",
    "320x180",
    "--frames",
    "3",
    "--fft-size",
    "64",
    "--cascades",
    "2",
    "--seed",
    "5",
    "--wind-speed",
    "12",
    "--validation",
];

#[test]
fn dump_matches_the_cpu_reference_and_is_deterministic() {
    let dirs = [scratch("dump-a"), scratch("dump-b")];
    for dir in &dirs {
        let mut args = ARGS.to_vec();
        args.extend(["--dump", dir.to_str().unwrap()]);
        let out = run(&args);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    }
    for name in ["h0.npy", "displacement.npy", "normals.npy", "params.json"] {
        let a = std::fs::read(dirs[0].join(name)).unwrap();
        let b = std::fs::read(dirs[1].join(name)).unwrap();
        assert!(a == b, "{name} differs between two runs with the same seed");
    }

    let params: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dirs[0].join("params.json")).unwrap())
            .unwrap();
    let t = params["t"].as_f64().unwrap();
    assert!(
        (t - 2.0 / 60.0).abs() < 1e-6,
        "last of 3 frames at 1/60 s steps: t = {t}"
    );
    assert_eq!(params["fft_size"], 64);
    assert_eq!(params["seed"], 5);
    assert_eq!(params["depth_m"], serde_json::Value::Null);

    let (header, h0) = read_npy_f32(&dirs[0].join("h0.npy"));
    assert!(
        header.contains("'<c8'") && header.contains("(2, 64, 64)"),
        "{header}"
    );
    let (header, displacement) = read_npy_f32(&dirs[0].join("displacement.npy"));
    assert!(
        header.contains("'<f4'") && header.contains("(2, 64, 64, 4)"),
        "{header}"
    );

    let settings = OceanSettings {
        sea: SeaState {
            wind_speed_m_s: 12.0,
            ..SeaState::default()
        },
        fft_size: 64,
        cascades: 2,
        seed: 5,
        ..OceanSettings::default()
    };
    let cpu = CpuOcean::new(&settings);
    let h0_cpu: Vec<f32> = (0..2)
        .flat_map(|c| cpu.h0(c).iter().flat_map(|v| *v).collect::<Vec<_>>())
        .collect();
    assert!(
        h0 == h0_cpu,
        "h0.npy holds the h0 the CPU reference generates"
    );
    // The shore's Hs is the rendered sea's, 4√m₀ with m₀ = Σ 2|h0|² (Parseval).
    let m0: f64 = h0.iter().map(|v| 2.0 * (*v as f64).powi(2)).sum();
    let hs = params["shore"]["hs_m"].as_f64().unwrap();
    assert!(
        (hs / (4.0 * m0.sqrt()) - 1.0).abs() < 1e-9,
        "shore Hs {hs} vs 4√m₀ = {}",
        4.0 * m0.sqrt()
    );
    let fields = cpu.fields(t);
    let (mut err, mut norm) = (0.0, 0.0);
    for (c, f) in fields.iter().enumerate() {
        for (i, d) in f.displacement.iter().enumerate() {
            for comp in 0..3 {
                let gpu = displacement[((c * 64 * 64) + i) * 4 + comp] as f64;
                err += (gpu - d[comp]).powi(2);
                norm += d[comp].powi(2);
            }
        }
    }
    assert!(
        (err / norm).sqrt() < 1e-4,
        "dumped displacement vs CPU: relative L2 {}",
        (err / norm).sqrt()
    );
}

#[test]
fn stats_prints_one_line_per_frame() {
    let out = run(&ARGS);
    let mut args = ARGS.to_vec();
    args.push("--stats");
    let out_stats = run(&args);
    assert_eq!(out.status.code(), Some(0));
    assert_eq!(out_stats.status.code(), Some(0), "{}", stderr(&out_stats));
    let text = String::from_utf8_lossy(&out_stats.stdout);
    let lines: Vec<serde_json::Value> = text
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect();
    assert_eq!(lines.len(), 3);
    for (i, line) in lines.iter().enumerate() {
        assert_eq!(line["frame"], i as u64);
        assert_eq!(line["cascades"].as_array().unwrap().len(), 2);
        let s = &line["surface"];
        let (std, hs) = (s["std"].as_f64().unwrap(), s["hs"].as_f64().unwrap());
        assert!(std > 0.0 && (hs - 4.0 * std).abs() < 1e-9, "{line}");
        assert!(
            s["min"].as_f64().unwrap() < s["mean"].as_f64().unwrap()
                && s["mean"].as_f64().unwrap() < s["max"].as_f64().unwrap(),
            "{line}"
        );
    }
}

#[test]
fn dump_needs_headless_and_a_writable_dir() {
    let out = run(&["--dump", "/tmp/x"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("--dump needs --headless"));
    let out = run(&["--headless", "--dump", "/proc/vkocean-no"]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert_eq!(stderr(&out).lines().count(), 1);
}

/// A headless Gerstner run (64² images) of the wave table `csv`, dumped: (run output, dump
/// directory, params.json). `extra` flags are added.
fn gerstner_dump(name: &str, csv: &str, extra: &[&str]) -> (Output, PathBuf, serde_json::Value) {
    let dir = scratch(name);
    let table = dir.join("waves.csv");
    std::fs::write(&table, csv).unwrap();
    let out_dir = dir.join("out");
    let mut args = vec![
        "--headless",
        "--fft-size",
        "64",
        "--waves",
        "gerstner",
        "--gerstner-waves",
        table.to_str().unwrap(),
        "--dump",
        out_dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    let out = run(&args);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let params =
        serde_json::from_str(&std::fs::read_to_string(out_dir.join("params.json")).unwrap())
            .unwrap();
    (out, out_dir, params)
}

#[test]
fn gerstner_dump_from_a_wave_file() {
    let (out, out_dir, params) = gerstner_dump(
        "dump-gerstner",
        "kx,kz,amplitude,phase,steepness\n0.3,-0.46,0.2,0,1\n-0.33,0.4,0.12,0.5,0.5\n",
        &["--size", "320x180", "--frames", "2", "--validation"],
    );
    assert!(!out_dir.join("h0.npy").exists(), "Gerstner mode has no h0");
    assert_eq!(params["waves"], "gerstner");
    assert_eq!(params["waves_table"].as_array().unwrap().len(), 2);
    assert_eq!(params["waves_table"][1]["steepness"], 0.5);
    assert!(
        !stderr(&out).contains("steepness"),
        "Σ Q·k·a = 0.14: no scaling"
    );
    assert!(params["origin_m"].as_array().is_some_and(|o| o.len() == 2));
    // The shore's sea: Hs = 4√(Σ a²/2) and the mean of ω = √(g k) weighted by a²/2.
    let waves = [(0.3f64, -0.46f64, 0.2f64), (-0.33, 0.4, 0.12)];
    let m0: f64 = waves.iter().map(|w| w.2 * w.2 / 2.0).sum();
    let m1: f64 = waves
        .iter()
        .map(|w| w.2 * w.2 / 2.0 * (9.8 * w.0.hypot(w.1)).sqrt())
        .sum();
    let shore = &params["shore"];
    assert!((shore["hs_m"].as_f64().unwrap() - 4.0 * m0.sqrt()).abs() < 1e-9);
    assert!((shore["mean_omega_rad_s"].as_f64().unwrap() - m1 / m0).abs() < 1e-9);
    let (header, _) = read_npy_f32(&out_dir.join("displacement.npy"));
    assert!(header.contains("(1, 64, 64, 4)"), "{header}");
}

/// A table steep enough to fold (Σ Q·k·a > 1) has its Q scaled to the limit, says so on stderr,
/// and the dump records the Q that ran.
#[test]
fn too_steep_gerstner_waves_are_scaled_to_the_fold_limit() {
    // k = 0.5 rad/m, a = 2 m, Q = 3: Σ Q·k·a = 3.
    let (out, _, params) = gerstner_dump(
        "dump-gerstner-steep",
        "0.3,0.4,2.0,0,3\n",
        &["--size", "64x64", "--frames", "1"],
    );
    let err = stderr(&out);
    assert!(
        err.contains("steepness Q scaled by 0.333") && err.contains("was 3.000"),
        "{err}"
    );
    let q = params["waves_table"][0]["steepness"].as_f64().unwrap();
    assert!((q - 1.0).abs() < 1e-12, "Q·k·a = 1 after scaling: Q {q}");
}

/// Every extreme the command line accepts (wind, fetch, depth, patch size, choppiness, cascades,
/// time; render scale, RTT scale, tessellation edge, terrain grid, camera height, sun, a 1x1
/// image): the run succeeds validation-clean, no NaN or Inf reaches the dumped fields (h0,
/// displacement, normals), and the screenshot has the requested size.
#[test]
fn accepted_extremes_give_finite_dumps_and_pictures() {
    let cases: [&[&str]; 10] = [
        &[
            "--wind-speed",
            "100",
            "--fetch",
            "10000",
            "--choppiness",
            "10",
        ],
        &[
            "--wind-speed",
            "0.001",
            "--fetch",
            "0.001",
            "--depth",
            "0.001",
        ],
        &[
            "--spectrum",
            "phillips",
            "--wind-speed",
            "100",
            "--patch-size",
            "100000",
            "--cascades",
            "4",
        ],
        &[
            "--spectrum",
            "pierson-moskowitz",
            "--wind-speed",
            "0.001",
            "--patch-size",
            "0.001",
            "--depth",
            "11000",
        ],
        &["--preset", "storm", "--time", "1000000", "--dt", "10"],
        &[
            "--waves",
            "gerstner",
            "--time",
            "1000000",
            "--choppiness",
            "10",
        ],
        &[
            "--render-scale",
            "0.25",
            "--rtt-scale",
            "0.1",
            "--tess-edge",
            "2",
            "--terrain-grid",
            "512",
        ],
        &[
            "--camera",
            "0,20000,0",
            "--sun",
            "0,90",
            "--tess-edge",
            "256",
        ],
        &[
            "--camera",
            "0,0.5,0",
            "--sun",
            "180,0",
            "--sea-floor",
            "500",
        ],
        &["--size", "1x1", "--quality", "low", "--sea-floor", "1"],
    ];
    for (i, extra) in cases.iter().enumerate() {
        let dir = scratch(&format!("extreme-{i}"));
        let shot = dir.join("shot.png");
        let (dump, shot_arg) = (dir.to_str().unwrap(), shot.to_str().unwrap());
        let mut args = vec![
            "--headless",
            "--validation",
            "--size",
            "96x54",
            "--fft-size",
            "64",
            "--frames",
            "2",
            "--dump",
            dump,
            "--screenshot",
            shot_arg,
        ];
        // Later flags win: a case's own --size replaces the default above.
        args.extend_from_slice(extra);
        let out = run(&args);
        clean_run(&out, &format!("{extra:?}"));
        let files: &[&str] = if extra.contains(&"gerstner") {
            &["displacement.npy", "normals.npy"]
        } else {
            &["h0.npy", "displacement.npy", "normals.npy"]
        };
        for file in files {
            let (_, values) = read_npy_f32(&dir.join(file));
            assert!(!values.is_empty(), "{extra:?}: {file} is empty");
            let bad = values.iter().filter(|v| !v.is_finite()).count();
            assert_eq!(bad, 0, "{extra:?}: {bad} NaN/Inf values in {file}");
        }
        let (w, h, _) = common::read_png(&shot);
        let want = if extra.contains(&"1x1") {
            (1, 1)
        } else {
            (96, 54)
        };
        assert_eq!((w, h), want, "{extra:?}");
    }
}
