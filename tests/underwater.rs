//! Caustics (issue 34; shaders/common/caustics.glsl): from 8 m under the calm sea over the
//! island's shelf, looking straight down at the sand 10 m below, the sun focused by the
//! simulated waves draws a network of bright lines on the floor that moves with the waves, and
//! an overcast (no sun) draws none.
//!
//! Measured on lavapipe (640x360, --quality low): luma high-pass std (the picture less its
//! 15 px box mean) 11.4 in the sun, 0.11 under the overcast; mean luma change over 0.1 s 15.7;
//! the floor's mean luma 48.5. The mean light with the caustics over the same build without
//! them (`--caustics off`; linear luma): 0.96 at low, 1.20 at high (README, "Caustics").

mod common;

use common::{linear, luma, shot};

const W: usize = 640;
const H: usize = 360;
/// 8 m under the surface, 1.5 island radii out on the shelf (18 m deep, away from the
/// objects), looking straight down.
const SCENE: [&str; 4] = [
    "--preset",
    "calm",
    "--camera=-102,-8,-582",
    "--look-at=-102,-18,-581.99",
];

/// The floor's RGBA pixels at `time` (s) with `extra` arguments (`tag`: the test's, for its
/// scratch directory).
fn floor_rgba(tag: &str, time: &str, extra: &[&str]) -> Vec<u8> {
    let mut args = vec!["--time", time];
    args.extend_from_slice(&SCENE);
    args.extend_from_slice(extra);
    shot(
        &format!("underwater-{tag}-{time}-{}", extra.join("")),
        (W as u32, H as u32),
        &args,
        &[],
    )
}

/// The floor's luma at `time` (s) with `extra` arguments.
fn floor(time: &str, extra: &[&str]) -> Vec<f64> {
    luma(&floor_rgba("pattern", time, extra))
}

/// Mean linear luminance (Rec. 709 weights on the linear channels).
fn linear_luma(rgba: &[u8]) -> f64 {
    rgba.chunks(4)
        .map(|p| 0.2126 * linear(p[0]) + 0.7152 * linear(p[1]) + 0.0722 * linear(p[2]))
        .sum::<f64>()
        / (rgba.len() / 4) as f64
}

/// Standard deviation of `v` less its mean over the (2r + 1)² box around each pixel (the box
/// clamped at the picture's edges), over the pixels at least r from an edge.
fn high_pass_std(v: &[f64], r: usize) -> f64 {
    let mut residual = Vec::new();
    for y in r..H - r {
        for x in r..W - r {
            let mut sum = 0.0;
            for yy in y - r..=y + r {
                sum += v[yy * W + x - r..=yy * W + x + r].iter().sum::<f64>();
            }
            let n = ((2 * r + 1) * (2 * r + 1)) as f64;
            residual.push(v[y * W + x] - sum / n);
        }
    }
    common::std_dev(&residual)
}

#[test]
fn the_sun_draws_moving_caustics_on_the_shelf_floor_and_an_overcast_none() {
    let now = floor("5", &[]);
    let later = floor("5.1", &[]);
    let overcast = floor("5", &["--clouds", "1"]);
    let mean = now.iter().sum::<f64>() / now.len() as f64;
    let (sun, grey) = (high_pass_std(&now, 7), high_pass_std(&overcast, 7));
    let moved = now
        .iter()
        .zip(&later)
        .map(|(a, b)| (a - b).abs())
        .sum::<f64>()
        / now.len() as f64;
    eprintln!("floor luma {mean:.1}; high-pass std {sun:.2} (overcast {grey:.2}); change over 0.1 s {moved:.2}");
    // The bounds: std >= 4 grey levels, change >= 2.
    assert!(sun >= 4.0, "the caustics' high-pass std {sun:.2} < 4");
    assert!(
        moved >= 2.0,
        "the caustics moved {moved:.2} < 2 levels in 0.1 s"
    );
    // The pattern is the sun's: without it the sand is even (no texture of its own).
    assert!(grey < 1.0, "an overcast floor's high-pass std {grey:.2}");
    // The floor is seen, not lost in the water between.
    assert!(mean >= 35.0, "the floor's mean luma {mean:.1}");
}

/// The caustics move the sun's light on the floor; they do not add to it: the mean linear
/// luminance with them is within 10 % of the same picture's with `--caustics off` (measured
/// 0.96). Without the division by the area ratio's mean (common/caustics.glsl) it was 1.97.
#[test]
fn the_caustics_move_the_light_and_do_not_make_it() {
    let on = linear_luma(&floor_rgba("light", "5", &[]));
    let off = linear_luma(&floor_rgba("light", "5", &["--caustics", "off"]));
    eprintln!(
        "mean linear luma with the caustics {on:.4}, without {off:.4}: {:.3}",
        on / off
    );
    assert!(
        (on / off - 1.0).abs() <= 0.1,
        "with/without {:.3}",
        on / off
    );
}
