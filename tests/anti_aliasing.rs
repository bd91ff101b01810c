//! The anti-aliasing pass (`--aa`), headless on lavapipe: FXAA turns the stair steps of a
//! high-contrast silhouette into blended pixels and leaves flat regions as they were; it runs
//! validation-clean scaled, copied and into a UNORM output, only where it should (`--profile`);
//! and the config file's `aa` is the flag.

mod common;

use common::{luma, scratch};
use vkocean::pass_names::{ANTI_ALIASING, FFT_FRAME, OUTPUT, SPRAY};

const W: usize = 320;
const H: usize = 180;

/// Looking up at the island from its shore at `--quality high`, the main view's sky painted
/// solid magenta (`--background`), at `--render-scale 1` (no scaling blit to blend pixels of
/// its own): green hills, grey pillars and the sea against a colour found nowhere else.
const SILHOUETTE: [&str; 12] = [
    "--quality",
    "high",
    "--render-scale",
    "1",
    "--background",
    "1,0,1",
    "--time",
    "5",
    "--camera=-120,14,-560",
    "--look-at=-400,10,-860",
    "--fft-size",
    "64",
];

fn shot(name: &str, args: &[&str]) -> Vec<u8> {
    let mut all = SILHOUETTE.to_vec();
    all.extend_from_slice(args);
    common::shot(&format!("aa-{name}"), (W as u32, H as u32), &all, &[])
}

/// How magenta a pixel is: min(R, B) − G. The background (linear (1, 0, 1), tone-mapped:
/// (232, 0, 232)) is 232; the island, the pillars, the sea and its haze are below 20.
fn magenta(p: &[u8]) -> Vec<i32> {
    p.chunks(4)
        .map(|c| c[0].min(c[2]) as i32 - c[1] as i32)
        .collect()
}

/// Pixels between the background and the scene in front of it: a blend of the two.
fn blended(p: &[u8], background: i32) -> usize {
    magenta(p)
        .iter()
        .filter(|&&m| m > 40 && m < background - 40)
        .count()
}

/// Pixels whose 5x5 neighbourhood's luma spans less than 4 levels in `p`: far from any edge.
fn flat_pixels(p: &[u8]) -> Vec<usize> {
    let l = luma(p);
    let at = |x: usize, y: usize| l[y * W + x];
    let mut flat = Vec::new();
    for y in 2..H - 2 {
        for x in 2..W - 2 {
            let (mut lo, mut hi) = (f64::MAX, f64::MIN);
            for v in y - 2..=y + 2 {
                for u in x - 2..=x + 2 {
                    lo = lo.min(at(u, v));
                    hi = hi.max(at(u, v));
                }
            }
            if hi - lo < 4.0 {
                flat.push(y * W + x);
            }
        }
    }
    flat
}

#[test]
fn fxaa_blends_the_stair_steps_of_an_edge_and_leaves_flat_regions_alone() {
    let off = shot("off", &["--aa", "off"]);
    let fxaa = shot("fxaa", &["--aa", "fxaa"]);
    let background = magenta(&off)[0];
    assert_eq!(background, 232, "the top-left pixel is the magenta sky");
    // The silhouette's length: scene pixels next to a background pixel.
    let m = magenta(&off);
    let is_bg = |i: usize| m[i] >= background - 8;
    let edge = (W..W * (H - 1))
        .filter(|&i| !is_bg(i) && [i - W, i + W, i - 1, i + 1].into_iter().any(is_bg))
        .count();
    // Measured (lavapipe, 2026-12-05): no blended pixel without anti-aliasing (every pixel is
    // the sky or the scene: hard steps), 181 with FXAA along a 405-pixel silhouette.
    let (hard, soft) = (blended(&off, background), blended(&fxaa, background));
    eprintln!("silhouette {edge} px, blended: off {hard}, fxaa {soft}");
    assert!(edge > 200, "the silhouette is {edge} pixels long");
    assert!(
        hard <= 2,
        "--aa off: {hard} blended pixels along {edge} edge pixels (expected hard steps)"
    );
    assert!(
        soft >= 100 && soft >= 20 * hard.max(1),
        "--aa fxaa: {soft} blended pixels along {edge} edge pixels (--aa off: {hard}); expected ≥ 100"
    );
    // `--quality low`'s fast preset (3 search steps, edge threshold 0.25) on the same view:
    // the silhouette's contrast passes its threshold, and its shorter search still blends the
    // steps (measured: 111 blended pixels, none without anti-aliasing).
    let fast: Vec<&str> = SILHOUETTE
        .iter()
        .map(|&a| if a == "high" { "low" } else { a })
        .collect();
    let mut fast_args = fast.clone();
    fast_args.extend_from_slice(&["--aa", "fxaa"]);
    let quick = common::shot("aa-fxaa-fast", (W as u32, H as u32), &fast_args, &[]);
    let mut fast_off = fast;
    fast_off.extend_from_slice(&["--aa", "off"]);
    let quick_off = common::shot("aa-off-fast", (W as u32, H as u32), &fast_off, &[]);
    let (quick_hard, quick_soft) = (blended(&quick_off, background), blended(&quick, background));
    eprintln!("--quality low: blended: off {quick_hard}, fxaa {quick_soft}");
    assert!(
        quick_soft >= 100 && quick_soft >= 20 * quick_hard.max(1),
        "--quality low --aa fxaa: {quick_soft} blended pixels (--aa off: {quick_hard}); expected ≥ 100"
    );
    // Away from edges FXAA returns the pixel as it was (measured: exactly, mean 0.0).
    let flat = flat_pixels(&off);
    assert!(flat.len() > W * H / 4, "{} flat pixels", flat.len());
    let diff = flat
        .iter()
        .map(|&i| {
            (0..3)
                .map(|c| off[4 * i + c].abs_diff(fxaa[4 * i + c]) as f64)
                .sum::<f64>()
                / 3.0
        })
        .sum::<f64>()
        / flat.len() as f64;
    assert!(
        diff < 0.1,
        "flat regions differ by {diff:.3} levels on average (expected < 0.1)"
    );
}

/// The pass names of a `--profile` run at 320x180 (common::profiled_passes).
fn profiled_passes(name: &str, args: &[&str]) -> Vec<String> {
    common::profiled_passes(&format!("aa-{name}"), "320x180", args)
}

#[test]
fn fxaa_is_validation_clean_and_runs_only_with_the_final_view() {
    // An FFT frame's passes without anti-aliasing, and with it just before the output.
    let without: Vec<&str> = FFT_FRAME
        .iter()
        .copied()
        .filter(|&n| n != ANTI_ALIASING)
        .collect();
    let mut with = without.clone();
    with.insert(with.len() - 1, ANTI_ALIASING);
    assert_eq!(with.last(), Some(&OUTPUT));
    // Scaled up by the output's blit (--quality low: half size), copied (render scale 1), and
    // into a UNORM output (the shader then works on encoded colour).
    for (name, args) in [
        ("low", &["--aa", "fxaa", "--quality", "low"][..]),
        ("copy", &["--aa", "fxaa", "--render-scale", "1"]),
        ("unorm", &["--aa", "fxaa", "--unorm-output"]),
    ] {
        assert_eq!(profiled_passes(name, args), with, "{name}");
    }
    assert_eq!(profiled_passes("off", &["--aa", "off"]), without);
    // The debug views show their data as drawn (and no spray over it).
    let debug: Vec<&str> = without.iter().copied().filter(|&n| n != SPRAY).collect();
    assert_eq!(
        profiled_passes("normals", &["--aa", "fxaa", "--view", "normals"]),
        debug
    );
}

#[test]
fn the_config_key_aa_is_the_flag() {
    let dir = scratch("aa-config");
    let picture = |value: &str| {
        let config = dir.join(format!("{value}.toml"));
        std::fs::write(&config, format!("aa = \"{value}\"\n")).unwrap();
        let by_file = shot(
            &format!("config-{value}"),
            &["--config", config.to_str().unwrap()],
        );
        let by_flag = shot(&format!("flag-{value}"), &["--aa", value]);
        assert!(
            by_file == by_flag,
            "aa = \"{value}\" draws what --aa {value} draws"
        );
        by_file
    };
    let (off, fxaa) = (picture("off"), picture("fxaa"));
    let _ = std::fs::remove_dir_all(&dir);
    assert!(off != fxaa, "the two values draw different pictures");
}

/// Mean absolute luma step between neighbouring pixels (across and down) in the bottom third
/// of a `w`-wide picture: the near water, where the scaled-up `low` picture looked soft.
fn water_gradient(p: &[u8], w: usize) -> f64 {
    let l = luma(p);
    let h = l.len() / w;
    let (mut sum, mut n) = (0.0, 0usize);
    for y in 2 * h / 3..h - 1 {
        for x in 0..w - 1 {
            let i = y * w + x;
            sum += (l[i + 1] - l[i]).abs() + (l[i + w] - l[i]).abs();
            n += 2;
        }
    }
    sum / n as f64
}

#[test]
fn the_sharpening_gives_the_scaled_up_water_part_of_the_full_size_picture_s_contrast() {
    // The default view at 1280x720, the scene drawn at half size (`low`) and scaled up
    // bilinearly by the output pass (`--upscale bilinear`), without and with the sharpening, against the same scene
    // drawn at full size. Measured: the water's mean luma step 1.57 (bilinear), 1.99 (--sharpen
    // 0.75, the default when scaling), 2.50 (full size); the mean difference from the full-size
    // picture 2.49 and 2.71 grey levels: the sharpening restores contrast, not detail (the
    // scaled pictures miss the same), and must not add much that is not there.
    let size = (1280u32, 720u32);
    let at = |name: &str, args: &[&str]| {
        let mut all = vec!["--quality", "low", "--time", "3"];
        all.extend_from_slice(args);
        common::shot(&format!("aa-sharpen-{name}"), size, &all, &[])
    };
    let bilinear = at("0", &["--sharpen", "0", "--upscale", "bilinear"]);
    let sharp = at("default", &["--upscale", "bilinear"]);
    let full = at("full", &["--render-scale", "1"]);
    let w = size.0 as usize;
    let (g0, g1, gf) = (
        water_gradient(&bilinear, w),
        water_gradient(&sharp, w),
        water_gradient(&full, w),
    );
    let third = |p: &[u8]| p[p.len() * 2 / 3..].to_vec();
    let (d0, d1) = (
        common::mean_abs_diff(&third(&bilinear), &third(&full)),
        common::mean_abs_diff(&third(&sharp), &third(&full)),
    );
    eprintln!("water's luma step: bilinear {g0:.3}, sharpened {g1:.3}, full size {gf:.3}; from full size: {d0:.3} and {d1:.3}");
    assert!(
        g1 >= 1.15 * g0 && g1 <= 0.95 * gf,
        "luma step: sharpened {g1:.3} against bilinear {g0:.3} (≥ 1.15×) and full size {gf:.3} (≤ 0.95×)"
    );
    assert!(
        d1 <= 1.15 * d0,
        "from the full-size picture: sharpened {d1:.3} against bilinear {d0:.3} (≤ 1.15×)"
    );
}

/// Luma gradient magnitude (central differences; 0 on the border) of a `w`-wide picture.
fn gradient(l: &[f64], w: usize) -> Vec<f64> {
    let h = l.len() / w;
    let mut g = vec![0.0; l.len()];
    for y in 1..h - 1 {
        for x in 1..w - 1 {
            let i = y * w + x;
            g[i] = 0.5 * (l[i + 1] - l[i - 1]).hypot(l[i + w] - l[i - w]);
        }
    }
    g
}

/// Share of pixels of `l` more than 2 levels of luma outside the range of `reference`'s 5x5
/// neighbourhood around them (overshoot, ringing).
fn outside_range(l: &[f64], reference: &[f64], w: usize) -> f64 {
    let h = l.len() / w;
    let mut outside = 0usize;
    for y in 2..h - 2 {
        for x in 2..w - 2 {
            let (mut lo, mut hi) = (f64::MAX, f64::MIN);
            for dy in 0..5 {
                for dx in 0..5 {
                    let r = reference[(y + dy - 2) * w + x + dx - 2];
                    lo = lo.min(r);
                    hi = hi.max(r);
                }
            }
            let v = l[y * w + x];
            outside += usize::from(v > hi + 2.0 || v < lo - 2.0);
        }
    }
    outside as f64 / ((w - 4) * (h - 4)) as f64
}

#[test]
fn the_edge_directed_upscale_steepens_the_blit_s_edges_without_ringing() {
    // The default view at 1280x720, `low` (the scene drawn at 640x360): scaled up by the blit
    // (`VKOCEAN_OUTPUT=transfer`: vkCmdBlitImage, bilinear), by the edge-directed draw
    // (`--upscale edge`, shaders/post/output.frag), and drawn at full size. Where the full-size picture has its
    // edges (its steepest 2 % of pixels: silhouettes, the buoy, glitter) the edge-directed
    // picture is steeper than the blit's. Measured on lavapipe (Mesa 22.3): mean luma gradient
    // there 11.6 (blit), 14.7 (edge-directed), 25.3 (full size); pixels outside the blit's 5x5
    // range 0.004 % (moving the bilinear sample across the edge instead of sharpening it, tried
    // first, gave 1.9 %, and stair steps); mean difference from the full-size picture 2.04 and
    // 2.09 levels: it steepens what the half-size picture has, it cannot add what it misses.
    let size = (1280u32, 720u32);
    let w = size.0 as usize;
    let at = |name: &str, args: &[&str], env: &[(&str, &str)]| {
        let mut all = vec!["--quality", "low", "--time", "3"];
        all.extend_from_slice(args);
        common::shot(&format!("aa-upscale-{name}"), size, &all, env)
    };
    let blit = at("blit", &[], &[("VKOCEAN_OUTPUT", "transfer")]);
    let edge = at("edge", &["--upscale", "edge"], &[]);
    let full = at("full", &["--render-scale", "1"], &[]);
    let (lb, le, lf) = (luma(&blit), luma(&edge), luma(&full));
    let (gb, ge, gf) = (gradient(&lb, w), gradient(&le, w), gradient(&lf, w));
    let mut sorted = gf.clone();
    sorted.sort_by(f64::total_cmp);
    let threshold = sorted[sorted.len() * 98 / 100];
    let at_edges = |g: &[f64]| {
        let (sum, n) = g
            .iter()
            .zip(&gf)
            .filter(|(_, f)| **f >= threshold)
            .fold((0.0, 0usize), |(s, n), (v, _)| (s + v, n + 1));
        sum / n as f64
    };
    let (eb, ee, ef) = (at_edges(&gb), at_edges(&ge), at_edges(&gf));
    let ringing = outside_range(&le, &lb, w);
    let (db, de) = (
        common::mean_abs_diff(&blit, &full),
        common::mean_abs_diff(&edge, &full),
    );
    eprintln!(
        "gradient at the full-size picture's edges: blit {eb:.2}, edge-directed {ee:.2}, full \
         size {ef:.2}; outside the blit's 5x5 range {:.4} %; from full size {db:.3} and {de:.3}",
        100.0 * ringing
    );
    assert!(
        ee >= 1.15 * eb && ee <= 0.9 * ef,
        "edges: edge-directed {ee:.2} against the blit's {eb:.2} (≥ 1.15×) and full size {ef:.2} \
         (≤ 0.9×)"
    );
    assert!(
        ringing <= 0.0005,
        "{:.4} % of the pixels overshoot the blit's 5x5 range (≤ 0.05 %)",
        100.0 * ringing
    );
    assert!(
        de <= 1.05 * db,
        "from the full-size picture: edge-directed {de:.3} against the blit's {db:.3} (≤ 1.05×)"
    );
}
