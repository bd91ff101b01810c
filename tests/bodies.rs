//! Floating bodies in a run (issue 35, `--bodies N`): moved by the physics of
//! src/ocean/bodies.rs (whose checks on analytic surfaces are its unit tests) on the GPU's height
//! queries, answered within the frames in flight; their states dumped to bodies.json; drawn.
//! Validation-clean.

mod common;

use std::process::Output;

use vkocean::ocean::surface::SurfaceQuery;

/// `vkocean --headless --validation --size 160x90 --dump DIR ARGS`; returns the run and the
/// parsed bodies.json.
fn run_bodies(name: &str, args: &[&str]) -> (Output, serde_json::Value, impl Fn(f64, f64) -> f64) {
    let dir = common::scratch(&format!("bodies-{name}"));
    let dump = dir.join("dump");
    let mut all = vec![
        "--headless",
        "--validation",
        "--size",
        "160x90",
        "--quality",
        "low",
        "--dump",
        dump.to_str().expect("temp paths are UTF-8"),
    ];
    all.extend_from_slice(args);
    let out = common::run(&all);
    common::clean_run(&out, &format!("{all:?}"));
    let json = std::fs::read_to_string(dump.join("bodies.json")).expect("bodies.json written");
    let params: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dump.join("params.json")).expect("params.json written"),
    )
    .expect("params.json is JSON");
    let (_, texels) = common::read_npy_f32(&dump.join("displacement.npy"));
    let _ = std::fs::remove_dir_all(&dir);
    let n = params["fft_size"].as_u64().expect("fft_size") as usize;
    let steps: Vec<f64> = params["patch_sizes_m"]
        .as_array()
        .expect("patch sizes")
        .iter()
        .map(|l| l.as_f64().expect("a size") / n as f64)
        .collect();
    // The surface the dumped images draw (deep water here: no shore factor).
    let surface = move |x: f64, z: f64| {
        let lattice = common::ImageLattice {
            texels: texels
                .chunks_exact(4)
                .map(|t| [t[0], t[1], t[2], t[3]])
                .collect(),
            n,
            steps: steps.clone(),
            origin: None,
        };
        SurfaceQuery::new(Box::new(lattice)).height_at(x, z, 0.0)
    };
    (
        out,
        serde_json::from_str(&json).expect("bodies.json is JSON"),
        surface,
    )
}

/// The number after `after` on the summary's bodies line.
fn number_after(stderr: &str, after: &str) -> u64 {
    let line = stderr
        .lines()
        .find(|l| l.contains("height queries a frame"))
        .unwrap_or_else(|| panic!("no bodies line in {stderr}"));
    let rest = &line[line.find(after).expect("field") + after.len()..];
    rest.split(|c: char| !c.is_ascii_digit())
        .next()
        .and_then(|n| n.parse().ok())
        .expect("a number")
}

/// The "answered N frames late (median; max M)" of the summary.
fn latency(stderr: &str) -> (u64, u64) {
    (
        number_after(stderr, "answered "),
        number_after(stderr, "max "),
    )
}

#[test]
fn bodies_float_at_their_draft_on_the_gpu_queries() {
    // A nearly still sea (1 m/s wind: millimetre waves): 10 s in 0.05 s frames, from the mean
    // level. Each settles with its shape's centre at height/2 − draft, the draft its relative
    // density times its height (`Fleet::scattered`: a 0.5 m high crate of 0.5, a 0.8 m deep boat of
    // 0.3, a 1.2 m buoy of 0.4, ballasted): 0, 0.16 and 0.12 m, within 2 cm, and upright.
    let (out, json, _) = run_bodies(
        "still",
        &[
            "--preset",
            "calm",
            "--wind-speed",
            "1",
            "--bodies",
            "9",
            "--frames",
            "200",
            "--dt",
            "0.05",
        ],
    );
    let err = common::stderr(&out);
    let (median, max) = latency(&err);
    assert!(
        max <= 2 && median >= 1,
        "answers {median} frames late (max {max}): expected 1–2, the frames in flight"
    );
    let bodies = json.as_array().expect("a list of bodies");
    assert_eq!(bodies.len(), 9);
    let steps = number_after(&err, "), ");
    assert!(steps >= 1150, "{steps} physics steps in 10 s of 1/120 s");
    for b in bodies {
        let shape = b["shape"].as_str().expect("shape");
        let y = b["position"][1].as_f64().expect("position");
        let expected = match shape {
            "box" => 0.0,
            "hull" => 0.4 - 0.3 * 0.8,
            "buoy" => 0.6 - 0.4 * 1.2,
            other => panic!("shape {other}"),
        };
        let speed: f64 = (0..3)
            .map(|i| b["velocity"][i].as_f64().expect("velocity").powi(2))
            .sum::<f64>()
            .sqrt();
        let q: Vec<f64> = (0..4)
            .map(|i| b["orientation"][i].as_f64().expect("orientation"))
            .collect();
        // The body's up axis: y of the rotated unit y, 1 − 2(x² + z²).
        let up = 1.0 - 2.0 * (q[0] * q[0] + q[2] * q[2]);
        assert!(
            up > 0.999,
            "{shape}: tilted to {:.1}°",
            up.acos().to_degrees()
        );
        assert!(
            (y - expected).abs() < 0.02 && speed < 0.05,
            "{shape}: centre at {y:.3} m (expected {expected:.2} ± 0.02), moving at {speed:.3} m/s"
        );
    }
}

#[test]
fn bodies_ride_a_storm_and_are_drawn() {
    // The storm (Hs 11.7 m) from 25 m: every body rides the surface, its shape's centre within
    // 1 m of the surface above it (measured: 0.89 m, a 0.5 m crate pulled under by a steep
    // crest's fall; the model leaves out the water's horizontal motion) in the dumped images (the bodies are 0.5–1.2 m high; the
    // surface found as the water draws it, `SurfaceQuery` over the dumped displacement), under
    // 6 m/s. And they show in the picture: against the same view without them, pixels change
    // where they float.
    let view = [
        "--preset",
        "storm",
        "--camera=30,12,-20",
        "--look-at=40,0,-58",
    ];
    let mut args = view.to_vec();
    args.extend_from_slice(&["--bodies", "30", "--frames", "120"]);
    let (_, json, surface) = run_bodies("storm", &args);
    let mut worst = 0.0f64;
    for b in json.as_array().expect("a list of bodies") {
        let p: Vec<f64> = (0..3)
            .map(|i| b["position"][i].as_f64().expect("position"))
            .collect();
        let speed: f64 = (0..3)
            .map(|i| b["velocity"][i].as_f64().expect("velocity").powi(2))
            .sum::<f64>()
            .sqrt();
        let water = surface(p[0], p[2]);
        worst = worst.max((p[1] - water).abs());
        assert!(
            (p[1] - water).abs() < 1.0 && speed < 6.0,
            "{}: centre at {:.2} m over water at {water:.2} m, {speed:.2} m/s",
            b["shape"],
            p[1]
        );
    }
    eprintln!("storm: bodies within {worst:.2} m of the surface");
    let mut with = view.to_vec();
    with.extend_from_slice(&["--bodies", "30", "--frames", "8", "--quality", "low"]);
    let mut without = view.to_vec();
    without.extend_from_slice(&["--frames", "8", "--quality", "low"]);
    let a = common::shot("bodies-with", (320, 180), &with, &[]);
    let b = common::shot("bodies-without", (320, 180), &without, &[]);
    let changed = a
        .chunks(4)
        .zip(b.chunks(4))
        .filter(|(p, q)| (0..3).any(|i| (p[i] as i32 - q[i] as i32).abs() > 24))
        .count();
    let share = changed as f64 / (320.0 * 180.0);
    eprintln!("bodies drawn: {:.2} % of the pixels changed", share * 100.0);
    assert!(
        share > 0.005,
        "only {:.3} % of the pixels changed with 30 bodies in view",
        share * 100.0
    );
}
