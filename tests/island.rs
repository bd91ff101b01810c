//! The island's surface (issue 34; shaders/common/terrain_material.glsl): not an untextured
//! green hill. From 40 m up off its eastern shore, looking at its flank and summit
//! (640x360, `--quality low`): the flank has detail (grass in clumps and patches, a 15 px
//! high-pass std of the luma ≥ 1.2 grey levels; measured 2.16, the untextured hill 0.58) and
//! stays mostly grass (≥ 40 % of its pixels green: measured 0.53), the summit is rock (mean
//! saturation ≤ 0.35: measured 0.29; grass there was 0.47). Seen from the sun's side, a
//! pillar's concrete is dark with algae just above the waterline (the band's mean luma ≤ 0.7
//! of the concrete 3–8 m up: measured 0.58; plain grey before, 1.00).

mod common;

use common::{luma, shot};

const W: usize = 640;
const H: usize = 360;

/// The view of the island from `camera` toward `look_at` (x,y,z strings): RGBA.
fn view(tag: &str, camera: &str, look_at: &str) -> Vec<u8> {
    let camera = format!("--camera={camera}");
    let look = format!("--look-at={look_at}");
    shot(
        &format!("island-{tag}"),
        (W as u32, H as u32),
        &["--time", "5", &camera, &look],
        &[],
    )
}

/// The pixels (RGB) of `rgba` in rows `rows` and columns `cols`.
fn region(
    rgba: &[u8],
    rows: std::ops::Range<usize>,
    cols: std::ops::Range<usize>,
) -> Vec<[f64; 3]> {
    rows.flat_map(|y| cols.clone().map(move |x| (y, x)))
        .map(|(y, x)| {
            let p = &rgba[(y * W + x) * 4..];
            [0, 1, 2].map(|c| f64::from(p[c]))
        })
        .collect()
}

/// Standard deviation of `v` (rows `rows` of a W-wide picture) less its mean over the 15x15
/// box around each pixel, over the pixels at least 7 from the band's edges.
fn high_pass_std(v: &[f64], rows: std::ops::Range<usize>) -> f64 {
    let r = 7;
    let mut residual = Vec::new();
    for y in rows.start + r..rows.end - r {
        for x in r..W - r {
            let sum: f64 = (y - r..=y + r)
                .map(|yy| v[yy * W + x - r..=yy * W + x + r].iter().sum::<f64>())
                .sum();
            residual.push(v[y * W + x] - sum / 225.0);
        }
    }
    common::std_dev(&residual)
}

#[test]
fn the_island_has_grass_in_clumps_and_a_rocky_summit() {
    let rgba = view("flank", "-170,40,-750", "-380,15,-880");
    let detail = high_pass_std(&luma(&rgba), 200..H);
    let flank = region(&rgba, 250..H, 0..W);
    let green = flank
        .iter()
        .filter(|[r, g, b]| *g > 1.1 * r && *g > 1.1 * b)
        .count() as f64
        / flank.len() as f64;
    let summit = region(&rgba, 115..150, 220..420);
    let saturation = summit
        .iter()
        .map(|p| {
            let (hi, lo) = (
                p.iter().cloned().fold(0.0, f64::max),
                p.iter().cloned().fold(255.0, f64::min),
            );
            (hi - lo) / hi.max(1.0)
        })
        .sum::<f64>()
        / summit.len() as f64;
    eprintln!("the flank: high-pass std {detail:.2}, green {green:.2}; the summit: saturation {saturation:.2}");
    assert!(
        detail >= 1.2,
        "the flank is untextured: high-pass std {detail:.2}"
    );
    assert!(green >= 0.4, "the flank is not grass: {green:.2} green");
    assert!(
        saturation <= 0.35,
        "the summit is not rock: saturation {saturation:.2}"
    );
}

#[test]
fn a_pillar_wears_algae_at_the_waterline() {
    // Pillar 1 (`SceneLayout::objects`: 6 m across) from 25 m on the sun's side (the default
    // sun, azimuth −70.7°), level with its foot.
    let rgba = view("pillar", "-126.7,5,-758.5", "-135,4,-735");
    let l = luma(&rgba);
    let band_mean = |rows: std::ops::Range<usize>| {
        let n = rows.len() * 80;
        rows.map(|y| l[y * W + 280..y * W + 360].iter().sum::<f64>())
            .sum::<f64>()
            / n as f64
    };
    // Rows 232–242: just above the waterline (row 245); 150–200: 3–8 m above it.
    let (algae, concrete) = (band_mean(232..242), band_mean(150..200));
    eprintln!("the pillar: {algae:.1} above the waterline, {concrete:.1} higher up");
    assert!(
        algae <= 0.7 * concrete,
        "no stain at the waterline: {algae:.1} against {concrete:.1}"
    );
}
