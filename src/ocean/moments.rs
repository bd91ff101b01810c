//! What the renderer needs to know of the rendered waves, from their spectral moments: the
//! significant height 4√m₀ and mean frequency m₁/m₀ (the shores, `ocean::shore`) and each
//! layer's mean-square slope Σ k²E (the sun's reflection: what the normal images resolve of
//! the sea's roughness) and mean-square curvature Σ k⁴E (how deep its waves focus the sun:
//! the caustics), and Cox & Munk's mean-square slopes of the whole sea surface, upwind and
//! crosswind.

/// The depth that stands for deep water (m): k·h is past 10 there for any ω above 0.1 rad/s
/// (periods under a minute), so c_g = g/(2ω).
pub const DEEP_WATER_M: f64 = 1.0e4;

/// One rendered wave component: its share of the height variance (m²), angular frequency
/// (rad/s), wave vector (rad/m, world x and z) and the image layer (cascade) that holds it.
#[derive(Clone, Copy, Debug)]
pub struct Component {
    pub energy: f64,
    pub omega: f64,
    pub k: [f64; 2],
    pub layer: usize,
}

/// The rendered sea's moments.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeaMoments {
    /// Significant wave height of the rendered waves, 4√m₀ (m).
    pub hs_m: f64,
    /// Mean angular frequency m₁/m₀ (rad/s).
    pub mean_omega: f64,
    /// Depth the sea is simulated for (m; `DEEP_WATER_M` for deep water).
    pub depth_m: f64,
    /// Mean-square slope of each layer's waves, Σ k²E (both directions).
    pub slope_variance: [f64; 4],
    /// How each layer's slopes differ by direction: (Σ(k_x² − k_z²)E, Σ k_x k_z E). The mean
    /// square of the slope along the unit vector (cos φ, sin φ) of the water is
    /// ½Σk²E + ½Σ(k_x² − k_z²)E·cos 2φ + Σk_x k_z E·sin 2φ (`slope_along`).
    pub slope_anisotropy: [[f64; 2]; 4],
    /// Mean square of the Laplacian of each layer's height, Σ k⁴E (1/m²).
    pub curvature_variance: [f64; 4],
    /// The part of `slope_variance` in waves shorter than `SHORT_WAVE_M`: what a natural
    /// slick damps (`render::slicks`).
    pub short_slope_variance: [f64; 4],
    /// What each mip level of the normal images leaves of each layer's slopes, [level][layer]
    /// (`slope_mip_gains`; all 1 until `with_mip_gains`).
    pub slope_mip_gain: [[f64; 4]; MIP_LEVELS],
}

/// The normal images' mip levels (`crate::shared::SLOPE_LEVELS`), as an array length.
pub const MIP_LEVELS: usize = crate::shared::SLOPE_LEVELS as usize;

/// The longest waves a film of surface-active matter damps (m): Lucassen (1982) found its
/// effect can reach waves of up to about 1 m.
pub const SHORT_WAVE_M: f64 = 1.0;

impl SeaMoments {
    /// From the rendered waves, simulated for `depth_m` (`None`: deep water).
    pub fn from_waves(waves: impl Iterator<Item = Component>, depth_m: Option<f64>) -> Self {
        let (mut m0, mut m1, mut slopes, mut curvatures) = (0.0, 0.0, [0.0; 4], [0.0; 4]);
        let mut short = [0.0; 4];
        let k_short = std::f64::consts::TAU / SHORT_WAVE_M;
        let mut anisotropy = [[0.0; 2]; 4];
        for w in waves {
            m0 += w.energy;
            m1 += w.energy * w.omega;
            let [kx, kz] = w.k;
            let k2 = kx * kx + kz * kz;
            let layer = w.layer.min(3);
            slopes[layer] += w.energy * k2;
            curvatures[layer] += w.energy * k2 * k2;
            if k2 > k_short * k_short {
                short[layer] += w.energy * k2;
            }
            anisotropy[layer][0] += w.energy * (kx * kx - kz * kz);
            anisotropy[layer][1] += w.energy * kx * kz;
        }
        SeaMoments {
            hs_m: 4.0 * f64::sqrt(m0),
            mean_omega: if m0 > 0.0 { m1 / m0 } else { 1.0 },
            depth_m: depth_m.unwrap_or(DEEP_WATER_M),
            slope_variance: slopes,
            slope_anisotropy: anisotropy,
            curvature_variance: curvatures,
            short_slope_variance: short,
            slope_mip_gain: [[1.0; 4]; MIP_LEVELS],
        }
    }

    /// The same with `slope_mip_gain` of `waves` (those it was made from), each layer's images
    /// `texel_m` apart.
    pub fn with_mip_gains(self, waves: impl Iterator<Item = Component>, texel_m: [f64; 4]) -> Self {
        SeaMoments {
            slope_mip_gain: slope_mip_gains(waves, texel_m),
            ..self
        }
    }
}

/// The root-mean-square share of each layer's slopes that each mip level of its normal image
/// keeps, [level][layer]: level l's texel is the mean of 2^l x 2^l texels t apart
/// (shaders/ocean/slope_mips.comp), which passes a wave of wave vector k with the gain
/// D(k_x t)·D(k_z t), D(θ) = sin(2^l θ/2) / (2^l sin(θ/2)) (a box of 2^l samples), so the slopes
/// keep √(Σ k²E D² / Σ k²E). water.frag returns what a level took off to the slopes the pixel
/// does not resolve, as LEAN mapping (Olano & Baker 2010) keeps the variance its filtered
/// moments lose; here from the spectrum rather than from second moments in the images.
pub fn slope_mip_gains(
    waves: impl Iterator<Item = Component>,
    texel_m: [f64; 4],
) -> [[f64; 4]; MIP_LEVELS] {
    rms_gains(waves, texel_m, |[kx, kz], t, m| {
        (kx * kx + kz * kz, box_gain(kx * t, m) * box_gain(kz * t, m))
    })
}

/// A box of `m` samples' gain on a wave whose phase steps by `theta` from one to the next:
/// sin(mθ/2) / (m sin(θ/2)).
fn box_gain(theta: f64, m: f64) -> f64 {
    let s = (theta / 2.0).sin();
    if s.abs() < 1e-12 {
        1.0
    } else {
        (m * theta / 2.0).sin() / (m * s)
    }
}

/// √(Σ E·weight·gain² / Σ E·weight) per level and layer, `weigh` giving a wave's (weight,
/// gain) from its wave vector, its layer's texel spacing and the level's 2^l.
fn rms_gains(
    waves: impl Iterator<Item = Component>,
    texel_m: [f64; 4],
    weigh: impl Fn([f64; 2], f64, f64) -> (f64, f64),
) -> [[f64; 4]; MIP_LEVELS] {
    let mut kept = [[0.0; 4]; MIP_LEVELS];
    let mut total = [0.0; 4];
    for w in waves {
        let layer = w.layer.min(3);
        let t = texel_m[layer];
        for (l, row) in kept.iter_mut().enumerate() {
            let (weight, g) = weigh(w.k, t, (1u32 << l) as f64);
            if l == 0 {
                total[layer] += w.energy * weight;
            }
            row[layer] += w.energy * weight * g * g;
        }
    }
    kept.map(|row| {
        std::array::from_fn(|c| {
            if total[c] > 0.0 {
                (row[c] / total[c]).sqrt()
            } else {
                1.0
            }
        })
    })
}

/// The mean-square slope along the unit vector `dir` of the water (x, z) of slopes whose mean
/// square over both directions is `total` and whose anisotropy is `anisotropy`
/// (`SeaMoments::slope_anisotropy`); common/glitter.glsl's `slope_covariance` is its twin.
pub fn slope_along(total: f64, anisotropy: [f64; 2], dir: [f64; 2]) -> f64 {
    let [c, s] = dir;
    0.5 * total + 0.5 * anisotropy[0] * (c * c - s * s) + anisotropy[1] * 2.0 * c * s
}

/// Mean-square slope of a clean sea surface at wind speed `u` (m/s): Cox & Munk (1954),
/// σ² = 0.003 + 5.12·10⁻³·U (±0.004), U measured 12.5 m above the sea (we pass U10: the
/// difference is about 2 %, within their scatter).
pub fn cox_munk_mean_square_slope(u: f64) -> f64 {
    0.003 + COX_MUNK_TOTAL_PER_M_S * u
}

/// Cox & Munk's (1954) clean-surface fits' growth with the wind (per m/s): the total
/// mean-square slope's, and the upwind's (3.16·10⁻³) and crosswind's (1.92·10⁻³) slopes'.
pub const COX_MUNK_TOTAL_PER_M_S: f64 = 5.12e-3;
pub const COX_MUNK_UPWIND_PER_M_S: f64 = 3.16e-3;
pub const COX_MUNK_CROSSWIND_PER_M_S: f64 = 1.92e-3;
/// The upwind excess' growth with the wind (per m/s): 1.24·10⁻³.
pub const COX_MUNK_EXCESS_PER_M_S: f64 = COX_MUNK_UPWIND_PER_M_S - COX_MUNK_CROSSWIND_PER_M_S;

/// Cox & Munk's (1954) clean surface by direction: upwind σ_u² = 3.16·10⁻³·U (±0.004) and
/// crosswind σ_c² = 0.003 + 1.92·10⁻³·U (±0.004). Their difference, σ_u² − σ_c² =
/// 1.24·10⁻³·U − 0.003, is what the sea's slopes favour the wind's direction by (none below
/// 2.4 m/s, where their fit would make the crosswind slopes the larger); their sum,
/// 0.003 + 5.08·10⁻³·U, is within 1 % of the total fit above.
pub fn cox_munk_upwind_excess(u: f64) -> f64 {
    (COX_MUNK_UPWIND_PER_M_S * u - (0.003 + COX_MUNK_CROSSWIND_PER_M_S * u)).max(0.0)
}

/// `SeaMoments::slope_anisotropy` of slopes whose mean square is `excess` more along the unit
/// vector `wind` than across it.
pub fn anisotropy_along(excess: f64, wind: [f64; 2]) -> [f64; 2] {
    let [wx, wz] = wind;
    [excess * (wx * wx - wz * wz), excess * wx * wz]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_slick_s_short_waves_are_those_under_a_metre() {
        // Waves of 0.5 m and 2 m, equal energy, in one layer: only the first counts as short.
        let wave = |length: f64| Component {
            energy: 1e-4,
            omega: 1.0,
            k: [std::f64::consts::TAU / length, 0.0],
            layer: 1,
        };
        let s = SeaMoments::from_waves([wave(0.5), wave(2.0)].into_iter(), None);
        let k_half = std::f64::consts::TAU / 0.5;
        assert!((s.short_slope_variance[1] - 1e-4 * k_half * k_half).abs() < 1e-12);
        assert!(s.slope_variance[1] > s.short_slope_variance[1]);
        assert_eq!(s.short_slope_variance[0], 0.0);
    }

    #[test]
    fn a_mip_level_keeps_what_a_box_of_its_texels_passes() {
        // One wave 8 texels long along x in layer 0, one 16 texels long diagonally in layer
        // 1 (texels 0.5 m and 2 m apart). A box of 2^l samples passes a wave of phase step θ
        // with sin(2^l θ/2) / (2^l sin(θ/2)): level 1 cos(θ/2), level 3 nothing of the first
        // (8 samples span its wavelength).
        let tau = std::f64::consts::TAU;
        let k1 = tau / (8.0 * 0.5);
        let k2 = tau / (16.0 * 2.0);
        let d = k2 / 2f64.sqrt();
        let waves = [
            Component {
                energy: 1.0,
                omega: 1.0,
                k: [k1, 0.0],
                layer: 0,
            },
            Component {
                energy: 1.0,
                omega: 1.0,
                k: [d, d],
                layer: 1,
            },
        ];
        let g = slope_mip_gains(waves.into_iter(), [0.5, 2.0, 1.0, 1.0]);
        let theta = tau / 8.0;
        assert_eq!(g[0][0], 1.0);
        assert!((g[1][0] - (theta / 2.0).cos()).abs() < 1e-12, "{}", g[1][0]);
        assert!(g[3][0].abs() < 1e-12, "{}", g[3][0]);
        // Diagonal: the gain of each axis's phase step, multiplied.
        let phi = d * 2.0;
        let box_gain = |m: f64| (m * phi / 2.0).sin() / (m * (phi / 2.0).sin());
        for (l, row) in g.iter().enumerate() {
            let m = (1u32 << l) as f64;
            assert!(
                (row[1] - box_gain(m).powi(2).abs()).abs() < 1e-12,
                "level {l}"
            );
        }
        // A layer without waves keeps everything (nothing to take off).
        assert_eq!(g[5][2], 1.0);
    }

    #[test]
    fn moments_are_height_frequency_and_slopes() {
        let c = |energy, omega, k, layer| Component {
            energy,
            omega,
            k: [k, 0.0],
            layer,
        };
        let s =
            SeaMoments::from_waves([c(1.0, 0.5, 0.1, 0), c(3.0, 1.0, 0.2, 1)].into_iter(), None);
        assert!((s.hs_m - 8.0).abs() < 1e-12);
        assert!((s.mean_omega - 3.5 / 4.0).abs() < 1e-12);
        assert_eq!(s.depth_m, DEEP_WATER_M);
        assert!((s.slope_variance[0] - 0.01).abs() < 1e-12);
        assert!((s.slope_variance[1] - 0.12).abs() < 1e-12);
        assert!((s.curvature_variance[0] - 1e-4).abs() < 1e-15);
        assert!((s.curvature_variance[1] - 0.0048).abs() < 1e-14);
        // Waves along x: all their slope is along x.
        assert!((s.slope_anisotropy[1][0] - 0.12).abs() < 1e-12);
        let along = |dir| slope_along(s.slope_variance[1], s.slope_anisotropy[1], dir);
        assert!((along([1.0, 0.0]) - 0.12).abs() < 1e-12);
        assert!(along([0.0, 1.0]).abs() < 1e-12);
        assert!((along([0.6, 0.8]) - 0.12 * 0.36).abs() < 1e-12);
    }

    #[test]
    fn a_wave_s_slope_along_any_direction_is_its_projection() {
        // One wave of wave vector k at 30° from x: its mean-square slope along a unit vector d
        // is E (k·d)².
        let k = [
            0.2 * 30f64.to_radians().cos(),
            0.2 * 30f64.to_radians().sin(),
        ];
        let s = SeaMoments::from_waves(
            [Component {
                energy: 2.0,
                omega: 1.0,
                k,
                layer: 0,
            }]
            .into_iter(),
            None,
        );
        for deg in [0.0f64, 17.0, 60.0, 120.0, 200.0] {
            let d = [deg.to_radians().cos(), deg.to_radians().sin()];
            let expected = 2.0 * (k[0] * d[0] + k[1] * d[1]).powi(2);
            let got = slope_along(s.slope_variance[0], s.slope_anisotropy[0], d);
            assert!(
                (got - expected).abs() < 1e-12,
                "{deg}°: {got} vs {expected}"
            );
        }
    }

    #[test]
    fn the_sea_s_slopes_upwind_and_crosswind_are_cox_and_munk_s() {
        // Cox & Munk (1954), clean surface at 10 m/s: σ_u² = 0.0316, σ_c² = 0.0222 (their
        // separate fits), from the total fit and the upwind excess within 2 %, whichever way
        // the wind blows.
        let u = 10.0;
        let total = cox_munk_mean_square_slope(u);
        for deg in [0.0f64, 35.0, 90.0, 230.0] {
            let wind = [deg.to_radians().cos(), deg.to_radians().sin()];
            let a = anisotropy_along(cox_munk_upwind_excess(u), wind);
            let upwind = slope_along(total, a, wind);
            let crosswind = slope_along(total, a, [-wind[1], wind[0]]);
            assert!(
                (upwind / 0.0316 - 1.0).abs() < 0.02,
                "{deg}°: upwind {upwind}"
            );
            assert!(
                (crosswind / 0.0222 - 1.0).abs() < 0.02,
                "{deg}°: crosswind {crosswind}"
            );
        }
        // Calm: no direction.
        assert_eq!(cox_munk_upwind_excess(2.0), 0.0);
    }
}
