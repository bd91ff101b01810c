//! Wakes (issue 35, src/ocean/wake.rs): the GPU's eWave step against the CPU reference in f64,
//! and the wake of a boat at 3 m/s in deep water against Kelvin's theory, measured on the dumped
//! field (wake.npy): its waves are stationary in the boat's frame, their energy lies on the
//! stationary-wave curve √(g|k|) = U|k·û|, and its cusp lines open at arcsin(1/3) = 19.47°.

mod common;

use std::path::Path;

use rustfft::num_complex::Complex64;
use vkocean::ocean::wake::{fft2, Boat, CpuWake, GRID_N, SPONGE_TEXELS};

/// The dumped wake: heights `[j * N + i]`, the grid's texel (0, 0) and size, the boat.
struct Dumped {
    h: Vec<f64>,
    origin: [f64; 2],
    spacing: f64,
    boat: Boat,
    t: f64,
}

/// Runs `args` headless with `--dump` (validation on, asserted clean) and reads the wake.
fn dumped(name: &str, args: &[&str]) -> Dumped {
    let dir = common::scratch(name);
    let dump = dir.join("dump");
    let dump_arg = dump.to_str().unwrap();
    let mut all = vec![
        "--headless",
        "--size",
        "64x36",
        "--validation",
        "--dump",
        dump_arg,
    ];
    all.extend_from_slice(args);
    let out = common::run(&all);
    common::clean_run(&out, name);
    let d = read(&dump);
    let _ = std::fs::remove_dir_all(&dir);
    d
}

fn read(dump: &Path) -> Dumped {
    let (descr, h) = common::read_npy_f32(&dump.join("wake.npy"));
    assert!(descr.contains("'shape': (256, 256)"), "{descr}");
    let params: serde_json::Value =
        serde_json::from_slice(&std::fs::read(dump.join("params.json")).unwrap()).unwrap();
    let w = &params["wake"];
    let pair = |v: &serde_json::Value| [v[0].as_f64().unwrap(), v[1].as_f64().unwrap()];
    let t = params["t"].as_f64().unwrap();
    let b = &w["boat"];
    Dumped {
        h: h.into_iter().map(f64::from).collect(),
        origin: pair(&w["origin_m"]),
        spacing: w["spacing_m"].as_f64().unwrap(),
        boat: Boat {
            speed_m_s: b["speed_m_s"].as_f64().unwrap(),
            heading_deg: b["heading_deg"].as_f64().unwrap(),
            anchor: pair(&b["position"]),
            anchor_time_s: t,
        },
        t,
    }
}

#[test]
fn the_gpu_wake_is_the_cpu_reference() {
    // The first frame: the warm-up's steps (the boat's 40 s before it, the grid following it
    // on a diagonal course) on the GPU in f32, on the CPU in f64 with rustfft.
    let d = dumped("wake-reference", &["--frames", "1", "--boat", "3,30"]);
    let steps = d.boat.warmup(d.t, d.origin);
    let mut cpu = CpuWake::new(steps[0].origin, None);
    cpu.run(&d.boat, &steps);
    let (mut err, mut norm, mut most) = (0.0, 0.0, 0.0f64);
    for (g, c) in d.h.iter().zip(&cpu.h) {
        err += (g - c).powi(2);
        norm += c * c;
        most = most.max((g - c).abs());
    }
    let relative = (err / norm).sqrt();
    println!(
        "{} steps: relative rms {relative:.2e}, most {:.3} mm",
        steps.len(),
        most * 1e3
    );
    assert!(
        relative < 2e-4 && most < 2e-5,
        "relative {relative}, most {most} m"
    );
}

/// The wake in the boat's frame: height at `behind` m astern and `across` m to port,
/// bilinear (NaN off the grid).
fn in_boat_frame(d: &Dumped, behind: f64, across: f64) -> f64 {
    let p = d.boat.position(d.t);
    let u = d.boat.course();
    let x = p[0] - behind * u[0] - across * u[1];
    let z = p[1] - behind * u[1] + across * u[0];
    let (fi, fj) = ((x - d.origin[0]) / d.spacing, (z - d.origin[1]) / d.spacing);
    let (i, j) = (fi.floor(), fj.floor());
    if i < 0.0 || j < 0.0 || i >= (GRID_N - 1) as f64 || j >= (GRID_N - 1) as f64 {
        return f64::NAN;
    }
    let (a, c) = (fi - i, fj - j);
    let at = |di: usize, dj: usize| d.h[(j as usize + dj) * GRID_N + i as usize + di];
    at(0, 0) * (1.0 - a) * (1.0 - c)
        + at(1, 0) * a * (1.0 - c)
        + at(0, 1) * (1.0 - a) * c
        + at(1, 1) * a * c
}

/// Kelvin's half-angle as the wake shows it: for each distance astern from 12 to 48 m (out of
/// the hull's near field, inside the absorbing layer), the envelope of |h| over one transverse
/// wavelength 2πU²/g, and the outermost of its maxima on each side above half the side's
/// largest: the cusp, where the transverse and divergent waves meet and the wake is highest.
/// The cusps lie on a line whose slope is the angle (its offset is the hull's size, and the
/// Airy function's shift of the maximum inside the caustic, which grows as x^(1/3) and so
/// bends the line a little). Returns the angle of the line fitted to each side (degrees).
fn cusp_angles(d: &Dumped) -> [f64; 2] {
    let step = 0.25;
    let wavelength = 2.0 * std::f64::consts::PI * d.boat.speed_m_s.powi(2) / 9.81;
    let across: Vec<f64> = (0..=280).map(|k| -35.0 + step * k as f64).collect();
    let behind: Vec<f64> = (0..=208).map(|k| step * k as f64).collect();
    let field: Vec<Vec<f64>> = behind
        .iter()
        .map(|&x| across.iter().map(|&y| in_boat_frame(d, x, y)).collect())
        .collect();
    let half = (wavelength / step / 2.0).round() as usize;
    let mut angles = [0.0; 2];
    for (side, angle) in [1.0, -1.0].into_iter().zip(&mut angles) {
        let mut points = Vec::new();
        for (ix, &x) in behind.iter().enumerate() {
            if !(12.0..=48.0).contains(&x) {
                continue;
            }
            let rows = &field[ix.saturating_sub(half)..(ix + half + 1).min(field.len())];
            // (|y|, envelope) on this side, outward.
            let envelope: Vec<(f64, f64)> = across
                .iter()
                .enumerate()
                .filter(|(_, &y)| y * side > 0.0)
                .map(|(k, &y)| (y.abs(), rows.iter().map(|r| r[k].abs()).fold(0.0, f64::max)))
                .collect();
            let mut envelope = envelope;
            envelope.sort_by(|a, b| a.0.total_cmp(&b.0));
            let top = envelope.iter().map(|e| e.1).fold(0.0, f64::max);
            let cusp = (1..envelope.len() - 1)
                .rev()
                .find(|&k| {
                    let e = envelope[k].1;
                    e >= envelope[k - 1].1 && e >= envelope[k + 1].1 && e > 0.5 * top
                })
                .expect("a maximum");
            points.push((x, envelope[cusp].0));
        }
        let n = points.len() as f64;
        let (mx, my) = (
            points.iter().map(|p| p.0).sum::<f64>() / n,
            points.iter().map(|p| p.1).sum::<f64>() / n,
        );
        let slope = points.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum::<f64>()
            / points.iter().map(|p| (p.0 - mx).powi(2)).sum::<f64>();
        *angle = slope.atan().to_degrees();
    }
    angles
}

/// The share of the wake's spectral energy within `cells` resolution cells of the curve on
/// which a wave is stationary in the boat's frame, √(g|k|) = U|k·û| (deep water), and the
/// share of the spectral plane that band covers. The field is windowed (Hann, inside the
/// absorbing layer) and the hull's near field masked out (its static trough is no wave).
fn energy_on_the_curve(d: &Dumped, cells: f64) -> (f64, f64) {
    let n = GRID_N;
    let inner = n - 2 * SPONGE_TEXELS as usize;
    let hann = |i: usize| {
        let s = SPONGE_TEXELS as usize;
        if i < s || i >= n - s {
            0.0
        } else {
            let x = (i - s) as f64 / (inner - 1) as f64;
            0.5 - 0.5 * (2.0 * std::f64::consts::PI * x).cos()
        }
    };
    let p = d.boat.position(d.t);
    let mut z: Vec<Complex64> = (0..n * n)
        .map(|idx| {
            let (i, j) = (idx % n, idx / n);
            let x = d.origin[0] + i as f64 * d.spacing - p[0];
            let y = d.origin[1] + j as f64 * d.spacing - p[1];
            let near = 1.0 - (-(x.hypot(y) / 6.0).powi(4)).exp();
            Complex64::new(d.h[idx] * near * hann(i) * hann(j), 0.0)
        })
        .collect();
    fft2(&mut z, n, false);
    let dk = 2.0 * std::f64::consts::PI / (n as f64 * d.spacing);
    let resolution = 2.0 * std::f64::consts::PI / (inner as f64 * d.spacing);
    let u = d.boat.course();
    let (mut on, mut all, mut band) = (0.0, 0.0, 0usize);
    for (idx, v) in z.iter().enumerate() {
        let signed = |i: usize| {
            if i < n / 2 {
                i as f64
            } else {
                i as f64 - n as f64
            }
        };
        let k = [signed(idx % n) * dk, signed(idx / n) * dk];
        let omega = (9.81 * k[0].hypot(k[1])).sqrt();
        let doppler = d.boat.speed_m_s * (k[0] * u[0] + k[1] * u[1]).abs();
        let e = v.norm_sqr();
        all += e;
        if (omega - doppler).abs() <= cells * d.boat.speed_m_s * resolution {
            on += e;
            band += 1;
        }
    }
    (on / all, band as f64 / (n * n) as f64)
}

#[test]
fn a_boat_at_3_m_s_leaves_a_kelvin_wake() {
    // Fr = U/√(gL) = 0.34 on the 8 m hull: below Rabaud & Moisy's (2013) 0.5, where the
    // brightest arms lie on Kelvin's angle.
    let first = dumped("wake-kelvin", &["--frames", "1", "--boat", "3,0"]);
    let kelvin = (1.0f64 / 3.0).asin().to_degrees();
    let angles = cusp_angles(&first);
    println!("cusp lines at {angles:?} degrees (Kelvin {kelvin:.2})");
    for a in angles {
        // 5 %: the cusps are found on a 0.25 m lattice over 36 m, and the Airy shift bends
        // their line by about a degree over it.
        assert!((a / kelvin - 1.0).abs() < 0.05, "{a} degrees");
    }
    let (share, area) = energy_on_the_curve(&first, 2.0);
    println!("{share:.3} of the energy on {area:.3} of the spectral plane");
    // The band's area checks the method (it depends only on N, the spacing and U): most of
    // the energy on a band this narrow is what says the waves are the stationary ones.
    assert!(
        area < 0.06,
        "the band covers {area} of the plane: too wide to say anything"
    );
    assert!(share > 0.85, "{share} of the energy on the curve's band");

    // Stationary in the boat's frame: 3 s (9 m) later the same wake follows it.
    let later = dumped(
        "wake-later",
        &["--frames", "31", "--dt", "0.1", "--boat", "3,0"],
    );
    assert!((later.t - first.t - 3.0).abs() < 1e-9);
    let (mut ab, mut aa, mut bb) = (0.0, 0.0, 0.0);
    for k in 0..120 {
        let behind = 10.0 + 0.25 * k as f64;
        for m in 0..=160 {
            let across = -20.0 + 0.25 * m as f64;
            let (a, b) = (
                in_boat_frame(&first, behind, across),
                in_boat_frame(&later, behind, across),
            );
            ab += a * b;
            aa += a * a;
            bb += b * b;
        }
    }
    let correlation = ab / (aa * bb).sqrt();
    println!("correlation in the boat's frame 3 s apart: {correlation:.4}");
    assert!(correlation > 0.95, "{correlation}");

    // A jump in time longer than the warm-up (60 s, `--dt 10 --time-scale 6`; the warm-up
    // spans 40 s at 3 m/s) runs the warm-up again, the
    // boat anchored in front of the camera once more: the same wake as the first frame's
    // (stepping through the jump instead, the boat would have left the grid 180 m behind).
    let jumped = dumped(
        "wake-jump",
        &[
            "--frames",
            "2",
            "--dt",
            "10",
            "--time-scale",
            "6",
            "--boat",
            "3,0",
        ],
    );
    assert!((jumped.t - first.t - 60.0).abs() < 1e-9);
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let same =
        dot(&first.h, &jumped.h) / (dot(&first.h, &first.h) * dot(&jumped.h, &jumped.h)).sqrt();
    println!("after a 60 s jump, correlation with the first frame's wake: {same:.6}");
    assert!(same > 0.999, "{same}");
}

/// The newest answers after `frames` frames 1/60 s apart from `t0_s` of a simulation with
/// `settings`, its wake grid placed by a camera at the origin looking along −z.
fn answers_after(
    ctx: &std::sync::Arc<vkocean::gpu::Context>,
    settings: &vkocean::ocean::OceanSettings,
    points: &[[f64; 2]],
    t0_s: f64,
    frames: u64,
) -> vkocean::ocean::simulation::Answers {
    use vkocean::gpu::FRAMES_IN_FLIGHT;
    use vkocean::ocean::foam::FoamScene;
    let mut sim = vkocean::ocean::simulation::Simulation::new(ctx, settings).unwrap();
    for f in 0..frames {
        sim.place_window([0.0; 2]);
        sim.wake.place([0.0; 2], [0.0, -1.0]);
        sim.ask(ctx, points).unwrap();
        let t = t0_s + f as f64 / 60.0;
        sim.submit(
            f as usize % FRAMES_IN_FLIGHT,
            f + 1,
            None,
            t,
            &FoamScene::default(),
            None,
        )
        .unwrap();
    }
    let start = std::time::Instant::now();
    loop {
        if let Some(a) = sim.answers().unwrap() {
            if a.value == frames {
                return a.clone();
            }
        }
        assert!(start.elapsed().as_secs() < 60, "no answers");
        std::thread::sleep(std::time::Duration::from_millis(2));
    }
}

#[test]
fn height_queries_carry_the_wake() {
    // The same sea with and without a boat: the answers differ by the wake at each point's
    // rest position, as the CPU reference has it (the wake is what the water adds there).
    let ctx = common::gpu_context();
    let plain = vkocean::ocean::OceanSettings {
        fft_size: 64,
        ..Default::default()
    };
    let boat = vkocean::ocean::OceanSettings {
        boat: Some([3.0, 0.0]),
        ..plain.clone()
    };
    // The grid: centred 0.35 of its side ahead of the camera, the boat at its centre.
    let origin = vkocean::ocean::wake::grid_origin([0.0; 2], [0.0, -1.0]);
    let centre = [origin[0] + 64.0, origin[1] + 64.0];
    let points: Vec<[f64; 2]> = (0..256)
        .map(|k| {
            let (a, r) = (k as f64 * 2.399, 2.0 + 0.1 * k as f64);
            [centre[0] + r * a.cos() - 10.0, centre[1] + r * a.sin()]
        })
        .collect();
    let (t0, frames) = (7.0, 3);
    let with = answers_after(&ctx, &boat, &points, t0, frames);
    let without = answers_after(&ctx, &plain, &points, t0, frames);
    common::assert_validation_clean(ctx);

    let b = Boat {
        speed_m_s: 3.0,
        heading_deg: 0.0,
        anchor: centre,
        anchor_time_s: t0,
    };
    let mut cpu = CpuWake::new(origin, None);
    let mut steps = b.warmup(t0, origin);
    let mut last = t0;
    for f in 1..frames {
        let t = t0 + f as f64 / 60.0;
        steps.extend(vkocean::ocean::wake::steps_since(last, t, origin, 3.0));
        last = t;
    }
    cpu.run(&b, &steps);
    let (mut most, mut largest) = (0.0f64, 0.0f64);
    for ((a, w), p) in with.surface.iter().zip(&without.surface).zip(&points) {
        let rest = [p[0] - a.displacement[0], p[1] - a.displacement[2]];
        let (fi, fj) = ((rest[0] - origin[0]) / 0.5, (rest[1] - origin[1]) / 0.5);
        let (i, j) = (fi.floor() as usize, fj.floor() as usize);
        let (x, z) = (fi - i as f64, fj - j as f64);
        let at = |di: usize, dj: usize| cpu.h[(j + dj) * GRID_N + i + di];
        let expected = at(0, 0) * (1.0 - x) * (1.0 - z)
            + at(1, 0) * x * (1.0 - z)
            + at(0, 1) * (1.0 - x) * z
            + at(1, 1) * x * z;
        let got = a.height_m() - w.height_m();
        most = most.max((got - expected).abs());
        largest = largest.max(expected.abs());
    }
    println!(
        "wake in the answers: most error {:.4} mm, largest wake {largest:.3} m",
        most * 1e3
    );
    assert!(largest > 0.05, "the points see the wake ({largest} m)");
    assert!(most < 1e-4, "{most} m");
}

#[test]
fn the_boat_leaves_white_water_that_fades_behind_it() {
    // Straight down from 60 m over the calm sea (the grid, and the boat at its centre, under
    // the camera), with floating bodies too (validation with both on): the strip 8–25 m astern
    // (past the hull) is brighter than the same strip ahead of the bow, and 40–55 m astern the
    // white water has mostly faded (τ = 8 s, 13–18 s old there).
    let (w, h) = (480u32, 270u32);
    let pixels = common::shot(
        "wake-foam",
        (w, h),
        &[
            "--boat",
            "3,0",
            "--bodies",
            "3",
            "--preset",
            "calm",
            "--camera",
            "0,60,0",
            "--look-at",
            "0,0,-1",
        ],
        &[],
    );
    let luma = common::luma(&pixels);
    // Pixels per metre on the water 60 m down (60° vertical field of view).
    let per_m = h as f64 / (2.0 * 60.0 * 30f64.to_radians().tan());
    let (cx, cy) = (w as f64 / 2.0, h as f64 / 2.0);
    let strip = |from_m: f64, to_m: f64| {
        let rows = (cy - 1.5 * per_m) as usize..(cy + 1.5 * per_m) as usize;
        let columns = (cx + from_m * per_m) as usize..(cx + to_m * per_m) as usize;
        let values: Vec<f64> = rows
            .flat_map(|y| columns.clone().map(move |x| y * w as usize + x))
            .map(|i| luma[i])
            .collect();
        values.iter().sum::<f64>() / values.len() as f64
    };
    let (astern, ahead, far) = (strip(-25.0, -8.0), strip(8.0, 25.0), strip(-55.0, -40.0));
    println!("luma astern {astern:.1}, ahead {ahead:.1}, far astern {far:.1}");
    assert!(astern > 1.5 * ahead, "{astern} against {ahead}");
    assert!(far - ahead < 0.4 * (astern - ahead), "{far}");
}
