//! CPU-side pieces of the scene: the DU/DV map (generated, or loaded with `--dudv`) and the
//! terrain height (mirror of shaders/common/terrain.glsl, used to place cameras and in tests).

use std::path::Path;

use crate::input::{decode_png_rgba8, png_size, InputError};

use super::uniforms::{SceneLayout, WATER_LEVEL_M};
use crate::ocean::moments::SeaMoments;
use crate::ocean::shore::shore_waves;
use crate::ocean::surface::DisplacementScale;

/// Side of the generated DU/DV map (px).
pub const DUDV_SIDE: u32 = 256;

/// (kx, ky) whole periods per tile, amplitude, phase of the DU/DV map's waves.
const DUDV_WAVES: [(f32, f32, f32, f32); 6] = [
    (1.0, 2.0, 0.35, 0.3),
    (-3.0, 1.0, 0.25, 1.7),
    (2.0, -5.0, 0.18, 4.1),
    (7.0, 3.0, 0.10, 2.2),
    (-6.0, -9.0, 0.07, 5.3),
    (13.0, -4.0, 0.05, 0.9),
];

/// (du, dv) in [-1, 1] at tile coordinates (u, v): sums of sines with whole numbers of periods
/// per tile, so the map is periodic in u and v with period 1.
pub fn dudv_at(u: f32, v: f32) -> (f32, f32) {
    let tau = std::f32::consts::TAU;
    let total: f32 = DUDV_WAVES.iter().map(|w| w.2).sum();
    let (mut du, mut dv) = (0.0, 0.0);
    for (i, &(kx, ky, a, phase)) in DUDV_WAVES.iter().enumerate() {
        du += a * (tau * (kx * u + ky * v) + phase).sin();
        // dv: the same waves turned by 90 degrees, other phases.
        dv += a * (tau * (-ky * u + kx * v) + phase * 1.7 + i as f32).sin();
    }
    (du / total, dv / total)
}

/// A tileable DU/DV map (RGBA8: du in red, dv in green, 128 = no offset) sampled from
/// `dudv_at` (seed 001 §3.3, Fig. 4 shows such a map). Deterministic.
pub fn generate_dudv(side: u32) -> Vec<u8> {
    let byte = |s: f32| (128.0 + 127.0 * s.clamp(-1.0, 1.0)).round() as u8;
    let mut texels = Vec::with_capacity((side * side * 4) as usize);
    for y in 0..side {
        for x in 0..side {
            let (du, dv) = dudv_at(x as f32 / side as f32, y as f32 / side as f32);
            texels.extend_from_slice(&[byte(du), byte(dv), 128, 255]);
        }
    }
    texels
}

/// The size of `--dudv`'s PNG (read from its header), checked against the device's largest
/// 2D image before a byte of it is decoded.
pub fn dudv_size(path: &Path, max_side: u32) -> Result<(u32, u32), InputError> {
    let (w, h) = png_size("--dudv", path)?;
    if w > max_side || h > max_side {
        return Err(InputError(format!(
            "--dudv {}: {w}x{h} is larger than this device's largest 2D image ({max_side}x{max_side})",
            path.display()
        )));
    }
    Ok((w, h))
}

/// Decodes `--dudv`'s PNG (red = du, green = dv, 128 = no offset) as RGBA8 into `out`.
pub fn load_dudv(path: &Path, size: (u32, u32), out: &mut [u8]) -> Result<(), InputError> {
    decode_png_rgba8("--dudv", path, size, out)
}

/// Height of the island terrain at world (x, z) (m): `terrain_height` of
/// shaders/common/terrain.glsl.
pub fn terrain_height(layout: &SceneLayout, x: f32, z: f32) -> f32 {
    use crate::shared::{PEAK_M, SHELF_EDGE_R, SHELF_FOOT_R};
    let dx = (x - layout.island_xz[0]) / layout.island_radius_m;
    let dz = (z - layout.island_xz[1]) / layout.island_radius_m;
    let r2 = dx * dx + dz * dz;
    let island = (-r2 * 1.6).exp();
    // GLSL's smoothstep.
    let t = ((r2.sqrt() - SHELF_EDGE_R) / (SHELF_FOOT_R - SHELF_EDGE_R)).clamp(0.0, 1.0);
    let slope = t * t * (3.0 - 2.0 * t);
    let dot = |a: f32, b: f32| dx * a + dz * b;
    let n = 0.50 * (dot(3.1, 1.7) + 0.4).sin()
        + 0.25 * (dot(-4.3, 6.1) + 1.3).sin()
        + 0.12 * (dot(11.7, -7.9) + 2.1).sin()
        + 0.06 * (dot(-19.3, -23.1) + 0.7).sin();
    let shelf = layout.sea_floor_m;
    let depth = shelf + (layout.deep_floor_m - shelf) * slope;
    -depth + (shelf + PEAK_M) * island * (1.0 + 0.45 * n) + 1.5 * n * (1.0 - island) * (1.0 - slope)
}

/// The factor the water puts on the waves at a rest point (x, z) over the island's terrain
/// (`ocean::shore`, as shaders/surface/water.tese applies it): the buoy's height queries.
pub fn shore_scale(layout: SceneLayout, sea: SeaMoments) -> DisplacementScale {
    Box::new(move |x, z| {
        let depth = WATER_LEVEL_M - terrain_height(&layout, x as f32, z as f32);
        shore_waves(&sea, depth as f64).scale
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn dudv_tiles_without_seams_and_is_centred() {
        for i in 0..50 {
            let t = i as f32 / 50.0;
            for (a, b) in [
                (dudv_at(t, 0.0), dudv_at(t, 1.0)),
                (dudv_at(0.0, t), dudv_at(1.0, t)),
            ] {
                assert!((a.0 - b.0).abs() < 1e-4 && (a.1 - b.1).abs() < 1e-4);
            }
        }
        let side = 64;
        let t = generate_dudv(side);
        for c in 0..2 {
            let values: Vec<f64> = t.chunks(4).map(|p| p[c] as f64).collect();
            let mean = values.iter().sum::<f64>() / values.len() as f64;
            assert!((mean - 128.0).abs() < 4.0, "channel {c} mean {mean}");
            let (lo, hi) = values
                .iter()
                .fold((255.0f64, 0.0f64), |(lo, hi), &v| (lo.min(v), hi.max(v)));
            assert!(hi - lo > 100.0, "channel {c} range {lo}..{hi}");
        }
    }

    #[test]
    fn the_waves_die_on_the_beach_and_keep_their_height_at_sea() {
        let layout = SceneLayout::default();
        let sea = SeaMoments {
            hs_m: 2.5,
            mean_omega: 0.9,
            depth_m: crate::ocean::moments::DEEP_WATER_M,
            slope_variance: [0.0; 4],
            slope_anisotropy: [[0.0; 2]; 4],
            curvature_variance: [0.0; 4],
            short_slope_variance: [0.0; 4],
            slope_mip_gain: [[1.0; 4]; crate::ocean::moments::MIP_LEVELS],
        };
        let scale = shore_scale(layout, sea);
        let [x, z] = layout.island_xz;
        let r = layout.island_radius_m as f64;
        let (x, z) = (x as f64, z as f64);
        assert_eq!(scale(x, z), 0.0, "the island's peak");
        assert!((scale(x + 10.0 * r, z) - 1.0).abs() < 1e-3, "the open sea");
        // Along the shore: where the water is d deep the waves are at most 0.78·d / Hs.
        let mut shallow = 0;
        for i in 0..400 {
            let px = x + 0.8 * r + i as f64 * 0.002 * r;
            let depth = -terrain_height(&layout, px as f32, z as f32) as f64;
            if depth > 0.0 && depth < 2.0 {
                shallow += 1;
                assert!(scale(px, z) <= 0.78 * depth / 2.5 + 1e-6, "{depth} m deep");
            }
        }
        assert!(shallow > 5, "the line crosses the shallows");
    }

    #[test]
    fn island_rises_from_its_shelf_and_the_floor_falls_to_the_open_sea() {
        let layout = SceneLayout::default();
        let [x, z] = layout.island_xz;
        let r = layout.island_radius_m;
        assert!(terrain_height(&layout, x, z) > 20.0);
        // The shelf: --sea-floor deep, roughened by the ridges.
        let shelf = terrain_height(&layout, x + 1.7 * r, z);
        assert!((shelf + layout.sea_floor_m).abs() < 3.0, "shelf {shelf}");
        // Past the slope's foot, and to the horizon: the open sea's floor, flat.
        for d in [4.0, 10.0, 60.0] {
            let far = terrain_height(&layout, x + d * r, z + 0.3 * d * r);
            assert!(
                (far + layout.deep_floor_m).abs() < 1e-3,
                "floor {far} {d} radii out"
            );
        }
        // The slope in between goes down all the way.
        let depths: Vec<f32> = (0..12)
            .map(|i| terrain_height(&layout, x + (1.8 + 0.2 * i as f32) * r, z))
            .collect();
        assert!(depths.windows(2).all(|p| p[1] < p[0] + 1.0), "{depths:?}");
    }
}
