//! The buoy (`--buoy X,Z`): a moored float that heaves, pitches and rolls with the waves. The
//! session asks it for its pose every frame, before the frame's uniforms are written
//! (`FrameInputs::buoy`); shaders/terrain/objects.vert draws it.
//!
//! Model: a quasi-static wave follower. A float whose natural periods in heave, pitch and roll
//! are short against the wave periods moves with the surface it sits on, its waterline plane
//! the surface's local tangent plane. Pitch-roll buoys measure directional wave spectra on this
//! assumption (Longuet-Higgins, Cartwright & Smith 1963, "Observations of the directional
//! spectrum of sea waves using the motions of a floating buoy"); a 1.6 m float's heave period,
//! 2π√(draft/g) ≈ 2.2 s for a 1.2 m draft, is short against this sea's ≈ 6–8 s waves.
//!
//! - heave: the surface height at the buoy's centre (`SurfaceQuery::height_at`, the surface as
//!   the GPU draws it from its images);
//! - axis: the normal of the least-squares plane through the surface heights at `RING_POINTS`
//!   points of the waterline circle (radius r). For N ≥ 3 points evenly spaced at angles θ_k
//!   (Σ cos θ_k = Σ sin θ_k = Σ cos θ_k sin θ_k = 0, Σ cos² θ_k = N/2), the plane
//!   h = h̄ + s_x dx + s_z dz has s_x = 2 Σ h_k cos θ_k / (N r), s_z = 2 Σ h_k sin θ_k / (N r), and
//!   the axis is (−s_x, 1, −s_z) normalized. Waves much shorter than the waterline's diameter
//!   average out, as they do under a real float.
//!
//! The buoy stays at its mooring's (x, z): no drift.

use super::params::OceanSettings;
use super::surface::{lattice_for, DisplacementScale, Lattice, SurfaceQuery};
use crate::shared::BUOY_RADIUS_M;

/// Points on the waterline circle the tilt is fitted through.
pub const RING_POINTS: usize = 6;
/// RMS of the FFT modes the height queries leave out, per lattice node (m, `SpectralLattice`).
pub const DROPPED_MODES_M: f64 = 0.002;

/// Where the buoy is in a frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuoyPose {
    /// Height of the waterline's centre (m).
    pub heave_m: f64,
    /// Unit axis, bottom to top (the surface normal of the fitted waterline plane).
    pub axis: [f64; 3],
}

impl Default for BuoyPose {
    /// Upright at the mean water level (flat water).
    fn default() -> Self {
        BuoyPose {
            heave_m: 0.0,
            axis: [0.0, 1.0, 0.0],
        }
    }
}

impl BuoyPose {
    /// Tilt from the vertical (degrees).
    pub fn tilt_deg(&self) -> f64 {
        self.axis[1].clamp(-1.0, 1.0).acos().to_degrees()
    }
}

/// A buoy moored at (x, z), floating on the surface a [`Lattice`] describes.
pub struct Buoy {
    xz: [f64; 2],
    surface: SurfaceQuery<dyn Lattice + Send>,
}

impl Buoy {
    pub fn new(xz: [f64; 2], lattice: Box<dyn Lattice + Send>) -> Buoy {
        Buoy {
            xz,
            surface: SurfaceQuery::new(lattice),
        }
    }

    /// A buoy on the surface of a run's wave model (FFT cascades or Gerstner waves), its
    /// displacement scaled by `shore` as the water draws it over the shallows.
    pub fn on(settings: &OceanSettings, xz: [f64; 2], shore: DisplacementScale) -> Buoy {
        Buoy {
            xz,
            surface: SurfaceQuery::scaled(lattice_for(settings, DROPPED_MODES_M), shore),
        }
    }

    /// Where it is moored (m).
    pub fn xz(&self) -> [f64; 2] {
        self.xz
    }

    /// Lattice nodes the last pose evaluated (its cost).
    pub fn nodes_evaluated(&self) -> usize {
        self.surface.nodes_evaluated()
    }

    /// Height of the surface the buoy floats on at the world point (x, z) at time `t` (s): the
    /// same query, asked elsewhere (the camera's dive, `FrameInputs::camera_surface_m`).
    pub fn surface_height_at(&mut self, x: f64, z: f64, t: f64) -> f64 {
        self.surface.height_at(x, z, t)
    }

    /// The surface's slope (∂h/∂x, ∂h/∂z) at the world point (x, z) at time `t` (s): central
    /// differences 0.25 m apart, the scale of the camera's near plane (the waterline's tilt,
    /// `FrameInputs::camera_slope`).
    pub fn surface_slope_at(&mut self, x: f64, z: f64, t: f64) -> [f64; 2] {
        let d = 0.25;
        let mut along = |dx: f64, dz: f64| {
            (self.surface.height_at(x + dx, z + dz, t) - self.surface.height_at(x - dx, z - dz, t))
                / (2.0 * d)
        };
        [along(d, 0.0), along(0.0, d)]
    }

    /// The pose at time `t` (s).
    pub fn pose(&mut self, t: f64) -> BuoyPose {
        let [x, z] = self.xz;
        let heave_m = self.surface.height_at(x, z, t);
        let r = BUOY_RADIUS_M as f64;
        let (mut sx, mut sz) = (0.0, 0.0);
        for k in 0..RING_POINTS {
            let theta = std::f64::consts::TAU * k as f64 / RING_POINTS as f64;
            let (s, c) = theta.sin_cos();
            let h = self.surface.height_at(x + r * c, z + r * s, t);
            sx += h * c;
            sz += h * s;
        }
        let scale = 2.0 / (RING_POINTS as f64 * r);
        let n = [-sx * scale, 1.0, -sz * scale];
        let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
        BuoyPose {
            heave_m,
            axis: n.map(|v| v / len),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ocean::gerstner::{evaluate, Wave};
    use crate::ocean::surface::GerstnerLattice;

    fn angle_deg(a: [f64; 3], b: [f64; 3]) -> f64 {
        let dot: f64 = (0..3).map(|i| a[i] * b[i]).sum();
        let len = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        (dot / (len(a) * len(b)))
            .clamp(-1.0, 1.0)
            .acos()
            .to_degrees()
    }

    /// A tilted plane h = h0 + p x + q z, its nodes on a 1.5 m lattice.
    struct Plane([f64; 3]);

    impl Lattice for Plane {
        fn steps(&self) -> Vec<f64> {
            vec![1.5]
        }
        fn set_time(&mut self, _t: f64) {}
        fn node(&self, _c: usize, i: i64, j: i64) -> [f64; 3] {
            let [h0, p, q] = self.0;
            [0.0, h0 + p * 1.5 * i as f64 + q * 1.5 * j as f64, 0.0]
        }
    }

    #[test]
    fn on_a_plane_the_buoy_sits_on_it_along_its_normal() {
        let [h0, p, q] = [0.4, 0.12, -0.07];
        let (x, z) = (9.3, -55.2);
        let pose = Buoy::new([x, z], Box::new(Plane([h0, p, q]))).pose(1.0);
        let height = h0 + p * x + q * z;
        assert!(
            (pose.heave_m - height).abs() < 1e-9,
            "heave {} vs the plane's {height}",
            pose.heave_m
        );
        let angle = angle_deg(pose.axis, [-p, 1.0, -q]);
        assert!(angle < 1e-6, "axis off the plane's normal by {angle}°");
        assert!((pose.tilt_deg() - (p.hypot(q)).atan().to_degrees()).abs() < 1e-6);
    }

    #[test]
    fn on_a_gerstner_wave_heave_is_the_surface_and_the_axis_its_normal() {
        // One 40 m wave travelling along x, steepness Q = 0.6 (ka = 0.08: slopes up to 4.6°),
        // evaluated on a fine lattice (5 cm) so that the bilinear surface is the analytic one.
        let k = std::f64::consts::TAU / 40.0;
        let wave = Wave {
            kx: k,
            kz: 0.0,
            amplitude: 0.5,
            phase: 0.3,
            steepness: 0.6,
        };
        let lattice = || Box::new(GerstnerLattice::new(&[wave], 0.05));
        let t = 4.0;
        let omega = (crate::ocean::gerstner::G_SEED * k).sqrt();
        // θ = k α − ω t − φ: 0 at a crest, π/2 on the steepest down-slope.
        for (what, theta) in [("crest", 0.0), ("slope", std::f64::consts::FRAC_PI_2)] {
            let alpha = (theta + omega * t + wave.phase) / k;
            let (p, normal) = evaluate(&[wave], alpha, 7.0, t);
            let mut buoy = Buoy::new([p[0], p[2]], lattice());
            let pose = buoy.pose(t);
            let height = SurfaceQuery::new(lattice()).height_at(p[0], p[2], t);
            assert!(
                (pose.heave_m - height).abs() < 1e-12,
                "{what}: heave {} vs the height query {height}",
                pose.heave_m
            );
            assert!(
                (pose.heave_m - p[1]).abs() < 0.002,
                "{what}: heave {} vs the wave's {} (tolerance 2 mm)",
                pose.heave_m,
                p[1]
            );
            let angle = angle_deg(pose.axis, normal);
            assert!(
                angle < 1.0,
                "{what}: axis off the normal by {angle:.3}° (max 1°)"
            );
            if what == "slope" {
                assert!(pose.tilt_deg() > 3.0, "the slope tilts the buoy");
            }
        }
    }
}
