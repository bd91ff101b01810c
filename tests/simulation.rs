//! The GPU simulation (evolve → FFT → assemble on the compute queue) against the CPU reference
//! (rustfft, f64) from the same h0: displacement and normals within relative L2 < 1e-4, for
//! several spectra, depths and sizes; validation-clean.

mod common;

use vkocean::ocean::cpu::CpuOcean;
use vkocean::ocean::foam::FoamScene;
use vkocean::ocean::simulation::Simulation;
use vkocean::ocean::{OceanSettings, SeaState, SpectrumKind};

/// Relative L2 error of components `comps` of GPU values against CPU values.
fn relative_l2(gpu: &[[f32; 4]], cpu: &[[f64; 4]], comps: std::ops::Range<usize>) -> f64 {
    common::relative_l2(
        gpu.iter()
            .zip(cpu)
            .flat_map(|(g, c)| comps.clone().map(move |i| (g[i] as f64, c[i]))),
    )
}

#[test]
fn gpu_fields_match_the_cpu_reference() {
    let ctx = common::gpu_context();
    // Late times too: the GPU gets the time as ticks of the repeat period computed in f64, so
    // t = 10^6 s (the CLI's limit) matches the f64 reference as well as t = 3.25 s does.
    let cases = [
        (SpectrumKind::Jonswap, None, 128usize, 3usize, 1.0, 3.25),
        (SpectrumKind::PiersonMoskowitz, Some(15.0), 64, 2, 0.7, 1e6),
        (SpectrumKind::Phillips, None, 256, 4, 1.3, 123_456.789),
    ];
    for (spectrum, depth_m, n, cascades, choppiness, t) in cases {
        let settings = OceanSettings {
            sea: SeaState {
                spectrum,
                depth_m,
                ..SeaState::default()
            },
            fft_size: n,
            patch_size_m: 300.0,
            cascades,
            choppiness,
            seed: 42,
            waves: vkocean::ocean::Waves::Fft,
            spray: true,
            foam_sim: None,
            boat: None,
        };
        let mut sim = Simulation::new(&ctx, &settings).unwrap();
        sim.submit(0, 1, None, t, &FoamScene::default(), None)
            .unwrap();
        let (displacement, normals) = sim.read_back(&ctx, 0).unwrap();
        let cpu = CpuOcean::new(&settings).fields(t);
        let plane = n * n;
        for (c, fields) in cpu.iter().enumerate() {
            let gpu_d = &displacement[c * plane..(c + 1) * plane];
            let gpu_n = &normals[c * plane..(c + 1) * plane];
            let e_d = relative_l2(gpu_d, &fields.displacement, 0..3);
            let e_s = relative_l2(gpu_n, &fields.normals, 0..2);
            let e_j = relative_l2(gpu_n, &fields.normals, 2..3);
            assert!(e_d < 1e-4 && e_s < 1e-4 && e_j < 1e-4, "{spectrum:?} N={n} cascade {c}: displacement {e_d:e}, slopes {e_s:e}, Jacobian {e_j:e}");
            assert!(
                gpu_n.iter().all(|v| v.iter().all(|x| x.is_finite())),
                "finite normals"
            );
        }
    }
    common::assert_validation_clean(ctx);
}

#[test]
fn same_seed_same_surface() {
    let ctx = common::gpu_context();
    let settings = OceanSettings {
        fft_size: 64,
        ..OceanSettings::default()
    };
    let mut a = Simulation::new(&ctx, &settings).unwrap();
    let mut b = Simulation::new(&ctx, &settings).unwrap();
    a.submit(0, 1, None, 1.5, &FoamScene::default(), None)
        .unwrap();
    // Each simulation has its own compute timeline: its first frame is value 1.
    b.submit(0, 1, None, 1.5, &FoamScene::default(), None)
        .unwrap();
    let ra = a.read_back(&ctx, 0).unwrap();
    let rb = b.read_back(&ctx, 0).unwrap();
    assert!(
        ra.0 == rb.0 && ra.1 == rb.1,
        "identical seeds give identical fields"
    );
    let other = OceanSettings {
        seed: 2,
        ..settings
    };
    let mut c = Simulation::new(&ctx, &other).unwrap();
    c.submit(0, 1, None, 1.5, &FoamScene::default(), None)
        .unwrap();
    assert!(
        c.read_back(&ctx, 0).unwrap().0 != ra.0,
        "another seed, another sea"
    );
}

#[test]
fn gerstner_gpu_matches_the_analytic_waves() {
    use vkocean::ocean::gerstner::{default_waves, evaluate};
    use vkocean::ocean::Waves;
    let ctx = common::gpu_context();
    let waves = default_waves();
    let (n, window) = (64usize, 100.0f64);
    let settings = OceanSettings {
        fft_size: n,
        patch_size_m: window,
        waves: Waves::Gerstner(waves.clone()),
        ..OceanSettings::default()
    };
    let mut sim = Simulation::new(&ctx, &settings).unwrap();
    // Far from the world origin, where a naive float phase would lose precision.
    let (t, camera) = (2.75f64, [1234.5, -678.25]);
    sim.place_window(camera);
    sim.submit(0, 1, None, t, &FoamScene::default(), None)
        .unwrap();
    let origin = sim.origin_m();
    let step = window / n as f64;
    for (o, c) in origin.iter().zip(camera) {
        assert!(
            (o + window / 2.0 - c).abs() <= step,
            "window centred on the camera: origin {origin:?}"
        );
        assert!(
            (o / step - (o / step).round()).abs() < 1e-9,
            "origin on the world lattice"
        );
    }
    let (displacement, normals) = sim.read_back(&ctx, 0).unwrap();
    let (mut max_d, mut max_n) = (0.0f64, 0.0f64);
    for m in 0..n {
        for col in 0..n {
            let (a, b) = (origin[0] + col as f64 * step, origin[1] + m as f64 * step);
            let (p, normal) = evaluate(&waves, a, b, t);
            let d = displacement[m * n + col];
            let expected = [p[0] - a, p[1], p[2] - b];
            for i in 0..3 {
                max_d = max_d.max((d[i] as f64 - expected[i]).abs());
            }
            let s = normals[m * n + col];
            let g = [-s[0] as f64, 1.0, -s[1] as f64];
            let len = (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]).sqrt();
            for i in 0..3 {
                max_n = max_n.max((g[i] / len - normal[i]).abs());
            }
        }
    }
    assert!(max_d < 1e-4, "max displacement error {max_d:e} m");
    assert!(max_n < 1e-4, "max normal error {max_n:e}");
    drop(sim);
    common::assert_validation_clean(ctx);
}

#[test]
fn no_nan_or_inf_on_the_gpu_across_sea_states_and_sizes() {
    // Extreme sea states (calm and shallow, storm over a long fetch, Phillips in a storm) at the
    // smallest and largest FFT sizes: every texel of both images stays finite.
    let ctx = common::gpu_context();
    let states = [
        SeaState {
            spectrum: SpectrumKind::Jonswap,
            wind_speed_m_s: 0.5,
            fetch_km: 1.0,
            depth_m: Some(1.0),
            ..SeaState::default()
        },
        SeaState {
            spectrum: SpectrumKind::PiersonMoskowitz,
            wind_speed_m_s: 40.0,
            depth_m: Some(1.0),
            ..SeaState::default()
        },
        SeaState {
            spectrum: SpectrumKind::Jonswap,
            wind_speed_m_s: 40.0,
            fetch_km: 1000.0,
            depth_m: None,
            ..SeaState::default()
        },
        SeaState {
            spectrum: SpectrumKind::Phillips,
            wind_speed_m_s: 40.0,
            ..SeaState::default()
        },
    ];
    for (i, sea) in states.iter().enumerate() {
        for n in [64usize, 1024] {
            // The largest size once (it costs a second or two on lavapipe).
            if n == 1024 && i != 2 {
                continue;
            }
            let settings = OceanSettings {
                sea: sea.clone(),
                fft_size: n,
                cascades: 3,
                ..OceanSettings::default()
            };
            let mut sim = Simulation::new(&ctx, &settings).unwrap();
            sim.submit(0, 1, None, 10.0, &FoamScene::default(), None)
                .unwrap();
            let (displacement, normals) = sim.read_back(&ctx, 0).unwrap();
            let finite = |t: &[[f32; 4]]| t.iter().all(|v| v.iter().all(|x| x.is_finite()));
            assert!(
                finite(&displacement) && finite(&normals),
                "{sea:?} N={n}: NaN or Inf on the GPU"
            );
        }
    }
    common::assert_validation_clean(ctx);
}
