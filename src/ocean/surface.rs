//! Height queries of the surface the GPU draws, cheap enough for every frame (the buoy, `buoy.rs`).
//!
//! The water shaders displace a rest point (α, β) by the sum over cascades of the simulation
//! images, filtered bilinearly between texels; texel (i, j) of a cascade holds the displacement
//! (λD_x, h, λD_z) of the lattice node (i·s, j·s), s = patch / N (the Gerstner window's texels
//! sit on the same world lattice, `Simulation::place_window`). A [`Lattice`] gives those node
//! values without the images; [`SurfaceQuery`] interpolates them as the GPU does and inverts the
//! horizontal displacement by fixed-point iteration (as `CpuOcean::rest_position`), caching
//! the nodes it visits for one time.
//!
//! Node values:
//! - FFT ([`SpectralLattice`]): the inverse DFT of `cpu.rs` at one node by direct summation,
//!   f(i, j) = Σ_k h̃(k, t) e^{2πi((a − N/2) i + (b − N/2) j)/N} (the sign-corrected inverse FFT,
//!   Tessendorf 2001 eq. 19 and 44), over the modes that matter. A full set of fields at
//!   --quality high is 12 FFTs of 256² (≈ 50 ms here); a query needs a few dozen nodes.
//! - Gerstner ([`GerstnerLattice`]): `gerstner::evaluate` at the node.

use std::collections::HashMap;
use std::f64::consts::PI;

use rustfft::num_complex::Complex64;

use super::gerstner::{evaluate, Wave};
use super::params::{OceanSettings, Waves};
use super::spectrum::{h0, omega_steps, phase_turns, time_ticks, wave_vector};

/// Displacement (λD_x, h, λD_z) at the nodes of one or more square lattices (cascades).
pub trait Lattice {
    /// Node spacing of each lattice (m): node (i, j) of lattice c rests at (i·s_c, j·s_c).
    fn steps(&self) -> Vec<f64>;
    /// Makes `t` (s) the time of the following `node` calls.
    fn set_time(&mut self, t: f64);
    /// The displacement of node (i, j) of lattice `c` at the time last set.
    fn node(&self, c: usize, i: i64, j: i64) -> [f64; 3];
}

/// One spectral mode of a cascade: grid element (a, b) with wave number (a − N/2, b − N/2)·2π/L.
#[derive(Clone, Copy, Debug)]
struct Mode {
    /// a − N/2 and b − N/2.
    a: i64,
    b: i64,
    /// h0(k) and conj(h0(−k)) (`CpuOcean::spectrum_at`).
    plus: Complex64,
    minus: Complex64,
    /// ω in quanta (`spectrum::omega_steps`).
    steps: u32,
    /// k̂ = k / |k| (zero at k = 0).
    unit: [f64; 2],
}

/// The FFT model's cascades at lattice nodes, by direct summation over the modes that matter.
///
/// Modes are dropped, smallest first, while the dropped ones' B = |h0(k)| + |h0(−k)| (a mode
/// adds at most B to h and to each of D_x, D_z, as |k̂| ≤ 1) satisfy √(Σ B²) ≤ `rms_m` over all
/// cascades: their sum at a node, of random phases, has an RMS of at most `rms_m` (·λ for D).
/// A hard bound (Σ B) would keep nearly every mode of the finest cascade at N = 256 (thousands
/// of tiny ones). Modes k and −k have the same B and are kept or dropped together, so the sums
/// stay real.
pub struct SpectralLattice {
    n: usize,
    choppiness: f64,
    steps_m: Vec<f64>,
    /// Per cascade: the kept modes.
    modes: Vec<Vec<Mode>>,
    /// Per cascade: h̃(k, t) of each kept mode at the time last set.
    current: Vec<Vec<Complex64>>,
    /// e^{2πi j/N}, j = 0..N.
    roots: Vec<Complex64>,
}

impl SpectralLattice {
    /// The cascades of `settings` (FFT), from the same h0 as the GPU's, dropping modes whose sum
    /// has an RMS of at most `rms_m` per node.
    pub fn new(settings: &OceanSettings, rms_m: f64) -> SpectralLattice {
        let n = settings.fft_size;
        let cascades = settings.cascade_list();
        let half = (n / 2) as i64;
        let mut modes = Vec::new();
        for (c, cascade) in cascades.iter().enumerate() {
            let grid = h0(&settings.sea, n, cascade, c as u32, settings.seed);
            let at = |m: usize, col: usize| {
                let [re, im] = grid[m * n + col];
                Complex64::new(re as f64, im as f64)
            };
            let mut all: Vec<(f64, Mode)> = Vec::new();
            for m in 0..n {
                for col in 0..n {
                    let minus = if m == 0 || col == 0 {
                        Complex64::new(0.0, 0.0)
                    } else {
                        at(n - m, n - col).conj()
                    };
                    let plus = at(m, col);
                    let bound = plus.norm() + minus.norm();
                    if bound == 0.0 {
                        continue;
                    }
                    let k = wave_vector(col, m, n, cascade.patch_m);
                    let k_len = (k[0] * k[0] + k[1] * k[1]).sqrt();
                    let unit = if k_len > 0.0 {
                        [k[0] / k_len, k[1] / k_len]
                    } else {
                        [0.0, 0.0]
                    };
                    let mode = Mode {
                        a: col as i64 - half,
                        b: m as i64 - half,
                        plus,
                        minus,
                        steps: omega_steps(k_len, settings.sea.depth_m),
                        unit,
                    };
                    all.push((bound, mode));
                }
            }
            // Largest first; drop from the end while the dropped variance fits the budget
            // (shared equally by the cascades).
            all.sort_by(|p, q| q.0.total_cmp(&p.0));
            let mut budget = rms_m * rms_m / cascades.len() as f64;
            while let Some(&(bound, _)) = all.last() {
                if bound * bound > budget {
                    break;
                }
                budget -= bound * bound;
                all.pop();
            }
            modes.push(all.into_iter().map(|(_, m)| m).collect::<Vec<_>>());
        }
        SpectralLattice {
            n,
            choppiness: settings.choppiness,
            steps_m: cascades.iter().map(|c| c.patch_m / n as f64).collect(),
            current: modes
                .iter()
                .map(|m| vec![Complex64::default(); m.len()])
                .collect(),
            modes,
            roots: (0..n)
                .map(|j| Complex64::from_polar(1.0, 2.0 * PI * j as f64 / n as f64))
                .collect(),
        }
    }

    /// Modes kept per cascade.
    pub fn mode_counts(&self) -> Vec<usize> {
        self.modes.iter().map(Vec::len).collect()
    }
}

impl Lattice for SpectralLattice {
    fn steps(&self) -> Vec<f64> {
        self.steps_m.clone()
    }

    fn set_time(&mut self, t: f64) {
        let ticks = time_ticks(t);
        for (modes, current) in self.modes.iter().zip(&mut self.current) {
            for (mode, h) in modes.iter().zip(current.iter_mut()) {
                // As the evolve shader and `CpuOcean::spectrum_at`: ω in quanta, t in ticks.
                let phase = Complex64::from_polar(1.0, 2.0 * PI * phase_turns(mode.steps, ticks));
                *h = mode.plus * phase + mode.minus * phase.conj();
            }
        }
    }

    fn node(&self, c: usize, i: i64, j: i64) -> [f64; 3] {
        let mask = self.n as i64 - 1; // N is a power of two
        let (mut dx, mut h, mut dz) = (0.0, 0.0, 0.0);
        for (mode, ht) in self.modes[c].iter().zip(&self.current[c]) {
            let e = ht * self.roots[((mode.a * i + mode.b * j) & mask) as usize];
            // h = Re e; D = Re(i k̂ e) = −k̂ Im e (cpu.rs).
            h += e.re;
            dx -= mode.unit[0] * e.im;
            dz -= mode.unit[1] * e.im;
        }
        [self.choppiness * dx, h, self.choppiness * dz]
    }
}

/// Gerstner waves at the nodes of the GPU window's world lattice (step = window / N).
pub struct GerstnerLattice {
    waves: Vec<Wave>,
    step_m: f64,
    t: f64,
}

impl GerstnerLattice {
    /// `waves` exactly as the GPU gets them (after `limit_steepness`), on a lattice of `step_m`.
    pub fn new(waves: &[Wave], step_m: f64) -> GerstnerLattice {
        GerstnerLattice {
            waves: waves.to_vec(),
            step_m,
            t: 0.0,
        }
    }
}

impl Lattice for GerstnerLattice {
    fn steps(&self) -> Vec<f64> {
        vec![self.step_m]
    }

    fn set_time(&mut self, t: f64) {
        self.t = t;
    }

    fn node(&self, _c: usize, i: i64, j: i64) -> [f64; 3] {
        let (a, b) = (i as f64 * self.step_m, j as f64 * self.step_m);
        let (p, _) = evaluate(&self.waves, a, b, self.t);
        [p[0] - a, p[1], p[2] - b]
    }
}

/// The lattice of a run's wave model: `rms_m` bounds the RMS of the FFT's dropped modes.
pub fn lattice_for(settings: &OceanSettings, rms_m: f64) -> Box<dyn Lattice + Send> {
    match &settings.waves {
        Waves::Fft => Box::new(SpectralLattice::new(settings, rms_m)),
        Waves::Gerstner(waves) => Box::new(GerstnerLattice::new(
            waves,
            settings.patch_size_m / settings.fft_size as f64,
        )),
    }
}

/// A factor on the displacement at each rest point (x, z): the waves over the shallows
/// (`ocean::shore`), as shaders/surface/water.tese applies it.
pub type DisplacementScale = Box<dyn Fn(f64, f64) -> f64 + Send>;

/// Surface queries over a [`Lattice`]: bilinear between nodes and summed over lattices, as the
/// water shaders sample the images, times an optional [`DisplacementScale`]; node values cached
/// for one time.
pub struct SurfaceQuery<L: ?Sized + Lattice> {
    steps: Vec<f64>,
    time: Option<f64>,
    cache: HashMap<(usize, i64, i64), [f64; 3]>,
    lattice: Box<L>,
    scale: Option<DisplacementScale>,
}

impl<L: ?Sized + Lattice> SurfaceQuery<L> {
    pub fn new(lattice: Box<L>) -> SurfaceQuery<L> {
        SurfaceQuery {
            steps: lattice.steps(),
            time: None,
            cache: HashMap::new(),
            lattice,
            scale: None,
        }
    }

    /// The same queries with the displacement at each rest point scaled by `scale`.
    pub fn scaled(lattice: Box<L>, scale: DisplacementScale) -> SurfaceQuery<L> {
        SurfaceQuery {
            scale: Some(scale),
            ..SurfaceQuery::new(lattice)
        }
    }

    /// Nodes evaluated since the time last changed (the cost of the queries).
    pub fn nodes_evaluated(&self) -> usize {
        self.cache.len()
    }

    fn at_time(&mut self, t: f64) {
        if self.time != Some(t) {
            self.lattice.set_time(t);
            self.cache.clear();
            self.time = Some(t);
        }
    }

    /// Where the rest point (α, β) is at time t: (x, y, z).
    pub fn displaced(&mut self, alpha: f64, beta: f64, t: f64) -> [f64; 3] {
        self.at_time(t);
        let mut d = [0.0; 3];
        for c in 0..self.steps.len() {
            let (fx, fz) = (alpha / self.steps[c], beta / self.steps[c]);
            let (i, j) = (fx.floor() as i64, fz.floor() as i64);
            let (tx, tz) = (fx - fx.floor(), fz - fz.floor());
            let lattice = &self.lattice;
            let mut node = |di: i64, dj: i64| {
                *self
                    .cache
                    .entry((c, i + di, j + dj))
                    .or_insert_with(|| lattice.node(c, i + di, j + dj))
            };
            let (v00, v10, v01, v11) = (node(0, 0), node(1, 0), node(0, 1), node(1, 1));
            for (k, out) in d.iter_mut().enumerate() {
                *out += (v00[k] * (1.0 - tx) + v10[k] * tx) * (1.0 - tz)
                    + (v01[k] * (1.0 - tx) + v11[k] * tx) * tz;
            }
        }
        let s = self.scale.as_ref().map_or(1.0, |f| f(alpha, beta));
        [alpha + s * d[0], s * d[1], beta + s * d[2]]
    }

    /// Rest point carried to (x, z) at time t (fixed-point iteration α ← α + x − X(α, β), as
    /// `CpuOcean::rest_position`; it converges where the surface does not fold, J > 0).
    pub fn rest_position(&mut self, x: f64, z: f64, t: f64) -> [f64; 2] {
        let (mut a, mut b) = (x, z);
        for _ in 0..16 {
            let p = self.displaced(a, b, t);
            let (ex, ez) = (x - p[0], z - p[2]);
            a += ex;
            b += ez;
            if ex.abs().max(ez.abs()) < 1e-6 {
                break;
            }
        }
        [a, b]
    }

    /// Height of the surface above the world point (x, z) at time t.
    pub fn height_at(&mut self, x: f64, z: f64, t: f64) -> f64 {
        let [a, b] = self.rest_position(x, z, t);
        self.displaced(a, b, t)[1]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ocean::cpu::CpuOcean;

    #[test]
    fn spectral_nodes_match_the_fft_and_heights_match_cpu_ocean() {
        let settings = OceanSettings {
            fft_size: 64,
            ..OceanSettings::default()
        };
        let t = 7.25;
        let fields = CpuOcean::new(&settings).fields(t);
        // Every mode: the node values are the FFT's texels to rounding.
        let mut exact = SpectralLattice::new(&settings, 0.0);
        exact.set_time(t);
        for (c, f) in fields.iter().enumerate() {
            for &(i, j) in &[(0i64, 0i64), (5, 63), (-3, 17), (70, -1)] {
                let texel = f.displacement[(j.rem_euclid(64) * 64 + i.rem_euclid(64)) as usize];
                let node = exact.node(c, i, j);
                for k in 0..3 {
                    assert!(
                        (node[k] - texel[k]).abs() < 1e-9,
                        "cascade {c} node ({i},{j})[{k}]: {} vs FFT {}",
                        node[k],
                        texel[k]
                    );
                }
            }
        }
        // Dropped modes of RMS 2 mm: heights within 6 mm (3σ) of CpuOcean's (same bilinear, same inversion).
        let mut query = SurfaceQuery::new(Box::new(SpectralLattice::new(&settings, 0.002)));
        let mut cpu = CpuOcean::new(&settings);
        for &(x, z) in &[(9.0, -55.0), (123.4, 56.7), (-300.0, 2.5)] {
            let (ours, reference) = (query.height_at(x, z, t), cpu.height_at(x, z, t));
            assert!(
                (ours - reference).abs() < 0.006,
                "height at ({x},{z}): {ours} vs CpuOcean {reference} (tolerance 6 mm)"
            );
        }
    }
}
