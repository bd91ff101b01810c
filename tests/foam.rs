//! Whitecaps (src/ocean/foam.rs) end to end: the GPU's foam is the CPU reference's (the whole
//! surface's Jacobian, persistence, the first frame's warm-up). The whitecap fraction against
//! Monahan & O'Muircheartaigh (1980) is in tests/accuracy.rs.

mod common;

use common::{read_npy_f32, run, scratch, stderr};
use vkocean::ocean::cpu::{surface_jacobian, CpuOcean};
use vkocean::ocean::foam;
use vkocean::ocean::{OceanSettings, SeaState};

#[test]
fn first_frame_foam_matches_the_cpu_reference() {
    let dir = scratch("foam-dump");
    let out = run(&[
        "--headless",
        "--size",
        "64x36",
        "--preset",
        "storm",
        "--fft-size",
        "64",
        "--time",
        "40",
        "--dump",
        dir.to_str().unwrap(),
        "--validation",
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let p: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("params.json")).unwrap()).unwrap();
    assert_eq!(p["spectrum"], "jonswap");
    let n = p["fft_size"].as_u64().unwrap() as usize;
    let settings = OceanSettings {
        sea: SeaState {
            wind_speed_m_s: p["wind_speed_m_s"].as_f64().unwrap(),
            wind_dir_deg: p["wind_dir_deg"].as_f64().unwrap(),
            fetch_km: p["fetch_km"].as_f64().unwrap(),
            ..SeaState::default()
        },
        fft_size: n,
        patch_size_m: p["patch_sizes_m"][0].as_f64().unwrap(),
        cascades: p["cascades"].as_u64().unwrap() as usize,
        choppiness: p["choppiness"].as_f64().unwrap(),
        seed: p["seed"].as_u64().unwrap(),
        ..OceanSettings::default()
    };
    let threshold = p["foam"]["threshold"].as_f64().unwrap();
    assert!(
        (threshold - foam::threshold(&settings) as f64).abs() < 1e-6,
        "params.json's threshold {threshold} is foam::threshold of its settings"
    );

    // The CPU replays the warm-up steps and the frame: foam = max(prev·e^(−dt/τ), source).
    let t = p["t"].as_f64().unwrap();
    let cpu = CpuOcean::new(&settings);
    let patches: Vec<f64> = cpu.cascades().iter().map(|c| c.patch_m).collect();
    let step = foam::WARMUP_STEP_S as f64;
    let decay = (-step / foam::DECAY_S as f64).exp();
    let mut expected = vec![0.0f64; n * n];
    let mut source = Vec::new();
    for i in (0..=foam::WARMUP_STEPS).rev() {
        let j = surface_jacobian(&cpu.fields(t - i as f64 * step), &patches, n);
        source = j
            .iter()
            .map(|j| ((threshold - j) * foam::GAIN as f64).clamp(0.0, 1.0))
            .collect();
        for (f, s) in expected.iter_mut().zip(&source) {
            *f = (*f * decay).max(*s);
        }
    }
    let normals = read_npy_f32(&dir.join("normals.npy")).1;
    let gpu: Vec<f64> = (0..n * n).map(|i| normals[i * 4 + 3] as f64).collect();
    let max_err = gpu
        .iter()
        .zip(&expected)
        .map(|(g, e)| (g - e).abs())
        .fold(0.0, f64::max);
    assert!(
        max_err < 2e-3,
        "GPU foam vs CPU reference: max error {max_err}"
    );
    let others = normals[n * n * 4..].chunks_exact(4).map(|t| t[3].abs());
    assert_eq!(
        others.fold(0.0, f32::max),
        0.0,
        "foam lives in layer 0 only"
    );
    // The reference is not trivial: whitecaps, and fading foam beyond the current source.
    let covered = expected.iter().filter(|f| **f >= 0.5).count() as f64 / (n * n) as f64;
    let trails = expected
        .iter()
        .zip(&source)
        .filter(|(f, s)| **f >= 0.5 && **s < 0.5)
        .count();
    assert!(
        covered > 0.05 && trails > 0,
        "storm: {covered} covered, {trails} texels of fading foam"
    );
}
