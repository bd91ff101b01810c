//! The rendering issue's picture tests, headless on lavapipe, every run validation-clean:
//! debug views, reflection and refraction textures reacting to the scene, the shallow bottom seen
//! through calm water, cracks between ocean patches and clipmap tiles, the two water
//! geometries against each other, and a golden image.

mod common;

use common::{clean_run, luma, mean_abs_diff, read_png, run, scratch, std_dev, stderr};
use vkocean::render::scene::terrain_height;
use vkocean::render::SceneLayout;

const W: u32 = 320;
const H: u32 = 180;

/// One headless frame at W x H at `--quality high` (the golden image's level; lavapipe's own
/// default is low) unless `args` sets its parts, without the foam simulation near the camera:
/// what these tests look at does not depend on it, and its warm-up is two thirds of a frame's
/// cost at `high` on lavapipe (9.1 s a picture against 2.8 s). The golden image and the surf
/// test keep it ([`shot_as_shipped`]).
fn shot(name: &str, args: &[&str]) -> Vec<u8> {
    let mut all = vec!["--foam-sim", "off"];
    all.extend_from_slice(args);
    shot_as_shipped(name, &all)
}

/// [`shot`] with the foam simulation as `--quality high` ships it.
fn shot_as_shipped(name: &str, args: &[&str]) -> Vec<u8> {
    let mut all = vec!["--quality", "high"];
    all.extend_from_slice(args);
    common::shot(&format!("render-{name}"), (W, H), &all, &[])
}

/// Pixels whose colour differs by more than `threshold` in some channel.
fn changed_pixels(a: &[u8], b: &[u8], threshold: u8) -> usize {
    a.chunks(4)
        .zip(b.chunks(4))
        .filter(|(p, q)| (0..3).any(|c| p[c].abs_diff(q[c]) > threshold))
        .count()
}

/// Mean (r, g, b) of the whole picture.
fn mean_rgb(p: &[u8]) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for c in p.chunks(4) {
        for i in 0..3 {
            sum[i] += c[i] as f64;
        }
    }
    sum.map(|s| s / (p.len() / 4) as f64)
}

// A fixed moment, seen from near the island (default layout), looking across its shallow shore.
const NEAR_ISLAND: [&str; 6] = [
    "--time",
    "5",
    "--camera=-120,14,-560",
    "--look-at=-400,0,-860",
    "--fft-size",
    "128",
];

#[test]
fn every_view_is_a_picture_and_the_views_differ() {
    let views = [
        "final",
        "reflection",
        "refraction",
        "displacement",
        "normals",
        "foam",
        "dudv",
        "wireframe",
        "crests",
        "triangles",
    ];
    let pictures: Vec<(&str, Vec<u8>)> = views
        .iter()
        .map(|v| {
            let mut args = NEAR_ISLAND.to_vec();
            args.extend(["--view", v, "--choppiness", "2", "--wind-speed", "14"]);
            (*v, shot(&format!("view-{v}"), &args))
        })
        .collect();
    for (name, p) in &pictures {
        let sd = std_dev(&luma(p));
        assert!(
            sd > 2.0,
            "--view {name} is nearly uniform (luma std {sd:.2})"
        );
    }
    for (i, (a, pa)) in pictures.iter().enumerate() {
        for (b, pb) in &pictures[i + 1..] {
            let d = mean_abs_diff(pa, pb);
            assert!(
                d > 1.0,
                "--view {a} and --view {b} look the same (mean diff {d:.2})"
            );
        }
    }
}

#[test]
fn the_same_settings_give_the_same_picture() {
    let a = shot("same-a", &NEAR_ISLAND);
    let b = shot("same-b", &NEAR_ISLAND);
    assert_eq!(changed_pixels(&a, &b, 0), 0);
}

#[test]
fn the_reflection_texture_follows_an_object_above_the_water() {
    // The buoy stands 3.5 m out of the water 55 m ahead of the default camera.
    let base = ["--time", "2", "--fft-size", "64", "--view", "reflection"];
    let at = |xz: &str| {
        let mut args = base.to_vec();
        args.extend(["--buoy", xz]);
        shot(&format!("buoy-{xz}"), &args)
    };
    let here = at("9,-55");
    let moved = at("-9,-55");
    let changed = changed_pixels(&here, &moved, 40);
    assert!(
        changed > 40,
        "moving the buoy changed only {changed} reflection pixels"
    );
}

#[test]
fn the_refraction_texture_follows_the_sea_floor() {
    let at = |floor: &str| {
        let mut args = NEAR_ISLAND.to_vec();
        args.extend(["--view", "refraction", "--sea-floor", floor]);
        shot(&format!("floor-{floor}"), &args)
    };
    let shallow = at("8");
    let deep = at("40");
    let changed = changed_pixels(&shallow, &deep, 20);
    assert!(
        changed > (W * H / 10) as usize,
        "changing the sea floor changed only {changed} refraction pixels"
    );
}

/// A point of the island's shore where the water is about `depth` m deep, found along the ray
/// from the island's centre toward +x.
fn shore_point(depth: f32) -> [f32; 2] {
    let layout = SceneLayout::default();
    let [cx, cz] = layout.island_xz;
    let mut r = 0.0;
    while terrain_height(&layout, cx + r, cz) > -depth {
        r += 1.0;
        assert!(r < 3.0 * layout.island_radius_m, "no shore found");
    }
    [cx + r, cz]
}

#[test]
fn calm_water_seen_from_above_shows_the_terrain() {
    let [x, z] = shore_point(2.5);
    let above = |x: f32, z: f32, view: &str| {
        let camera = format!("--camera={x},25,{z}");
        let look = format!("--look-at={},0,{}", x + 4.0, z);
        shot(
            &format!("above-{view}-{x}"),
            &[
                &camera,
                &look,
                "--wind-speed",
                "0.5",
                "--fft-size",
                "64",
                // Mean colours of the water as shaded: FXAA spreads the glints' light over
                // their neighbours, which raises the open sea's mean red by 5 levels (the
                // sRGB encoding is concave).
                "--aa",
                "off",
                "--view",
                view,
            ],
        )
    };
    // Over the shore the refraction texture shows sand; over the open sea, where nothing lies
    // within the refraction's reach, it is the uniform deep-water colour.
    let shore = above(x, z, "refraction");
    let open = above(4000.0, 4000.0, "refraction");
    assert!(
        std_dev(&luma(&open)) < 1.0,
        "open sea refraction is uniform"
    );
    let (s, o) = (mean_rgb(&shore), mean_rgb(&open));
    assert!(
        s[0] > o[0] + 40.0 && s[1] > o[1] + 30.0,
        "shore refraction {s:?} vs open sea {o:?}"
    );
    // And the final picture shows it through the water.
    let shore_final = above(x, z, "final");
    let open_final = above(4000.0, 4000.0, "final");
    let (s, o) = (mean_rgb(&shore_final), mean_rgb(&open_final));
    assert!(
        s[0] > o[0] + 20.0,
        "final picture over the shore {s:?} vs open sea {o:?}"
    );
}

/// Share of the water pixels of a `--view foam` picture (exactly grey; the terrain is not)
/// whose foam whitens the water by 0.3 or more (its reflectance R), and how many water pixels
/// there are.
fn foam_share(p: &[u8]) -> (f64, usize) {
    let water: Vec<f64> = p
        .chunks(4)
        .filter(|c| c[0] == c[1] && c[1] == c[2])
        .map(|c| common::linear(c[0]))
        .collect();
    let foamy = water.iter().filter(|&&f| f >= 0.3).count();
    (foamy as f64 / water.len().max(1) as f64, water.len())
}

#[test]
fn waves_break_into_surf_where_they_reach_0_78_of_the_depth() {
    // Looking down from 30 m on the shore where the water is 0.8 m deep, and on the shelf where
    // it is 15 m deep. The moderate sea's Hs (2.5 m) breaks on the first (Hs > 0.78·0.8 m,
    // McCowan 1894) but not on the second (Hs < 0.78·15 m); the calm sea's (0.13 m) on neither
    // but the last few centimetres at the waterline. The surf is bores whose white rollers
    // come and go (The ocean, Surf): the share is the mean of three instants a third of the
    // moderate sea's 6.6 s period apart. Measured on lavapipe: 0.313 (over 15 m 0.010, the
    // calm sea 0.009).
    let above = |preset: &str, depth: f32| {
        let [x, z] = shore_point(depth);
        let camera = format!("--camera={x},30,{z}");
        let look = format!("--look-at={},0,{}", x + 4.0, z);
        let mut total = (0.0, 0);
        for time in ["5", "7.2", "9.4"] {
            let args = [
                "--preset",
                preset,
                &camera,
                &look,
                "--time",
                time,
                "--fft-size",
                "128",
                "--view",
                "foam",
            ];
            let (share, water) = foam_share(&shot_as_shipped(
                &format!("surf-{preset}-{depth}-{time}"),
                &args,
            ));
            total = (total.0 + share / 3.0, water);
        }
        eprintln!(
            "{preset} over {depth} m: foam on {:.3} of the water",
            total.0
        );
        total
    };
    let (surf, water) = above("moderate", 0.8);
    assert!(water > (W * H / 2) as usize, "mostly water: {water} pixels");
    assert!(
        surf > 0.15,
        "surf covers {surf:.3} of the 0.8 m shallows (expected > 0.15; the shelf 0.003)"
    );
    let (shelf, _) = above("moderate", 15.0);
    // Only the whitecaps out there (about 2 % at 12.3 m/s, Monahan & O'Muircheartaigh 1980).
    assert!(
        shelf < 0.1,
        "foam covers {shelf:.3} of the 15 m shelf (expected < 0.1)"
    );
    let (calm, _) = above("calm", 0.8);
    assert!(
        calm < 0.1,
        "a calm sea foams over {calm:.3} of the shallows (expected < 0.1)"
    );
}

#[test]
fn the_sun_is_a_round_disc_of_its_real_size() {
    // Looking at a sun 20° up at 1920x1080 (60° vertical field: focal length 935 px), the
    // disc's radius is 0.00465 rad × 935 = 4.35 px (the sun's 0.533° diameter). Near-white
    // pixels (every channel ≥ 230: the tone map leaves the disc a warm tint, (255, 248, 240) at
    // its centre, common/display.glsl; the sky around it is below 210) cover the disc and the
    // half-covered pixels of its anti-aliased edge: the radius of a circle of their area is
    // within a pixel of it. (The sky cube's texels drew a square of radius 12.8 px.)
    let p = common::shot(
        "render-sun",
        (1920, 1080),
        &[
            "--render-scale",
            "1",
            "--sun",
            "30,20",
            "--camera",
            "0,4,0",
            "--look-at",
            "814,346,470",
        ],
        &[],
    );
    // Within 32 px of the centre, where the camera looks (the sun's glitter on the water below
    // saturates too).
    let white = p
        .chunks(4)
        .enumerate()
        .filter(|(i, _)| (i % 1920).abs_diff(960) < 32 && (i / 1920).abs_diff(540) < 32)
        .filter(|(_, c)| c[..3].iter().all(|&v| v >= 230))
        .count();
    let radius = (white as f64 / std::f64::consts::PI).sqrt();
    let want = 0.00465 * 540.0 / (30f64.to_radians()).tan();
    assert!(
        (radius - want).abs() < 1.0,
        "sun disc radius {radius:.2} px ({white} near-white pixels), expected {want:.2} ± 1"
    );
}

/// Glitter pixels per row of the water below the horizon (rows from `first` down): brighter
/// than the row's median by more than 60 (the sun's reflection, not the sky's: the reflection
/// of the bright sky around a low sun, blurred up and down by the unresolved slopes, streaks
/// the far field up to about 50 levels over its row's median).
fn glitter_widths(p: &[u8], w: usize, first: usize) -> Vec<usize> {
    let rows: Vec<Vec<f64>> = luma(p).chunks(w).map(|r| r.to_vec()).collect();
    rows[first..]
        .iter()
        .map(|row| {
            let mut sorted = row.clone();
            sorted.sort_by(f64::total_cmp);
            let median = sorted[sorted.len() / 2];
            row.iter().filter(|&&v| v > median + 60.0).count()
        })
        .collect()
}

#[test]
fn the_sun_glitter_is_a_path_that_widens_with_distance_and_wind() {
    // Toward a sun on the horizon: a path that widens toward the camera (the unresolved slopes'
    // Beckmann lobe, Cox & Munk 1954), not the one-pixel line a mirror draws (0.7 px wide in
    // every third of the water before).
    let look = ["--camera", "0,6,0", "--look-at", "866,0,500"];
    let at = |sun: &str, wind: &str| {
        let mut args = vec!["--sun", sun, "--wind-speed", wind];
        args.extend_from_slice(&look);
        let name = format!("glitter-{sun}-{wind}");
        glitter_widths(&shot(&name, &args), W as usize, H as usize / 2 + 3)
    };
    // Widths row by row, summed over three moments: one picture's near rows hold a handful of
    // wave facets, and whether they glint varies from frame to frame (the near third's mean
    // width, measured at t = 0, 3, 6 s: 13, 45, 10 px; the far third's 7, 7, 8).
    let widths = ["0", "3", "6"]
        .map(|t| {
            let mut args = vec!["--sun", "30,1", "--wind-speed", "10", "--time", t];
            args.extend_from_slice(&look);
            glitter_widths(
                &shot(&format!("glitter-path-{t}"), &args),
                W as usize,
                H as usize / 2 + 3,
            )
        })
        .into_iter()
        .reduce(|a, b| a.iter().zip(&b).map(|(x, y)| x + y).collect())
        .unwrap();
    let third = widths.len() / 3;
    // Per row and picture.
    let mean = |w: &[usize]| w.iter().sum::<usize>() as f64 / (3 * w.len()) as f64;
    let (far, near) = (mean(&widths[..third]), mean(&widths[2 * third..]));
    assert!(
        far > 3.0 && near > 1.5 * far,
        "glitter {far:.1} px wide far, {near:.1} px near (expected > 3 and widening 1.5×)"
    );
    // Cox & Munk's σ² = 0.003 + 5.12·10⁻³·U: 0.018 at 3 m/s, 0.049 at 9 m/s. A sun 8° up
    // glitters over a larger area of the sea in the stronger wind.
    let area = |wind| at("30,8", wind).iter().sum::<usize>() as f64;
    let (light, fresh) = (area("3"), area("9"));
    assert!(
        fresh > 1.3 * light,
        "glitter area {fresh} px at 9 m/s vs {light} px at 3 m/s (expected > 1.3×)"
    );
}

#[test]
fn the_mid_field_shimmers_no_more_than_the_near_field() {
    // Two frames 1/60 s apart from the default camera (12 m up, the sun ahead) at 480x270: the
    // mean luma change per pixel in bands of the water from just below the horizon (rows
    // 0.5–0.75 of the height) against the near field (the bottom eighth). Before the slopes
    // faded with the pixel's footprint the mid field changed by 6.6 grey levels against 1.6
    // near (960x540), a shimmer the eye reads as noise.
    let (w, h) = (480usize, 270usize);
    let frame = |t: &str| {
        let p = common::shot(
            &format!("render-shimmer-{t}"),
            (w as u32, h as u32),
            &["--quality", "high", "--foam-sim", "off", "--time", t],
            &[],
        );
        luma(&p)
    };
    let (a, b) = (frame("5"), frame("5.0166667"));
    let band = |lo: usize, hi: usize| {
        let n = (hi - lo) * w;
        a[lo * w..hi * w]
            .iter()
            .zip(&b[lo * w..hi * w])
            .map(|(x, y)| (x - y).abs())
            .sum::<f64>()
            / n as f64
    };
    let near = band(h * 7 / 8, h);
    assert!(near > 0.5, "the near field moves: {near:.2}");
    for i in 0..5 {
        let lo = h / 2 + i * h / 20;
        let mid = band(lo, lo + h / 20);
        assert!(
            mid <= 1.2 * near,
            "rows {lo}..: {mid:.2} grey levels between frames against {near:.2} near (≤ 1.2×)"
        );
    }
}

/// Pixels of the solid magenta test background (linear (1, 0, 1), tone-mapped and sRGB-encoded).
fn background_pixels(p: &[u8]) -> usize {
    p.chunks(4)
        .filter(|c| c[0] > 180 && c[1] < 40 && c[2] > 180)
        .count()
}

#[test]
fn no_background_shows_through_the_water_between_patches_or_tiles() {
    // The main view's sky is painted magenta, found nowhere else in the scene; looking down
    // 50 degrees the whole picture is water, so any magenta pixel is a crack: between the
    // tessellated patches, or between clipmap tiles of two levels.
    for geometry in ["tessellated", "clipmap"] {
        for height in [3.0f32, 30.0, 300.0] {
            let camera = format!("--camera=37,{height},11");
            let look = format!(
                "--look-at={},0,{}",
                37.0 + height * 0.84,
                11.0 - height * 0.1
            );
            let p = shot(
                &format!("crack-{geometry}-{height}"),
                &[
                    "--geometry",
                    geometry,
                    &camera,
                    &look,
                    "--background",
                    "1,0,1",
                    "--wind-speed",
                    "16",
                    "--choppiness",
                    "1.5",
                    "--time",
                    "7",
                ],
            );
            assert_eq!(
                background_pixels(&p),
                0,
                "background shows through the {geometry} water seen from {height} m"
            );
        }
    }
    // The check can fail: looking at the horizon, the sky is the background.
    let p = shot("crack-control", &["--background", "1,0,1"]);
    assert!(background_pixels(&p) > (W * H / 4) as usize);
}

/// Per-channel tolerance of the golden image: lavapipe renders the same picture bit for bit on
/// one machine; other LLVM or Mesa builds round differently.
const GOLDEN_MEAN_DIFF: f64 = 1.5;
const GOLDEN_PIXEL_DIFF: u8 = 48;
const GOLDEN_MAX_CHANGED: f64 = 0.01;

#[test]
fn golden_image() {
    let golden = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/final.png");
    let p = shot_as_shipped("golden", &NEAR_ISLAND);
    if std::env::var_os("VKOCEAN_UPDATE_GOLDEN").is_some() {
        image::save_buffer(&golden, &p, W, H, image::ColorType::Rgba8).expect("golden written");
        eprintln!("golden image written to {}", golden.display());
        return;
    }
    let (w, h, g) = read_png(&golden);
    assert_eq!((w, h), (W, H));
    let mean = mean_abs_diff(&p, &g);
    let changed = changed_pixels(&p, &g, GOLDEN_PIXEL_DIFF) as f64 / (W * H) as f64;
    assert!(
        mean <= GOLDEN_MEAN_DIFF && changed <= GOLDEN_MAX_CHANGED,
        "the picture differs from tests/golden/final.png: mean channel difference {mean:.2} \
         (max {GOLDEN_MEAN_DIFF}), {:.2}% of pixels off by more than {GOLDEN_PIXEL_DIFF} (max {}%). \
         If the look changed on purpose: VKOCEAN_UPDATE_GOLDEN=1 cargo test --release --test render golden_image",
        changed * 100.0,
        GOLDEN_MAX_CHANGED * 100.0
    );
}

/// `--profile`'s water-draw counters (medians) of the tessellated water at `--tess-edge
/// edge_px`.
fn tessellation_counts(edge_px: &str) -> DrawCounts {
    draw_counts("tessellated", edge_px, "320x180")
}

/// `--profile`'s water-draw counters (medians) of `geometry` at `--tess-edge edge_px`.
fn draw_counts(geometry: &str, edge_px: &str, size: &str) -> DrawCounts {
    let dir = scratch(&format!("render-lod-{geometry}-{edge_px}-{size}"));
    let profile = dir.join("p.json");
    let out = run(&[
        "--headless",
        "--validation",
        "--quality",
        "high",
        "--size",
        size,
        "--geometry",
        geometry,
        "--frames",
        "7",
        "--fft-size",
        "64",
        "--tess-edge",
        edge_px,
        "--profile",
        profile.to_str().unwrap(),
    ]);
    let err = clean_run(&out, "vkocean");
    assert!(err.contains("water draw"), "{err}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&profile).unwrap()).unwrap();
    let t = &json["water_tessellation"];
    let c = &json["water_coverage"];
    let _ = std::fs::remove_dir_all(&dir);
    let median = |key: &str| t[key]["median"].as_f64().unwrap();
    DrawCounts {
        patches: median("patches"),
        tess_eval: median("tess_eval_invocations"),
        triangles: median("primitives"),
        fragments: median("fragment_invocations"),
        per_pixel: c["invocations_per_pixel"]["median"].as_f64().unwrap(),
        covered: c["covered_pixels"]["median"].as_f64().unwrap(),
    }
}

/// The water draw's medians in a `--profile` report.
struct DrawCounts {
    patches: f64,
    tess_eval: f64,
    triangles: f64,
    fragments: f64,
    /// `water_coverage`: fragment invocations per covered pixel, and the covered pixels.
    per_pixel: f64,
    covered: f64,
}

#[test]
fn the_clipmap_shades_fewer_fragments_per_covered_pixel_than_the_tessellation() {
    // At --quality high's cell size on a 1280x720 frame (the default camera: the water covers
    // the lower half). Mesa 22.3's lavapipe counts 16 invocations for every 4x4 block a
    // triangle touches (it runs the shader on whole blocks): measured 2.61 per covered pixel
    // for the clipmap, 3.48 tessellated, over the same 0.525 M pixels. Mesa 25.0's counts the
    // covered pixels only (1.00 for both, in `VKOCEAN_DEBIAN13_ALL=1 tools/debian13`'s root;
    // this test runs on the host only otherwise): there the ratio says
    // nothing of the blocks, and only "never more" is asked.
    let counts_blocks = |c: &DrawCounts| c.per_pixel > 1.2;
    let clipmap = draw_counts("clipmap", "16", "1280x720");
    let tessellated = draw_counts("tessellated", "16", "1280x720");
    for (name, c) in [("clipmap", &clipmap), ("tessellated", &tessellated)] {
        // Precise occlusion counts: about half of the 0.92 M pixels, each shaded at least once.
        assert!(
            (0.4..0.7).contains(&(c.covered / (1280.0 * 720.0))),
            "{name}: {} pixels covered",
            c.covered
        );
        assert!(c.per_pixel >= 0.999, "{name}: {}", c.per_pixel);
        // Medians of per-frame ratios against the ratio of medians: the frames barely differ.
        assert!((c.fragments / c.covered - c.per_pixel).abs() < 0.02 * c.per_pixel);
    }
    assert_eq!(clipmap.patches, 0.0);
    assert!(
        (clipmap.covered / tessellated.covered - 1.0).abs() < 0.01,
        "the two cover different areas: {} against {}",
        clipmap.covered,
        tessellated.covered
    );
    let fewer = if counts_blocks(&tessellated) {
        0.85
    } else {
        1.001
    };
    assert!(
        clipmap.per_pixel < fewer * tessellated.per_pixel
            && clipmap.triangles < tessellated.triangles,
        "clipmap {:.2} per pixel, {} triangles; tessellated {:.2}, {} (at most {fewer}x)",
        clipmap.per_pixel,
        clipmap.triangles,
        tessellated.per_pixel,
        tessellated.triangles
    );
    // Larger cells: fewer triangles, and (where blocks are counted) fewer invocations per pixel.
    let coarse = draw_counts("clipmap", "32", "1280x720");
    assert!(coarse.triangles < 0.5 * clipmap.triangles);
    if counts_blocks(&clipmap) {
        assert!(coarse.per_pixel < clipmap.per_pixel);
    } else {
        assert!(coarse.per_pixel <= clipmap.per_pixel * 1.001);
    }
}

/// Distinct colours per `block`×`block` block among the `water` pixels of `p` (RGBA), times the
/// block's pixels, over the water pixels: the fragment invocations per covered pixel of a
/// rasterizer that shades whole blocks, for a `--view triangles` picture (a colour per
/// triangle) of the triangles it shows.
fn block_invocations(p: &[u8], water: &[bool], (w, h): (usize, usize), block: usize) -> f64 {
    let mut shaded = 0;
    for by in 0..h.div_ceil(block) {
        for bx in 0..w.div_ceil(block) {
            let mut seen: Vec<&[u8]> = Vec::new();
            for y in by * block..((by + 1) * block).min(h) {
                for x in bx * block..((bx + 1) * block).min(w) {
                    let i = y * w + x;
                    let c = &p[4 * i..4 * i + 3];
                    if water[i] && !seen.contains(&c) {
                        seen.push(c);
                    }
                }
            }
            shaded += seen.len() * block * block;
        }
    }
    shaded as f64 / water.iter().filter(|&&b| b).count().max(1) as f64
}

#[test]
fn a_gpu_s_quads_shade_the_clipmap_at_about_one_and_a_half_invocations_per_pixel() {
    // What a GPU shades is 2x2 quads (a quad's lanes without a covered pixel centre run as
    // helper invocations), which no counter here shows: Mesa 22.3's lavapipe counts its own
    // 4x4 blocks, Mesa 25.0's the covered pixels. --view triangles colours each triangle its
    // own, so counting the triangles that show in each block gives both, for the triangles
    // the depth test keeps (the counter also counts the fragments it rejects: about 5 % more
    // in 4x4 blocks, so a GPU that shaded every hidden fragment too would shade about 1.52).
    // The water's pixels: exactly grey in --view foam over a magenta sky, and of another
    // colour in --view triangles (the rest of the scene is the same in both). Measured
    // (2026-12-06): 1.45 in 2x2 quads and 2.47 in 4x4 blocks, where Mesa 22.3's counter
    // says 2.6; issue 32 asks for 1.5 at most.
    let size = (1280, 720);
    let picture = |view: &str| {
        common::shot(
            &format!("quads-{view}"),
            size,
            &[
                "--quality",
                "high",
                "--geometry",
                "clipmap",
                "--fft-size",
                "64",
                "--foam-sim",
                "off",
                "--background",
                "1,0,1",
                "--view",
                view,
            ],
            &[],
        )
    };
    let (triangles, foam) = (picture("triangles"), picture("foam"));
    let water: Vec<bool> = foam
        .chunks(4)
        .zip(triangles.chunks(4))
        .map(|(f, t)| f[0] == f[1] && f[1] == f[2] && f[..3] != t[..3])
        .collect();
    let share = water.iter().filter(|&&b| b).count() as f64 / water.len() as f64;
    assert!(
        (0.4..0.7).contains(&share),
        "{share} of the picture is water"
    );
    let wh = (size.0 as usize, size.1 as usize);
    let quads = block_invocations(&triangles, &water, wh, 2);
    let blocks = block_invocations(&triangles, &water, wh, 4);
    eprintln!("per covered pixel: {quads:.3} in 2x2 quads, {blocks:.3} in 4x4 blocks");
    assert!(quads <= 1.5, "{quads:.3} per covered pixel in 2x2 quads");
    // The counting checked against the counter where it counts 4x4 blocks (another run: 7
    // frames' median, its pixels counted once per fragment that passes the depth test): the
    // visible triangles' blocks are most of them, within 10 %.
    let counter = draw_counts("clipmap", "16", "1280x720").per_pixel;
    if counter > (quads + blocks) / 2.0 {
        assert!(
            blocks <= counter && counter < 1.1 * blocks,
            "4x4 blocks: {blocks:.3} from the picture, {counter:.3} counted"
        );
    }
}

/// Mean channel difference and the share of pixels off by more than 48 in a channel.
fn difference(a: &[u8], b: &[u8]) -> (f64, f64) {
    let n = (a.len() / 4) as f64;
    (mean_abs_diff(a, b), changed_pixels(a, b, 48) as f64 / n)
}

#[test]
fn both_geometries_draw_the_same_sea() {
    // One shading routine for both (water_vertex.glsl, water.frag): the pictures differ where
    // the geometry does, the silhouettes of crests and the edges of foam their slightly
    // different triangles move. Measured at 320x180 on lavapipe: calm mean 0.41, 0.02 % of
    // pixels off by more than 48; default 1.48, 0.09 %; storm 1.82, 0.48 %; 3 m above the
    // water 2.47, 0.80 %. Bounds: on a calm sea (no silhouettes) a mean of 0.7; else 3 and 1.5 %.
    // (Calm: 0.52 on 2026-12-05 under a bound of 0.6, and 0.64 once the normal images' mip
    // levels kept the ripples 10-30 m out that the fade had taken: the two surfaces' slightly
    // different points differ more where more of the slopes are drawn. The same on Mesa 25.)
    for (name, args, mean_bound) in [
        ("calm", &["--preset", "calm"][..], 0.7),
        ("default", &[][..], 3.0),
        ("storm", &["--preset", "storm"][..], 3.0),
        ("low", &["--camera=0,3,0"][..], 3.0),
    ] {
        let pictures = ["tessellated", "clipmap"].map(|geometry| {
            let mut all = vec!["--geometry", geometry];
            all.extend_from_slice(args);
            shot(&format!("geometries-{name}-{geometry}"), &all)
        });
        let (mean, changed) = difference(&pictures[0], &pictures[1]);
        assert!(
            mean <= mean_bound && changed <= 0.015,
            "{name}: mean channel difference {mean:.2} (max {mean_bound}), {:.2} % of pixels off by more than 48 (max 1.5 %)",
            changed * 100.0
        );
    }
}

#[test]
fn profile_counts_the_tessellation_and_finer_edges_cost_more() {
    let coarse = tessellation_counts("32");
    let fine = tessellation_counts("8");
    // Every patch of the 32 x 32 grid reaches the control shader (culling happens there).
    assert_eq!(coarse.patches, 1024.0);
    assert_eq!(fine.patches, 1024.0);
    // Edge levels scale with 1 / target length: 4x finer edges, many times more vertices and
    // triangles.
    let (f, c) = (&fine, &coarse);
    assert!(
        f.tess_eval > 4.0 * c.tess_eval,
        "{} vs {}",
        f.tess_eval,
        c.tess_eval
    );
    assert!(
        f.triangles > 4.0 * c.triangles,
        "{} vs {}",
        f.triangles,
        c.triangles
    );
    // The water covers about half of the 320x180 target: at least that many fragments. More
    // triangles over the same pixels never shade fewer (lavapipe, shading whole 4x4 blocks,
    // shades more; a device counting covered samples only, the same).
    assert!(c.fragments > 0.3 * 320.0 * 180.0, "{}", c.fragments);
    assert!(
        f.fragments >= c.fragments,
        "{} vs {}",
        f.fragments,
        c.fragments
    );
}

#[test]
fn a_loaded_skybox_and_dudv_map_are_used_and_bad_files_are_one_line_errors() {
    let dir = scratch("render-files");
    // Six 16x16 faces in one colour each; looking at the horizon shows the side faces' colours.
    let sky = dir.join("sky");
    std::fs::create_dir_all(&sky).unwrap();
    let colours = [
        [200u8, 40, 40],
        [40, 200, 40],
        [40, 40, 200],
        [200, 200, 40],
        [40, 200, 200],
        [200, 40, 200],
    ];
    for (face, c) in ["px", "nx", "py", "ny", "pz", "nz"].iter().zip(colours) {
        let texels: Vec<u8> = (0..16 * 16).flat_map(|_| [c[0], c[1], c[2], 255]).collect();
        image::save_buffer(
            sky.join(format!("{face}.png")),
            &texels,
            16,
            16,
            image::ColorType::Rgba8,
        )
        .unwrap();
    }
    let flat: Vec<u8> = (0..8 * 8).flat_map(|_| [128u8, 128, 128, 255]).collect();
    let dudv = dir.join("flat.png");
    image::save_buffer(&dudv, &flat, 8, 8, image::ColorType::Rgba8).unwrap();
    let p = shot(
        "skybox",
        &[
            "--skybox",
            sky.to_str().unwrap(),
            "--dudv",
            dudv.to_str().unwrap(),
        ],
    );
    // The default camera looks toward -z: the top rows are the nz face's magenta.
    let top = &p[..(W * 10 * 4) as usize];
    let [r, g, b] = mean_rgb(top);
    assert!(
        r > 150.0 && b > 150.0 && g < 80.0,
        "top of the sky {r} {g} {b}"
    );

    // Not PNGs: bad input (exit 2, as every input file's problem), one line naming the flag.
    let garbage = dir.join("garbage.png");
    std::fs::write(&garbage, b"not a png").unwrap();
    for (flag, value) in [("--dudv", &garbage), ("--skybox", &sky)] {
        if flag == "--skybox" {
            std::fs::write(sky.join("py.png"), b"not a png").unwrap();
        }
        let out = run(&["--headless", flag, value.to_str().unwrap()]);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with("vkocean: ") && err.contains(flag), "{err}");
    }
    let _ = std::fs::remove_dir_all(&dir);
}
