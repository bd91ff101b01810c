//! The floating buoy (issue 16): its CPU-driven heave against the surface the GPU computed (the
//! images read back, summed and inverted as the water shaders sample them), for the FFT and the
//! Gerstner model; and a headless picture in which it moves. Validation-clean.

mod common;

use vkocean::ocean::buoy::Buoy;
use vkocean::ocean::foam::FoamScene;
use vkocean::ocean::simulation::Simulation;
use vkocean::ocean::surface::SurfaceQuery;
use vkocean::ocean::OceanSettings;

/// Max |buoy heave − GPU surface height| over a few times, at the buoy and a second mooring.
fn max_heave_error(settings: &OceanSettings, times: &[f64]) -> f64 {
    let ctx = common::gpu_context();
    let mut sim = Simulation::new(&ctx, settings).unwrap();
    let mut worst = 0.0f64;
    for (f, &t) in times.iter().enumerate() {
        for xz in [[9.0, -55.0], [-31.7, 12.4]] {
            // The Gerstner window around the buoy, as around a camera beside it.
            sim.place_window(xz);
            sim.submit(
                0,
                2 * f as u64 + 1 + (xz[0] < 0.0) as u64,
                None,
                t,
                &FoamScene::default(),
                None,
            )
            .unwrap();
            let (texels, _) = sim.read_back(&ctx, 0).unwrap();
            let n = settings.fft_size;
            let steps: Vec<f64> = sim.cascades.iter().map(|c| c.patch_m / n as f64).collect();
            let origin = sim
                .is_window()
                .then(|| sim.origin_m().map(|o| (o / steps[0]).round() as i64));
            let gpu = SurfaceQuery::new(Box::new(common::ImageLattice {
                texels,
                n,
                steps,
                origin,
            }))
            .height_at(xz[0], xz[1], t);
            let heave = Buoy::on(settings, xz, Box::new(|_, _| 1.0)).pose(t).heave_m;
            worst = worst.max((heave - gpu).abs());
        }
    }
    drop(sim);
    common::assert_validation_clean(ctx);
    worst
}

#[test]
fn fft_buoy_heaves_with_the_gpu_surface() {
    // --quality high's grid: 256², 3 cascades.
    let settings = OceanSettings::default();
    let error = max_heave_error(&settings, &[2.0, 7.3, 31.9]);
    eprintln!("FFT: max |heave − GPU surface| = {:.2} mm", error * 1e3);
    assert!(
        error < 0.03,
        "FFT buoy {:.1} mm off the GPU surface (max 30 mm)",
        error * 1e3
    );
}

#[test]
fn gerstner_buoy_heaves_with_the_gpu_surface() {
    let settings = common::gerstner_window_settings();
    let error = max_heave_error(&settings, &[2.0, 7.3, 31.9]);
    eprintln!(
        "Gerstner: max |heave − GPU surface| = {:.2} mm",
        error * 1e3
    );
    assert!(
        error < 0.03,
        "Gerstner buoy {:.1} mm off the GPU surface (max 30 mm)",
        error * 1e3
    );
}

/// Rows (top = 0) of the buoy's red bands in a picture: mean row of the strongly red pixels
/// (red over twice green and blue: sunlit, the tone map's shoulder lifts the bands' green and
/// blue to about 0.4 of their red).
fn red_rows(p: &[u8], width: usize) -> (usize, f64) {
    let rows: Vec<f64> = p
        .chunks(4)
        .enumerate()
        .filter(|(_, c)| {
            c[0] > 90 && (c[0] as u32) > 2 * c[1] as u32 && (c[0] as u32) > 2 * c[2] as u32
        })
        .map(|(i, _)| (i / width) as f64)
        .collect();
    (
        rows.len(),
        rows.iter().sum::<f64>() / rows.len().max(1) as f64,
    )
}

#[test]
fn the_buoy_moves_in_the_picture() {
    // 12 m from the buoy, eye 3 m up, looking at its waterline: at t = 2 and 4 s its heave
    // differs by tens of cm (the unit tests pin the pose; here the picture follows). Without
    // anti-aliasing: its red bands are one pixel of the 80x45 main target, which FXAA blends
    // with the white ones into pink (48 and 80 red pixels without, 0 and 14 with).
    let (w, h) = (160usize, 90usize);
    let at = |t: &str| {
        common::shot(
            &format!("buoy-{t}"),
            (w as u32, h as u32),
            &[
                "--time",
                t,
                "--fft-size",
                "64",
                "--camera=9,3,-43",
                "--look-at=9,0.5,-55",
                // The sun behind the camera lights the side it sees (in the buoy's shade the
                // sky's blue light leaves the red bands dark).
                "--sun",
                "90,30",
                "--clouds",
                "0",
                "--aa",
                "off",
            ],
            &[],
        )
    };
    let (a, b) = (at("2"), at("4"));
    let settings = OceanSettings {
        fft_size: 64,
        ..OceanSettings::default()
    };
    let mut buoy = Buoy::on(&settings, [9.0, -55.0], Box::new(|_, _| 1.0));
    let heave = (buoy.pose(2.0).heave_m, buoy.pose(4.0).heave_m);
    let ((na, ra), (nb, rb)) = (red_rows(&a, w), red_rows(&b, w));
    assert!(
        na > 30 && nb > 30,
        "the buoy's red bands show: {na} and {nb} pixels"
    );
    // Up in the world is up in the picture: the higher buoy's bands sit on higher rows.
    assert!(
        (ra - rb).abs() > 1.0 && (ra < rb) == (heave.0 > heave.1),
        "red bands at rows {ra:.1} and {rb:.1} for heaves {:.2} and {:.2} m",
        heave.0,
        heave.1
    );
}
