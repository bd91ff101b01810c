//! Wind gusts: patches of sea under a stronger or weaker wind than the mean, racing downwind,
//! so the far sea is not the same 400 m lattice of whitecaps and roughness repeated to the
//! horizon (shaders/common/gusts.glsl draws them; this is its CPU twin and their law).
//!
//! - **How strong.** The wind's turbulence in the neutral surface layer: σ_u ≈ 2.39·u*
//!   (Panofsky & Dutton 1984, *Atmospheric Turbulence*, §7), the friction velocity
//!   u* = √C_D·U10 with Large & Pond's (1981) drag coefficient over the sea, 10³·C_D = 1.2 from 4
//!   to 11 m/s and 0.49 + 0.065·U10 above (to 25 m/s; held outside 4–25). At 10 m/s
//!   σ_u/U10 = 0.083. The local wind is U10·(1 + g), g = (σ_u/U10)·n with n the gusts' noise
//!   made zero-mean and of unit variance.
//! - **Where and how they move.** The clouds' fractal noise (`clouds::shape`, another place in
//!   it) stretched along the wind (`GUST_ALONG_M` by `GUST_ACROSS_M`, src/shared.rs, which says
//!   why), carried downwind at U10: Taylor's (1938) frozen turbulence, the eddies advected by
//!   the mean wind.
//! - **What they change.** What the sea answers within seconds, the short waves and the
//!   breaking. The unresolved slopes' mean square follows Cox & Munk's (1954) clean-surface
//!   fits at the local wind (upwind 3.16·10⁻³·U, crosswind 0.003 + 1.92·10⁻³·U: the total
//!   grows 5.12·10⁻³ and the upwind excess 1.24·10⁻³ per m/s), so a gust is rougher: wider
//!   glitter, and far off a darker reflection of sky higher up. The whitecaps follow Monahan &
//!   O'Muircheartaigh's (1980) W ∝ U^3.41 at the local wind, normalised so the sea's mean
//!   coverage stays W(U10) (Monahan's U10 is a mean over the gusts): r times the foam laid at
//!   random over the foam layer's reflectance R (its share of the water) leaves (1 − R)^r of
//!   the water bare (`gust_foam`), so thin and far foam scales by r and opaque foam stays. The
//!   crests that break are the lattice's (new ones in a gust would need the surface's Jacobian
//!   where the water is drawn). The resolved waves (metres and longer) take minutes to hours
//!   to grow and are left as the spectrum has them.

use std::sync::OnceLock;

use crate::ocean::moments::{
    cox_munk_upwind_excess, COX_MUNK_EXCESS_PER_M_S, COX_MUNK_TOTAL_PER_M_S,
};
use crate::ocean::spectrum::wind_vector;
use crate::ocean::{OceanSettings, Waves};
use crate::shared::{
    GUST_ACROSS_M, GUST_ALONG_M, GUST_NOISE_MEAN, GUST_NOISE_OFFSET_X, GUST_NOISE_OFFSET_Y,
    GUST_NOISE_STD, WHITECAP_WIND_EXPONENT,
};

/// σ_u over the friction velocity u* in the neutral surface layer (Panofsky & Dutton 1984).
pub const SIGMA_U_PER_U_STAR: f64 = 2.39;

/// Large & Pond's (1981) neutral drag coefficient at 10 m over the sea at the wind `u10`
/// (m/s): 1.2·10⁻³ from 4 to 11 m/s, (0.49 + 0.065·U10)·10⁻³ from 11 to 25 m/s; held at the
/// ends outside that range.
pub fn drag_coefficient(u10: f64) -> f64 {
    let u = u10.clamp(4.0, 25.0);
    if u < 11.0 {
        1.2e-3
    } else {
        (0.49 + 0.065 * u) * 1e-3
    }
}

/// The gusts' strength σ_u / U10 at the wind `u10` (m/s): 2.39·√C_D.
pub fn gust_strength(u10: f64) -> f64 {
    SIGMA_U_PER_U_STAR * drag_coefficient(u10).sqrt()
}

/// The gusts' noise at (x, y) in cells of the stretched space (0–1).
fn shape_at(x: f32, y: f32) -> f32 {
    super::clouds::shape(x + GUST_NOISE_OFFSET_X, y + GUST_NOISE_OFFSET_Y)
}

/// The noise made zero-mean and of unit variance (`GUST_NOISE_MEAN`, `GUST_NOISE_STD`) at
/// points every 0.37 cells over 95 cells square: every place in the cells and octaves.
fn unit_noise_sample() -> &'static [f32] {
    static SAMPLE: OnceLock<Vec<f32>> = OnceLock::new();
    SAMPLE.get_or_init(|| {
        const SIDE: usize = 256;
        (0..SIDE * SIDE)
            .map(|i| {
                let (x, y) = ((i % SIDE) as f32 * 0.37, (i / SIDE) as f32 * 0.37);
                (shape_at(x, y) - GUST_NOISE_MEAN) / GUST_NOISE_STD
            })
            .collect()
    })
}

/// Monahan's whitecap coverage under the local wind U10·(1 + g) over W(U10): (1 + g)^3.41.
pub fn whitecap_ratio(g: f64) -> f64 {
    (1.0 + g).max(0.0).powf(f64::from(WHITECAP_WIND_EXPONENT))
}

/// The gusts of a sea.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gusts {
    /// σ_u / U10 (`gust_strength`; 0 for Gerstner waves, which have no wind).
    pub strength: f64,
    /// The mean wind (m/s) and its unit vector (x, z).
    pub wind_m_s: f64,
    pub wind: [f64; 2],
    /// The mean over the sea of `whitecap_ratio` (above 1: the law is convex), which the
    /// local ratio is divided by so the mean coverage stays W(U10).
    pub mean_whitecap_ratio: f64,
}

impl Gusts {
    /// The gusts over the sea `settings` simulates.
    pub fn of_sea(settings: &OceanSettings) -> Gusts {
        let u = settings.sea.wind_speed_m_s;
        let strength = match settings.waves {
            Waves::Fft => gust_strength(u),
            Waves::Gerstner(_) => 0.0,
        };
        let sample = unit_noise_sample();
        let mean_whitecap_ratio = sample
            .iter()
            .map(|&n| whitecap_ratio(strength * f64::from(n)))
            .sum::<f64>()
            / sample.len() as f64;
        Gusts {
            strength,
            wind_m_s: u,
            wind: wind_vector(&settings.sea),
            mean_whitecap_ratio,
        }
    }

    /// `FrameUniforms::gusts` at time `t_s` (`on`: `--gusts`), and `sea_slopes.z`: the upwind
    /// excess' growth per unit of g over the excess (0 where Cox & Munk's fit has none, below
    /// 2.4 m/s).
    pub fn uniforms(&self, t_s: f64, on: bool) -> ([f32; 4], f32) {
        let strength = if on { self.strength } else { 0.0 };
        // Carried at the mean wind, in the noise's cells along it, wrapped far beyond any
        // view's reach (a jump once every 4096 cells: 3,700 km of travel).
        let drift = (self.wind_m_s * t_s / f64::from(GUST_ALONG_M)).rem_euclid(4096.0);
        let excess = cox_munk_upwind_excess(self.wind_m_s);
        let growth = if excess > 0.0 {
            COX_MUNK_EXCESS_PER_M_S * self.wind_m_s / excess
        } else {
            0.0
        };
        (
            [
                drift as f32,
                strength as f32,
                (COX_MUNK_TOTAL_PER_M_S * self.wind_m_s) as f32,
                if on {
                    (1.0 / self.mean_whitecap_ratio) as f32
                } else {
                    1.0
                },
            ],
            growth as f32,
        )
    }
}

/// `gust_at` (shaders/common/gusts.glsl): the local wind's excess g over the mean at the world
/// point (`x`, `z`) (m), the local wind being U10·(1 + g), for `FrameUniforms::gusts` `u` and the
/// wind's unit vector `wind` (`slick_space.zw`).
pub fn gust_at(x: f32, z: f32, u: &[f32; 4], wind: [f32; 2]) -> f32 {
    let n = super::clouds::wind_shape(
        (x, z),
        wind,
        [GUST_ALONG_M, GUST_ACROSS_M],
        u[0],
        [GUST_NOISE_OFFSET_X, GUST_NOISE_OFFSET_Y],
    );
    u[1] * (n - GUST_NOISE_MEAN) / GUST_NOISE_STD
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_noise_s_mean_and_deviation_are_the_shared_constants() {
        let sample = unit_noise_sample();
        let n = sample.len() as f64;
        let mean = sample.iter().map(|&v| f64::from(v)).sum::<f64>() / n;
        let var = sample
            .iter()
            .map(|&v| (f64::from(v) - mean).powi(2))
            .sum::<f64>()
            / n;
        println!("unit noise: mean {mean:.4}, std {:.4}", var.sqrt());
        assert!(mean.abs() < 0.02, "mean {mean}");
        assert!((var.sqrt() - 1.0).abs() < 0.02, "std {}", var.sqrt());
    }

    #[test]
    fn the_gusts_are_carried_downwind_at_the_mean_wind() {
        // What lies at a point at t = 0 lies U·t downwind of it at t (Taylor's frozen
        // turbulence), and not upwind.
        let mut settings = OceanSettings::default();
        settings.sea.wind_dir_deg = 30.0;
        let gusts = Gusts::of_sea(&settings);
        let wind = gusts.wind.map(|v| v as f32);
        let (t, u10) = (40.0, gusts.wind_m_s as f32);
        let (before, _) = gusts.uniforms(0.0, true);
        let (after, _) = gusts.uniforms(f64::from(t), true);
        let (mut same, mut upwind) = (0.0f32, 0.0f32);
        for i in 0..200 {
            let (x, z) = (37.0 * i as f32, -23.0 * i as f32);
            let then = gust_at(x, z, &before, wind);
            let (dx, dz) = (u10 * t * wind[0], u10 * t * wind[1]);
            same = same.max((gust_at(x + dx, z + dz, &after, wind) - then).abs());
            upwind = upwind.max((gust_at(x - dx, z - dz, &after, wind) - then).abs());
        }
        assert!(same < 1e-3, "downwind {same}");
        assert!(upwind > 0.05, "upwind {upwind}");
    }

    #[test]
    fn gusts_are_panofsky_and_dutton_s_over_large_and_pond_s_drag() {
        // 10 m/s: u* = √(1.2·10⁻³)·10 = 0.346 m/s, σ_u = 2.39 u* = 0.828 m/s.
        assert!((gust_strength(10.0) - 0.0828).abs() < 5e-4);
        // 20 m/s: 10³·C_D = 0.49 + 1.3 = 1.79, σ_u/U = 2.39·0.0423 = 0.1011.
        assert!((gust_strength(20.0) - 0.1011).abs() < 5e-4);
        // Continuous at 11 m/s within Large & Pond's rounding (1.2 against 1.205).
        assert!((drag_coefficient(10.999) / drag_coefficient(11.0) - 1.0).abs() < 0.01);
    }

    #[test]
    fn the_foam_s_mean_coverage_stays_monahan_s() {
        let gusts = Gusts::of_sea(&OceanSettings::default());
        // Over another 95 cells square of the noise, far from the sample the mean was taken
        // over, the normalised ratio's mean is 1 within 0.5 %.
        let (u, _) = gusts.uniforms(0.0, true);
        let wind = gusts.wind.map(|v| v as f32);
        let side = 256;
        let mean = (0..side * side)
            .map(|i| {
                let (a, c) = ((i % side) as f32 * 0.37, (i / side) as f32 * 0.37);
                let (x, z) = ((a + 1000.0) * GUST_ALONG_M, (c - 700.0) * GUST_ACROSS_M);
                // Along and across the wind back to the world's x and z.
                let (wx, wz) = (wind[0], wind[1]);
                let g = gust_at(x * wx - z * wz, x * wz + z * wx, &u, wind);
                whitecap_ratio(f64::from(g))
            })
            .sum::<f64>()
            / (side * side) as f64
            / gusts.mean_whitecap_ratio;
        assert!((mean - 1.0).abs() < 0.005, "{mean}");
        // Convex: a few per cent above 1 at σ = 0.083 (3.41·2.41/2·σ² = 0.028 for a Gaussian).
        assert!(
            gusts.mean_whitecap_ratio > 1.01 && gusts.mean_whitecap_ratio < 1.05,
            "{}",
            gusts.mean_whitecap_ratio
        );
    }
}
