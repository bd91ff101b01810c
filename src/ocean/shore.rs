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
//! Not modelled: refraction (crests turning parallel to the shore), the wavelength shortening
//! in shallow water, wave set-up and run-up. The factor scales the displacement of every
//! cascade alike, so short waves that would not feel the bottom shrink with the long ones.

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

    #[test]
    fn a_sea_simulated_at_finite_depth_is_unchanged_at_that_depth() {
        let sea = SeaMoments {
            hs_m: 1.0,
            mean_omega: 0.9,
            depth_m: 12.0,
            slope_variance: [0.0; 4],
        };
        assert!((shoaling(&sea, 12.0) - 1.0).abs() < 1e-12);
        assert!((shore_waves(&sea, 12.0).scale - 1.0).abs() < 1e-12);
    }
}
