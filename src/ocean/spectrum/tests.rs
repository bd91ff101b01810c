//! Unit tests of `spectrum.rs`: spreading, dispersion, the spectra against their literature values,
//! the normalization, the RNG, the cascade bands and the time quantization.

use super::*;
use crate::ocean::accuracy::{
    banner_beta, bouws_phi, downwind_share, height_and_peak_period, jonswap_literature,
};

#[test]
fn quantized_time_repeats_exactly_and_keeps_its_precision() {
    // h(t) = h(t mod T): the same ticks, so the same phase, one period later.
    for t in [0.0, 1.5, 1e3, 1e6] {
        assert_eq!(time_ticks(t), time_ticks(t + REPEAT_PERIOD_S), "t = {t}");
    }
    // The phase of the finest wave of the default scene (k ≈ 38 rad/m, ω ≈ 19 rad/s) one
    // frame apart at t = 10^6 s advances by ω·dt, as at t = 0 (an f32 time would step by
    // 62.5 ms there).
    let k = 38.0;
    let steps = omega_steps(k, None);
    let omega = steps as f64 * omega_quantum();
    for t in [0.0, 1e6] {
        let dt = 1.0 / 60.0;
        let d = phase_turns(steps, time_ticks(t + dt)) - phase_turns(steps, time_ticks(t));
        let d = (d + 0.5).rem_euclid(1.0) - 0.5;
        let expected = omega * dt / (2.0 * PI);
        // Each end's time is rounded to a tick (T / 2^32 = 15 µs): at most ω·tick/2π.
        let tick_s = REPEAT_PERIOD_S / 4_294_967_296.0;
        let bound = omega * tick_s / (2.0 * PI);
        assert!(
            (d - expected).abs() <= bound,
            "t = {t}: phase step {d} turns, expected {expected} ± {bound}"
        );
    }
    // The quantized frequency stays within half a quantum of the dispersion relation.
    for k in [2.0 * PI / 1000.0, 0.1, 1.0, 38.0, 600.0] {
        let exact = dispersion(k, None).0;
        let q = omega_steps(k, None) as f64 * omega_quantum();
        assert!(
            (q - exact).abs() <= omega_quantum() / 2.0 + 1e-12,
            "k = {k}"
        );
    }
}

#[test]
fn donelan_banner_integrates_to_one() {
    for r in [0.3, 0.8, 1.0, 1.3, 1.6, 2.0, 2.5, 4.0, 5.0] {
        let n = 20000;
        let sum: f64 = (0..n)
            .map(|i| {
                donelan_banner(r, 1.0, -PI + 2.0 * PI * (i as f64 + 0.5) / n as f64) * 2.0 * PI
                    / n as f64
            })
            .sum();
        assert!((sum - 1.0).abs() < 1e-6, "ω/ωp = {r}: ∫D = {sum}");
    }
}

#[test]
fn donelan_banner_width_follows_donelan_and_banner() {
    // (r = ω/ω_p, β from the paper's formula, β as a number to 3 digits)
    let cases = [
        (0.6, 2.61 * 0.6f64.powf(1.3), 1.343),
        (1.0, 2.28, 2.28),
        (1.3, 2.28 * 1.3f64.powf(-1.3), 1.621),
        (1.6, banner_beta(1.6), 1.238),
        (2.5, banner_beta(2.5), 0.789),
        (4.0, banner_beta(4.0), 0.595),
    ];
    for (r, formula, literature) in cases {
        let beta = donelan_banner_beta(r);
        assert!(
            (beta / formula - 1.0).abs() < 1e-3,
            "r = {r}: β = {beta}, Donelan et al. (1985) / Banner (1990) give {formula}"
        );
        assert!(
            (beta / literature - 1.0).abs() < 2e-3,
            "r = {r}: β = {beta}, REFERENCES.md's formula gives {literature}"
        );
        // D(θ) = β / (2 tanh(βπ)) sech²(βθ) at a few angles, with the formula's β.
        for theta in [0.0, 0.4, -1.2, 2.5, PI] {
            let expected =
                formula / (2.0 * (formula * PI).tanh()) / (formula * theta).cosh().powi(2);
            let d = donelan_banner(r * 0.9, 0.9, theta);
            assert!(
                (d / expected - 1.0).abs() < 1e-3,
                "r = {r}, θ = {theta}: D = {d}, Donelan–Banner's sech² gives {expected}"
            );
        }
    }
    // Continuity where Banner's law takes over: 2.28·1.6^−1.3 = 1.2376 (Donelan et al.) against
    // 10^(−0.4 + 0.8393·1.6^−1.134) = 1.2375 (Banner).
    let (below, above) = (donelan_banner_beta(1.6 - 1e-9), donelan_banner_beta(1.6));
    assert!(
        (above / below - 1.0).abs() < 0.01,
        "β jumps at r = 1.6: {below} below, {above} above (Donelan's and Banner's laws meet at 1.2376)"
    );
}

#[test]
fn donelan_banner_high_frequencies_travel_mostly_downwind() {
    // Downwind share: the fraction of the energy of the band 2.5 ≤ ω/ω_p ≤ 4 of the
    // Pierson–Moskowitz spectrum travelling within 90° of the wind (|θ| < π/2), from the code's
    // spreading against the PM-weighted tanh(βπ/2)/tanh(βπ) of Banner's β (`accuracy`).
    let (share, expected) = downwind_share();
    assert!(
        (share / expected - 1.0).abs() < 0.005,
        "downwind share {share}, Banner's β gives {expected}"
    );
    assert!(
        (share / 0.82 - 1.0).abs() < 0.02,
        "downwind share {share} at ω/ω_p 2.5–4, Banner (1990) via Horvath (2015): about 0.82"
    );
}

#[test]
fn deep_and_shallow_dispersion() {
    let (w, d) = dispersion(0.1, None);
    assert!((w - (G * 0.1f64).sqrt()).abs() < 1e-12 && (d - G / (2.0 * w)).abs() < 1e-12);
    // Deep limit of finite depth, and shallow-water speed √(g h).
    let (w_deep, _) = dispersion(0.1, Some(1000.0));
    assert!((w_deep - w).abs() < 1e-9);
    let (w_shallow, _) = dispersion(1e-3, Some(2.0));
    assert!((w_shallow / 1e-3 - (G * 2.0f64).sqrt()).abs() < 1e-3);
    // No NaN at extremes.
    for k in [0.0, 1e-12, 1e6] {
        for h in [None, Some(1e-6), Some(1.0), Some(1e9)] {
            let (w, d) = dispersion(k, h);
            assert!(w.is_finite() && d.is_finite(), "k {k} h {h:?}");
        }
    }
}

#[test]
fn pierson_moskowitz_peak_and_height() {
    // Fully developed sea (Pierson & Moskowitz 1964): Hs = 0.21 U19.5²/g, ω_p = 0.877 g/U19.5,
    // U19.5 = 1.026 U10 (2.25 m and 7.49 s at U10 = 10 m/s).
    for u10 in [5.0, 10.0, 20.0] {
        let sea = SeaState {
            spectrum: SpectrumKind::PiersonMoskowitz,
            wind_speed_m_s: u10,
            ..SeaState::default()
        };
        let (hs, tp) = height_and_peak_period(&sea);
        let u195 = 1.026 * u10;
        let (hs_pm, tp_pm) = (0.21 * u195 * u195 / G, 2.0 * PI * u195 / (0.877 * G));
        assert!(
            (hs / hs_pm - 1.0).abs() < 0.02,
            "U10 {u10}: Hs {hs} m, Pierson & Moskowitz (1964): 0.21 U19.5²/g = {hs_pm} m"
        );
        assert!(
            (tp / tp_pm - 1.0).abs() < 0.02,
            "U10 {u10}: Tp {tp} s, Pierson & Moskowitz (1964): 2π U19.5/(0.877 g) = {tp_pm} s"
        );
        assert!(
            (2.0 * PI / peak_omega(&sea) / tp - 1.0).abs() < 1e-3,
            "peak_omega is the spectrum's peak"
        );
    }
}

#[test]
fn jonswap_peak_enhancement_adds_half_the_energy() {
    // ∫ x⁻⁵ exp(−5/4 x⁻⁴) dx = 1/5 exactly; the JONSWAP peak (γ = 3.3) multiplies the variance by
    // 1/(1 − 0.287 ln γ) = 1.521 (Goda's normalising factor, as in DNV-RP-C205, §3.5.5).
    let j1 = shape_integral(1.0);
    assert!((j1 - 0.2).abs() < 1e-6, "J(1) = {j1}, exactly 1/5");
    let ratio = shape_integral(3.3) / j1;
    let goda = 1.0 / (1.0 - 0.287 * 3.3f64.ln());
    assert!(
        (ratio / goda - 1.0).abs() < 0.02,
        "JONSWAP/PM variance at the same α and ω_p: {ratio}, Goda: 1/(1 − 0.287 ln 3.3) = {goda}"
    );
}

fn jonswap(u10: f64, fetch_km: f64) -> SeaState {
    SeaState {
        spectrum: SpectrumKind::Jonswap,
        wind_speed_m_s: u10,
        fetch_km,
        ..SeaState::default()
    }
}

#[test]
fn jonswap_height_follows_the_growth_law_until_fully_developed() {
    // Hs within 2 % of min(growth law, PM) and T_p of the peak law (or PM's) over the grid.
    for u10 in [5.0, 10.0, 15.0, 25.0] {
        for fetch_km in [10.0, 30.0, 100.0, 300.0, 1000.0] {
            let (hs, tp) = height_and_peak_period(&jonswap(u10, fetch_km));
            let (hs_lit, tp_lit) = jonswap_literature(u10, fetch_km);
            assert!(
                (hs / hs_lit - 1.0).abs() < 0.02,
                "U10 {u10}, F {fetch_km} km: Hs {hs} m, Hasselmann et al. (1973) growth law \
                 1.6e-3 X^½ U²/g capped at Pierson–Moskowitz's 0.21 U19.5²/g: {hs_lit} m"
            );
            assert!(
                (tp / tp_lit - 1.0).abs() < 0.02,
                "U10 {u10}, F {fetch_km} km: Tp {tp} s, Hasselmann et al. (1973) \
                 ω_p = 22 (g²/(U F))^⅓, at most Pierson–Moskowitz's: {tp_lit} s"
            );
        }
    }
}

#[test]
fn jonswap_grows_continuously_into_pierson_moskowitz() {
    // Through the fully developed limit (X = gF/U² ≈ 1.7–1.9·10⁴, 17–19 km at 10 m/s): Hs within
    // 2 % of min(growth law, PM) at every fetch, and never more than PM's.
    for i in 0..=24 {
        let fetch_km = 10.0 * 1.1f64.powi(i);
        let (hs, _) = height_and_peak_period(&jonswap(10.0, fetch_km));
        let (hs_lit, _) = jonswap_literature(10.0, fetch_km);
        assert!(
            (hs / hs_lit - 1.0).abs() < 0.02,
            "F {fetch_km} km: Hs {hs} m, Hasselmann et al. (1973) / Pierson–Moskowitz: {hs_lit} m"
        );
    }
    // Very long fetch: the Pierson–Moskowitz sea itself (2.25 m and 7.49 s at 10 m/s).
    for u10 in [10.0, 25.0] {
        let sea = jonswap(u10, 10_000.0);
        let pm = SpectrumShape::pierson_moskowitz(u10);
        assert_eq!(spectrum_shape(&sea), pm, "U10 {u10}: fully developed");
        let (hs, tp) = height_and_peak_period(&sea);
        let u195 = 1.026 * u10;
        let (hs_pm, tp_pm) = (0.21 * u195 * u195 / G, 2.0 * PI * u195 / (0.877 * G));
        assert!(
            (hs / hs_pm - 1.0).abs() < 0.02 && (tp / tp_pm - 1.0).abs() < 0.02,
            "U10 {u10}, 10⁴ km: Hs {hs} m, Tp {tp} s; Pierson & Moskowitz (1964): {hs_pm} m, {tp_pm} s"
        );
    }
}

#[test]
fn tma_attenuates_the_default_sea_in_shallow_water() {
    // Φ at the ends of its pieces (Bouws et al. 1985): 1/8 at ω_h = ½, ½ at 1, 7/8 at 1.5, 1 at 2.
    for (wh, phi) in [
        (0.5, 0.125),
        (1.0, 0.5),
        (1.5, 0.875),
        (2.0, 1.0),
        (3.0, 1.0),
    ] {
        let depth = 7.0;
        let got = tma_attenuation(wh / (depth / G).sqrt(), Some(depth));
        assert!(
            (got - phi).abs() < 1e-9,
            "Φ(ω_h = {wh}) = {got}, Bouws et al.: {phi}"
        );
    }
    // Hs of the default sea (JONSWAP, 10 m/s, 100 km; deep Hs 1.62 m) at 10 m and 5 m over its
    // deep-water Hs, against the deep spectrum times Φ integrated here, and against the ratios an
    // independent Python integration of the same formulas gives: 0.789 (1.27 m) and 0.605 (0.98 m).
    let (deep, _) = height_and_peak_period(&SeaState::default());
    for (depth, ratio_expected) in [(10.0, 0.789), (5.0, 0.605)] {
        let sea = SeaState {
            depth_m: Some(depth),
            ..SeaState::default()
        };
        let (shallow, _) = height_and_peak_period(&sea);
        let (n, top) = (400_000, 20.0);
        let dw = top / n as f64;
        let m0: f64 = (0..n)
            .map(|i| {
                let w = (i as f64 + 0.5) * dw;
                frequency_spectrum(&SeaState::default(), w) * bouws_phi(w, depth) * dw
            })
            .sum();
        let expected = 4.0 * m0.sqrt() / deep;
        let ratio = shallow / deep;
        assert!(
            (ratio / expected - 1.0).abs() < 0.005,
            "h = {depth} m: TMA Hs / deep Hs = {ratio}, the JONSWAP spectrum times Bouws et al.'s \
             (1985) Φ gives {expected}"
        );
        assert!(
            (ratio / ratio_expected - 1.0).abs() < 0.02,
            "h = {depth} m: TMA Hs / deep Hs = {ratio}, Bouws et al. (1985) Φ on the JONSWAP spectrum \
             (Python): {ratio_expected}"
        );
    }
}

#[test]
fn frequency_and_wavenumber_spectra_agree() {
    // ∫ S(k) d²k = ∫ S(ω) dω, since the spreading integrates to 1.
    for spectrum in [SpectrumKind::Jonswap, SpectrumKind::PiersonMoskowitz] {
        for depth in [None, Some(20.0)] {
            let sea = SeaState {
                spectrum,
                depth_m: depth,
                ..SeaState::default()
            };
            let n = 100_000;
            let var_w: f64 = (1..n)
                .map(|i| frequency_spectrum(&sea, 10.0 * i as f64 / n as f64) * 10.0 / n as f64)
                .sum();
            let var_k = integrate_density(&sea, 1e-4, 10.0 * 10.0 / G * 4.0);
            assert!(
                (var_k / var_w - 1.0).abs() < 0.01,
                "{spectrum:?} {depth:?}: {var_k} vs {var_w}"
            );
        }
    }
}

#[test]
fn phillips_variance_matches_closed_form() {
    // ∫ A e^{−1/(kL)²} k^{−4} cos²θ (1 or 0.07) k dk dθ = A (π/2)(1 + 0.07) L²/2 (ℓ-suppression negligible).
    let sea = SeaState {
        spectrum: SpectrumKind::Phillips,
        ..SeaState::default()
    };
    let l = sea.wind_speed_m_s.powi(2) / G;
    let expected = PHILLIPS_A * PI / 2.0 * (1.0 + PHILLIPS_AGAINST_WIND) * l * l / 2.0;
    let got = integrate_density(&sea, 1e-4, 1e4);
    assert!((got / expected - 1.0).abs() < 0.01, "{got} vs {expected}");
}

#[test]
fn gaussians_are_standard_and_deterministic() {
    let n = 200_000;
    let (mut sum, mut sq) = (0.0, 0.0);
    for i in 0..n {
        let (a, b) = gaussian_pair(7, 0, i, -i);
        sum += a + b;
        sq += a * a + b * b;
    }
    let mean = sum / (2 * n) as f64;
    let var = sq / (2 * n) as f64 - mean * mean;
    assert!(
        mean.abs() < 0.01 && (var - 1.0).abs() < 0.01,
        "mean {mean} var {var}"
    );
    assert_eq!(gaussian_pair(1, 2, 3, 4), gaussian_pair(1, 2, 3, 4));
    assert_ne!(gaussian_pair(1, 2, 3, 4), gaussian_pair(2, 2, 3, 4));
}

#[test]
fn no_nan_or_inf_across_sea_states() {
    // Wind 0.5-40 m/s, depth 1 m to deep, fetch 1-1000 km, k up to the Nyquist limit of the
    // finest cascade at N = 1024 (and the h0 of a small grid).
    let patch = 400.0;
    let finest = cascades(patch, 4)[3].patch_m;
    let k_max = PI * 1024.0 / finest;
    for spectrum in [
        SpectrumKind::Phillips,
        SpectrumKind::Jonswap,
        SpectrumKind::PiersonMoskowitz,
    ] {
        for wind in [0.5, 3.0, 10.0, 25.0, 40.0] {
            for depth in [Some(1.0), Some(10.0), Some(200.0), None] {
                for fetch in [1.0, 30.0, 1000.0] {
                    let sea = SeaState {
                        spectrum,
                        wind_speed_m_s: wind,
                        wind_dir_deg: 33.0,
                        fetch_km: fetch,
                        depth_m: depth,
                    };
                    for i in 0..=400 {
                        let k = k_max * (i as f64 / 400.0).powi(3);
                        for t in [-2.0f64, 0.0, 0.7, 3.1] {
                            let s = directional_density(&sea, [k * t.cos(), k * t.sin()]);
                            assert!(s.is_finite() && s >= 0.0, "{sea:?} k {k}: S = {s}");
                        }
                    }
                    for (c, cascade) in cascades(patch, 2).iter().enumerate() {
                        let h = h0(&sea, 64, cascade, c as u32, 7);
                        assert!(
                            h.iter().all(|v| v[0].is_finite() && v[1].is_finite()),
                            "{sea:?}"
                        );
                    }
                }
            }
        }
    }
}

#[test]
fn cascade_bands_are_disjoint_and_resolvable() {
    let cs = cascades(400.0, 4);
    for w in cs.windows(2) {
        assert_eq!(w[0].k_max, w[1].k_min);
        assert!(
            w[0].k_max < PI * 64.0 / w[0].patch_m,
            "boundary below the coarse Nyquist at N = 64"
        );
        assert!(
            w[1].k_min > 2.0 * PI / w[1].patch_m * 5.0,
            "boundary well above the fine Δk"
        );
    }
}
