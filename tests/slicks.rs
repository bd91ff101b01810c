//! Natural slicks (src/render/slicks.rs, shaders/common/slicks.glsl) as a viewer sees them:
//! bands along the wind where the sea is smoother, so far off, at grazing angles, it reflects
//! more of the sky (Bruneton et al.'s rough-sea Fresnel falls with the unresolved slopes).
//! Where the bands lie comes from the CPU twin of their noise; the rows of the far sea are
//! compared pixel by pixel, slick against clean, in the same picture and in one drawn without
//! slicks. Their slopes against Cox & Munk's slick fits: tests/sun_glitter.rs.

mod common;

use glam::Vec3;
use vkocean::ocean::moments::SeaMoments;
use vkocean::ocean::{OceanSettings, SeaState};
use vkocean::render::slicks::{slick_at, Slicks};
use vkocean::render::Camera;

const W: usize = 480;
const H: usize = 270;

/// Where the band test looks from (far from the world's origin: the bands are the world's, not
/// the water grid's) and toward, and when: T_S s of drift at 3 % of 5 m/s carry them 300 m.
const EYE: [f32; 3] = [5000.0, 30.0, -3000.0];
const TARGET: [f32; 3] = [5000.0, 0.0, -3600.0];
const T_S: f64 = 2000.0;

/// The median over the far sea's rows of a row's mean luma in slicks over its mean luma out of
/// them, for the picture `pixels` of the view `camera`, the bands of `share` at 5 m/s (wind
/// toward +z) at T_S; and how many rows had both (NaN and 0 without any).
fn slick_over_clean(pixels: &[u8], camera: &Camera, share: f64) -> (f64, usize) {
    let settings = OceanSettings {
        sea: SeaState {
            wind_speed_m_s: 5.0,
            wind_dir_deg: 90.0,
            ..SeaState::default()
        },
        ..OceanSettings::default()
    };
    // Where the bands lie depends on the wind alone, not on the sea's slopes.
    let calm = SeaMoments::from_waves(std::iter::empty(), None);
    let bands = Slicks::of_sea(&settings, &calm, 0.03).uniforms(share, T_S);
    let luma = common::luma(pixels);
    let mut ratios = Vec::new();
    for y in 0..H {
        let (mut slick, mut clean) = (Vec::new(), Vec::new());
        for x in 0..W {
            let Some([px, pz]) = camera.pixel_water_point((x, y), (W, H), 3000.0) else {
                continue;
            };
            if (px - EYE[0]).hypot(pz - EYE[2]) < 200.0 {
                continue;
            }
            match slick_at(px, pz, &bands) {
                s if s > 0.95 => slick.push(luma[y * W + x]),
                s if s < 0.05 => clean.push(luma[y * W + x]),
                _ => {}
            }
        }
        if slick.len() >= 20 && clean.len() >= 20 {
            let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
            ratios.push(mean(&slick) / mean(&clean));
        }
    }
    ratios.sort_by(f64::total_cmp);
    match ratios.len() {
        0 => (f64::NAN, 0),
        n => (ratios[n / 2], n),
    }
}

#[test]
fn slicks_are_brighter_bands_of_the_far_sea_where_their_noise_puts_them() {
    // Measured (480x270, 30 m up, the sun behind): rows of the sea 200 m–3 km off, slick over
    // clean 1.045 with the slicks, 0.999 in the same bands without them (30 rows). With the
    // bands placed without their drift 1.027, with it the wrong way 0.997.
    let camera = Camera::looking_at(Vec3::from(EYE), Vec3::from(TARGET)).expect("a camera");
    let (eye, target, time) = (
        format!("{},{},{}", EYE[0], EYE[1], EYE[2]),
        format!("{},{},{}", TARGET[0], TARGET[1], TARGET[2]),
        T_S.to_string(),
    );
    let picture = |share: &str| {
        common::shot(
            &format!("slicks-{share}"),
            (W as u32, H as u32),
            &[
                "--wind-speed",
                "5",
                "--wind-dir",
                "90",
                "--camera",
                &eye,
                "--look-at",
                &target,
                "--sun",
                "90,30",
                "--clouds",
                "0",
                "--time",
                &time,
                "--slicks",
                share,
            ],
            &[],
        )
    };
    let (with, rows) = slick_over_clean(&picture("0.35"), &camera, 0.35);
    let (without, _) = slick_over_clean(&picture("0"), &camera, 0.35);
    println!("slick over clean: {with:.3} with slicks, {without:.3} without ({rows} rows)");
    assert!(rows >= 20, "{rows} rows of far sea with both");
    // 3 %: the bands must stand out of the sea; 1 %: without them, the same pixels are the
    // sea's.
    assert!(with > 1.03, "slick over clean {with:.3}");
    assert!((without - 1.0).abs() < 0.01, "without slicks {without:.3}");
}

#[test]
fn a_slick_damps_the_drawn_short_waves_as_the_cox_and_munk_totals_ask() {
    // One cascade (21.1 m patch: waves of 16 cm to 21 m) at 5 m/s, seen 12 m up looking 45°
    // down, in the normals view: in a slick every pixel's drawn slope is the clean one times
    // √(1 − (1 − d)·s/v), s/v the cascade's share of its mean square in waves under 1 m, d
    // the damping that takes the sea to Cox & Munk's slick total (`Slicks::of_sea`).
    // Measured (--quality high: N = 256): 0.840 against 0.841 predicted.
    let sea = [
        "--quality",
        "high",
        "--cascades",
        "1",
        "--patch-size",
        "21.1",
        "--wind-speed",
        "5",
    ];
    let dir = common::scratch("slicks-dump");
    let dump = dir.join("dump");
    let mut args = vec![
        "--headless",
        "--validation",
        "--size",
        "64x36",
        "--dump",
        dump.to_str().expect("temp paths are UTF-8"),
    ];
    args.extend_from_slice(&sea);
    let out = common::run(&args);
    common::clean_run(&out, &format!("{args:?}"));
    let params: serde_json::Value = serde_json::from_str(
        &std::fs::read_to_string(dump.join("params.json")).expect("params.json written"),
    )
    .expect("params.json is JSON");
    let _ = std::fs::remove_dir_all(&dir);
    let slopes = &params["slopes"];
    let first = |key: &str| slopes[key][0].as_f64().expect(key);
    let mut moments = SeaMoments::from_waves(std::iter::empty(), None);
    moments.slope_variance[0] = first("resolved");
    moments.short_slope_variance[0] = first("short");
    let clean = slopes["mean_square_slope"].as_f64().expect("mean square");
    let settings = OceanSettings {
        sea: SeaState {
            wind_speed_m_s: 5.0,
            ..SeaState::default()
        },
        ..OceanSettings::default()
    };
    let slicks = Slicks::of_sea(&settings, &moments, clean);
    let predicted = slicks.cascades[0];
    println!(
        "resolved {:.5}, of it under 1 m {:.5}, clean total {clean:.5}, d {:.3}",
        moments.slope_variance[0], moments.short_slope_variance[0], slicks.short_damping
    );
    let picture = |share: &str| {
        let mut args = vec![
            "--foam-sim",
            "off",
            "--camera",
            "0,12,0",
            "--look-at",
            "0,0,-12",
            "--time",
            "3",
            "--view",
            "normals",
            "--slicks",
            share,
        ];
        args.extend_from_slice(&sea);
        let pixels = common::shot(&format!("slick-normals-{share}"), (320, 180), &args, &[]);
        // The view draws n·0.5 + 0.5 through the exposure and tone map: about linear in the
        // slopes here (n_x and n_z within ±0.2 of 0, the curve's input within 10 % of its
        // middle), so each channel's deviation from its mean stands for the slope.
        [0, 2].map(|c| {
            let v: Vec<f64> = pixels.chunks(4).map(|p| f64::from(p[c])).collect();
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            v.into_iter().map(|x| x - mean).collect::<Vec<_>>()
        })
    };
    let (slick, clean) = (picture("1"), picture("0"));
    // Least squares through the origin of the slick's slopes on the clean ones.
    let (mut sc, mut cc) = (0.0, 0.0);
    for (s, c) in slick.iter().zip(&clean) {
        for (a, b) in s.iter().zip(c) {
            sc += a * b;
            cc += b * b;
        }
    }
    let measured = sc / cc;
    println!("slopes in a slick over clean: {measured:.4}, predicted {predicted:.4}");
    assert!(predicted < 0.97, "the cascade's short waves: {predicted}");
    // 2 %: 8-bit values about 5 levels apart, the tone map's curvature.
    assert!((measured / predicted - 1.0).abs() < 0.02);
}
