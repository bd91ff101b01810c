//! Light scattered more than once in the air, after Hillaire (2020, "A scalable and production
//! ready sky and atmosphere rendering technique", EGSR, §5.5): the sky's single scattering
//! (shaders/common/sky.glsl, `atmosphere::clear_sky_zenith`) misses the light that the air
//! has already scattered, which brightens the whole sky, above all at twilight, when the
//! sunlight reaches the eye's air only after a second scattering high up.
//!
//! Hillaire's approximation: past the first order, every order is scattered isotropically
//! (phase 1/4π) and the light reaching a point comes equally from every direction, so at a
//! point of altitude h under a sun of zenith cosine μs
//! - the second order is L₂ = ∫_Ω L′(x, −ω) p_u dω, with L′ the single scattering (isotropic,
//!   with the planet's shadow) and the ground's diffuse reflection seen along −ω;
//! - the share of light scattered back to the point, f_ms = ∫_Ω L_f(x, −ω) p_u dω with
//!   L_f = ∫ T σ_s dt, is the same for every order, so all orders sum as a geometric series:
//!   Ψ_ms = L₂ / (1 − f_ms).
//!
//! The sky then adds σ_s(p) Ψ_ms(h, μs) at every sample of its march (common/sky.glsl). Ψ_ms
//! depends only on the atmosphere, so it is computed once per process (`lut`), 64 directions
//! of 20 samples a texel as in the paper, and uploaded as a 32x32 table (`SIDE`), h along x
//! (as √(h / height), dense near the sea), μs along y.

use std::f64::consts::PI;
use std::sync::OnceLock;

use crate::shared::{
    ATMOSPHERE_TOP_M, EARTH_RADIUS_M, MIE_EXTINCTION, MIE_SCALE_HEIGHT_M, MIE_SCATTERING,
    OZONE_ABSORPTION, OZONE_HALF_WIDTH_M, OZONE_PEAK_M, RAYLEIGH_SCALE_HEIGHT_M,
    RAYLEIGH_SCATTERING,
};

/// Texels of the table along each axis (Hillaire's 32x32).
pub const SIDE: usize = 32;
/// Directions over the sphere per texel, and samples along each (Hillaire: 64 and 20).
const DIRECTIONS: usize = 64;
const SAMPLES: usize = 20;
/// The sea's albedo to diffuse light: about 0.06 (Payne 1972, "Albedo of the sea surface",
/// J. Atmos. Sci. 29: monthly means 0.06–0.07 at high sun), the ground the multiple
/// scattering sees below the air.
pub const SEA_ALBEDO: f64 = 0.06;

/// The table, texel (x: altitude, y: μs) at `[y * SIDE + x]`: Ψ_ms for the red, green and
/// blue (680, 550, 440 nm) of a sun of unit irradiance.
pub fn lut() -> &'static [[f32; 3]] {
    static LUT: OnceLock<Vec<[f32; 3]>> = OnceLock::new();
    LUT.get_or_init(|| {
        let transmittance = Transmittance::new();
        let mut out = Vec::with_capacity(SIDE * SIDE);
        for y in 0..SIDE {
            for x in 0..SIDE {
                let (h, mu_s) = texel_at(x, y);
                out.push(psi(&transmittance, h, mu_s).map(|v| v as f32));
            }
        }
        out
    })
}

/// The altitude (m) and sun zenith cosine at texel centre (x, y): the inverse of `coords`, which
/// puts the first and last texels' centres at the ends of each range (h = 0 and the top,
/// μs = −1 and 1).
fn texel_at(x: usize, y: usize) -> (f64, f64) {
    let u = x as f64 / (SIDE - 1) as f64;
    let v = y as f64 / (SIDE - 1) as f64;
    (u * u * height(), v * 2.0 - 1.0)
}

/// The texture coordinates (0–1, texel centres at the table's ends) of altitude `h` (m) and
/// sun zenith cosine `mu_s`: what common/sky.glsl's `multiple_scattering` samples at.
pub fn coords(h: f64, mu_s: f64) -> (f64, f64) {
    let u = (h / height()).clamp(0.0, 1.0).sqrt();
    let v = (mu_s * 0.5 + 0.5).clamp(0.0, 1.0);
    let to_centres = |s: f64| (0.5 + s * (SIDE as f64 - 1.0)) / SIDE as f64;
    (to_centres(u), to_centres(v))
}

/// Ψ_ms at altitude `h` and sun zenith cosine `mu_s`, bilinear between texel centres as the
/// GPU samples it: the twin of the shaders' lookup, for `atmosphere::clear_sky_zenith`.
pub fn at(h: f64, mu_s: f64) -> [f64; 3] {
    let table = lut();
    let (u, v) = coords(h, mu_s);
    let fx = (u * SIDE as f64 - 0.5).clamp(0.0, SIDE as f64 - 1.0);
    let fy = (v * SIDE as f64 - 0.5).clamp(0.0, SIDE as f64 - 1.0);
    let (x0, y0) = (fx.floor() as usize, fy.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(SIDE - 1), (y0 + 1).min(SIDE - 1));
    let (ax, ay) = (fx - x0 as f64, fy - y0 as f64);
    let texel = |x: usize, y: usize| table[y * SIDE + x].map(f64::from);
    let (a, b, c, d) = (texel(x0, y0), texel(x1, y0), texel(x0, y1), texel(x1, y1));
    std::array::from_fn(|i| {
        let top = a[i] + (b[i] - a[i]) * ax;
        let bottom = c[i] + (d[i] - c[i]) * ax;
        top + (bottom - top) * ay
    })
}

fn height() -> f64 {
    (ATMOSPHERE_TOP_M - EARTH_RADIUS_M) as f64
}

/// Densities (Rayleigh, aerosol, ozone) at altitude `h`, as common/sky.glsl's `air_density`.
fn density(h: f64) -> [f64; 3] {
    [
        (-h / RAYLEIGH_SCALE_HEIGHT_M as f64).exp(),
        (-h / MIE_SCALE_HEIGHT_M as f64).exp(),
        (1.0 - (h - OZONE_PEAK_M as f64).abs() / OZONE_HALF_WIDTH_M as f64).max(0.0),
    ]
}

/// Scattering and extinction (1/m) per channel at densities `rho`.
fn coefficients(rho: [f64; 3]) -> ([f64; 3], [f64; 3]) {
    let scattering = std::array::from_fn(|c| {
        RAYLEIGH_SCATTERING[c] as f64 * rho[0] + MIE_SCATTERING as f64 * rho[1]
    });
    let extinction = std::array::from_fn(|c| {
        RAYLEIGH_SCATTERING[c] as f64 * rho[0]
            + MIE_EXTINCTION as f64 * rho[1]
            + OZONE_ABSORPTION[c] as f64 * rho[2]
    });
    (scattering, extinction)
}

/// Distance from radius `r` along zenith cosine `mu` to the top of the atmosphere, and to the
/// ground if the ray meets it first.
fn ray_length(r: f64, mu: f64) -> (f64, bool) {
    let (ground, top) = (EARTH_RADIUS_M as f64, ATMOSPHERE_TOP_M as f64);
    let below = r * r * (mu * mu - 1.0) + ground * ground;
    if mu < 0.0 && below >= 0.0 {
        return (-r * mu - below.sqrt(), true);
    }
    (
        -r * mu + (r * r * (mu * mu - 1.0) + top * top).max(0.0).sqrt(),
        false,
    )
}

/// The sunlight's transmittance from altitude h toward zenith cosine μ, tabulated (the table
/// is marched once; Ψ_ms looks it up 1,280 times a texel, 1.3 million times in all).
struct Transmittance {
    table: Vec<[f64; 3]>,
}

const T_HEIGHTS: usize = 64;
const T_COSINES: usize = 256;

impl Transmittance {
    fn new() -> Self {
        let mut table = Vec::with_capacity(T_HEIGHTS * T_COSINES);
        for j in 0..T_COSINES {
            for i in 0..T_HEIGHTS {
                let u = i as f64 / (T_HEIGHTS - 1) as f64;
                let mu = j as f64 / (T_COSINES - 1) as f64 * 2.0 - 1.0;
                table.push(Self::march(u * u * height(), mu));
            }
        }
        Self { table }
    }

    /// Optical depth marched over 200 midpoint steps crowded toward the start; 0 where the
    /// planet hides the sun.
    fn march(h: f64, mu: f64) -> [f64; 3] {
        let r = EARTH_RADIUS_M as f64 + h;
        let (len, ground) = ray_length(r, mu);
        if ground {
            return [0.0; 3];
        }
        const STEPS: usize = 200;
        let mut depth = [0.0; 3];
        for i in 0..STEPS {
            let (u0, u1) = (i as f64 / STEPS as f64, (i + 1) as f64 / STEPS as f64);
            let dt = len * (u1 * u1 - u0 * u0);
            let t = len * 0.5 * (u0 * u0 + u1 * u1);
            let hp = (r * r + t * t + 2.0 * r * mu * t).sqrt() - EARTH_RADIUS_M as f64;
            let (_, ext) = coefficients(density(hp));
            for c in 0..3 {
                depth[c] += ext[c] * dt;
            }
        }
        depth.map(|d| (-d).exp())
    }

    /// Bilinear lookup at altitude `h` (m) and zenith cosine `mu`.
    fn at(&self, h: f64, mu: f64) -> [f64; 3] {
        let fx = (h.max(0.0) / height()).min(1.0).sqrt() * (T_HEIGHTS - 1) as f64;
        let fy = ((mu.clamp(-1.0, 1.0) + 1.0) * 0.5) * (T_COSINES - 1) as f64;
        let (x0, y0) = (
            (fx.floor() as usize).min(T_HEIGHTS - 2),
            (fy.floor() as usize).min(T_COSINES - 2),
        );
        let (ax, ay) = (fx - x0 as f64, fy - y0 as f64);
        let t = |x: usize, y: usize| self.table[y * T_HEIGHTS + x];
        let (a, b, c, d) = (t(x0, y0), t(x0 + 1, y0), t(x0, y0 + 1), t(x0 + 1, y0 + 1));
        std::array::from_fn(|i| {
            let top = a[i] + (b[i] - a[i]) * ax;
            let bottom = c[i] + (d[i] - c[i]) * ax;
            top + (bottom - top) * ay
        })
    }
}

/// A unit direction of a spherical Fibonacci set of `n` (nearly even over the sphere).
fn direction(i: usize, n: usize) -> [f64; 3] {
    let golden = PI * (3.0 - 5f64.sqrt());
    let y = 1.0 - (i as f64 + 0.5) / n as f64 * 2.0;
    let ring = (1.0 - y * y).sqrt();
    let phi = golden * i as f64;
    [ring * phi.cos(), y, ring * phi.sin()]
}

/// Ψ_ms = L₂ / (1 − f_ms) at altitude `h` under a sun of zenith cosine `mu_s` (unit
/// irradiance), in the plane x–y (the sun toward +x).
fn psi(transmittance: &Transmittance, h: f64, mu_s: f64) -> [f64; 3] {
    let r = EARTH_RADIUS_M as f64 + h;
    let sun = [(1.0 - mu_s * mu_s).max(0.0).sqrt(), mu_s, 0.0];
    let phase = 1.0 / (4.0 * PI);
    let mut second = [0.0; 3];
    let mut f_ms = [0.0; 3];
    for i in 0..DIRECTIONS {
        let d = direction(i, DIRECTIONS);
        let (len, ground) = ray_length(r, d[1]);
        let dt = len / SAMPLES as f64;
        let mut depth = [0.0; 3];
        for s in 0..SAMPLES {
            let t = (s as f64 + 0.5) * dt;
            // The sample's position relative to the planet's centre (the point at (0, r, 0)).
            let p = [d[0] * t, r + d[1] * t, d[2] * t];
            let rp = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            let (scattering, ext) = coefficients(density(rp - EARTH_RADIUS_M as f64));
            let mu_p = (p[0] * sun[0] + p[1] * sun[1]) / rp;
            let sun_t = transmittance.at(rp - EARTH_RADIUS_M as f64, mu_p);
            for c in 0..3 {
                let seen = (-(depth[c] + 0.5 * ext[c] * dt)).exp();
                second[c] += seen * scattering[c] * sun_t[c] * phase * dt;
                f_ms[c] += seen * scattering[c] * dt;
                depth[c] += ext[c] * dt;
            }
        }
        if ground {
            // The sea seen along d: the sunlight on it, reflected diffusely (albedo / π).
            let p = [d[0] * len, r + d[1] * len, d[2] * len];
            let rp = (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt();
            let mu_g = (p[0] * sun[0] + p[1] * sun[1]) / rp;
            let sun_t = transmittance.at(0.0, mu_g);
            for c in 0..3 {
                second[c] += (-depth[c]).exp() * sun_t[c] * mu_g.max(0.0) * SEA_ALBEDO / PI;
            }
        }
    }
    // ∫_Ω g(ω) p_u dω over n even directions: the mean of g.
    std::array::from_fn(|c| {
        let l2 = second[c] / DIRECTIONS as f64;
        let f = f_ms[c] / DIRECTIONS as f64;
        l2 / (1.0 - f)
    })
}

/// The table as RGBA16F texels (alpha 1), tightly packed for an upload: a format every device
/// filters linearly.
pub fn lut_rgba16f() -> Vec<u8> {
    lut()
        .iter()
        .flat_map(|&[r, g, b]| [r, g, b, 1.0])
        .flat_map(|v| half_bits(v).to_le_bytes())
        .collect()
}

/// IEEE 754 binary16 of a finite `x`, rounded to nearest with ties away from zero (IEEE's
/// default breaks ties to even: at most one unit in the last place apart, on ties only);
/// beyond 65504 infinity.
fn half_bits(x: f32) -> u16 {
    let bits = x.to_bits();
    let sign = ((bits >> 16) & 0x8000) as u16;
    let exponent = ((bits >> 23) & 0xff) as i32 - 127 + 15;
    let mantissa = bits & 0x7f_ffff;
    if exponent >= 31 {
        return sign | 0x7c00;
    }
    if exponent <= 0 {
        if exponent < -10 {
            return sign;
        }
        let full = mantissa | 0x80_0000;
        let shift = (14 - exponent) as u32;
        let rounded = (full >> shift) + ((full >> (shift - 1)) & 1);
        return sign | rounded as u16;
    }
    let rounded = ((exponent as u32) << 10 | (mantissa >> 13)) + ((mantissa >> 12) & 1);
    sign | rounded.min(0x7c00) as u16
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_floats_are_binary16_rounded_to_nearest() {
        assert_eq!(half_bits(1.0), 0x3c00);
        assert_eq!(half_bits(0.5), 0x3800);
        assert_eq!(half_bits(-2.0), 0xc000);
        assert_eq!(half_bits(65504.0), 0x7bff);
        assert_eq!(half_bits(1e6), 0x7c00);
        // The smallest subnormal, 2^-24, and one of its multiples.
        assert_eq!(half_bits(2f32.powi(-24)), 0x0001);
        assert_eq!(half_bits(3.0 * 2f32.powi(-24)), 0x0003);
        assert_eq!(half_bits(1e-9), 0);
        // 1 + 2^-11 lies halfway between 1 and the next half: the tie goes away from zero.
        assert_eq!(half_bits(1.0 + 2f32.powi(-11)), 0x3c01);
    }

    #[test]
    fn the_table_is_finite_and_positive() {
        assert_eq!(lut().len(), SIDE * SIDE);
        assert!(lut().iter().flatten().all(|v| v.is_finite() && *v >= 0.0));
    }
}
