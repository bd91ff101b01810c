//! What the renderer needs to know of the rendered waves, from their spectral moments: the
//! significant height 4√m₀ and mean frequency m₁/m₀ (the shores, `ocean::shore`) and each
//! layer's mean-square slope Σ k²E (the sun's reflection: what the normal images resolve of
//! the sea's roughness) and mean-square curvature Σ k⁴E (how deep its waves focus the sun:
//! the caustics), and Cox & Munk's mean-square slope of the whole sea surface.

/// The depth that stands for deep water (m): k·h is past 10 there for any ω above 0.1 rad/s
/// (periods under a minute), so c_g = g/(2ω).
pub const DEEP_WATER_M: f64 = 1.0e4;

/// One rendered wave component: its share of the height variance (m²), angular frequency
/// (rad/s), wavenumber (rad/m) and the image layer (cascade) that holds it.
#[derive(Clone, Copy, Debug)]
pub struct Component {
    pub energy: f64,
    pub omega: f64,
    pub k: f64,
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
    /// Mean square of the Laplacian of each layer's height, Σ k⁴E (1/m²).
    pub curvature_variance: [f64; 4],
}

impl SeaMoments {
    /// From the rendered waves, simulated for `depth_m` (`None`: deep water).
    pub fn from_waves(waves: impl Iterator<Item = Component>, depth_m: Option<f64>) -> Self {
        let (mut m0, mut m1, mut slopes, mut curvatures) = (0.0, 0.0, [0.0; 4], [0.0; 4]);
        for w in waves {
            m0 += w.energy;
            m1 += w.energy * w.omega;
            let k2 = w.k * w.k;
            slopes[w.layer.min(3)] += w.energy * k2;
            curvatures[w.layer.min(3)] += w.energy * k2 * k2;
        }
        SeaMoments {
            hs_m: 4.0 * f64::sqrt(m0),
            mean_omega: if m0 > 0.0 { m1 / m0 } else { 1.0 },
            depth_m: depth_m.unwrap_or(DEEP_WATER_M),
            slope_variance: slopes,
            curvature_variance: curvatures,
        }
    }
}

/// Mean-square slope of a clean sea surface at wind speed `u` (m/s): Cox & Munk (1954),
/// σ² = 0.003 + 5.12·10⁻³·U (±0.004), U measured 12.5 m above the sea (we pass U10: the
/// difference is about 2 %, within their scatter).
pub fn cox_munk_mean_square_slope(u: f64) -> f64 {
    0.003 + 5.12e-3 * u
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn moments_are_height_frequency_and_slopes() {
        let c = |energy, omega, k, layer| Component {
            energy,
            omega,
            k,
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
    }
}
