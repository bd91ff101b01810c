//! Natural slicks: bands of sea where a film of surface-active matter damps the short ripples,
//! so the surface is smoother and reflects the sky more like a mirror (shaders/common/slicks.glsl
//! draws them; this is its CPU twin and the law of how much sea they cover).
//!
//! - **Where and when.** Romano's (1996) two years of coastal photographs: slicks never at
//!   winds above 7 m/s, most often at 2–4 m/s. Romano & Garabetian (1996): at light winds they
//!   cover about 35 % of the sea (39 % at night), 12 % when the wind rises. So the share is
//!   35 % from 2 to 4 m/s and falls smoothly to none at 7 m/s; below 2 m/s it fades too, as the
//!   whole sea turns glassy and a slick has nothing rougher around it (our choice: from 1 m/s).
//! - **How smooth.** Cox & Munk's (1954) slick-surface fits: upwind σ_u² = 0.005 + 0.78·10⁻³·U,
//!   crosswind σ_c² = 0.003 + 0.84·10⁻³·U (±0.002), against the clean sea's 3.16·10⁻³·U and
//!   0.003 + 1.92·10⁻³·U: at 5 m/s 0.56 of its mean square. The film damps the capillary and
//!   short gravity waves, up to about 1 m long (Lucassen 1982; `moments::SHORT_WAVE_M`), so
//!   one factor d on the mean square of every wave shorter than that, drawn or not, takes the
//!   clean sea's total to the slick's (`Slicks::of_sea`); the longer waves' mean square stays.
//!   The cascades' slopes in a slick shrink as a whole by their short waves' share
//!   (`Slicks::cascades`: the same mean square taken off, though a cascade's longer waves
//!   shrink with its short ones: cascade 1's 1–15 m waves by about 5 % at the default size),
//!   the glitter's lobe completes the slick's total, and the DU/DV ripples shrink by √d.
//! - **Their shape.** The clouds' fractal noise (`clouds::shape`, another place in it),
//!   stretched along the wind (cells `SLICK_ALONG_M` by `SLICK_ACROSS_M`, src/shared.rs; our
//!   choice: windrows and slick bands lie along the wind) and carried by the wind's drift of
//!   the surface, about 3 % of the wind (the rule of thumb oil-spill drift uses). A point is in
//!   a slick where the noise exceeds the quantile that leaves the share's area above it.
//!
//! The water's vertices evaluate the noise (the bands are hundreds of metres wide), with
//! slicks or without: with none (above 7 m/s, Gerstner waves, `--slicks 0`) the threshold
//! `SLICK_NONE` lies above the noise's range. A uniform branch that skipped it leaked host
//! memory on lavapipe (shaders/common/slicks.glsl).

use std::sync::OnceLock;

use crate::ocean::moments::{anisotropy_along, SeaMoments};
use crate::ocean::spectrum::wind_vector;
use crate::ocean::{OceanSettings, Waves};
use crate::shared::{
    SLICK_ACROSS_M, SLICK_ALONG_M, SLICK_EDGE, SLICK_NOISE_OFFSET_X, SLICK_NOISE_OFFSET_Y,
    SLICK_NONE,
};

/// The surface's drift with the wind, as a share of the wind's speed (our choice: the 3 %
/// wind factor oil-spill drift models commonly take).
pub const DRIFT_SHARE: f64 = 0.03;

/// The share of the sea slicks cover at the wind speed `u` (m/s), 0–0.35: Romano & Garabetian
/// (1996)'s 35 % at light winds from 2 to 4 m/s, where Romano (1996) saw them most often, and
/// none from 7 m/s, above which he never did; fading below 2 m/s (our choice, module docs).
pub fn slick_share(u: f64) -> f64 {
    let smooth = |e0: f64, e1: f64, x: f64| {
        let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
        t * t * (3.0 - 2.0 * t)
    };
    0.35 * smooth(1.0, 2.0, u) * (1.0 - smooth(4.0, 7.0, u))
}

/// Cox & Munk's (1954) slick-surface mean-square slope, upwind plus crosswind:
/// 0.008 + 1.62·10⁻³·U (their total fit, 0.008 + 1.56·10⁻³·U, is within 2.5 % of it at
/// 2–7 m/s).
pub fn slick_mean_square_slope(u: f64) -> f64 {
    0.005 + 0.78e-3 * u + 0.003 + 0.84e-3 * u
}

/// Cox & Munk's slick surface by direction: σ_u² − σ_c² = 0.002 − 0.06·10⁻³·U.
pub fn slick_upwind_excess(u: f64) -> f64 {
    (0.002 - 0.06e-3 * u).max(0.0)
}

/// The noise's values over a large area, sorted: its quantiles.
fn noise_quantiles() -> &'static [f32] {
    static SORTED: OnceLock<Vec<f32>> = OnceLock::new();
    SORTED.get_or_init(|| {
        const SIDE: usize = 256;
        // A point every 0.37 cells, 95 cells square: every place in the cells and octaves.
        let mut v: Vec<f32> = (0..SIDE * SIDE)
            .map(|i| {
                let (x, y) = ((i % SIDE) as f32 * 0.37, (i / SIDE) as f32 * 0.37);
                shape_at(x, y)
            })
            .collect();
        v.sort_by(f32::total_cmp);
        v
    })
}

/// The slicks' noise at (x, y) in cells of the stretched space.
fn shape_at(x: f32, y: f32) -> f32 {
    super::clouds::shape(x + SLICK_NOISE_OFFSET_X, y + SLICK_NOISE_OFFSET_Y)
}

/// The noise's threshold (the edge's lower end) that leaves about `share` of the sea in
/// slicks: the noise's (1 − share) quantile less half the edge; `SLICK_NONE` at share 0 and −1
/// (everywhere) at share 1.
pub fn threshold_for(share: f64) -> f32 {
    if share <= 0.0 {
        return SLICK_NONE;
    }
    if share >= 1.0 {
        return -1.0;
    }
    let q = noise_quantiles();
    let i = (((1.0 - share) * q.len() as f64) as usize).min(q.len() - 1);
    q[i] - 0.5 * SLICK_EDGE
}

/// The slicks of a sea.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slicks {
    /// The share of the sea they cover by the wind (`slick_share`; 0 for Gerstner waves,
    /// which have no wind).
    pub share: f64,
    /// Their mean-square slope (Cox & Munk's slick fit; the clean sea's for Gerstner waves,
    /// which `--slicks` leaves alone).
    pub mean_square_slope: f64,
    /// Their slopes' excess along the wind (`SeaMoments::slope_anisotropy`'s form).
    pub anisotropy: [f64; 2],
    /// What is left in a slick of the mean-square slope of the waves shorter than
    /// `SHORT_WAVE_M`, drawn or not (0–1).
    pub short_damping: f64,
    /// Each cascade's slopes in a slick over its slopes out of one: √(1 − (1 − d)·s/v), its
    /// short waves' share s/v of its mean square damped by `short_damping` d.
    pub cascades: [f64; 4],
    /// Unit vector of the wind (x, z).
    pub wind: [f64; 2],
    /// How fast they drift along the wind (m/s).
    pub drift_m_s: f64,
    /// The sea has a wind (FFT waves): Gerstner waves have no slicks, `--slicks` or not.
    pub fft: bool,
}

impl Slicks {
    /// The slicks of the sea `settings` simulates, whose cascades have the moments `sea`, and
    /// whose whole surface has the mean-square slope `clean` out of a slick
    /// (`Simulation::mean_square_slope`). The film damps the waves shorter than
    /// `SHORT_WAVE_M` (those the cascades draw and all the finer ones) by one factor d, so
    /// the sea's mean square in a slick is Cox & Munk's slick fit: the drawn longer waves'
    /// `long` plus d·(clean − long).
    pub fn of_sea(settings: &OceanSettings, sea: &SeaMoments, clean: f64) -> Slicks {
        let u = settings.sea.wind_speed_m_s;
        let wind = wind_vector(&settings.sea);
        let fft = matches!(settings.waves, Waves::Fft);
        let long: f64 = (0..4)
            .map(|c| sea.slope_variance[c] - sea.short_slope_variance[c])
            .sum();
        let slick = if fft {
            slick_mean_square_slope(u).min(clean).max(long)
        } else {
            clean
        };
        let short_damping = if clean > long {
            ((slick - long) / (clean - long)).clamp(0.0, 1.0)
        } else {
            1.0
        };
        Slicks {
            share: if fft { slick_share(u) } else { 0.0 },
            mean_square_slope: slick,
            anisotropy: anisotropy_along(if fft { slick_upwind_excess(u) } else { 0.0 }, wind),
            short_damping,
            cascades: std::array::from_fn(|c| {
                let (v, s) = (sea.slope_variance[c], sea.short_slope_variance[c]);
                if v > 0.0 {
                    (1.0 - (1.0 - short_damping) * s / v).sqrt()
                } else {
                    1.0
                }
            }),
            wind,
            drift_m_s: DRIFT_SHARE * u,
            fft,
        }
    }

    /// `FrameUniforms::slicks`, `slick_space` and `slick_cascades` at time `t_s` with `share`
    /// of the sea in slicks (`--slicks`, or `self.share`; none for Gerstner waves).
    pub fn uniforms(&self, share: f64, t_s: f64) -> [[f32; 4]; 3] {
        let share = if self.fft { share } else { 0.0 };
        // The drift in the noise's cells along the wind, wrapped far beyond any view's
        // reach (a jump once every 4096 cells: about 2,500 km of drift).
        let drift = (self.drift_m_s * t_s / f64::from(SLICK_ALONG_M)).rem_euclid(4096.0);
        [
            [
                self.mean_square_slope as f32,
                self.anisotropy[0] as f32,
                self.anisotropy[1] as f32,
                threshold_for(share),
            ],
            [
                drift as f32,
                self.short_damping.sqrt() as f32,
                self.wind[0] as f32,
                self.wind[1] as f32,
            ],
            self.cascades.map(|a| a as f32),
        ]
    }
}

/// `slick_at` (shaders/common/slicks.glsl): how much of the world point (`x`, `z`) (m) lies in
/// a slick (0–1), for `FrameUniforms::slicks` and `slick_space` `u`.
pub fn slick_at(x: f32, z: f32, u: &[[f32; 4]; 3]) -> f32 {
    let [_, [drift, _, wx, wz], _] = *u;
    let n = super::clouds::wind_shape(
        (x, z),
        [wx, wz],
        [SLICK_ALONG_M, SLICK_ACROSS_M],
        drift,
        [SLICK_NOISE_OFFSET_X, SLICK_NOISE_OFFSET_Y],
    );
    let t = ((n - u[0][3]) / SLICK_EDGE).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn slicks_cover_romano_s_share_at_light_winds_and_none_above_7_m_s() {
        for (u, want) in [
            (0.5, 0.0),
            (2.0, 0.35),
            (3.0, 0.35),
            (4.0, 0.35),
            (7.0, 0.0),
        ] {
            assert!(
                (slick_share(u) - want).abs() < 1e-12,
                "{u} m/s: {}",
                slick_share(u)
            );
        }
        assert!(slick_share(5.5) > 0.1 && slick_share(5.5) < 0.25);
        assert_eq!(slick_share(10.0), 0.0);
    }

    #[test]
    fn the_slick_fits_are_cox_and_munk_s() {
        // Their total fit 0.008 + 1.56·10⁻³·U: the two directions' sum within 2.5 % at 2–7 m/s
        // (2.2 % at 7 m/s).
        for u in [2.0, 4.0, 7.0] {
            let total = 0.008 + 1.56e-3 * u;
            assert!(
                (slick_mean_square_slope(u) / total - 1.0).abs() < 0.025,
                "{u}"
            );
        }
        // At 5 m/s the slick's slopes are 0.56 of the clean sea's mean square.
        let r =
            slick_mean_square_slope(5.0) / crate::ocean::moments::cox_munk_mean_square_slope(5.0);
        assert!((r - 0.565).abs() < 0.01, "{r}");
    }

    #[test]
    fn in_a_slick_the_drawn_and_finer_waves_sum_to_the_slick_fit() {
        let u = 5.0;
        let settings = OceanSettings {
            sea: crate::ocean::SeaState {
                wind_speed_m_s: u,
                ..Default::default()
            },
            ..OceanSettings::default()
        };
        let mut sea = SeaMoments::from_waves(std::iter::empty(), None);
        sea.slope_variance = [0.002, 0.004, 0.006, 0.0];
        sea.short_slope_variance = [0.0, 0.001, 0.004, 0.0];
        let clean = crate::ocean::moments::cox_munk_mean_square_slope(u);
        let s = Slicks::of_sea(&settings, &sea, clean);
        let drawn: f64 = (0..4)
            .map(|c| s.cascades[c].powi(2) * sea.slope_variance[c])
            .sum();
        let finer = s.short_damping * (clean - sea.slope_variance.iter().sum::<f64>());
        assert!((drawn + finer - slick_mean_square_slope(u)).abs() < 1e-12);
        assert_eq!(s.cascades[0], 1.0, "no waves under 1 m: untouched");
        assert!(s.cascades[2] < s.cascades[1] && s.cascades[1] < 1.0);
        // Gerstner waves have no wind: no slicks, and none forced either.
        let gerstner = OceanSettings {
            waves: Waves::Gerstner(Default::default()),
            ..settings
        };
        let g = Slicks::of_sea(&gerstner, &sea, clean);
        assert_eq!((g.share, g.mean_square_slope), (0.0, clean));
        assert!(g.cascades.iter().all(|&a| a == 1.0) && g.short_damping == 1.0);
        assert_eq!(g.uniforms(0.5, 0.0)[0][3], SLICK_NONE);
    }

    #[test]
    fn the_drawn_slicks_cover_the_share_asked_for() {
        // Over 40 km² of sea (a point every 37 m), the mean of `slick_at` is the share within
        // 0.02 (the noise's quantiles come from another sample of it).
        let sea = SeaMoments::from_waves(std::iter::empty(), None);
        let s = Slicks::of_sea(&OceanSettings::default(), &sea, 0.05);
        for share in [0.1, 0.35, 0.6] {
            let u = s.uniforms(share, 1234.0);
            let n = 170;
            let mean: f32 = (0..n * n)
                .map(|i| slick_at((i % n) as f32 * 37.0, (i / n) as f32 * 37.0, &u))
                .sum::<f32>()
                / (n * n) as f32;
            assert!(
                (f64::from(mean) - share).abs() < 0.02,
                "share {share}: {mean}"
            );
        }
        assert_eq!(slick_at(10.0, 20.0, &s.uniforms(0.0, 0.0)), 0.0);
        assert_eq!(slick_at(10.0, 20.0, &s.uniforms(1.0, 0.0)), 1.0);
    }
}
