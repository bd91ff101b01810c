//! The far sea (issue 34): grazing views that do not alias (the slopes filtered along and
//! across the view by the pixel's footprint in each direction, shaders/surface/water.frag),
//! and the broken clouds' shadows on the sea where the sky's layer casts them
//! (shaders/common/clouds.glsl). Headless on lavapipe, validation-clean.

mod common;

use common::linear_luminance;
use glam::Vec3;
use vkocean::render::{clouds, Camera};

/// Back to an sRGB-encoded grey level (0..255) from a linear luminance.
fn encoded(l: f64) -> f64 {
    255.0
        * if l <= 0.0031308 {
            12.92 * l
        } else {
            1.055 * l.powf(1.0 / 2.4) - 0.055
        }
}

/// Mean of |I(x, y) − (I(x, y − 1) + I(x, y + 1)) / 2| over `rows` of a `w`-wide picture of
/// grey levels, leaving out the edge columns: the detail one pixel high, where a sea seen at a
/// grazing angle aliases (its waves along the view squeezed into few rows).
fn vertical_detail(g: &[f64], w: usize, rows: std::ops::Range<usize>) -> f64 {
    let mut sum = 0.0;
    let mut n = 0.0;
    for y in rows {
        for x in 1..w - 1 {
            let i = y * w + x;
            sum += (g[i] - 0.5 * (g[i - w] + g[i + w])).abs();
            n += 1.0;
        }
    }
    sum / n
}

/// The first row from the top whose mean grey level falls below 0.85 of the row above it:
/// where the sky meets the sea.
fn horizon_row(g: &[f64], w: usize, h: usize) -> usize {
    let row = |y: usize| g[y * w..(y + 1) * w].iter().sum::<f64>() / w as f64;
    (h / 4..h)
        .find(|&y| row(y) < 0.85 * row(y - 1))
        .expect("a horizon")
}

#[test]
fn a_grazing_view_away_from_the_sun_holds_no_more_detail_than_a_supersampled_one() {
    // A moderate sea from 3 m, looking away from the sun at the water 400 m out, at
    // `--quality high` without anti-aliasing: drawn at 320x180, and at 1280x720 averaged in
    // 4x4 blocks (in linear light) to 320x180, the reference each pixel should approach. Seen
    // this low, a pixel's footprint on the water is up to 100 times longer along the view
    // than across it; slopes filtered by one footprint for both directions (their geometric
    // mean, before) were too fine along the view for the pixels to hold, and the sea from
    // about 30 m out to the horizon broke into one-pixel filaments: 1.37x the reference's detail one pixel high
    // there (measured on the build before). Filtered by the footprint in each direction: 1.03x;
    // by the normal images' mip levels at that footprint (SLOPE_MIPS): 1.04x.
    let (w, h) = (320usize, 180usize);
    let args = [
        "--quality",
        "high",
        "--aa",
        "off",
        "--camera",
        "0,3,0",
        "--look-at",
        "0,-2,400",
        "--time",
        "3",
    ];
    let small = linear_luminance(&common::shot(
        "far-grazing-1x",
        (w as u32, h as u32),
        &args,
        &[],
    ));
    let big = linear_luminance(&common::shot(
        "far-grazing-4x",
        (4 * w as u32, 4 * h as u32),
        &args,
        &[],
    ));
    let small: Vec<f64> = small.into_iter().map(encoded).collect();
    let reference: Vec<f64> = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let sum: f64 = (0..16)
                .map(|k| big[(4 * y + k / 4) * 4 * w + 4 * x + k % 4])
                .sum();
            encoded(sum / 16.0)
        })
        .collect();
    // The horizon found in the picture drawn at 320x180 (the averaged one's may fall a row
    // apart); rows 1-14 below it: the water from about 30 m out to the horizon.
    let horizon = horizon_row(&small, w, h);
    let far = horizon + 1..horizon + 15;
    let ratio = vertical_detail(&small, w, far.clone()) / vertical_detail(&reference, w, far);
    println!("detail one pixel high, 30 m to the horizon: {ratio:.2}x the supersampled picture's");
    assert!(
        ratio <= 1.25,
        "the far sea aliases: {ratio:.2}x the supersampled picture's one-pixel detail"
    );
    assert!(
        ratio >= 0.75,
        "the far sea is blurred: {ratio:.2}x the supersampled picture's one-pixel detail"
    );
    // Rows 17-48 below it: the water 10-30 m out, where a pixel is 3-10 times longer along the
    // view than across it. Filtering a cascade by fading its slopes out as a whole once the
    // footprint passed its shortest waves took its longer waves with them: 0.63x the
    // reference's detail there (0.44x at 12-16 m), the build before the normal images' mip
    // levels. Each cascade looked up at the level of the footprint along the view and across
    // it (water.frag's SLOPE_MIPS): 0.93x.
    let near = horizon + 17..horizon + 49;
    let ratio = vertical_detail(&small, w, near.clone()) / vertical_detail(&reference, w, near);
    println!("detail one pixel high, 10-30 m out: {ratio:.2}x the supersampled picture's");
    assert!(
        (0.8..=1.25).contains(&ratio),
        "the sea 10-30 m out holds {ratio:.2}x the supersampled picture's one-pixel detail \
         (0.8-1.25 asked)"
    );
}

#[test]
fn the_clouds_shadows_take_the_sun_off_the_sea_where_the_sky_casts_them() {
    // The default sun (11.7 deg up), a sky 0.6 clouded, from 20 m at a point 750 m south of
    // the origin, looking along the sun's path on the water: src/render/clouds.rs (the
    // layer's CPU twin) puts the path's first 200 m in the sun and its last kilometres under
    // a cloud. The same view under a clear sky is the reference: pixel by pixel, what the
    // clouds change is the sky's and the exposure's (about the same for every pixel) and,
    // under a cloud, the sun's light on the water. So the shaded pixels' share of their clear
    // light over the lit pixels' share must fall well below 1. Measured: 0.83 (the lit path
    // keeps 101 % of its clear light, the shaded 85 %); with one sun for the whole sea (the
    // cube's alpha toward the sun from the origin, the build before) 1.20.
    let (w, h) = (640usize, 360usize);
    let sun = vkocean::render::default_sun_dir().normalize();
    let eye = Vec3::new(0.0, 20.0, 750.0);
    let flat = Vec3::new(sun.x, 0.0, sun.z).normalize();
    let target = eye + flat * 100.0 - Vec3::new(0.0, 10.0, 0.0);
    let camera = format!("{},{},{}", eye.x, eye.y, eye.z);
    let look = format!("{},{},{}", target.x, target.y, target.z);
    let shot = |name: &str, clouds: &str| {
        let args = [
            "--clouds",
            clouds,
            "--camera",
            &camera,
            "--look-at",
            &look,
            "--time",
            "3",
        ];
        linear_luminance(&common::shot(name, (w as u32, h as u32), &args, &[]))
    };
    let clouded = shot("far-clouds", "0.6");
    let clear = shot("far-clear", "0");
    let view = Camera::looking_at(eye, target).expect("a camera");
    // The sun's path: the middle 60 columns. Pixels whose water the twin puts in the sun
    // (> 0.9 of it through) and in shadow (< 0.2).
    let (mut lit, mut shaded) = ([0.0f64; 2], [0.0f64; 2]);
    let (mut n_lit, mut n_shaded) = (0, 0);
    for y in 0..h {
        for x in w / 2 - 30..w / 2 + 30 {
            let Some([px, pz]) = view.pixel_water_point((x, y), (w, h), 20e3) else {
                continue;
            };
            let t = clouds::through(Vec3::new(px, 0.0, pz), sun, 0.6);
            let i = y * w + x;
            if t > 0.9 {
                lit[0] += clouded[i];
                lit[1] += clear[i];
                n_lit += 1;
            } else if t < 0.2 {
                shaded[0] += clouded[i];
                shaded[1] += clear[i];
                n_shaded += 1;
            }
        }
    }
    assert!(
        n_lit >= 2000 && n_shaded >= 300,
        "the view holds both: {n_lit} lit and {n_shaded} shaded pixels of the path"
    );
    let (lit_share, shaded_share) = (lit[0] / lit[1], shaded[0] / shaded[1]);
    let ratio = shaded_share / lit_share;
    println!(
        "the sun's path under the clouds keeps {:.1} % of its clear light where it is lit \
         ({n_lit} px), {:.1} % in a cloud's shadow ({n_shaded} px): {ratio:.2}",
        100.0 * lit_share,
        100.0 * shaded_share
    );
    assert!(
        ratio <= 0.9,
        "the cloud's shadow keeps {ratio:.2} of the lit path's share of its clear light"
    );
}
