//! Wakes (`--boat SPEED,HEADING`): the waves a moving boat makes, on a local grid near the camera,
//! by Tessendorf's eWave (2014, "eWave: Using an Exponential Solver on the iWave Problem").
//!
//! The model is linear potential flow at the surface: the height h and the surface velocity
//! potential φ, driven by the pressure p a hull presses on the water (linearized Bernoulli):
//!   ∂h/∂t = K φ,  ∂φ/∂t = −g h − p/ρ,   K = √(−∇²) tanh(√(−∇²) d),
//! so every Fourier mode oscillates at ω(k) = √(g k tanh k d), the sea's own dispersion relation.
//! eWave's point is that the free step is exact in Fourier space for any Δt (a rotation of (h, φ)
//! by ωΔt): the waves keep their speed and dispersion whatever the frame rate, with no
//! stability limit. Per step:
//!   h̃' = cos(ωΔt) h̃ + (ω/g) sin(ωΔt) φ̃,   φ̃' = −(g/ω) sin(ωΔt) h̃ + cos(ωΔt) φ̃,
//! then in space the boat's impulse φ −= Δt p/ρ and an absorbing layer at the grid's edge, so
//! the wake leaves the grid instead of wrapping round (the FFT's grid is periodic).
//!
//! On the GPU (`simulation/wake_sim.rs`) the state is one complex field z = h + iφ transformed by
//! our Stockham FFT (`ocean::fft`): a forward and an inverse transform a step. Its spectrum
//! Z = H + iΦ gives back H(k) = (Z(k) + Z̄(−k))/2 and Φ(k) = (Z(k) − Z̄(−k))/(2i), so the step
//! treats k and −k together. The grid follows the camera in whole texels: a shift by s texels is
//! the phase e^{2πi k·s/N} on the spectrum, applied in the same pass. [`CpuWake`] is the same
//! model with rustfft in f64: the GPU's reference.
//!
//! The boat's hull is a pressure patch, a Gaussian along and across its heading (a common model
//! of a ship in wake theory, e.g. Darmon, Benzaquen & Raphaël 2014, *J. Fluid Mech.* 738): at
//! rest it sinks the water by `DRAFT_M` under its centre, as a hull of that draft displaces it.
//! Its length sets the Froude number Fr = U/√(gL): below about 0.5 the wake's brightest arms lie
//! on Kelvin's half-angle arcsin(1/3) = 19.47°; faster they close in, as Fr⁻¹ (Rabaud & Moisy
//! 2013, *Phys. Rev. Lett.* 110, 214503).

use rustfft::num_complex::Complex64;

use super::spectrum::G;

/// Wake grid: N × N texels (a power of two for the FFT).
pub const GRID_N: usize = 256;
/// Texel size (m): the grid is 128 m across. A 3 m/s boat's transverse waves (λ = 2πU²/g =
/// 5.8 m) get 11 texels a wavelength.
pub const SPACING_M: f64 = 0.5;
/// The grid's side (m).
pub const GRID_SIDE_M: f64 = GRID_N as f64 * SPACING_M;
/// Width of the absorbing layer at each edge (texels: 12 m).
pub const SPONGE_TEXELS: u32 = 24;
/// The layer's damping rate at the very edge (1/s), ramping up as the square of the depth
/// into the layer: waves crossing it at a group velocity of 1–3 m/s lose e^-5 and more of
/// their amplitude, and the ramp is gentle enough over a wavelength not to reflect them.
pub const SPONGE_RATE_PER_S: f64 = 2.5;
/// The hull's pressure patch: length and beam (m) between the Gaussian's ±2σ points.
pub const HULL_LENGTH_M: f64 = 8.0;
pub const HULL_BEAM_M: f64 = 3.0;
/// The Gaussian's σ along the course and across it (m).
pub const HULL_SIGMA_M: [f64; 2] = [HULL_LENGTH_M / 4.0, HULL_BEAM_M / 4.0];
/// How deep the patch presses the water at rest under its centre (m): p0 = ρ g DRAFT_M.
pub const DRAFT_M: f64 = 1.0;
/// Longest step (s), in the warm-up (the boat's path before the first frame, a few hundred
/// exact steps) and in every frame (`max_step_s`): the hull's pressure is an impulse a step.
pub const MAX_STEP_S: f64 = 0.1;
/// How far the boat travels in the warm-up (m; `Boat::warmup_span_s`).
pub const WARMUP_TRAVEL_M: f64 = 120.0;
/// How far ahead of the camera the grid's centre lies, over the grid's side: the camera sits
/// near the back, where it sees most of the grid in front of it.
pub const AHEAD: f64 = 0.35;
/// The boat's pressure ramps up over its first seconds (s): a boat starting at full speed
/// would ring the whole grid with the waves of its sudden start.
pub const RAMP_S: f64 = 6.0;
/// The e-folding time of the foam the boat leaves (s): its turbulent wake's white water, a
/// choice (a small boat's trail stays white for tens of metres behind it).
pub const FOAM_DECAY_S: f64 = 8.0;
/// How fast the white water spreads sideways (m²/s): an eddy diffusivity, a choice (its trail
/// widens by about a metre in its life).
pub const FOAM_SPREAD_M2_S: f64 = 0.05;
/// Below this speed the hull makes no white water (m/s); it churns fully from twice it.
pub const CHURN_SPEED_M_S: f64 = 1.5;

/// How much white water the hull churns up at `speed_m_s` (0 to 0.8).
pub fn churn(speed_m_s: f64) -> f64 {
    let x = ((speed_m_s - CHURN_SPEED_M_S) / CHURN_SPEED_M_S).clamp(0.0, 1.0);
    0.8 * x * x * (3.0 - 2.0 * x)
}

/// Slowest and fastest boat (m/s). At 10 m/s the transverse waves are 2πU²/g = 64 m long, half
/// the grid's side; faster, they would not fit on it, and the boat would cross it in seconds.
pub const MIN_SPEED_M_S: f64 = 0.5;
pub const MAX_SPEED_M_S: f64 = 10.0;

/// A boat driven along a straight line at a constant speed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Boat {
    pub speed_m_s: f64,
    /// The direction it travels, degrees from +x toward +z.
    pub heading_deg: f64,
    /// Where it is at `anchor_time_s` (world x, z; m).
    pub anchor: [f64; 2],
    pub anchor_time_s: f64,
}

impl Boat {
    /// Unit vector of its course (x, z).
    pub fn course(&self) -> [f64; 2] {
        let a = self.heading_deg.to_radians();
        [a.cos(), a.sin()]
    }

    /// Where it is at time `t_s` (x, z).
    pub fn position(&self, t_s: f64) -> [f64; 2] {
        let u = self.course();
        let d = self.speed_m_s * (t_s - self.anchor_time_s);
        [self.anchor[0] + d * u[0], self.anchor[1] + d * u[1]]
    }

    /// Its Froude number on the hull's length, U/√(gL).
    pub fn froude(&self) -> f64 {
        self.speed_m_s / (G * HULL_LENGTH_M).sqrt()
    }

    /// The pressure under it over the water's density, p/ρ (m²/s²), at world `xz` when it is at
    /// `at`: a Gaussian with σ a quarter of the hull's length along its course and a quarter of
    /// its beam across.
    pub fn pressure(&self, at: [f64; 2], xz: [f64; 2]) -> f64 {
        let u = self.course();
        let d = [xz[0] - at[0], xz[1] - at[1]];
        let along = d[0] * u[0] + d[1] * u[1];
        let across = -d[0] * u[1] + d[1] * u[0];
        let [sl, sb] = HULL_SIGMA_M;
        G * DRAFT_M * (-0.5 * ((along / sl).powi(2) + (across / sb).powi(2))).exp()
    }

    /// How long the warm-up before the first frame lasts (s): 120 m of travel, 10 to 40 s. The
    /// grid follows the boat meanwhile, so the waves of its start are left behind in the
    /// absorbing layer and the wake behind it has settled over half that distance (the
    /// transverse waves' energy falls back at half the boat's speed, their group velocity).
    pub fn warmup_span_s(&self) -> f64 {
        (WARMUP_TRAVEL_M / self.speed_m_s).clamp(10.0, 40.0)
    }

    /// How hard it presses at time `t_s`, 0 to 1: a smoothstep over `RAMP_S` from the start of
    /// the warm-up.
    pub fn strength(&self, t_s: f64) -> f64 {
        let start = self.anchor_time_s - self.warmup_span_s();
        let x = ((t_s - start) / RAMP_S).clamp(0.0, 1.0);
        x * x * (3.0 - 2.0 * x)
    }

    /// The warm-up before a first frame at `t_s` whose grid lies at `origin`: steps of at most
    /// `max_step_s` over `warmup_span_s`, the grid centred on the boat at each step's end (on
    /// `origin` at the last).
    pub fn warmup(&self, t_s: f64, origin: [f64; 2]) -> Vec<Step> {
        let span = self.warmup_span_s();
        let count = (span / max_step_s(self.speed_m_s)).ceil() as usize;
        let time = |i: usize| t_s - span + span * i as f64 / count as f64;
        let half = GRID_SIDE_M / 2.0;
        let centred = |t: f64| {
            let p = self.position(t);
            [0, 1].map(|i| ((p[i] - half) / SPACING_M).round() * SPACING_M)
        };
        (1..=count)
            .map(|i| Step {
                from_s: time(i - 1),
                to_s: time(i),
                origin: if i == count { origin } else { centred(time(i)) },
            })
            .collect()
    }
}

/// One step of the wake: from and to (s), and where the grid lies during it (its texel (0, 0)).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Step {
    pub from_s: f64,
    pub to_s: f64,
    pub origin: [f64; 2],
}

/// The steps from the last submission (`last`: its time) to `t_s`, the grid at `origin`: as
/// many as keep each within `max_step_s`, at least one (it writes the frame's image).
pub fn steps_since(last_s: f64, t_s: f64, origin: [f64; 2], speed_m_s: f64) -> Vec<Step> {
    let dt = (t_s - last_s).max(0.0);
    let count = (dt / max_step_s(speed_m_s)).ceil().max(1.0) as usize;
    let time = |i: usize| last_s + dt * i as f64 / count as f64;
    (1..=count)
        .map(|i| Step {
            from_s: time(i - 1),
            to_s: time(i),
            origin,
        })
        .collect()
}

/// Longest step: `MAX_STEP_S`, and one texel of the boat's travel (the impulses it leaves
/// along its path then overlap into a smooth line: the patch is 1.5 texels wide at ±σ).
pub fn max_step_s(speed_m_s: f64) -> f64 {
    MAX_STEP_S.min(SPACING_M / speed_m_s.max(1e-6))
}

/// World position of the grid's texel (0, 0) for a camera at `camera_xz` whose unit view
/// direction has the horizontal part `forward_xz`: the grid's centre `AHEAD` of a side in front
/// of the camera as it looks toward the horizon, under it as it looks straight down, snapped to
/// whole texels so the field stays on a fixed world lattice.
pub fn grid_origin(camera_xz: [f64; 2], forward_xz: [f64; 2]) -> [f64; 2] {
    let side = GRID_SIDE_M;
    let len = forward_xz[0].hypot(forward_xz[1]).max(1.0);
    [0, 1].map(|i| {
        let centre = camera_xz[i] + forward_xz[i] / len * AHEAD * side;
        ((centre - side / 2.0) / SPACING_M).round() * SPACING_M
    })
}

/// The absorbing layer's damping rate (1/s) at texel `(i, j)`.
pub fn sponge_rate(i: u32, j: u32) -> f64 {
    let n = GRID_N as u32;
    let edge = i.min(j).min(n - 1 - i).min(n - 1 - j);
    if edge >= SPONGE_TEXELS {
        return 0.0;
    }
    let depth = (SPONGE_TEXELS - edge) as f64 / SPONGE_TEXELS as f64;
    SPONGE_RATE_PER_S * depth * depth
}

/// Angular frequency of a wave number (rad/m) at `depth_m` (deep water: `None`): the sea's own
/// dispersion (`spectrum::dispersion`).
pub fn omega(k: f64, depth_m: Option<f64>) -> f64 {
    super::spectrum::dispersion(k, depth_m).0
}

/// Signed frequency index of FFT bin `i` (0..N/2−1, then −N/2..−1).
pub fn signed(i: usize, n: usize) -> i64 {
    if i < n / 2 {
        i as i64
    } else {
        i as i64 - n as i64
    }
}

/// The wake on the CPU in f64 (rustfft), step for step as the GPU runs it: the reference.
pub struct CpuWake {
    /// Height (m) and potential (m²/s), row-major `[j * N + i]`, rows along z.
    pub h: Vec<f64>,
    pub phi: Vec<f64>,
    pub depth_m: Option<f64>,
    /// World position of texel (0, 0).
    pub origin: [f64; 2],
}

impl CpuWake {
    pub fn new(origin: [f64; 2], depth_m: Option<f64>) -> CpuWake {
        let n2 = GRID_N * GRID_N;
        CpuWake {
            h: vec![0.0; n2],
            phi: vec![0.0; n2],
            depth_m,
            origin,
        }
    }

    /// One step of `dt_s` with the grid moved to `origin` (whole texels from the last) and the
    /// boat (none: no boat) pressing at the step's midpoint time `t_mid`.
    pub fn step(&mut self, dt_s: f64, origin: [f64; 2], boat: Option<(&Boat, f64)>) {
        let n = GRID_N;
        let shift = [0, 1].map(|i| ((origin[i] - self.origin[i]) / SPACING_M).round() as i64);
        self.origin = origin;
        let mut z: Vec<Complex64> = self
            .h
            .iter()
            .zip(&self.phi)
            .map(|(&h, &p)| Complex64::new(h, p))
            .collect();
        fft2(&mut z, n, false);
        let dk = 2.0 * std::f64::consts::PI / (n as f64 * SPACING_M);
        let mut out = vec![Complex64::new(0.0, 0.0); n * n];
        for j in 0..n {
            for i in 0..n {
                let (ki, kj) = (signed(i, n), signed(j, n));
                let k = dk * ((ki * ki + kj * kj) as f64).sqrt();
                let w = omega(k, self.depth_m);
                let (c, s) = ((w * dt_s).cos(), (w * dt_s).sin());
                let a = if w > 0.0 { w / G * s } else { 0.0 };
                let b = if w > 0.0 { G / w * s } else { G * dt_s };
                let phase = 2.0
                    * std::f64::consts::PI
                    * ((ki * shift[0] + kj * shift[1]).rem_euclid(n as i64) as f64)
                    / n as f64;
                let e = Complex64::from_polar(1.0, phase);
                let zk = z[j * n + i] * e;
                let zm = z[((n - j) % n) * n + (n - i) % n] * e.conj();
                let hk = (zk + zm.conj()) * 0.5;
                let pk = (zk - zm.conj()) * Complex64::new(0.0, -0.5);
                let h2 = hk * c + pk * a;
                let p2 = -hk * b + pk * c;
                out[j * n + i] = h2 + p2 * Complex64::new(0.0, 1.0);
            }
        }
        fft2(&mut out, n, true);
        let scale = 1.0 / (n * n) as f64;
        for j in 0..n {
            for i in 0..n {
                let idx = j * n + i;
                let damp = (-sponge_rate(i as u32, j as u32) * dt_s).exp();
                // Texel i held texel i + shift: where that lies off the old grid, the spectrum's
                // periodic shift brought the far edge's water in; the water there is still.
                let from = [i as i64 + shift[0], j as i64 + shift[1]];
                let inside = from.iter().all(|&f| (0..n as i64).contains(&f));
                let (h, mut phi) = if inside {
                    (out[idx].re * scale, out[idx].im * scale)
                } else {
                    (0.0, 0.0)
                };
                if let Some((boat, t_mid)) = boat {
                    let xz = [
                        origin[0] + i as f64 * SPACING_M,
                        origin[1] + j as f64 * SPACING_M,
                    ];
                    let at = boat.position(t_mid);
                    phi -= dt_s * boat.strength(t_mid) * boat.pressure(at, xz);
                }
                self.h[idx] = h * damp;
                self.phi[idx] = phi * damp;
            }
        }
    }
}

impl CpuWake {
    /// Runs `steps` of `boat` (`Boat::warmup`, `steps_since`).
    pub fn run(&mut self, boat: &Boat, steps: &[Step]) {
        for s in steps {
            let mid = 0.5 * (s.from_s + s.to_s);
            self.step(s.to_s - s.from_s, s.origin, Some((boat, mid)));
        }
    }
}

pub use super::cpu::fft_2d as fft2;

#[cfg(test)]
mod tests;
