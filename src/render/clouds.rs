//! The broken clouds' layer on the CPU: a twin of shaders/common/clouds.glsl in f32, as the GPU
//! evaluates it. The frame uniforms take the share of the sun the layer lets through on average
//! over the sea (`mean_through`: the water's own light is the sea's mean irradiance scaled by
//! a point's share over it), and the tests find where its shadows fall (`through`).

use glam::Vec3;

use crate::shared::{CLOUD_BASE_M, CLOUD_SCALE_M};

fn fract(x: f32) -> f32 {
    x - x.floor()
}

fn smoothstep(e0: f32, e1: f32, x: f32) -> f32 {
    let t = ((x - e0) / (e1 - e0)).clamp(0.0, 1.0);
    t * t * (3.0 - 2.0 * t)
}

/// `sky_hash`: a value in [0, 1) per lattice point.
fn hash(px: f32, py: f32) -> f32 {
    let q = [fract(px * 0.1031), fract(py * 0.1031), fract(px * 0.1031)];
    let d = q[0] * (q[1] + 33.33) + q[1] * (q[2] + 33.33) + q[2] * (q[0] + 33.33);
    let q = q.map(|v| v + d);
    fract((q[0] + q[1]) * q[2])
}

/// `sky_noise`: value noise in [0, 1].
fn noise(x: f32, y: f32) -> f32 {
    let (ix, iy) = (x.floor(), y.floor());
    let (fx, fy) = (x - ix, y - iy);
    let (ux, uy) = (fx * fx * (3.0 - 2.0 * fx), fy * fy * (3.0 - 2.0 * fy));
    let mix = |a: f32, b: f32, t: f32| a + (b - a) * t;
    mix(
        mix(hash(ix, iy), hash(ix + 1.0, iy), ux),
        mix(hash(ix, iy + 1.0), hash(ix + 1.0, iy + 1.0), ux),
        uy,
    )
}

/// `cloud_shape`: the noise's fractal sum (5 octaves) at (x, y) in cells.
pub fn shape(mut x: f32, mut y: f32) -> f32 {
    let (mut sum, mut amplitude) = (0.0, 0.5);
    for _ in 0..5 {
        sum += amplitude * noise(x, y);
        (x, y) = (1.6 * x - 1.2 * y + 7.3, 1.2 * x + 1.6 * y + 7.3);
        amplitude *= 0.5;
    }
    sum / 0.96875
}

/// `wind_shape`: the noise in a space stretched along the wind (its unit vector `wind`, x and
/// z): cells `cells_m` (m) along it and across it, carried `drift` cells downwind, at `offset`
/// (cells) from the clouds' place in it, at the world point (`x`, `z`) (m).
pub fn wind_shape(
    (x, z): (f32, f32),
    [wx, wz]: [f32; 2],
    cells_m: [f32; 2],
    drift: f32,
    offset: [f32; 2],
) -> f32 {
    let along = (x * wx + z * wz) / cells_m[0] - drift;
    let across = (-x * wz + z * wx) / cells_m[1];
    shape(along + offset[0], across + offset[1])
}

/// `cloud_alpha`: the share of the light the layer stops at its point (`x`, `z`) (world, m),
/// on a ray that travelled `dist` m to it, `cover` of the sky clouded.
pub fn alpha(x: f32, z: f32, dist: f32, cover: f32) -> f32 {
    let s = shape(x / CLOUD_SCALE_M, z / CLOUD_SCALE_M);
    let local = smoothstep(1.0 - cover, 1.3 - cover, s);
    let far = smoothstep(15e3, 60e3, dist);
    (local + (cover - local) * far) * (cover * 8.0).min(1.0)
}

/// `cloud_through`: the share of the sun's light (toward the unit vector `sun`) the clouds let
/// through to the world point `p` (m).
pub fn through(p: Vec3, sun: Vec3, cover: f32) -> f32 {
    let dist = (CLOUD_BASE_M - p.y).max(0.0) / sun.y.max(1e-3);
    let a = alpha(p.x + sun.x * dist, p.z + sun.z * dist, dist, cover);
    (1.0 - a) * (1.0 - smoothstep(0.85, 1.0, cover))
}

/// The share of the sun's light the layer lets through to the sea on average: `through` at
/// the sea's level over a 64x64 lattice about 200 km square (a point every 1.26 of the
/// noise's first cells, each at a different place in its cell).
pub fn mean_through(sun: Vec3, cover: f32) -> f32 {
    const SIDE: usize = 64;
    let step = 2.5 * CLOUD_SCALE_M / 2.0 + 37.0;
    let sum: f32 = (0..SIDE * SIDE)
        .map(|i| {
            let (x, z) = ((i % SIDE) as f32 * step, (i / SIDE) as f32 * step);
            through(Vec3::new(x, 0.0, z), sun, cover)
        })
        .sum();
    sum / (SIDE * SIDE) as f32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_layer_s_mean_share_falls_with_the_cover_and_is_none_under_an_overcast() {
        let sun = Vec3::new(0.33, 0.2, -0.92).normalize();
        let shares: Vec<f32> = [0.0, 0.3, 0.5, 0.6, 0.8, 1.0]
            .iter()
            .map(|&c| mean_through(sun, c))
            .collect();
        println!("mean through-share at cover 0, 0.3, 0.5, 0.6, 0.8, 1: {shares:.3?}");
        assert_eq!(shares[0], 1.0, "a clear sky");
        assert!(shares.windows(2).all(|w| w[1] <= w[0]), "{shares:?}");
        assert!(shares[3] < 0.8 && shares[3] > 0.4, "{shares:?}");
        assert_eq!(shares[5], 0.0, "an overcast");
    }
}
