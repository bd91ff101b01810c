//! Waves that feel the bottom near the island. The simulation computes one sea, for one depth
//! (deep water, or the spectrum's `--depth`); the water shader scales it at each point by what
//! the local depth d of the terrain under it makes of it (shaders/common/shore.glsl is the GLSL
//! twin of this file; tests/shared.rs compares them on the GPU):
//!
//! - **Shoaling** (linear theory, conservation of the energy flux E·c_g toward the shore): the
//!   height grows by K_s = √(c_g(ω, h_sim) / c_g(ω, d)), c_g = ½(1 + 2kh/sinh 2kh)·ω/k (e.g.
//!   Dean & Dalrymple 1991, §4.6): it dips to 0.913 at d/L₀ ≈ 0.15 and grows as Green's law
//!   (4k₀d)^−¼ in shallow water. One ω stands for the whole sea: its mean frequency
//!   ω̄ = m₁/m₀ (`SeaMoments`), where the energy is.
//! - **Depth-limited breaking**: the local significant height is min(K_s·Hs, γ·d) with the
//!   breaker index γ = 0.78 (McCowan 1894's limit H/d for a solitary wave; `BREAKER_INDEX`).
//!   How hard the waves break, 0 to 1, grows with K_s·Hs/(γ·d) − 1: the surf foam of
//!   shaders/surface/water.frag.
//! - On dry land (d ≤ 0) the factor is 0: the water lies flat under the sand.
//!
//! The literature's values (the minimum K_s, Green's law, γ) are rows of the Physical accuracy
//! table (src/ocean/accuracy.rs).
//!
//! - **The surf** (what the breaking looks like): where the waves have broken over a sloping
//!   bed the water is drawn as bores, one train of crests at the mean period P = 2π/ω̄ whose
//!   phase is the time T a crest still takes to the waterline at the phase speed ω̄/k(d)
//!   (`travel_time_s`), so the crests follow the depth contours (as refraction turns them) and
//!   slow and crowd as the water shoals; a crest-to-trough height of (√3/2)·the local Hs.
//!   On the beach each bore runs up as a ballistic sheet (Shen & Meyer 1963) whose set of
//!   waves reaches Stockdon et al. (2006)'s 2 % run-up (`runup_m`); the sand it reaches is wet.
//!   The clock that drives them is `surf_clock`; the GLSL is in shore.glsl.
//!
//! Not modelled: refraction of the simulated sea (its crests keep their direction; only the
//! bores follow the contours), the simulated waves' shortening in shallow water, wave set-up
//! apart from the run-up. The factor scales the displacement of every cascade alike, so short
//! waves that would not feel the bottom shrink with the long ones.

use super::moments::SeaMoments;
use super::spectrum::G;
use crate::shared::BREAKER_INDEX;

/// c_g(ω̄) at the depth the sea is simulated for (m/s): `frame.shore.z`.
pub fn reference_group_speed(sea: &SeaMoments) -> f64 {
    group_speed(sea.mean_omega.max(1e-3), sea.depth_m)
}

/// k·h of a wave of angular frequency ω over depth h (ω² = g k tanh kh): Guo (2002)'s explicit
/// approximation kh ≈ x²(1 − e^(−x^β))^(−1/β), x = ω√(h/g), β = 2.4908 (within 0.75 %), then
/// one Newton step (within 2·10⁻⁵: `kh_matches_the_dispersion_relation`). As shore.glsl does.
pub fn kh(omega: f64, h: f64) -> f64 {
    let k0h = omega * omega * h / G;
    let x = k0h.sqrt();
    let y = k0h
        * (1.0 - (-x.powf(2.4908)).exp())
            .max(1e-30)
            .powf(-1.0 / 2.4908);
    let t = y.min(10.0).tanh();
    y - (y * t - k0h) / (t + y * (1.0 - t * t))
}

/// Group velocity c_g = n·ω/k with n = ½(1 + 2kh/sinh 2kh) (m/s).
pub fn group_speed(omega: f64, h: f64) -> f64 {
    let y = kh(omega, h).max(1e-6);
    let z = (2.0 * y).min(20.0);
    let n = 0.5 * (1.0 + z / z.sinh());
    n * omega * h / y
}

/// The linear shoaling coefficient of the sea at `depth` (m).
pub fn shoaling(sea: &SeaMoments, depth: f64) -> f64 {
    let omega = sea.mean_omega.max(1e-3);
    (reference_group_speed(sea) / group_speed(omega, depth.max(0.01))).sqrt()
}

/// The waves at a point of the water over the shallows.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShoreWaves {
    /// Factor on the simulated displacement and slopes: local Hs / the sea's Hs.
    pub scale: f64,
    /// 0 where the waves do not break, 1 where the shoaled height is twice what the depth holds.
    pub breaking: f64,
    /// Local significant wave height (m).
    pub hs_m: f64,
}

/// The waves where the water is `depth` deep: `shore_waves` of shore.glsl.
pub fn shore_waves(sea: &SeaMoments, depth: f64) -> ShoreWaves {
    shore_waves_at(sea, shoaling(sea, depth), depth)
}

/// The same with the shoaling coefficient `ks` given: `shore_waves_at` of shore.glsl (the water
/// shader interpolates `ks` between vertices and takes the depth per pixel).
pub fn shore_waves_at(sea: &SeaMoments, ks: f64, depth: f64) -> ShoreWaves {
    let hs = sea.hs_m.max(1e-3);
    let limit = BREAKER_INDEX as f64 * depth.max(0.0);
    let local = (ks * hs).min(limit);
    ShoreWaves {
        scale: local / hs,
        breaking: (ks * hs / limit.max(1e-3) - 1.0).clamp(0.0, 1.0),
        hs_m: local,
    }
}

/// Waves the surf's clock counts before it starts again (`SURF_WAVES` of shore.glsl): a wave's
/// strength is drawn from its number mod this.
pub const SURF_WAVES: f64 = 256.0;

/// The surf's clock at time `time_s` (s) for a sea of mean angular frequency `mean_omega`:
/// the waves since t = 0, mod `SURF_WAVES`, reduced in f64 so it keeps its precision however
/// late (`frame.shore.w`).
pub fn surf_clock(time_s: f64, mean_omega: f64) -> f32 {
    (time_s * mean_omega.max(1e-3) / std::f64::consts::TAU).rem_euclid(SURF_WAVES) as f32
}

/// Below this bed slope the surf draws no bores (`SURF_SLOPE_MIN` of shore.glsl).
pub const SURF_SLOPE_MIN: f64 = 0.01;

/// The time (s) a crest of angular frequency `omega` takes from `depth` to the waterline over
/// a bed of slope `slope` at the phase speed c = ω/k: T = (1/(m·ω))·∫₀^d k(h) dh, the integral
/// by three-point Gauss–Legendre in u with h = d·u² (`shore_travel_s` of shore.glsl; exact in
/// shallow water, where T = 2√d/(m·√g)).
pub fn travel_time_s(omega: f64, depth: f64, slope: f64) -> f64 {
    if depth <= 0.0 {
        return 0.0;
    }
    let nodes = [
        (0.5 - 0.5 * 0.6f64.sqrt(), 5.0 / 18.0),
        (0.5, 8.0 / 18.0),
        (0.5 + 0.5 * 0.6f64.sqrt(), 5.0 / 18.0),
    ];
    let integral: f64 = nodes
        .iter()
        .map(|&(u, w)| w * 2.0 * kh(omega, (depth * u * u).max(1e-6)) / u)
        .sum();
    integral / (slope.max(SURF_SLOPE_MIN) * omega)
}

/// The 2 % run-up (m above the still water) of a sea of deep-water significant height `hs`
/// and mean angular frequency `omega` on a beach of slope `slope`: Stockdon et al. (2006),
/// eq. 19, R₂ = 1.1·(0.35·β·√(H₀L₀) + ½·√(H₀L₀·(0.563·β² + 0.004))), with L₀ = g·T²/2π at
/// the mean period (`shore_runup_m` of shore.glsl).
pub fn runup_m(hs: f64, omega: f64, slope: f64) -> f64 {
    let l0 = std::f64::consts::TAU * G / (omega * omega).max(1e-6);
    let hl = hs * l0;
    1.1 * (0.35 * slope * hl.sqrt() + 0.5 * (hl * (0.563 * slope * slope + 0.004)).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ocean::moments::DEEP_WATER_M;
    use crate::ocean::spectrum::dispersion;

    /// k·h from the exact dispersion relation (bisection on ω(k) of `spectrum::dispersion`).
    fn exact_kh(omega: f64, h: f64) -> f64 {
        let (mut lo, mut hi) = (0.0, 10.0 * (omega * omega / G + omega / (G * h).sqrt()));
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if dispersion(mid, Some(h)).0 < omega {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi) * h
    }

    #[test]
    fn kh_matches_the_dispersion_relation() {
        // k₀h from 10⁻⁴ (a 10 s wave over 2.5 cm) to 100 (deep water).
        let omega = 2.0 * std::f64::consts::PI / 10.0;
        let mut worst = 0.0f64;
        for i in -40..=20 {
            let k0h = 10f64.powf(i as f64 / 10.0);
            let h = k0h * G / (omega * omega);
            worst = worst.max((kh(omega, h) / exact_kh(omega, h) - 1.0).abs());
        }
        assert!(
            worst < 5e-5,
            "Guo (2002) + one Newton step: worst relative error {worst}"
        );
    }

    fn deep(omega: f64) -> SeaMoments {
        SeaMoments {
            hs_m: 1.0,
            mean_omega: omega,
            depth_m: DEEP_WATER_M,
            slope_variance: [0.0; 4],
            slope_anisotropy: [[0.0; 2]; 4],
            curvature_variance: [0.0; 4],
            short_slope_variance: [0.0; 4],
            slope_mip_gain: [[1.0; 4]; crate::ocean::moments::MIP_LEVELS],
        }
    }

    #[test]
    fn deep_water_does_not_shoal() {
        // Dean & Dalrymple's minimum (0.913) and Green's law are rows of the Physical accuracy
        // table (src/ocean/accuracy.rs, tests/accuracy.rs); here: no change where d ≥ L₀.
        let omega = 2.0 * std::f64::consts::PI / 8.0;
        let l0 = 2.0 * std::f64::consts::PI * G / (omega * omega);
        for r in [1.0, 2.0, 5.0] {
            let ks = shoaling(&deep(omega), r * l0);
            assert!((ks - 1.0).abs() < 1e-3, "K_s {ks} at d = {r} L₀");
        }
    }

    #[test]
    fn breaking_limits_the_height_to_the_breaker_index() {
        let sea = SeaMoments {
            hs_m: 3.0,
            ..deep(0.8)
        };
        for depth in [0.5, 1.0, 2.0, 3.0, 3.8] {
            let w = shore_waves(&sea, depth);
            // 3 m waves over less than 3.85 m: broken down to 0.78 d (McCowan 1894).
            assert!(
                (w.hs_m / (0.78 * depth) - 1.0).abs() < 1e-6,
                "Hs {} at {depth} m (0.78 d = {})",
                w.hs_m,
                0.78 * depth
            );
            assert!(w.breaking > 0.0 && w.breaking <= 1.0);
            assert!((w.scale - w.hs_m / 3.0).abs() < 1e-12);
        }
        // Deeper: shoaled, not broken; the breaking strength grows toward the shore.
        let w = shore_waves(&sea, 30.0);
        assert_eq!(w.breaking, 0.0);
        assert!((w.hs_m / (3.0 * shoaling(&sea, 30.0)) - 1.0).abs() < 1e-12);
        let strength: Vec<f64> = [3.6, 3.2, 2.8]
            .iter()
            .map(|&d| shore_waves(&sea, d).breaking)
            .collect();
        assert!(strength.windows(2).all(|p| p[0] < p[1]), "{strength:?}");
        // Dry land: flat water, full surf at the waterline.
        let w = shore_waves(&sea, -2.0);
        assert_eq!((w.scale, w.breaking), (0.0, 1.0));
    }

    /// k·h solving y·tanh y = ω²h/g by bisection (any depth: `spectrum::dispersion` floors
    /// the depth at 1 mm).
    fn solved_kh(omega: f64, h: f64) -> f64 {
        let k0h = omega * omega * h / G;
        let (mut lo, mut hi) = (0.0, k0h.sqrt() + k0h + 1.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid * mid.tanh() < k0h {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// ∫ ds / c from `depth` to the waterline over a plane bed of slope `slope`: ds = dh/m,
    /// c = ω/k, summed by the midpoint rule over 20,000 steps in u with h = d·u² (the
    /// integrand 2·d·u·k(d·u²) has no singularity at the waterline).
    fn travel_time_by_steps(omega: f64, depth: f64, slope: f64) -> f64 {
        let steps = 20_000;
        let du = 1.0 / steps as f64;
        (0..steps)
            .map(|i| {
                let u = (i as f64 + 0.5) * du;
                let h = depth * u * u;
                2.0 * depth * u * solved_kh(omega, h) / h * du
            })
            .sum::<f64>()
            / (slope * omega)
    }

    #[test]
    fn bores_travel_at_the_phase_speed() {
        // Airy's phase speed c = ω/k, so in shallow water √(g·d) (kh < 0.1 here): the time
        // to the waterline 2√d/(m·√g). Checked within 0.5 % against a fine sum of ds/c in
        // every regime, and within 1 % against the shallow-water limit where it holds.
        for period in [5.0, 8.0, 12.0] {
            let omega = std::f64::consts::TAU / period;
            for slope in [0.02, 0.1, 0.2] {
                for depth in [0.05, 0.5, 2.0, 8.0, 20.0] {
                    let t = travel_time_s(omega, depth, slope);
                    let reference = travel_time_by_steps(omega, depth, slope);
                    assert!(
                        (t / reference - 1.0).abs() < 5e-3,
                        "T {t} s, sum {reference} s (P {period} s, m {slope}, d {depth} m)"
                    );
                    if kh(omega, depth) < 0.1 {
                        let shallow = 2.0 * depth.sqrt() / (slope * G.sqrt());
                        assert!((t / shallow - 1.0).abs() < 1e-2, "T {t}, shallow {shallow}");
                    }
                }
            }
        }
        assert_eq!(
            travel_time_s(0.8, -1.0, 0.1),
            0.0,
            "dry land: the bore is there"
        );
    }

    #[test]
    fn the_runup_is_stockdons() {
        // Stockdon et al. (2006), eq. 19, by hand: H₀ 2 m, T 10 s (L₀ = 156.13 m), β 0.1:
        // √(H₀L₀) = 17.671 m; set-up 0.35·0.1·17.671 = 0.6185 m; swash
        // √(312.26·0.00963) = 1.7341 m; R₂ = 1.1·(0.6185 + 0.8671) = 1.634 m.
        let r = runup_m(2.0, std::f64::consts::TAU / 10.0, 0.1);
        assert!((r / 1.634 - 1.0).abs() < 2e-3, "R2 {r} m");
        // Steeper beaches reach higher; higher and longer waves too.
        let omega = 0.8;
        assert!(runup_m(2.0, omega, 0.15) > runup_m(2.0, omega, 0.05));
        assert!(runup_m(3.0, omega, 0.1) > runup_m(2.0, omega, 0.1));
        assert!(runup_m(2.0, 0.5, 0.1) > runup_m(2.0, omega, 0.1));
    }

    #[test]
    fn the_surf_clock_counts_waves() {
        let omega = std::f64::consts::TAU / 8.0;
        assert!((surf_clock(4.0, omega) - 0.5).abs() < 1e-6);
        // It starts again after SURF_WAVES waves, and keeps its precision a week in.
        assert!((surf_clock(8.0 * (SURF_WAVES + 2.25), omega) - 2.25).abs() < 1e-5);
        let week: f64 = 7.0 * 86_400.0;
        let t = (week / 8.0).floor() * 8.0 + 2.0;
        let expected = ((week / 8.0).floor() % SURF_WAVES + 0.25) as f32;
        assert!((surf_clock(t, omega) - expected).abs() < 1e-4);
    }

    #[test]
    fn a_sea_simulated_at_finite_depth_is_unchanged_at_that_depth() {
        let sea = SeaMoments {
            hs_m: 1.0,
            mean_omega: 0.9,
            depth_m: 12.0,
            slope_variance: [0.0; 4],
            slope_anisotropy: [[0.0; 2]; 4],
            curvature_variance: [0.0; 4],
            short_slope_variance: [0.0; 4],
            slope_mip_gain: [[1.0; 4]; crate::ocean::moments::MIP_LEVELS],
        };
        assert!((shoaling(&sea, 12.0) - 1.0).abs() < 1e-12);
        assert!((shore_waves(&sea, 12.0).scale - 1.0).abs() < 1e-12);
    }
}
