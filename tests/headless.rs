//! The acceptance run: 60 headless frames at 1280x720 with validation, a profile and a
//! screenshot (run once, checked by the tests below).

mod common;

use std::path::PathBuf;
use std::process::Output;
use std::sync::OnceLock;

use common::{clean_run, frames_rendered, read_png, run, scratch, stderr};

struct Run {
    out: Output,
    screenshot: PathBuf,
    profile: PathBuf,
}

fn acceptance_run() -> &'static Run {
    static RUN: OnceLock<Run> = OnceLock::new();
    RUN.get_or_init(|| {
        let dir = scratch("headless");
        let screenshot = dir.join("s.png");
        let profile = dir.join("p.json");
        let out = run(&[
            "--headless",
            "--frames",
            "60",
            "--validation",
            "--profile",
            profile.to_str().unwrap(),
            "--screenshot",
            screenshot.to_str().unwrap(),
        ]);
        Run {
            out,
            screenshot,
            profile,
        }
    })
}

#[test]
fn sixty_frames_are_validation_clean() {
    let r = acceptance_run();
    let err = clean_run(&r.out, "headless");
    assert_eq!(frames_rendered(&err), Some(60), "{err}");
}

/// Mean luma and mean (r, g, b) of a band of rows.
fn band(pixels: &[u8], width: u32, rows: std::ops::Range<u32>) -> (f64, [f64; 3]) {
    let mut sum = [0.0f64; 3];
    let mut n = 0.0;
    for y in rows {
        for x in 0..width {
            let i = ((y * width + x) * 4) as usize;
            for c in 0..3 {
                sum[c] += pixels[i + c] as f64;
            }
            n += 1.0;
        }
    }
    let mean = sum.map(|s| s / n);
    (0.2126 * mean[0] + 0.7152 * mean[1] + 0.0722 * mean[2], mean)
}

#[test]
fn screenshot_shows_sky_over_water() {
    let r = acceptance_run();
    assert_eq!(r.out.status.code(), Some(0), "{}", stderr(&r.out));
    let (w, h, px) = read_png(&r.screenshot);
    assert_eq!((w, h), (1280, 720));

    // The camera looks 4.6 degrees down with a 60 degree vertical field of view, so the horizon
    // lies 43% down the image: the top 10% is sky, the bottom 10% is water.
    let (sky_luma, sky) = band(&px, w, 0..h / 10);
    let (water_luma, water) = band(&px, w, h * 9 / 10..h);
    let (near_horizon_luma, _) = band(&px, w, h * 35 / 100..h * 40 / 100);
    assert!(sky[2] > sky[0] + 20.0, "sky is blue: {sky:?}");
    assert!(water[2] > water[0] + 20.0, "water is blue: {water:?}");
    assert!(
        water_luma + 40.0 < sky_luma,
        "water ({water_luma:.0}) darker than sky ({sky_luma:.0})"
    );
    assert!(
        near_horizon_luma > sky_luma + 10.0,
        "sky brightens toward the horizon: {near_horizon_luma:.0} vs {sky_luma:.0}"
    );

    // The sun disc is above the horizon, white or nearly: the tone map turns the brightest
    // light 70 % of the way to white (common/display.glsl), so the sun 11.7° up keeps a warm
    // tint (measured (255, 247, 236)): its brightest channel saturates, its weakest stays high.
    let upper = &px[..(w * h * 4 * 4 / 10) as usize];
    let brightest = upper
        .chunks_exact(4)
        .max_by_key(|p| p[0].min(p[1]).min(p[2]))
        .unwrap();
    let (top, bottom) = (brightest[..3].iter().max(), brightest[..3].iter().min());
    assert!(
        top >= Some(&250) && bottom >= Some(&225),
        "sun disc in the sky: brightest {:?}",
        &brightest[..3]
    );

    // Each row band differs: luma varies from top to bottom (no flat fill).
    let lumas: Vec<f64> = (0..10)
        .map(|i| band(&px, w, h * i / 10..h * (i + 1) / 10).0)
        .collect();
    let spread = lumas.iter().cloned().fold(f64::MIN, f64::max)
        - lumas.iter().cloned().fold(f64::MAX, f64::min);
    assert!(spread > 60.0, "row-band lumas {lumas:?}");
}

#[test]
fn profile_has_every_pass() {
    let r = acceptance_run();
    assert_eq!(r.out.status.code(), Some(0), "{}", stderr(&r.out));
    let text = std::fs::read_to_string(&r.profile).expect("profile written");
    let json: serde_json::Value = serde_json::from_str(&text).expect("profile is JSON");
    assert!(
        json["device"].as_str().is_some_and(|s| !s.is_empty()),
        "{json}"
    );
    assert!(
        json["driver"].as_str().is_some_and(|s| !s.is_empty()),
        "{json}"
    );
    assert_eq!(json["frames"], 60);
    assert_eq!(json["size"], serde_json::json!([1280, 720]));

    let stats_ok = |s: &serde_json::Value| {
        let get = |k: &str| s[k].as_f64().unwrap_or(f64::NAN);
        get("min") > 0.0
            && get("min") <= get("median")
            && get("median") <= get("p95")
            && get("p95") <= get("max")
            && get("min") <= get("mean")
            && get("mean") <= get("max")
    };
    let passes = json["passes"].as_array().expect("passes array");
    let names: Vec<&str> = passes.iter().map(|p| p["name"].as_str().unwrap()).collect();
    assert_eq!(names, vkocean::pass_names::FFT_FRAME);
    // (largest compute pass, largest graphics pass) medians.
    let mut largest = [0.0f64; 2];
    for (i, p) in passes.iter().enumerate() {
        assert!(stats_ok(&p["gpu_ms"]), "{p}");
        assert_eq!(p["samples"], 55, "60 frames minus 5 warm-up: {p}");
        // The compute passes are the simulation's, named "ocean …".
        let which = usize::from(!names[i].starts_with("ocean"));
        largest[which] = largest[which].max(p["gpu_ms"]["median"].as_f64().unwrap());
    }
    assert!(stats_ok(&json["frame_gpu_ms"]), "{json}");
    assert!(stats_ok(&json["compute_gpu_ms"]), "{json}");
    assert!(stats_ok(&json["frame_cpu_ms"]), "{json}");
    let median = |key: &str| json[key]["median"].as_f64().unwrap();
    assert!(
        median("compute_gpu_ms") >= largest[0],
        "the compute submission contains its passes"
    );
    assert!(
        median("frame_gpu_ms") >= largest[1],
        "a graphics frame contains its passes"
    );
}
