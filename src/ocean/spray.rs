//! Spray: the spume the wind tears off breaking crests, as GPU particles
//! (src/ocean/simulation/spray_sim.rs, shaders/ocean/spray.comp; drawn by
//! src/render/passes/spray.rs). Each particle is a puff of drops of one radius, flying
//! ballistically through the wind with drag until it falls back into the sea, where it leaves
//! foam. The constants and the drag law are here, with their sources; the kernel computes the
//! same `drag_rate` and `wind_at` per particle.

use super::foam::{drag_coefficient, AIR_DENSITY, WATER_DENSITY};

/// Standard gravity (m/s²).
pub const GRAVITY: f64 = 9.81;

/// Wind (U10, m/s) from which breaking crests make spray: the lower bound of Beaufort force 6
/// ("large waves begin to form; the white foam crests are more extensive everywhere; probably
/// some spray", WMO Manual on Codes, Beaufort scale). None below.
pub const MIN_WIND_M_S: f64 = 10.8;
/// Wind from which the emission is at its full rate: the lower bound of force 9 ("spray may
/// affect visibility"). Between the two the rate rises linearly (a choice).
pub const FULL_WIND_M_S: f64 = 20.8;

/// Puffs born per second per square metre of fully breaking crest at full rate (a choice, for
/// the look: a storm keeps a few thousand puffs in the air near the camera).
pub const EMIT_PER_M2_S: f64 = 2.0;
/// Spacing of the emission grid's candidate points (m): `SPRAY_EMIT_GRID` of them a side
/// around the camera, 256 m.
pub const EMIT_SPACING_M: f64 = 2.0;

/// Radii of the drops a puff stands for (m), drawn log-uniformly: spume drops, torn off the
/// crests by the wind, have radii from about 20 µm to 500 µm (Andreas 1992, J. Phys.
/// Oceanogr. 22; Andreas et al. 1995); the small ones stay in the air, the large ones fall
/// back within a second.
pub const DROP_RADIUS_M: [f64; 2] = [30e-6, 300e-6];
/// The drops' speed when they leave the crest (m/s): downwind at the speed of the water in a
/// breaking crest (about the phase speed of the short waves that break, 2.5 m/s for 4 m ones),
/// up at 1–3 m/s (choices: the wind takes over within a fraction of a second).
pub const LAUNCH_DOWNWIND_M_S: f64 = 2.5;
pub const LAUNCH_UP_M_S: [f64; 2] = [1.0, 3.0];

/// Dynamic viscosity of air at 15 °C (Pa·s; ISA sea level, 1.789·10⁻⁵).
pub const AIR_VISCOSITY: f64 = 1.789e-5;
/// von Kármán's constant.
pub const VON_KARMAN: f64 = 0.40;
/// Charnock's constant: the sea's aerodynamic roughness z0 = α·u*²/g, α = 0.011 (Smith 1988,
/// J. Geophys. Res. 93).
pub const CHARNOCK: f64 = 0.011;

/// How much of the foam's residual field a landing puff adds where it falls (0–1; a choice).
pub const LANDING_FOAM: f64 = 0.35;

/// The air a drop flies through: its density and viscosity.
#[derive(Clone, Copy, Debug)]
pub struct Air {
    pub density: f64,
    pub viscosity: f64,
}

/// The air over the sea.
pub const SEA_AIR: Air = Air {
    density: AIR_DENSITY,
    viscosity: AIR_VISCOSITY,
};

/// The drag coefficient of a sphere at Reynolds number `re` (Schiller & Naumann 1933):
/// C_D = 24/Re·(1 + 0.15·Re^0.687), within a few per cent of measurements up to Re ≈ 800.
pub fn sphere_drag(re: f64) -> f64 {
    24.0 / re.max(1e-9) * (1.0 + 0.15 * re.max(0.0).powf(0.687))
}

/// The drag deceleration rate k (1/s) of a drop of radius `r` (m) and density `rho_w` moving
/// at `speed` (m/s) through `air`: dv/dt = g − k·v_rel, k = 3ρ_a·C_D·|v_rel| / (8ρ_w·r) (drag
/// ½ρ_a·C_D·πr²·|v|v over the mass 4/3·πr³·ρ_w). In the Stokes limit k = 9μ/(2ρ_w·r²).
/// Computed as that Stokes rate times Schiller & Naumann's correction (1 + 0.15·Re^0.687), the
/// same product with the speed cancelled out, finite at any speed (as the kernel computes it).
pub fn drag_rate(r: f64, rho_w: f64, speed: f64, air: Air) -> f64 {
    let re = 2.0 * r * speed * air.density / air.viscosity;
    9.0 * air.viscosity / (2.0 * rho_w * r * r) * (1.0 + 0.15 * re.powf(0.687))
}

/// The fall speed (m/s) at which drag balances gravity, for a drop of radius `r` (m) and
/// density `rho_w` in `air` (fixed-point iteration on v = g / k(v)).
pub fn terminal_velocity(r: f64, rho_w: f64, air: Air) -> f64 {
    let mut v = 1.0;
    for _ in 0..200 {
        v = GRAVITY / drag_rate(r, rho_w, v, air);
    }
    v
}

/// The sea's roughness length z0 (m) at wind `u10`: Charnock's law with the friction velocity
/// u* = √C_D·U10 of Large & Pond's drag (`foam::drag_coefficient`), at least
/// `MIN_ROUGHNESS_M` (so that a calm keeps the profile finite).
pub fn roughness_m(u10: f64) -> f64 {
    let u_star = drag_coefficient(u10).sqrt() * u10;
    (CHARNOCK * u_star * u_star / GRAVITY).max(MIN_ROUGHNESS_M)
}

/// The least roughness length (m): about a smooth surface's 0.11·ν/u* at u* = 0.1 m/s (ν of
/// air 1.5·10⁻⁵ m²/s); Charnock's z0 passes it at a U10 of about 3.5 m/s, far below where
/// spray starts.
pub const MIN_ROUGHNESS_M: f64 = 1.6e-5;

/// The longest step the spray integrates at once (s): a stalled frame (a window dragged, a
/// debugger) moves the puffs by this much, not by the whole pause.
pub const MAX_STEP_S: f32 = 0.1;

/// The wind (m/s) at height `z_m` above the water: the logarithmic profile u(z) =
/// (u*/κ)·ln(z/z0), scaled so that u(10 m) = U10 (it then holds for the drag the profile
/// came from, C_D = (κ / ln(10/z0))²). Below 10·z0 the profile's value there.
pub fn wind_at(u10: f64, z_m: f64) -> f64 {
    let z0 = roughness_m(u10);
    u10 * (z_m.max(10.0 * z0) / z0).ln() / (10.0 / z0).ln()
}

/// Share of the full emission rate at wind `u10` (0 below Beaufort 6, 1 from force 9).
pub fn intensity(u10: f64) -> f64 {
    ((u10 - MIN_WIND_M_S) / (FULL_WIND_M_S - MIN_WIND_M_S)).clamp(0.0, 1.0)
}

/// Sea water's density (kg/m³), for the kernel.
pub const DROP_DENSITY: f64 = WATER_DENSITY;

#[cfg(test)]
mod tests {
    use super::*;

    /// Gunn & Kinzer (1949, J. Meteor. 6, table 2): terminal velocities of distilled-water drops
    /// in still air at 20 °C and 1013 hPa, by diameter: 0.2 mm 0.72 m/s, 0.3 mm 1.17 m/s,
    /// 0.5 mm 2.06 m/s, 1.0 mm 4.03 m/s. Schiller & Naumann's drag gives them within 3 % up to
    /// 0.5 mm (Re < 70) and 5 % at 1 mm (Re ≈ 260).
    #[test]
    fn drops_fall_at_gunn_and_kinzers_speeds() {
        let lab = Air {
            density: 1.204,
            viscosity: 1.81e-5,
        };
        for (diameter_mm, measured, tolerance) in [
            (0.2, 0.72, 0.03),
            (0.3, 1.17, 0.03),
            (0.5, 2.06, 0.03),
            (1.0, 4.03, 0.05),
        ] {
            let v = terminal_velocity(diameter_mm * 0.5e-3, 998.2, lab);
            let error = v / measured - 1.0;
            assert!(
                error.abs() < tolerance,
                "{diameter_mm} mm: {v:.3} m/s against {measured} ({:+.1} %)",
                100.0 * error
            );
        }
    }

    /// The Stokes limit: a 20 µm drop falls at 2ρ_w·g·r²/(9μ) (Re ≪ 1), within 2 %.
    #[test]
    fn small_drops_fall_at_stokes_speed() {
        let r = 10e-6;
        let stokes = 2.0 * DROP_DENSITY * GRAVITY * r * r / (9.0 * AIR_VISCOSITY);
        let v = terminal_velocity(r, DROP_DENSITY, SEA_AIR);
        assert!((v / stokes - 1.0).abs() < 0.02, "{v} against {stokes}");
    }

    /// The profile gives U10 at 10 m, less below, and its drag matches Large & Pond's to 10 %:
    /// (κ / ln(10/z0))² against C_D at 15 and 25 m/s.
    #[test]
    fn the_wind_profile_meets_u10_at_ten_metres() {
        for u10 in [12.0, 15.0, 26.5] {
            assert!((wind_at(u10, 10.0) - u10).abs() < 1e-9);
            assert!(wind_at(u10, 1.0) < 0.85 * u10);
            assert!(wind_at(u10, 0.1) < wind_at(u10, 1.0));
        }
        for u10 in [15.0, 25.0] {
            let z0 = roughness_m(u10);
            let profile = (VON_KARMAN / (10.0 / z0).ln()).powi(2);
            let large_pond = drag_coefficient(u10);
            assert!(
                (profile / large_pond - 1.0).abs() < 0.1,
                "{u10} m/s: profile C_D {profile:.2e} against {large_pond:.2e}"
            );
        }
    }

    /// A calm keeps the wind profile finite (zero everywhere), and the floor on z0 leaves
    /// Charnock's value alone where spray flies (U10 from 10.8 m/s).
    #[test]
    fn the_profile_is_finite_in_a_calm() {
        assert_eq!(wind_at(0.0, 1.0), 0.0);
        assert!(wind_at(0.5, 0.01).is_finite());
        let u_star = drag_coefficient(MIN_WIND_M_S).sqrt() * MIN_WIND_M_S;
        assert!(roughness_m(MIN_WIND_M_S) > 5.0 * MIN_ROUGHNESS_M);
        assert_eq!(
            roughness_m(MIN_WIND_M_S),
            CHARNOCK * u_star * u_star / GRAVITY
        );
    }

    #[test]
    fn spray_starts_at_beaufort_6_and_is_full_at_9() {
        assert_eq!(intensity(3.0), 0.0);
        assert_eq!(intensity(10.7), 0.0);
        assert!(intensity(12.3) > 0.1 && intensity(12.3) < 0.2);
        assert_eq!(intensity(26.5), 1.0);
    }
}
