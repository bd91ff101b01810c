//! The sun's light through the atmosphere, on the CPU: what is left of it at the sea
//! (`sun_transmittance`, the twin of shaders/common/sky.glsl's, which renders the sky cube with
//! it), and the sky the renderer draws (`Sky`: sun, cloud cover, irradiance). The atmosphere's
//! constants (src/shared.rs) are the Earth's of Bruneton (2017) and Hillaire (2020).

use glam::Vec3;

use crate::shared::{
    ATMOSPHERE_TOP_M, EARTH_RADIUS_M, MIE_EXTINCTION, MIE_SCALE_HEIGHT_M, OZONE_ABSORPTION,
    OZONE_HALF_WIDTH_M, OZONE_PEAK_M, RAYLEIGH_SCALE_HEIGHT_M, RAYLEIGH_SCATTERING,
    SKY_EYE_ALTITUDE_M,
};

/// The sun's irradiance above the atmosphere in the scene's radiance units (the display's
/// tone map takes 1 to a light grey): a white, sunlit, level surface of albedo 0.3 at
/// noon reflects 0.3 · E · T / π ≈ 1.5 in them.
pub const SUN_IRRADIANCE: f32 = 12.0;

/// The sky the renderer draws: what the sky cube is rendered for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Sky {
    /// Unit vector toward the sun.
    pub sun_dir: Vec3,
    /// Share of the sky under cloud, 0 (clear) to 1 (overcast).
    pub cloud_cover: f32,
}

impl Sky {
    fn elevation_rad(&self) -> f64 {
        (self.sun_dir.normalize().y as f64).clamp(-1.0, 1.0).asin()
    }

    /// The sun's irradiance at the sea on a surface facing it, before clouds (the shaders
    /// multiply by the share the clouds let through): SUN_IRRADIANCE × the transmittance.
    pub fn sun_light(&self) -> [f32; 3] {
        sun_transmittance(self.elevation_rad()).map(|t| (t * SUN_IRRADIANCE as f64) as f32)
    }

    /// The clear sky's radiance at the zenith (`clear_sky_zenith` × SUN_IRRADIANCE).
    pub fn zenith_radiance(&self) -> [f32; 3] {
        clear_sky_zenith(self.sun_dir.normalize().as_dvec3())
            .map(|l| (l * SUN_IRRADIANCE as f64) as f32)
    }

    /// The irradiance on the level sea from the sun and the sky: the clear sky's (the sun's
    /// beam times sin of its elevation, plus π times the zenith's radiance standing in for the
    /// sky's hemisphere), times Kasten & Czeplak (1980)'s cloud factor 1 − 0.75 C^3.4.
    pub fn global_irradiance(&self) -> [f64; 3] {
        let e = self.elevation_rad();
        let sun = sun_transmittance(e);
        let zenith = clear_sky_zenith(self.sun_dir.normalize().as_dvec3());
        let clouds = 1.0 - 0.75 * (self.cloud_cover as f64).powf(3.4);
        std::array::from_fn(|c| {
            (sun[c] * e.sin().max(0.0) + std::f64::consts::PI * zenith[c])
                * SUN_IRRADIANCE as f64
                * clouds
        })
    }

    /// The exposure the display applies. In daylight brighter than the default day's, the eye
    /// (and a camera's automatic exposure) adapts fully, exposure ∝ 1/E: lightness constancy,
    /// so a noon sea looks as dark as it is, not lit up like a pool. Below it, in the low sun,
    /// dusk and under cloud, it adapts halfway in log terms (exposure ∝ 1/√E), so an evening
    /// or an overcast is darker and a dusk still dark, but neither white nor black. 1 under
    /// `REFERENCE_IRRADIANCE`.
    pub fn exposure(&self) -> f32 {
        let [r, g, b] = self.global_irradiance();
        let luminance = 0.2126 * r + 0.7152 * g + 0.0722 * b;
        let ratio = REFERENCE_IRRADIANCE / luminance.max(1e-6);
        let exposure = if ratio < 1.0 { ratio } else { ratio.sqrt() };
        exposure.clamp(0.1, 6.0) as f32
    }
}

/// The cloud cover without `--clouds` or `--preset` (a fair day's few clouds).
pub const DEFAULT_CLOUD_COVER: f64 = 0.3;

/// The irradiance (luminance) on the sea at which the exposure is 1: the default day's, sun
/// 11.7° up, 0.3 of the sky clouded (1.52 with the multiple scattering, 1.45 without;
/// `the_default_day_has_exposure_one`).
pub const REFERENCE_IRRADIANCE: f64 = 1.52;

/// The default day's global irradiance (`global_irradiance`), under which deep water looks
/// `WATER_COLOUR`.
pub fn reference_light() -> [f64; 3] {
    static LIGHT: std::sync::OnceLock<[f64; 3]> = std::sync::OnceLock::new();
    *LIGHT.get_or_init(|| {
        Sky {
            sun_dir: crate::render::default_sun_dir(),
            cloud_cover: DEFAULT_CLOUD_COVER as f32,
        }
        .global_irradiance()
    })
}

/// The radiance of the clear sky at the zenith for a sun of unit irradiance along `sun`:
/// scattered once and more often (src/render/multiple_scattering.rs), the twin of `clear_sky`
/// in shaders/common/sky.glsl.
pub fn clear_sky_zenith(sun: glam::DVec3) -> [f64; 3] {
    zenith(sun, true)
}

/// The exposure's factor for an eye `depth` m under the water (≤ 0: above it): the eye, and a
/// camera's automatic exposure, adapt to the daylight at their depth, fully, as a diver's eyes
/// do over the minutes of a dive: 1 over the luminance (Rec. 709 weights) that is left of a
/// grey daylight after `depth` m of each channel's absorption (`ABSORPTION_PER_M`; capped at
/// 30 m). At 8 m the red is gone and the green halved: 2.6.
pub fn underwater_adaptation(depth: f64) -> f32 {
    let d = depth.clamp(0.0, 30.0);
    let weights = [0.2126, 0.7152, 0.0722];
    let left: f64 = (0..3)
        .map(|c| weights[c] * (-f64::from(crate::shared::ABSORPTION_PER_M[c]) * d).exp())
        .sum();
    (1.0 / left) as f32
}

/// `clear_sky_zenith` scattered once only (tests weigh the higher orders against it).
#[cfg(test)]
pub fn clear_sky_zenith_once(sun: glam::DVec3) -> [f64; 3] {
    zenith(sun, false)
}

fn zenith(sun: glam::DVec3, multiple: bool) -> [f64; 3] {
    use crate::shared::{MIE_G, MIE_SCATTERING};
    let r = EARTH_RADIUS_M as f64 + SKY_EYE_ALTITUDE_M as f64;
    let len = ATMOSPHERE_TOP_M as f64 - r;
    let nu = sun.y;
    let pi = std::f64::consts::PI;
    let phase_r = 3.0 / (16.0 * pi) * (1.0 + nu * nu);
    let g = MIE_G as f64;
    let phase_m = 3.0 / (8.0 * pi) * (1.0 - g * g) * (1.0 + nu * nu)
        / ((2.0 + g * g) * (1.0 + g * g - 2.0 * g * nu).powf(1.5));
    const STEPS: usize = 200;
    let mut depth = [0.0; 3];
    let mut sum = [0.0; 3];
    for i in 0..STEPS {
        let (u0, u1) = (i as f64 / STEPS as f64, (i + 1) as f64 / STEPS as f64);
        let dt = len * (u1 * u1 - u0 * u0);
        let t = len * 0.5 * (u0 * u0 + u1 * u1);
        let h = r + t - EARTH_RADIUS_M as f64;
        let rho = [
            (-h / RAYLEIGH_SCALE_HEIGHT_M as f64).exp(),
            (-h / MIE_SCALE_HEIGHT_M as f64).exp(),
            (1.0 - (h - OZONE_PEAK_M as f64).abs() / OZONE_HALF_WIDTH_M as f64).max(0.0),
        ];
        // The sun seen from the sample: elevation from its zenith cosine there (the sample is
        // straight above the eye, so the local vertical is the eye's).
        let sun_t = sun_transmittance_from(h, sun.y.clamp(-1.0, 1.0).asin());
        let multiple = if multiple {
            crate::render::multiple_scattering::at(h, sun.y)
        } else {
            [0.0; 3]
        };
        for c in 0..3 {
            let ext = RAYLEIGH_SCATTERING[c] as f64 * rho[0]
                + MIE_EXTINCTION as f64 * rho[1]
                + OZONE_ABSORPTION[c] as f64 * rho[2];
            let seen = (-(depth[c] + 0.5 * ext * dt)).exp();
            let light = seen * sun_t[c];
            sum[c] += light
                * (RAYLEIGH_SCATTERING[c] as f64 * rho[0] * phase_r
                    + MIE_SCATTERING as f64 * rho[1] * phase_m)
                * dt;
            sum[c] += seen
                * (RAYLEIGH_SCATTERING[c] as f64 * rho[0] + MIE_SCATTERING as f64 * rho[1])
                * multiple[c]
                * dt;
            depth[c] += ext * dt;
        }
    }
    sum
}

/// Optical depths (Rayleigh scattering, aerosol extinction, ozone absorption, each per unit of
/// its coefficient: metres of sea-level air) from the eye toward elevation `elevation_rad`, or
/// `None` when the Earth is in the way.
fn optical_paths(altitude_m: f64, elevation_rad: f64) -> Option<[f64; 3]> {
    let (ground, top) = (EARTH_RADIUS_M as f64, ATMOSPHERE_TOP_M as f64);
    let r = ground + altitude_m;
    let mu = elevation_rad.sin();
    if mu < 0.0 && r * r * (mu * mu - 1.0) + ground * ground >= 0.0 {
        return None;
    }
    let len = -r * mu + (r * r * (mu * mu - 1.0) + top * top).sqrt();
    // Fine midpoint steps crowded toward the eye (t ∝ u²), where the air is dense.
    const STEPS: usize = 4000;
    let mut paths = [0.0; 3];
    for i in 0..STEPS {
        let (u0, u1) = (i as f64 / STEPS as f64, (i + 1) as f64 / STEPS as f64);
        let dt = len * (u1 * u1 - u0 * u0);
        let t = len * 0.5 * (u0 * u0 + u1 * u1);
        let h = (r * r + t * t + 2.0 * r * mu * t).sqrt() - ground;
        paths[0] += (-h / RAYLEIGH_SCALE_HEIGHT_M as f64).exp() * dt;
        paths[1] += (-h / MIE_SCALE_HEIGHT_M as f64).exp() * dt;
        let ozone = 1.0 - (h - OZONE_PEAK_M as f64).abs() / OZONE_HALF_WIDTH_M as f64;
        paths[2] += ozone.max(0.0) * dt;
    }
    Some(paths)
}

/// The share of the sun's light at 680, 550 and 440 nm that reaches the sea from elevation
/// `elevation_rad` (0 once the sun is below the horizon).
pub fn sun_transmittance(elevation_rad: f64) -> [f64; 3] {
    sun_transmittance_from(SKY_EYE_ALTITUDE_M as f64, elevation_rad)
}

/// `sun_transmittance` at `altitude_m` above the sea.
fn sun_transmittance_from(altitude_m: f64, elevation_rad: f64) -> [f64; 3] {
    let Some([rayleigh, mie, ozone]) = optical_paths(altitude_m, elevation_rad) else {
        return [0.0; 3];
    };
    std::array::from_fn(|c| {
        (-(RAYLEIGH_SCATTERING[c] as f64 * rayleigh
            + MIE_EXTINCTION as f64 * mie
            + OZONE_ABSORPTION[c] as f64 * ozone))
            .exp()
    })
}

/// The relative optical air mass toward elevation `elevation_rad`: the Rayleigh optical path
/// there over the path to the zenith.
pub fn relative_air_mass(elevation_rad: f64) -> f64 {
    let path = |e: f64| optical_paths(SKY_EYE_ALTITUDE_M as f64, e).map_or(f64::INFINITY, |p| p[0]);
    path(elevation_rad) / path(std::f64::consts::FRAC_PI_2)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Kasten & Young (1989)'s relative air mass, m = 1 / (sin γ + 0.50572 (γ + 6.07995°)^−1.6364),
    /// γ the elevation in degrees: fitted to the ISO standard atmosphere within 0.5 %.
    fn kasten_young(elevation_deg: f64) -> f64 {
        1.0 / (elevation_deg.to_radians().sin() + 0.50572 * (elevation_deg + 6.07995).powf(-1.6364))
    }

    #[test]
    fn air_mass_follows_kasten_and_young_down_to_five_degrees() {
        // An exponential atmosphere (8 km scale height) over a spherical Earth against the
        // standard atmosphere's fit: within 2 % from the zenith down to 5°; 4 % at 2°, where
        // the real atmosphere's refraction (which K&Y include) lengthens the path.
        for (elevation, tolerance) in [(90.0, 0.02), (30.0, 0.02), (10.0, 0.02), (5.0, 0.02)] {
            let ours = relative_air_mass(f64::to_radians(elevation));
            let theirs = kasten_young(elevation);
            assert!(
                (ours / theirs - 1.0).abs() < tolerance,
                "{elevation}°: {ours:.3} against Kasten & Young's {theirs:.3}"
            );
        }
    }

    #[test]
    fn the_default_day_has_exposure_one_brighter_days_adapt_fully_darker_ones_halfway() {
        let day = |elevation: f32, cloud_cover| {
            let e = elevation.to_radians();
            let sun_dir = Vec3::new(e.cos(), e.sin(), 0.0);
            Sky {
                sun_dir,
                cloud_cover,
            }
        };
        let luminance = |sky: &Sky| {
            let [r, g, b] = sky.global_irradiance();
            0.2126 * r + 0.7152 * g + 0.0722 * b
        };
        let reference = day(crate::render::default_sun_dir().y.asin().to_degrees(), 0.3);
        assert!(
            (reference.exposure() - 1.0).abs() < 0.02,
            "{}",
            reference.exposure()
        );
        // Noon is brighter, so exposed less, by the whole ratio of the light (to f32 rounding).
        let noon = day(60.0, 0.3);
        let full = (REFERENCE_IRRADIANCE / luminance(&noon)) as f32;
        assert!(
            full < 0.3,
            "noon's light is {:.1}× the default's",
            1.0 / full
        );
        assert!(
            (noon.exposure() / full - 1.0).abs() < 1e-5,
            "{}",
            noon.exposure()
        );
        // An overcast lets a quarter through (Kasten & Czeplak): exposed √4 = 2 times more.
        let overcast =
            day(11.7, 1.0).global_irradiance()[1] / day(11.7, 0.0).global_irradiance()[1];
        assert!((overcast - 0.25).abs() < 1e-9, "{overcast}");
        let dim = day(11.7, 1.0);
        let half = (REFERENCE_IRRADIANCE / luminance(&dim)).sqrt() as f32;
        assert!(half > 1.5, "{half}");
        assert!(
            (dim.exposure() / half - 1.0).abs() < 1e-5,
            "{}",
            dim.exposure()
        );
        assert_eq!(day(-8.0, 0.0).exposure(), 6.0);
    }

    #[test]
    fn the_low_sun_is_red_and_the_set_sun_gives_no_light() {
        let high = sun_transmittance(60f64.to_radians());
        let low = sun_transmittance(2f64.to_radians());
        // Blue is scattered out first: the low sun's red/blue ratio is far above the high one's.
        assert!(
            low[0] / low[2] > 4.0 * high[0] / high[2],
            "{low:?} vs {high:?}"
        );
        // Overhead the sea gets most of it (Rayleigh τ(550 nm) = 0.108 + aerosols + ozone).
        assert!(high[1] > 0.8 && high[1] < 0.9, "{high:?}");
        assert_eq!(sun_transmittance(-5f64.to_radians()), [0.0; 3]);
    }

    /// The zenith's radiance with the table (the CPU twin of the sky cube) over the same
    /// without it, for a sun `elevation_deg` up: the multiple scattering's share.
    fn zenith_gain(elevation_deg: f64) -> [f64; 3] {
        let e = elevation_deg.to_radians();
        let sun = glam::DVec3::new(e.cos(), e.sin(), 0.0);
        let all = clear_sky_zenith(sun);
        let once = clear_sky_zenith_once(sun);
        std::array::from_fn(|c| all[c] / once[c])
    }

    #[test]
    fn the_multiple_scattering_brightens_the_sky_and_lights_the_twilight() {
        // By day the higher orders add a part to the sky overhead, more in the blue, which
        // the air scatters most (measured at 60°: red +14 %, green +22 %, blue +40 %).
        let start = std::time::Instant::now();
        let noon = zenith_gain(60.0);
        eprintln!(
            "zenith with / without the multiple scattering: 60° {noon:?} (table and zenith in {:.3} s)",
            start.elapsed().as_secs_f64()
        );
        assert!(
            noon[0] > 1.05 && noon[2] > 1.2 && noon[2] < 1.6 && noon[2] > noon[1],
            "{noon:?}"
        );
        // With the sun 4° below the horizon the air overhead up to about 20 km is in the
        // Earth's shadow; light scattered again from the sunlit air above and toward the sun
        // lights it: a third more red, more than twice the blue (measured 1.34, 1.77, 2.37).
        let dusk = zenith_gain(-4.0);
        eprintln!("at -4°: {dusk:?}");
        assert!(dusk[0] > 1.25 && dusk[2] > 2.0, "{dusk:?}");
    }
}
