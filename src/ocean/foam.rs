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
use crate::shared::WHITECAP_WIND_EXPONENT;

/// Whitecap fraction observed at sea at wind speed `u10` (m/s): Monahan & O'Muircheartaigh
/// (1980), W = 3.84·10⁻⁶·U10^3.41 (breeze 6.7 m/s: 0.25 %; 12.3 m/s: 2.0 %; 26.5 m/s: 27 %).
pub fn monahan_fraction(u10: f64) -> f64 {
    (3.84e-6 * u10.max(0.0).powf(f64::from(WHITECAP_WIND_EXPONENT))).min(1.0)
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
/// Steps run before those for the residual foam near the camera (`RESIDUAL_DECAY_S`), and
/// their time step (s): 60 s, two of its lifetimes (each step at `high` costs about as much
/// as a frame's compute, so fewer, longer steps).
pub const RESIDUAL_WARMUP_STEPS: usize = 12;
pub const RESIDUAL_WARMUP_STEP_S: f32 = 5.0;
/// The warm-up's steps before the first FFT frame, oldest first: (seconds before the frame,
/// time step), RESIDUAL_WARMUP_STEPS long ones and then WARMUP_STEPS short ones, the last
/// one short step before the frame. Without the foam near the camera (`near_camera` false)
/// the short ones only: the long ones feed the residual foam there, and the lattice's
/// whitecaps keep at most e^(−7/DECAY_S) = 6 % of what they held 7 s before the frame (12 FFT
/// steps, a second of a picture's 2.9 at `high` on lavapipe).
pub fn warmup_schedule(near_camera: bool) -> Vec<(f64, f64)> {
    let short = WARMUP_STEP_S as f64;
    let long = RESIDUAL_WARMUP_STEP_S as f64;
    let short_span = WARMUP_STEPS as f64 * short;
    let longs = (1..=RESIDUAL_WARMUP_STEPS)
        .filter(|_| near_camera)
        .rev()
        .map(|i| (short_span + i as f64 * long, long));
    let shorts = (1..=WARMUP_STEPS).rev().map(|i| (i as f64 * short, short));
    longs.chain(shorts).collect()
}

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

// ── The foam near the camera (shaders/ocean/foam.comp) ─────────────────────────────────────

/// Side of the finest level's texel (m): ≤ 0.25 m within 50 m of the camera (issue 33).
pub const FINEST_TEXEL_M: f64 = 0.25;
/// Each level's texel over the next finer one's.
pub const LEVEL_RATIO: f64 = 4.0;
/// Surface drift of the water the foam floats on, over U10: Wu (1975, J. Fluid Mech. 68) found
/// the total surface drift (wind drift and Stokes transport) tending to 3.5 % of the wind at
/// long fetch; the AMS Glossary gives 2.5–3 %. 3 %.
pub const DRIFT_SHARE: f64 = 0.03;
/// Air and sea water densities (kg/m³) for the friction velocity in the water.
pub const AIR_DENSITY: f64 = 1.22;
pub const WATER_DENSITY: f64 = 1025.0;
/// Langmuir circulation's characteristic velocity over the friction velocity in the water
/// u*_w: about 8 (AMS Glossary, after Leibovich 1983, Annu. Rev. Fluid Mech. 15): the
/// windrows' greatest lateral flow toward their lines.
pub const LANGMUIR_VELOCITY_PER_U_STAR: f64 = 8.0;
/// Mean spacing of the windrows (m). Langmuir circulation comes in a hierarchy of scales
/// (Leibovich 1983): the smallest rows, a few metres apart, form first and sit between the
/// larger ones (Weller et al. 1985 measured cells 20 m apart at 14 m/s, Smith 1992 16 m
/// growing with time). The foam near the camera draws the smallest: 5 m.
pub const WINDROW_SPACING_M: f64 = 5.0;
/// e-folding time of the residual foam a whitecap leaves (s): thin lace that outlives the
/// whitecap's stage-B foam (DECAY_S) many times over, long enough for the windrows to gather
/// it into streaks (at the moderate sea they converge at 2πV/λ ≈ 0.15/s: 7 s). A choice, not
/// a measured value: windrows of foam persist for minutes where surfactants stabilise it,
/// and 30 s is the shorter end of that. (12 s measured 0.92 along the wind over across at the
/// moderate sea, R ≥ 0.02; 30 s 1.15; storm R ≥ 0.2, 2.6 against 4.7 with the jet.)
pub const RESIDUAL_DECAY_S: f32 = 30.0;
/// The windrows' downwind jet over their lateral flow: the surface water runs faster
/// downwind along the lines than between them (the downwind jets under the convergence
/// zones of Langmuir 1938 and the observations Leibovich 1983 reviews, of the same order as
/// the lateral flow, both scaling with u*_w). Taken equal (a choice of that order): at the
/// moderate sea 0.12 m/s, a shear of about 2π·0.12/5 ≈ 0.15/s across a 5 m spacing, which
/// draws the residual foam out along the wind while the lines gather it.
pub const WINDROW_JET_SHARE: f64 = 1.0;
/// Turbulent diffusivity of the foam, the same along and across the wind (m²/s): it keeps a
/// windrow about √(K/k) wide where Langmuir circulation gathers foam at the rate k (storm: k = 2πV/λ ≈
/// 0.43/s, 0.76 m). A choice, of the order of the near-surface eddy diffusivity u*_w·z at z ≈ 6 m.
pub const SPREAD_M2_S: f32 = 0.25;
/// Share of a whitecap's foam it leaves as residual foam.
pub const RESIDUAL_SHARE: f32 = 0.8;

/// The 10 m drag coefficient C_D of Large & Pond (1981, J. Phys. Oceanogr. 11): 1.2·10⁻³ up
/// to 11 m/s, (0.49 + 0.065·U10)·10⁻³ above.
pub fn drag_coefficient(u10: f64) -> f64 {
    if u10 < 11.0 {
        1.2e-3
    } else {
        (0.49 + 0.065 * u10) * 1e-3
    }
}

/// Langmuir circulation's lateral flow (m/s) at wind speed `u10`: 8·u*_w, with
/// u*_w = √(ρ_a/ρ_w · C_D) · U10 (storm 26.5 m/s: 0.34 m/s; moderate 12.3 m/s: 0.12 m/s).
/// None below 3 m/s: Langmuir (1938) saw no windrows under 3–5 m/s.
pub fn windrow_velocity(u10: f64) -> f64 {
    let u_star_water = (AIR_DENSITY / WATER_DENSITY * drag_coefficient(u10)).sqrt() * u10;
    let onset = ((u10 - 3.0) / 2.0).clamp(0.0, 1.0);
    LANGMUIR_VELOCITY_PER_U_STAR * u_star_water * onset
}

/// The clipmap of the foam near the camera: `count` levels of `size`² texels, level l's texels
/// `finest_m·LEVEL_RATIO^l` on a side, each centred on the camera in whole texels (so a
/// texel stays on one spot of the sea while the camera moves).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FoamLevels {
    pub count: usize,
    pub size: u32,
    /// Side of the finest level's texel (m).
    pub finest_m: f64,
    /// World xz of each level's texel (0, 0) corner (m).
    pub origin_m: [[f64; 2]; MAX_LEVELS],
}

/// What the foam near the camera needs of the scene, as the frame uniforms hold it
/// (src/render/uniforms.rs, shaders/common/frame.glsl): the island (`terrain`), the sea over
/// the shallows (`shore`, `open_sea`) for the surf, the objects standing in the water.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FoamScene {
    pub terrain: [f32; 4],
    pub shore: [f32; 4],
    pub open_sea: [f32; 4],
    pub objects: [[f32; 4]; 4],
}

/// Most levels (`FOAM_MAX_LEVELS` of src/shared.rs).
pub const MAX_LEVELS: usize = crate::shared::FOAM_MAX_LEVELS as usize;

impl FoamLevels {
    /// The levels for an FFT grid of `fft_size` around the origin: three levels of 512² texels
    /// of 0.25, 1 and 4 m (64 m, 256 m and 1 km around the camera). None at N ≤ 64 (`--quality
    /// low`): the lattice's foam only, as on lavapipe one level of 128² texels of 0.5 m cost
    /// 1.1 ms of compute and 2 ms of water, 34.4 ms a frame against the 33 ms budget.
    pub fn layout(fft_size: usize) -> FoamLevels {
        if fft_size <= 64 {
            return FoamLevels::none();
        }
        FoamLevels::levels()
    }

    /// The three levels at any FFT size (`--foam-sim on`).
    pub fn levels() -> FoamLevels {
        FoamLevels {
            count: 3,
            size: 512,
            finest_m: FINEST_TEXEL_M,
            ..FoamLevels::default()
        }
    }

    /// No levels (Gerstner waves: the lattice's foam only).
    pub fn none() -> FoamLevels {
        FoamLevels {
            size: 1,
            ..FoamLevels::default()
        }
    }

    /// Level `l`'s texel side (m).
    pub fn texel_m(&self, l: usize) -> f64 {
        self.finest_m * LEVEL_RATIO.powi(l as i32)
    }

    /// These levels moved around a camera at `camera_xz`.
    pub fn around(&self, camera_xz: [f64; 2]) -> FoamLevels {
        let mut origin_m = [[0.0; 2]; MAX_LEVELS];
        for (l, o) in origin_m.iter_mut().enumerate().take(self.count) {
            let h = self.texel_m(l);
            *o = camera_xz.map(|c| (c / h).round() * h - h * (self.size / 2) as f64);
        }
        FoamLevels { origin_m, ..*self }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ocean::SeaState;

    #[test]
    fn windrow_flow_after_leibovich() {
        // 8·u*_w with Large & Pond's drag: the storm's 26.5 m/s gives C_D = 2.21·10⁻³,
        // u*_a = 1.25 m/s, u*_w = 4.3 cm/s; the moderate sea's 12.3 m/s 1.29·10⁻³ and 1.5 cm/s.
        for (u, v) in [(26.5, 0.344), (12.3, 0.122)] {
            let got = windrow_velocity(u);
            assert!(
                (got / v - 1.0).abs() < 0.02,
                "U10 {u}: {got} m/s, expected {v}"
            );
        }
        assert_eq!(windrow_velocity(2.5), 0.0);
    }

    #[test]
    fn foam_levels_are_centred_on_the_camera_in_whole_texels() {
        let camera = [1234.567, -89.01];
        let levels = FoamLevels::layout(256).around(camera);
        assert_eq!(levels.count, 3);
        for l in 0..levels.count {
            let h = levels.texel_m(l);
            let side = h * levels.size as f64;
            for (&o, &c) in levels.origin_m[l].iter().zip(&camera) {
                assert!(
                    (o / h - (o / h).round()).abs() < 1e-9,
                    "level {l}: origin {o}"
                );
                let centre = o + side / 2.0;
                assert!((centre - c).abs() <= h / 2.0 + 1e-9, "level {l}: {centre}");
            }
        }
        assert_eq!(levels.texel_m(0), FINEST_TEXEL_M);
        // 0.25 m a texel within 50 m of the camera (the issue's bound) at high: the water draws
        // the finest level alone out to 0.4 of its side from its centre (water.frag `foam_at`).
        assert!(0.4 * FINEST_TEXEL_M * levels.size as f64 >= 50.0);
    }

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
