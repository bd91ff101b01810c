//! Whitecaps: where the foam forms, how long it stays, and how much of the sea it covers.
//!
//! **Where** comes from the surface the renderer shows: foam forms where the Jacobian J_s of the
//! whole surface (every cascade summed, `cpu::surface_jacobian`) drops below a threshold, i.e.
//! where the choppy displacement squeezes the water into the steepest crests (Tessendorf 2001,
//! §4.4; Dupuy & Bruneton 2012 use the same criterion). assemble.comp writes it into layer 0 of
//! the normal image (the largest cascade's lattice, which tiles the whole sea):
//!
//! ```text
//! foam = max(foam_prev · exp(−dt/τ), clamp((J_threshold − J_s) · GAIN, 0, 1))
//! ```
//! frame-rate independent (a maximum, not a sum), and at rest positions, so it rides the choppy
//! displacement with the water it formed in and fades after the crest has passed.
//!
//! **How much** comes from observation. The resolved surface's J hardly depends on the wind: its
//! 1 % quantile is 0.84 at the breeze, 0.78 at the moderate sea and 0.72 in the storm (N = 64),
//! because the saturation range's slopes do not grow with the wind (Phillips 1958). A fixed
//! threshold therefore gives a coverage almost flat in the wind (J < 0.83: 0.26 % at 10 m/s,
//! 0.29 % at 12.3 m/s, 1.6 % at 26.5 m/s, against 1 %, 2 % and 27 % observed). So the threshold
//! is the J quantile at which the foam covers what Monahan & O'Muircheartaigh (1980) measured at
//! sea, W = 3.84·10⁻⁶·U10^3.41: the active foam source covers W / PERSISTENCE, and the fading
//! foam behind it brings the coverage (foam ≥ 0.5) to W. The quantile is taken from the CPU
//! reference (`cpu::CpuOcean`) of the same spectrum at startup.

use super::cpu::{surface_jacobian, CpuOcean};
use super::params::{OceanSettings, Waves};

/// Whitecap fraction observed at sea at wind speed `u10` (m/s): Monahan & O'Muircheartaigh
/// (1980), W = 3.84·10⁻⁶·U10^3.41 (breeze 6.7 m/s: 0.25 %; 12.3 m/s: 2.0 %; 26.5 m/s: 27 %).
pub fn monahan_fraction(u10: f64) -> f64 {
    (3.84e-6 * u10.max(0.0).powf(3.41)).min(1.0)
}

/// e-folding time of the foam after its crest has passed (s): a few seconds, like the decaying
/// (stage B) whitecaps of Monahan & Lu (1990).
pub const DECAY_S: f32 = 2.5;
/// Foam source per unit of J below the threshold: full foam 0.1 below it, so the source is
/// nearly all or nothing and the field's level says how long ago a crest broke there.
pub const GAIN: f32 = 10.0;
/// Coverage (foam ≥ 0.5) over the area of the active source (J_s ≤ threshold − 0.5/GAIN) with
/// DECAY_S and GAIN: measured on the GPU at the presets, 2.8 (storm: its patches overlap) to 7.4
/// (calm), 4.5–7 at the breeze and the moderate sea, at `low` and `high`. tests/accuracy.rs
/// checks the coverage that results.
pub const PERSISTENCE: f64 = 4.5;
/// J threshold of the Gerstner waves (no wind speed to calibrate against): foam where the
/// trochoids squeeze the surface to less than half its area.
pub const GERSTNER_THRESHOLD: f32 = 0.5;
/// Steps of the simulation run before the first FFT frame, and their time step (s): 2 s, most
/// of the fading foam a running sea would show (`Simulation::submit`).
pub const WARMUP_STEPS: usize = 20;
pub const WARMUP_STEP_S: f32 = 0.1;
/// Coverage that counts as a whitecap in `--stats` (`surface.whitecap_fraction`).
pub const WHITECAP_FOAM: f32 = 0.5;
/// Highest J threshold: foam needs the surface squeezed by a tenth at least. Below about 1 m/s
/// the resolved waves hardly fold (J's quantiles all sit near 1: 0.9992 at 0.5 m/s, N = 64), and
/// the ramp above the quantile would put a field of about 0.5 on the whole sea.
pub const MAX_THRESHOLD: f32 = 0.9;
/// Most FFT size the threshold's CPU calibration runs at (larger grids use this one's quantile:
/// a few more resolved short waves, a little more foam).
const CALIBRATION_MAX_N: usize = 256;
/// J samples the quantile is taken from (several times for small grids).
const CALIBRATION_SAMPLES: usize = 1 << 17;

/// The J threshold for `settings`: for the FFT ocean, the J_s quantile at W(U10)/PERSISTENCE
/// plus 0.5/GAIN (the source reaches 0.5 at the quantile), at most `MAX_THRESHOLD`; for Gerstner
/// waves, `GERSTNER_THRESHOLD`.
pub fn threshold(settings: &OceanSettings) -> f32 {
    if !matches!(settings.waves, Waves::Fft) {
        return GERSTNER_THRESHOLD;
    }
    let target = monahan_fraction(settings.sea.wind_speed_m_s) / PERSISTENCE;
    let quantile = surface_jacobian_quantile(settings, target);
    ((quantile + 0.5 / GAIN as f64) as f32).min(MAX_THRESHOLD)
}

/// The `p` quantile of the surface's Jacobian J_s (CPU reference, several times).
pub fn surface_jacobian_quantile(settings: &OceanSettings, p: f64) -> f64 {
    let mut cal = settings.clone();
    cal.fft_size = settings.fft_size.min(CALIBRATION_MAX_N);
    let n = cal.fft_size;
    let ocean = CpuOcean::new(&cal);
    let patches: Vec<f64> = ocean.cascades().iter().map(|c| c.patch_m).collect();
    let times = (CALIBRATION_SAMPLES / (n * n)).max(1);
    // Times 1.7 s apart: several periods of the short waves that make the low J values.
    let mut j: Vec<f64> = (0..times)
        .flat_map(|i| surface_jacobian(&ocean.fields(7.0 + 1.7 * i as f64), &patches, n))
        .filter(|v| v.is_finite())
        .collect();
    if j.is_empty() {
        return 0.0;
    }
    let index = ((j.len() as f64 * p) as usize).min(j.len() - 1);
    let (_, value, _) = j.select_nth_unstable_by(index, |a, b| a.total_cmp(b));
    *value
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ocean::SeaState;

    #[test]
    fn monahan_law_at_the_presets() {
        // Monahan & O'Muircheartaigh (1980): W = 3.84·10⁻⁶ U^3.41 (the issue's values).
        for (u, w) in [(6.7, 0.0025), (12.3, 0.020), (26.5, 0.274)] {
            let got = monahan_fraction(u);
            assert!((got / w - 1.0).abs() < 0.02, "W({u}) = {got}, Monahan {w}");
        }
    }

    #[test]
    fn the_threshold_rises_with_the_wind() {
        let sea = |u| OceanSettings {
            sea: SeaState {
                wind_speed_m_s: u,
                ..SeaState::default()
            },
            fft_size: 64,
            ..OceanSettings::default()
        };
        let (calm, storm) = (threshold(&sea(5.0)), threshold(&sea(25.0)));
        assert!(calm < storm && calm > 0.3 && storm < 1.0, "{calm} {storm}");
    }

    #[test]
    fn a_sea_that_does_not_fold_does_not_foam() {
        // The bulk of the surface (J's median, about 1) never reaches the source's ramp, however
        // light the wind: at 0.5 m/s the quantile is 0.9992 and the ramp alone would put about
        // 0.5 on every texel.
        for u in [0.3, 0.5, 1.0, 2.5, 12.3, 26.5] {
            let s = OceanSettings {
                sea: SeaState {
                    wind_speed_m_s: u,
                    ..SeaState::default()
                },
                fft_size: 64,
                ..OceanSettings::default()
            };
            let median = surface_jacobian_quantile(&s, 0.5) as f32;
            let t = threshold(&s);
            assert!(t < median, "U10 {u}: threshold {t}, median J {median}");
            // The cap binds only where the sea hardly folds: the presets (2.5 m/s and up)
            // keep their calibrated threshold.
            if u >= 2.5 {
                assert!(t < MAX_THRESHOLD, "U10 {u}: threshold {t} capped");
            }
        }
    }
}
