//! Sea state → directional wave spectrum → initial amplitudes h0(k), in SI units.
//!
//! # Conventions (shared with the GPU shaders, the CPU reference and `--dump`)
//! A cascade is an N×N grid over a square patch of side L. Element `[m][n]` holds the wave vector
//! k = (2π(n − N/2)/L, 2π(m − N/2)/L) = (k_x, k_z): x runs along n, z along m. The height is
//!
//! ```text
//! h(x, t) = Σ_k h(k, t) e^{i k·x},   h(k, t) = h0(k) e^{iω(k)t} + conj(h0(−k)) e^{−iω(k)t}
//! ```
//! (Tessendorf 2001, eq. 43), so `h(k,t)` is Hermitian and the height real. The term h0(k)e^{i(k·x+ωt)}
//! is a wave **travelling toward −k̂**; that is why every spectrum below is evaluated for the travel
//! direction −k̂ of the component it feeds (waves then run downwind).
//!
//! # Amplitude normalization (the contract)
//! With ξ = ξ_r + iξ_i, ξ_r, ξ_i independent standard normals, h0(k) = ξ·√(P(k)/2), so
//! E|h0(k)|² = P(k). The two terms of h(k,t) are independent with zero mean, hence
//! E|h(k,t)|² = P(k) + P(−k), and by Parseval the expected variance of the height field is
//!
//! ```text
//! Var h = Σ_k E|h(k,t)|² = Σ_k (P(k) + P(−k)) = 2 Σ_k P(k).
//! ```
//! A directional spectrum S(k) (m⁴, density over the k-plane, by direction of travel) gives the
//! variance Var h = ∫∫ S(k) dk_x dk_z ≈ Σ_k S(k) Δk² on a grid with Δk = 2π/L. Equating the two,
//! component by component (P(k) feeds the wave travelling toward −k̂):
//!
//! ```text
//! P(k) = S(−k) Δk² / 2.
//! ```
//! The frequency spectra S(ω) (m²·s) of Pierson–Moskowitz and JONSWAP become S(k) through the
//! directional spreading D(ω, θ) (∫_{−π}^{π} D dθ = 1) and the Jacobian of the dispersion relation:
//! S(k) d²k = S(ω) D(ω,θ) dω dθ and d²k = k dk dθ, so S(k) = S(ω) D(ω,θ) (dω/dk) / k.
//! The Phillips spectrum is used directly as S(k) (see [`phillips`]).

use std::f64::consts::PI;

/// Gravitational acceleration (m/s²).
pub const G: f64 = 9.81;

/// Which spectrum shapes the sea (`--spectrum`; the variants' doc comments are `--help`'s
/// descriptions of the values).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum SpectrumKind {
    /// Tessendorf's graphics spectrum (2001), from wind speed and direction only.
    Phillips,
    /// Fetch-limited sea (Hasselmann et al. 1973), from wind speed and fetch; Pierson–Moskowitz's
    /// once fully developed (see [`spectrum_shape`]).
    Jonswap,
    /// Fully developed sea (Pierson & Moskowitz 1964), from wind speed.
    PiersonMoskowitz,
}

impl SpectrumKind {
    pub fn name(self) -> &'static str {
        match self {
            SpectrumKind::Phillips => "phillips",
            SpectrumKind::Jonswap => "jonswap",
            SpectrumKind::PiersonMoskowitz => "pierson-moskowitz",
        }
    }
}

/// The physical sea state. All values SI except where the name says otherwise.
#[derive(Clone, Debug, PartialEq)]
pub struct SeaState {
    pub spectrum: SpectrumKind,
    /// Wind speed 10 m above the sea, U10 (m/s).
    pub wind_speed_m_s: f64,
    /// Direction the wind blows toward, degrees from +x toward +z.
    pub wind_dir_deg: f64,
    /// Distance over which the wind has blown (km); JONSWAP only.
    pub fetch_km: f64,
    /// Water depth (m); `None` is deep water. Finite depth changes the dispersion relation and
    /// applies the TMA attenuation to the physical spectra.
    pub depth_m: Option<f64>,
}

impl Default for SeaState {
    /// A moderate breeze over 100 km of fetch: Hs 1.62 m, T_p 6.2 s (JONSWAP, [`spectrum_shape`]).
    fn default() -> Self {
        SeaState {
            spectrum: SpectrumKind::Jonswap,
            wind_speed_m_s: 10.0,
            wind_dir_deg: 0.0,
            fetch_km: 100.0,
            depth_m: None,
        }
    }
}

/// Largest k·h passed to tanh/cosh: tanh(20) = 1 to f64 precision, and cosh stays finite.
const MAX_KH: f64 = 20.0;

/// Angular frequency ω(k) = √(g k tanh(k h)) and group slope dω/dk, for deep (`None`) or finite
/// depth. Arguments are clamped so no input produces NaN or infinity (k ≥ 0 assumed).
pub fn dispersion(k: f64, depth_m: Option<f64>) -> (f64, f64) {
    let k = k.max(0.0);
    match depth_m {
        None => {
            let omega = (G * k).sqrt();
            (omega, if omega > 0.0 { G / (2.0 * omega) } else { 0.0 })
        }
        Some(h) => {
            let kh = (k * h.max(1e-3)).min(MAX_KH);
            let t = kh.tanh();
            let omega = (G * k * t).max(0.0).sqrt();
            let sech2 = 1.0 / kh.cosh().powi(2);
            let d = if omega > 0.0 {
                G * (t + kh * sech2) / (2.0 * omega)
            } else {
                0.0
            };
            (omega, d)
        }
    }
}

/// Pierson & Moskowitz (1964): S(ω) = α g² ω⁻⁵ exp(−β (ω0/ω)⁴), ω0 = g/U19.5, with α = 8.1·10⁻³ ...
const PM_ALPHA: f64 = 8.1e-3;
/// ... and β = 0.74 (Pierson & Moskowitz 1964).
const PM_BETA: f64 = 0.74;
/// U19.5 ≈ 1.026 U10: Pierson & Moskowitz's winds were measured 19.5 m above the sea (Pierson &
/// Moskowitz 1964; Horvath 2015).
const U19_5_PER_U10: f64 = 1.026;

/// JONSWAP peak enhancement γ = 3.3 (Hasselmann et al. 1973, mean of the JONSWAP spectra).
const JONSWAP_GAMMA: f64 = 3.3;
/// JONSWAP peak widths σ = 0.07 below the peak and 0.09 above (Hasselmann et al. 1973).
const JONSWAP_SIGMA: [f64; 2] = [0.07, 0.09];
/// JONSWAP peak law ω_p = 22 (g²/(U10 F))^⅓ (Hasselmann et al. 1973; Horvath 2015, eq. 28).
const JONSWAP_PEAK: f64 = 22.0;
/// JONSWAP energy growth law m0 = 1.6·10⁻⁷ X (U10²/g)², X = gF/U10², i.e. Hs = 1.6·10⁻³ X^½ U10²/g
/// (Hasselmann et al. 1973): 1.62 m at U10 = 10 m/s over 100 km.
const JONSWAP_ENERGY_GROWTH: f64 = 1.6e-7;

/// Peak of the Pierson–Moskowitz spectrum (rad/s) for U10 = `u10`: where ω⁻⁵ exp(−β (ω0/ω)⁴) is
/// largest, ω_p = (4β/5)^¼ ω0 = 0.877 g/U19.5 = 0.855 g/U10 (Pierson & Moskowitz 1964). 0.855 is
/// the coefficient on U10: the 1.026 conversion is applied once.
pub fn pierson_moskowitz_peak(u10: f64) -> f64 {
    (0.8 * PM_BETA).powf(0.25) * G / (U19_5_PER_U10 * u10)
}

/// The form both physical spectra take (Hasselmann et al. 1973, with Pierson–Moskowitz as γ = 1):
/// S(ω) = α g² ω⁻⁵ exp(−5/4 (ω_p/ω)⁴) γ^exp(−(ω − ω_p)²/(2σ²ω_p²)), σ from `JONSWAP_SIGMA`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpectrumShape {
    /// Level of the ω⁻⁵ tail (the Phillips constant of the spectrum), α.
    pub alpha: f64,
    /// Peak angular frequency ω_p (rad/s).
    pub omega_p: f64,
    /// Peak enhancement γ (1: Pierson–Moskowitz).
    pub gamma: f64,
}

impl SpectrumShape {
    /// The fully developed sea of wind `u10` (Pierson & Moskowitz 1964).
    pub fn pierson_moskowitz(u10: f64) -> SpectrumShape {
        SpectrumShape {
            alpha: PM_ALPHA,
            omega_p: pierson_moskowitz_peak(u10),
            gamma: 1.0,
        }
    }

    /// Deep-water S(ω) (m²·s).
    pub fn density(&self, omega: f64) -> f64 {
        let wp = self.omega_p;
        let sigma = JONSWAP_SIGMA[usize::from(omega > wp)];
        let peak = (-(omega - wp).powi(2) / (2.0 * sigma * sigma * wp * wp)).exp();
        self.alpha * G * G / omega.powi(5)
            * (-1.25 * (wp / omega).powi(4)).exp()
            * self.gamma.powf(peak)
    }

    /// Deep-water variance m0 = ∫ S dω = α g² ω_p⁻⁴ J(γ) (m²), J from [`shape_integral`].
    pub fn variance(&self) -> f64 {
        let j = if self.gamma == 1.0 {
            0.2 // ∫₀^∞ x⁻⁵ exp(−5/4 x⁻⁴) dx = 1/5
        } else if self.gamma == JONSWAP_GAMMA {
            jonswap_shape_integral()
        } else {
            shape_integral(self.gamma)
        };
        self.alpha * G * G / self.omega_p.powi(4) * j
    }
}

/// J(γ) = ∫₀^∞ x⁻⁵ exp(−5/4 x⁻⁴) γ^exp(−(x − 1)²/(2σ²)) dx, the variance of the shape with α = 1
/// in units of g² ω_p⁻⁴: midpoint rule over 0.3 ≤ x ≤ 10 and the closed form
/// ∫ x⁻⁵ exp(−c x⁻⁴) dx = exp(−c x⁻⁴)/(4c) outside, where γ's factor is 1 to f64 precision.
/// J(1) = 1/5 exactly; J(3.3) = 0.3050.
pub fn shape_integral(gamma: f64) -> f64 {
    let (lo, hi, n) = (0.3f64, 10.0f64, 100_000);
    let ends = ((-1.25 / lo.powi(4)).exp() + 1.0 - (-1.25 / hi.powi(4)).exp()) / 5.0;
    let unit = SpectrumShape {
        alpha: 1.0 / (G * G),
        omega_p: 1.0,
        gamma,
    };
    let dx = (hi - lo) / n as f64;
    ends + (0..n)
        .map(|i| unit.density(lo + (i as f64 + 0.5) * dx) * dx)
        .sum::<f64>()
}

/// J(3.3), computed once.
fn jonswap_shape_integral() -> f64 {
    static J: std::sync::OnceLock<f64> = std::sync::OnceLock::new();
    *J.get_or_init(|| shape_integral(JONSWAP_GAMMA))
}

/// The deep-water spectrum of a sea state.
///
/// Pierson–Moskowitz (and Phillips' frequency spectrum): [`SpectrumShape::pierson_moskowitz`].
///
/// JONSWAP keeps Hasselmann et al.'s (1973) peak law, γ and σ, but takes α from their energy
/// growth law (m0 = 1.6·10⁻⁷ X (U10²/g)²) instead of their α fit 0.076 X^−0.22: the shape with the
/// fitted α integrates to about 1.75× the energy law (Hs 2.14 m instead of 1.62 m at 10 m/s over
/// 100 km); the two fits disagree, and the variance is the measured quantity that sets the wave
/// height. So α = m0 ω_p⁴/(g² J(3.3)) = 0.123 X^−⅓, 0.91× the fitted α at X = 160, 0.74× at 10³,
/// 0.54× at 1.7·10⁴. No sea grows beyond the fully developed one: ω_p stays at or above the
/// Pierson–Moskowitz peak (reached at X = 1.70·10⁴) and once the growth law's m0 reaches the
/// Pierson–Moskowitz variance (X = 1.90·10⁴) the spectrum is Pierson–Moskowitz's. Hs and ω_p are
/// continuous in the fetch; γ drops to 1 at X = 1.90·10⁴.
pub fn spectrum_shape(sea: &SeaState) -> SpectrumShape {
    let u = sea.wind_speed_m_s.max(1e-3);
    let developed = SpectrumShape::pierson_moskowitz(u);
    if sea.spectrum != SpectrumKind::Jonswap {
        return developed;
    }
    let fetch_m = sea.fetch_km.max(1e-3) * 1000.0;
    let x = G * fetch_m / (u * u);
    let variance = JONSWAP_ENERGY_GROWTH * x * (u * u / G).powi(2);
    if variance >= developed.variance() {
        return developed;
    }
    let omega_p = (JONSWAP_PEAK * (G * G / (u * fetch_m)).cbrt()).max(developed.omega_p);
    SpectrumShape {
        alpha: variance * omega_p.powi(4) / (G * G * jonswap_shape_integral()),
        omega_p,
        gamma: JONSWAP_GAMMA,
    }
}

/// Peak angular frequency ω_p (rad/s) of the physical spectra.
pub fn peak_omega(sea: &SeaState) -> f64 {
    spectrum_shape(sea).omega_p
}

/// One-dimensional frequency spectrum S(ω) (m²·s) of the physical spectra, TMA-attenuated at
/// finite depth. Zero at ω = 0.
pub fn frequency_spectrum(sea: &SeaState, omega: f64) -> f64 {
    if omega <= 1e-6 {
        return 0.0;
    }
    spectrum_shape(sea).density(omega) * tma_attenuation(omega, sea.depth_m)
}

/// Kitaigorodskii depth attenuation Φ(ω, h) of the TMA spectrum (Bouws et al. 1985; Horvath 2015
/// eq. 29): with ω_h = ω √(h/g), Φ = ω_h²/2 for ω_h ≤ 1, 1 − (2 − ω_h)²/2 for ω_h < 2, else 1.
pub fn tma_attenuation(omega: f64, depth_m: Option<f64>) -> f64 {
    let Some(h) = depth_m else { return 1.0 };
    let wh = omega * (h.max(0.0) / G).sqrt();
    if wh <= 1.0 {
        0.5 * wh * wh
    } else if wh < 2.0 {
        1.0 - 0.5 * (2.0 - wh).powi(2)
    } else {
        1.0
    }
}

/// Width β of the Donelan–Banner spreading at r = ω/ω_p (Donelan, Hamilton & Hui 1985, Banner 1990;
/// as in Horvath 2015, eq. 38): β = 2.61 r^1.3 for r < 0.95 (Donelan et al. fit 0.56 < r < 0.95; the
/// same power law is kept below 0.56), 2.28 r^−1.3 for 0.95 ≤ r < 1.6, and above it Banner's
/// β = 10^ε, ε = −0.4 + 0.8393 exp(−0.567 ln(r²)) = −0.4 + 0.8393 r^−1.134. Continuous at r = 1.6
/// (1.2376 from both sides).
pub fn donelan_banner_beta(r: f64) -> f64 {
    if r < 0.95 {
        2.61 * r.powf(1.3)
    } else if r < 1.6 {
        2.28 * r.powf(-1.3)
    } else {
        let eps = -0.4 + 0.8393 * (-0.567 * (r * r).ln()).exp();
        10f64.powf(eps)
    }
}

/// Donelan–Banner directional spreading D(ω, θ) (Donelan, Hamilton & Hui 1985 with Banner's 1990
/// high-frequency extension; Horvath 2015 eq. 38): D = β / (2 tanh(βπ)) · sech²(βθ), β from
/// [`donelan_banner_beta`], θ the angle between the direction of travel and the wind in (−π, π].
/// Integrates to exactly 1 over θ.
pub fn donelan_banner(omega: f64, omega_p: f64, theta: f64) -> f64 {
    let r = (omega / omega_p.max(1e-6)).max(1e-6);
    let beta = donelan_banner_beta(r).max(1e-3); // β → 0 would be isotropic; keep tanh(βπ) away from 0
    let sech = 1.0 / (beta * theta).cosh();
    beta / (2.0 * (beta * PI).tanh()) * sech * sech
}

/// Tessendorf's amplitude constant for the Phillips spectrum, A = α/π with α = 0.0081 (Phillips'
/// constant of the saturation range, as in Pierson & Moskowitz 1964). The variance is
/// ∫ S d²k = A (π/2)(1 + 0.07) L_w²/2 = 1.07 α L_w²/4 = 2.17·10⁻³ L_w² (L_w = U²/g; the e^{−k²ℓ²}
/// cut-off changes it by < 0.1 %): Hs = 0.186 U²/g, 1.90 m at 10 m/s, 0.71× the
/// Pierson–Moskowitz variance of the same U10 (Hs 0.85×). `phillips_variance_matches_closed_form`
/// checks it.
pub const PHILLIPS_A: f64 = 8.1e-3 / PI;
/// Factor on waves travelling against the wind (seed 003 `dirDepend`; NVIDIA's sample uses 0.07).
pub const PHILLIPS_AGAINST_WIND: f64 = 0.07;

/// Phillips spectrum as a density over the k-plane (m⁴), for a wave travelling along `k_travel`
/// (Tessendorf 2001 eq. 40, seed 003): A e^{−1/(kL)²}/k⁴ |k̂·ŵ|² · e^{−k²ℓ²}, L = U²/g, ℓ = L/1000
/// (suppresses waves much shorter than the wind scale), times `PHILLIPS_AGAINST_WIND` when k̂·ŵ < 0.
pub fn phillips(k_travel: [f64; 2], wind_speed_m_s: f64, wind_dir: [f64; 2]) -> f64 {
    let k2 = k_travel[0] * k_travel[0] + k_travel[1] * k_travel[1];
    if k2 < 1e-12 {
        return 0.0;
    }
    let l_wind = (wind_speed_m_s * wind_speed_m_s / G).max(1e-6);
    let k = k2.sqrt();
    let cos = (k_travel[0] * wind_dir[0] + k_travel[1] * wind_dir[1]) / k;
    let small = l_wind / 1000.0;
    let mut p = PHILLIPS_A * (-1.0 / (k2 * l_wind * l_wind)).exp() / (k2 * k2)
        * cos
        * cos
        * (-k2 * small * small).exp();
    if cos < 0.0 {
        p *= PHILLIPS_AGAINST_WIND;
    }
    p
}

/// Unit vector of the wind direction.
pub fn wind_vector(sea: &SeaState) -> [f64; 2] {
    let a = sea.wind_dir_deg.to_radians();
    [a.cos(), a.sin()]
}

/// Directional spectrum S(k) (m⁴) for waves travelling along `k_travel`.
pub fn directional_density(sea: &SeaState, k_travel: [f64; 2]) -> f64 {
    let wind = wind_vector(sea);
    if sea.spectrum == SpectrumKind::Phillips {
        return phillips(k_travel, sea.wind_speed_m_s, wind);
    }
    let k = (k_travel[0] * k_travel[0] + k_travel[1] * k_travel[1]).sqrt();
    if k < 1e-9 {
        return 0.0;
    }
    let (omega, domega_dk) = dispersion(k, sea.depth_m);
    let theta =
        (k_travel[1].atan2(k_travel[0]) - wind[1].atan2(wind[0]) + PI).rem_euclid(2.0 * PI) - PI;
    if omega <= 1e-6 {
        return 0.0;
    }
    let shape = spectrum_shape(sea);
    shape.density(omega)
        * tma_attenuation(omega, sea.depth_m)
        * donelan_banner(omega, shape.omega_p, theta)
        * domega_dk
        / k
}

/// Numerical ∫∫ S(k) d²k over the annulus k_min ≤ |k| ≤ k_max (polar midpoint rule, log-spaced
/// in k). Used to check the normalization of generated fields.
pub fn integrate_density(sea: &SeaState, k_min: f64, k_max: f64) -> f64 {
    let (nk, nt) = (4000, 720);
    let (lo, hi) = (k_min.max(1e-6).ln(), k_max.ln());
    let mut sum = 0.0;
    for i in 0..nk {
        let (a, b) = (
            lo + (hi - lo) * i as f64 / nk as f64,
            lo + (hi - lo) * (i + 1) as f64 / nk as f64,
        );
        let k = ((a + b) / 2.0).exp();
        let dk = b.exp() - a.exp();
        for j in 0..nt {
            let t = -PI + 2.0 * PI * (j as f64 + 0.5) / nt as f64;
            sum += directional_density(sea, [k * t.cos(), k * t.sin()])
                * k
                * dk
                * (2.0 * PI / nt as f64);
        }
    }
    sum
}

/// Portable counter-based RNG: SplitMix64 (Steele, Lea & Flood 2014) of a key. The same key gives
/// the same number on every machine.
fn splitmix64(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A complex standard normal pair (ξ_r, ξ_i) for wave index (i, j) of cascade `c` (Box–Muller).
/// Keyed by the integer wave index, not the array position, so the same waves keep their phases
/// when N changes.
pub fn gaussian_pair(seed: u64, cascade: u32, i: i64, j: i64) -> (f64, f64) {
    let key = splitmix64(
        seed ^ splitmix64(
            ((cascade as u64) << 48) ^ ((i as u64 & 0xFF_FFFF) << 24) ^ (j as u64 & 0xFF_FFFF),
        ),
    );
    let a = splitmix64(key);
    let b = splitmix64(a);
    // Uniforms in (0, 1]: 53 random bits.
    let u1 = ((a >> 11) + 1) as f64 / (1u64 << 53) as f64;
    let u2 = (b >> 11) as f64 / (1u64 << 53) as f64;
    let r = (-2.0 * u1.ln()).sqrt();
    (r * (2.0 * PI * u2).cos(), r * (2.0 * PI * u2).sin())
}

/// One cascade: its patch size and the band of |k| it owns (disjoint between cascades).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cascade {
    pub patch_m: f64,
    /// |k| ≥ k_min (rad/m).
    pub k_min: f64,
    /// |k| < k_max (rad/m); `f64::INFINITY` for the finest cascade (up to its Nyquist limit).
    pub k_max: f64,
}

/// Ratio between successive patch sizes: not a ratio of small integers, so the tiles of different
/// cascades never line up (no visible repetition).
pub const CASCADE_RATIO: f64 = 4.353;

/// Patch sizes and disjoint k bands for `count` cascades, the largest patch `patch_m`. The band
/// boundary between cascades c and c+1 is 12π/L_{c+1}: six waves across the finer tile, far
/// below the coarser cascade's Nyquist limit πN/L_c for every N ≥ 64.
pub fn cascades(patch_m: f64, count: usize) -> Vec<Cascade> {
    let patches: Vec<f64> = (0..count)
        .map(|c| patch_m / CASCADE_RATIO.powi(c as i32))
        .collect();
    (0..count)
        .map(|c| Cascade {
            patch_m: patches[c],
            k_min: if c == 0 { 0.0 } else { 12.0 * PI / patches[c] },
            k_max: if c + 1 < count {
                12.0 * PI / patches[c + 1]
            } else {
                f64::INFINITY
            },
        })
        .collect()
}

/// The surface repeats exactly after this time (s): every frequency is rounded to a whole
/// multiple of ω0 = 2π/T (Tessendorf 2001, §3.2, "looping in time": ω' = [ω/ω0]·ω0), so
/// h(k, t) = h(k, t mod T). 2^16 s ≈ 18 h: the rounding moves ω by at most π/T = 4.8·10⁻⁵ rad/s,
/// 0.02 % of the longest wave's frequency in a 1000 m patch.
pub const REPEAT_PERIOD_S: f64 = 65536.0;

/// ω0 = 2π/T, the frequency quantum (rad/s).
pub fn omega_quantum() -> f64 {
    2.0 * PI / REPEAT_PERIOD_S
}

/// The wave of wave number `k` at `depth_m` turns ω'·t = 2π·m·t/T: its frequency in quanta,
/// m = round(ω(k)/ω0) (`dispersion`). The GPU reads these from a buffer computed here, so the CPU
/// reference and the shaders use the same m.
pub fn omega_steps(k: f64, depth_m: Option<f64>) -> u32 {
    (dispersion(k, depth_m).0 / omega_quantum()).round() as u32
}

/// `omega_steps` of every element of one cascade's grid, row-major `[m][n]`.
pub fn omega_steps_grid(size: usize, patch_m: f64, depth_m: Option<f64>) -> Vec<u32> {
    (0..size * size)
        .map(|i| {
            let k = wave_vector(i % size, i / size, size, patch_m);
            omega_steps((k[0] * k[0] + k[1] * k[1]).sqrt(), depth_m)
        })
        .collect()
}

/// Time as the shaders get it: t mod T in units of T/2^32 (15 µs), computed in f64 so any
/// `--time` up to 10^6 s (and a window left running for days) keeps its precision.
pub fn time_ticks(t_s: f64) -> u32 {
    ((t_s / REPEAT_PERIOD_S).rem_euclid(1.0) * 4_294_967_296.0).round() as u64 as u32
}

/// The phase of a wave of `steps` quanta at `ticks`, in turns, in [−½, ½): ω'·t/2π mod 1 =
/// steps·ticks / 2^32 mod 1, exact in 32-bit integer arithmetic (the evolve shader does the same
/// with a `uint` multiply that wraps modulo 2^32).
pub fn phase_turns(steps: u32, ticks: u32) -> f64 {
    steps.wrapping_mul(ticks) as i32 as f64 / 4_294_967_296.0
}

/// Wave vector of element `[m][n]` of an N×N grid over a patch of side `patch_m`.
pub fn wave_vector(n: usize, m: usize, size: usize, patch_m: f64) -> [f64; 2] {
    let dk = 2.0 * PI / patch_m;
    let half = (size / 2) as f64;
    [(n as f64 - half) * dk, (m as f64 - half) * dk]
}

/// h0(k) of one cascade, row-major `[m][n]`, as (re, im) pairs in f32. Zero outside the cascade's
/// band, at k = 0 and on the Nyquist row and column (which have no −k partner on the grid).
pub fn h0(
    sea: &SeaState,
    size: usize,
    cascade: &Cascade,
    cascade_index: u32,
    seed: u64,
) -> Vec<[f32; 2]> {
    let dk = 2.0 * PI / cascade.patch_m;
    let half = size as i64 / 2;
    let mut out = vec![[0.0f32; 2]; size * size];
    for m in 0..size {
        for n in 0..size {
            let (i, j) = (n as i64 - half, m as i64 - half);
            if i == -half || j == -half {
                continue;
            }
            let k = wave_vector(n, m, size, cascade.patch_m);
            let k_len = (k[0] * k[0] + k[1] * k[1]).sqrt();
            if k_len < cascade.k_min || k_len >= cascade.k_max || k_len == 0.0 {
                continue;
            }
            // P(k) = S(−k) Δk² / 2: h0(k) feeds the wave travelling toward −k̂.
            let p = directional_density(sea, [-k[0], -k[1]]) * dk * dk / 2.0;
            let (xr, xi) = gaussian_pair(seed, cascade_index, i, j);
            let amp = (p / 2.0).sqrt();
            out[m * size + n] = [(xr * amp) as f32, (xi * amp) as f32];
        }
    }
    out
}

#[cfg(test)]
mod tests;
