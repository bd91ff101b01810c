use super::*;

/// A progressive wave h = A cos(k·x − ωt), φ = (gA/ω) sin(k·x − ωt) on the grid (a whole number
/// of wavelengths across it), at time `t`.
fn plane_wave(wake: &mut CpuWake, m: [i64; 2], amplitude: f64, t: f64) {
    let n = GRID_N;
    let dk = 2.0 * std::f64::consts::PI / (n as f64 * SPACING_M);
    let k = [m[0] as f64 * dk, m[1] as f64 * dk];
    let w = omega(k[0].hypot(k[1]), wake.depth_m);
    for j in 0..n {
        for i in 0..n {
            let x = [i as f64 * SPACING_M, j as f64 * SPACING_M];
            let phase = k[0] * x[0] + k[1] * x[1] - w * t;
            wake.h[j * n + i] = amplitude * phase.cos();
            wake.phi[j * n + i] = G * amplitude / w * phase.sin();
        }
    }
}

fn rms_difference(a: &[f64], b: &[f64]) -> f64 {
    let sum: f64 = a.iter().zip(b).map(|(x, y)| (x - y).powi(2)).sum();
    (sum / a.len() as f64).sqrt()
}

/// Away from the absorbing layer.
fn interior(v: &[f64]) -> Vec<f64> {
    let n = GRID_N;
    let s = SPONGE_TEXELS as usize;
    (s..n - s)
        .flat_map(|j| (s..n - s).map(move |i| v[j * n + i]))
        .collect()
}

#[test]
fn a_long_step_moves_a_wave_exactly_by_its_dispersion() {
    // eWave's point (Tessendorf 2014): the free step is exact for any Δt. One step of 2.7 s
    // (many periods of the shorter waves) against the analytic wave, deep and shallow water.
    for depth in [None, Some(3.0)] {
        for m in [[3, 0], [7, -11], [40, 25]] {
            let mut wake = CpuWake::new([0.0; 2], depth);
            plane_wave(&mut wake, m, 0.2, 0.0);
            wake.step(2.7, [0.0; 2], None);
            let mut expected = CpuWake::new([0.0; 2], depth);
            plane_wave(&mut expected, m, 0.2, 2.7);
            let err = rms_difference(&interior(&wake.h), &interior(&expected.h));
            assert!(err < 1e-9, "{depth:?} {m:?}: rms {err} m");
        }
    }
}

#[test]
fn the_grid_moves_by_whole_texels_without_changing_the_field() {
    let mut wake = CpuWake::new([0.0; 2], None);
    plane_wave(&mut wake, [5, 2], 0.1, 0.0);
    // A zero-length step with the grid 3 texels along x and 2 back along z: the same world
    // field seen from the new origin.
    let origin = [3.0 * SPACING_M, -2.0 * SPACING_M];
    wake.step(0.0, origin, None);
    let mut expected = CpuWake::new([0.0; 2], None);
    plane_wave(&mut expected, [5, 2], 0.1, 0.0);
    let n = GRID_N;
    let shifted: Vec<f64> = (0..n * n)
        .map(|idx| {
            let (i, j) = (idx % n, idx / n);
            expected.h[((j + n - 2) % n) * n + (i + 3) % n]
        })
        .collect();
    let err = rms_difference(&interior(&wake.h), &interior(&shifted));
    assert!(err < 1e-12, "rms {err} m");
}

#[test]
fn a_long_move_brings_still_water_in_not_the_far_edge() {
    // A bump of water 20 texels in from the grid's −x edge, then the grid moves 40 texels along
    // +x (past the absorbing layer's 24): the periodic shift would carry the bump round to
    // texel 256 − 20 on the far side. The water that came in is still, and the bump is gone
    // with the part of the grid left behind.
    let n = GRID_N;
    let mut wake = CpuWake::new([0.0; 2], None);
    for j in 0..n {
        for i in 0..n {
            let d2 = (i as f64 - 20.0).powi(2) + (j as f64 - 128.0).powi(2);
            wake.h[j * n + i] = 0.5 * (-d2 / 18.0).exp();
        }
    }
    wake.step(0.0, [40.0 * SPACING_M, 0.0], None);
    let came_in = (0..n)
        .flat_map(|j| (n - 40..n).map(move |i| (i, j)))
        .map(|(i, j)| wake.h[j * n + i].abs())
        .fold(0.0, f64::max);
    let kept = wake.h.iter().map(|h| h.abs()).fold(0.0, f64::max);
    assert!(
        came_in < 1e-12,
        "the far edge's water came back: {came_in} m"
    );
    assert!(
        kept < 1e-3,
        "the bump, now off the grid, is still on it: {kept} m"
    );
}

#[test]
fn a_hull_at_rest_sinks_the_water_by_its_draft() {
    // Hydrostatics: under a steady pressure p0 the water settles at −p0/(ρg) = −DRAFT_M. The
    // patch is switched on at t = 0 and its waves leave through the absorbing layer.
    let centre = GRID_SIDE_M / 2.0;
    let boat = Boat {
        speed_m_s: 1e-9,
        heading_deg: 0.0,
        anchor: [centre, centre],
        anchor_time_s: 0.0,
    };
    let mut wake = CpuWake::new([0.0; 2], Some(20.0));
    for _ in 0..400 {
        wake.step(0.1, [0.0; 2], Some((&boat, 100.0)));
    }
    let c = GRID_N / 2;
    let h = wake.h[c * GRID_N + c];
    assert!(
        (h + DRAFT_M).abs() < 0.05 * DRAFT_M,
        "h = {h} m under the hull"
    );
}

#[test]
fn the_absorbing_layer_takes_a_wave_out_of_the_grid() {
    // A packet heading for the edge: after it has crossed the layer, what is left anywhere is
    // under 2 % of its height (no wrap-around, no reflection back in).
    let n = GRID_N;
    let mut wake = CpuWake::new([0.0; 2], None);
    plane_wave(&mut wake, [16, 0], 0.1, 0.0);
    let centre = n as f64 / 2.0;
    for j in 0..n {
        for i in 0..n {
            let r2 = ((i as f64 - centre).powi(2) + (j as f64 - centre).powi(2)) / 16.0f64.powi(2);
            let envelope = (-r2).exp();
            wake.h[j * n + i] *= envelope;
            wake.phi[j * n + i] *= envelope;
        }
    }
    // λ = 8 m, c_g = 1.77 m/s: 64 m to the edge and 12 m of layer in about 45 s.
    for _ in 0..300 {
        wake.step(0.2, [0.0; 2], None);
    }
    let most = wake.h.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(most < 0.002, "{most} m left");
}

#[test]
fn warmup_ends_at_the_first_frame_in_short_steps() {
    let boat = Boat {
        speed_m_s: 3.0,
        heading_deg: 30.0,
        anchor: [10.0, 20.0],
        anchor_time_s: 5.0,
    };
    let origin = [-54.0, -44.0];
    let steps = boat.warmup(5.0, origin);
    assert!((5.0 - steps[0].from_s - 40.0).abs() < 1e-9);
    let last = steps.last().unwrap();
    assert!((last.to_s - 5.0).abs() < 1e-12 && last.origin == origin);
    for s in &steps {
        let dt = s.to_s - s.from_s;
        assert!(dt > 0.0 && dt <= max_step_s(3.0) + 1e-12);
        // The grid stays centred on the boat within a texel.
        let p = boat.position(s.to_s);
        let half = GRID_SIDE_M / 2.0;
        assert!((s.origin[0] + half - p[0]).abs() <= SPACING_M);
    }
    let p = boat.position(5.0 + 2.0);
    assert!((p[0] - 10.0 - 6.0 * 30f64.to_radians().cos()).abs() < 1e-12);
    assert_eq!(boat.strength(steps[0].from_s), 0.0);
    assert_eq!(boat.strength(5.0), 1.0);
    let later = steps_since(5.0, 5.25, origin, 3.0);
    assert_eq!(later.len(), 3);
}
