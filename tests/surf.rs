//! The surf as drawn (shaders/common/shore.glsl): bores that run shoreward at the phase speed,
//! swash that runs up the beach and back no higher than Stockdon's run-up, sand darkened where
//! the sea has reached it. Pictures straight down onto the island's shores in the moderate
//! sea (--quality high), measured with the terrain's own height (`terrain_height`, the Rust twin
//! of the shader's) at each pixel's ground point.

mod common;

use common::linear;

use vkocean::ocean::shore::{kh, runup_m};
use vkocean::render::scene::terrain_height;
use vkocean::render::uniforms::SceneLayout;

const W: usize = 480;
const H: usize = 270;
/// A camera `height` m straight above (x, z), the picture's x along world x and its rows
/// along world z (`--look-at` a hair toward −z puts −z at the top).
struct TopDown {
    x: f64,
    z: f64,
    height: f64,
}

impl TopDown {
    fn args(&self) -> [String; 2] {
        [
            format!("--camera={},{},{}", self.x, self.height, self.z),
            format!("--look-at={},0,{}", self.x, self.z - 0.01),
        ]
    }

    /// Metres a pixel spans on the ground (60° vertical field of view).
    fn metres_per_px(&self) -> f64 {
        2.0 * self.height * 30f64.to_radians().tan() / H as f64
    }

    /// The ground point (x, z) under pixel (px, py).
    fn ground(&self, px: usize, py: usize) -> (f64, f64) {
        let s = self.metres_per_px();
        (
            self.x + (px as f64 + 0.5 - W as f64 / 2.0) * s,
            self.z + (py as f64 + 0.5 - H as f64 / 2.0) * s,
        )
    }

    fn shot(&self, name: &str, time: f64, extra: &[&str]) -> Vec<u8> {
        let [camera, look] = self.args();
        let time = time.to_string();
        // The bores and the swash are drawn by the water and the terrain (common/shore.glsl),
        // not by the foam simulation near the camera, whose warm-up would be two thirds of
        // each picture's cost on lavapipe. The moderate preset's clouds (half the sky) shade
        // this beach under the default sun (common/clouds.glsl: 0.1 of the sun gets through):
        // a fair day's 0.3 keeps the sun on it, whose light tells the foam from the sand.
        let mut args = vec![
            "--quality",
            "high",
            "--foam-sim",
            "off",
            "--preset",
            "moderate",
            "--clouds",
            "0.3",
            "--time",
            &time,
            &camera,
            &look,
        ];
        args.extend_from_slice(extra);
        common::shot(name, (W as u32, H as u32), &args, &[])
    }
}

fn height(x: f64, z: f64) -> f64 {
    f64::from(terrain_height(&SceneLayout::default(), x as f32, z as f32))
}

/// The moderate sea's significant height (m) and mean angular frequency (rad/s), from
/// `--dump`'s params.json (`name`: the test's own scratch directory; tests run in parallel).
fn moderate_sea(name: &str) -> (f64, f64) {
    let dir = common::scratch(&format!("surf-dump-{name}"));
    let out = common::run(&[
        "--headless",
        "--validation",
        "--size",
        "64x36",
        "--preset",
        "moderate",
        "--dump",
        dir.to_str().unwrap(),
    ]);
    common::clean_run(&out, "--dump");
    let text = std::fs::read_to_string(dir.join("params.json")).unwrap();
    let params: serde_json::Value = serde_json::from_str(&text).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let shore = &params["shore"];
    (
        shore["hs_m"].as_f64().unwrap(),
        shore["mean_omega_rad_s"].as_f64().unwrap(),
    )
}

#[test]
fn bores_run_shoreward_at_the_phase_speed() {
    // The surf zone on the island's side that faces −z, from 25 m up (0.11 m a pixel), --view
    // normals at t, t + 0.5 s and t + 1 s (t = 20 and 30 s). There the wind (+x) and the
    // simulated waves run along the shore, so what moves across it is the bores. Each
    // column's pixels are placed by their distance s seaward of that column's waterline, so
    // the bores' faces (parallel to the depth contours) line up; each column's profile of the
    // normal's z (blue) over s, 3–14 m out (0.6–2.8 m deep on this 0.2 slope), less its
    // straight-line fit. What does not move cancels in the change from one instant to the
    // next; the lag that best matches the two changes, the correlation summed over columns,
    // is how far the bores ran in 0.5 s. Expected: the phase speed ω̄/k(d) of linear theory
    // averaged over the window, times 0.5 s (2.0 m), within −20 %/+25 % (a bin is 0.25 m, and
    // the simulated waves' own slopes add noise). Measured on lavapipe: 2.0 m.
    let (_, omega) = moderate_sea("bores");
    let camera = TopDown {
        x: -420.0,
        z: -1168.0,
        height: 25.0,
    };
    let dt = 0.5;
    let bin_m = 0.25;
    let (near, far) = (3.0, 14.0);
    let bins = ((far - near) / bin_m) as usize;
    let waterline: Vec<f64> = (0..W)
        .map(|px| {
            // From the island's side (its centre is at z = −900) out to the water.
            let (x, _) = camera.ground(px, 0);
            let mut z = -1000.0;
            while height(x, z) > 0.0 {
                z -= 0.05;
            }
            z
        })
        .collect();
    // Per column: the profile over s (water pixels), less its straight-line fit (the bores'
    // height grows with the depth: a trend that does not move); none where a bin is empty.
    let profiles = |pixels: &[u8]| -> Vec<Vec<f64>> {
        (0..W)
            .map(|px| {
                let mut sum = vec![0.0; bins];
                let mut count = vec![0usize; bins];
                for py in 0..H {
                    let (x, z) = camera.ground(px, py);
                    let s = waterline[px] - z;
                    if s >= near && s < far && height(x, z) < -0.1 {
                        let b = ((s - near) / bin_m) as usize;
                        sum[b] += f64::from(pixels[4 * (py * W + px) + 2]);
                        count[b] += 1;
                    }
                }
                if count.contains(&0) {
                    return vec![0.0; bins];
                }
                detrended(
                    &sum.iter()
                        .zip(&count)
                        .map(|(s, &c)| s / c.max(1) as f64)
                        .collect::<Vec<_>>(),
                )
            })
            .collect()
    };
    // Two runs of three instants, 10 s apart: the changes over the first and second half
    // second.
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for t in [20.0, 30.0] {
        let view = ["--view", "normals"];
        let [p0, p1, p2] = [0.0, dt, 2.0 * dt]
            .map(|d| profiles(&camera.shot(&format!("surf-run-{}", t + d), t + d, &view)));
        let change = |x: &[Vec<f64>], y: &[Vec<f64>]| -> Vec<Vec<f64>> {
            x.iter()
                .zip(y)
                .map(|(p, q)| p.iter().zip(q).map(|(u, v)| v - u).collect())
                .collect()
        };
        a.extend(change(&p0, &p1));
        b.extend(change(&p1, &p2));
    }
    // b(s) = a(s − lag), each column's own alignment kept: the best lag within ±6 m.
    let max_lag = (6.0 / bin_m) as i64;
    let score = |lag: i64| -> f64 {
        let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
        for (ra, rb) in a.iter().zip(&b) {
            for (i, &bv) in rb.iter().enumerate() {
                let j = i as i64 - lag;
                if (0..bins as i64).contains(&j) {
                    let av = ra[j as usize];
                    sab += av * bv;
                    saa += av * av;
                    sbb += bv * bv;
                }
            }
        }
        sab / (saa * sbb).sqrt().max(1e-12)
    };
    let (best, corr) = (-max_lag..=max_lag)
        .map(|l| (l, score(l)))
        .max_by(|x, y| x.1.total_cmp(&y.1))
        .unwrap();
    let moved_m = best as f64 * bin_m;
    let column = W / 2;
    let speeds: Vec<f64> = (0..bins)
        .map(|i| {
            let s = near + (i as f64 + 0.5) * bin_m;
            let depth = -height(camera.x, waterline[column] - s);
            omega * depth / kh(omega, depth)
        })
        .collect();
    let expected = -dt * speeds.iter().sum::<f64>() / bins as f64;
    eprintln!(
        "bores moved {moved_m:.2} m in {dt} s (correlation {corr:.2}, at rest {:.2}); \
         expected {expected:.2} m",
        score(0)
    );
    assert!(corr > 0.5, "the two profiles do not match: {corr}");
    assert!(
        moved_m < 0.0 && (0.8..1.25).contains(&(moved_m / expected)),
        "bores moved {moved_m} m, expected {expected} m (shoreward: negative)"
    );
}

/// `p` less its least-squares straight line.
fn detrended(p: &[f64]) -> Vec<f64> {
    let n = p.len() as f64;
    let (mx, my) = ((n - 1.0) / 2.0, p.iter().sum::<f64>() / n);
    let sxy: f64 = p
        .iter()
        .enumerate()
        .map(|(i, y)| (i as f64 - mx) * (y - my))
        .sum();
    let sxx: f64 = (0..p.len()).map(|i| (i as f64 - mx).powi(2)).sum();
    p.iter()
        .enumerate()
        .map(|(i, y)| y - my - sxy / sxx * (i as f64 - mx))
        .collect()
}

#[test]
fn the_swash_runs_up_the_beach_and_back_and_wets_the_sand() {
    // The beach from 30 m up (0.13 m a pixel) at eight instants a second apart (more than a
    // wave period, 6.6 s). Land pixels are binned by their height over the 2 % run-up R₂ of
    // Stockdon et al. (2006) at their own slope. The swash's foam (white: max − min of the
    // channels under 0.3 of the max, where the sand has 0.42–0.46, and a linear luminance
    // over 0.3: the sunlit foam has 0.42, dry sand 0.29) reaches up to a height that changes from shot to shot by
    // at least 0.25·R₂ (it runs up and back), never above 1.1·R₂ and at least once above
    // 0.4·R₂. Sand below 0.6·R₂ that the foam does not cover is darker than the dry sand at
    // 1.2–1.8·R₂ (below the grass) in linear luminance: ratio ≤ 0.8 (soaked sand is 0.68 of
    // dry, damp 0.84; the sheet over soaked sand about as dark).
    let (hs, omega) = moderate_sea("swash");
    let camera = TopDown {
        x: -165.0,
        z: -900.0,
        height: 30.0,
    };
    // Per pixel: its height over R₂ at its slope, or None for water and rock.
    let over_runup: Vec<Option<f64>> = (0..W * H)
        .map(|i| {
            let (x, z) = camera.ground(i % W, i / W);
            let y = height(x, z);
            let slope = (height(x + 0.5, z) - height(x - 0.5, z))
                .hypot(height(x, z + 0.5) - height(x, z - 0.5));
            (y > 0.05 && slope < 0.5).then(|| y / runup_m(hs, omega, slope.max(0.02)))
        })
        .collect();
    let mut reach = Vec::new();
    let (mut wet, mut dry) = ((0.0, 0usize), (0.0, 0usize));
    for k in 0..8 {
        let pixels = camera.shot(&format!("swash-{k}"), 20.0 + k as f64, &[]);
        let mut white: Vec<f64> = Vec::new();
        for (c, r) in pixels.chunks(4).zip(&over_runup) {
            let Some(r) = *r else { continue };
            let [red, green, blue] = [c[0], c[1], c[2]].map(linear);
            let luminance = 0.2126 * red + 0.7152 * green + 0.0722 * blue;
            let (max, min) = (c[0].max(c[1]).max(c[2]), c[0].min(c[1]).min(c[2]));
            if f64::from(max - min) < 0.3 * f64::from(max) && luminance > 0.3 {
                white.push(r);
            } else if (0.05..0.6).contains(&r) {
                wet = (wet.0 + luminance, wet.1 + 1);
            } else if (1.2..1.8).contains(&r) {
                dry = (dry.0 + luminance, dry.1 + 1);
            }
        }
        white.sort_by(f64::total_cmp);
        let top = if white.len() >= 50 {
            white[white.len() * 98 / 100]
        } else {
            0.0
        };
        eprintln!(
            "t = {}: {} px of swash foam, up to {top:.2} R2",
            20 + k,
            white.len()
        );
        reach.push(top);
    }
    let highest = reach.iter().cloned().fold(0.0, f64::max);
    let lowest = reach.iter().cloned().fold(f64::MAX, f64::min);
    let ratio = (wet.0 / wet.1.max(1) as f64) / (dry.0 / dry.1.max(1) as f64);
    eprintln!(
        "Hs {hs:.2} m, ω {omega:.3}: reach {lowest:.2}–{highest:.2} R2; wet/dry luminance \
         {ratio:.3} ({} and {} px)",
        wet.1, dry.1
    );
    assert!(
        (0.4..=1.1).contains(&highest),
        "the swash reached {highest} R2"
    );
    assert!(
        highest - lowest >= 0.25,
        "the swash's reach only moved from {lowest} to {highest} R2"
    );
    assert!(
        wet.1 > 2000 && dry.1 > 2000,
        "{} wet, {} dry px",
        wet.1,
        dry.1
    );
    assert!(ratio <= 0.8, "wet sand / dry sand luminance {ratio}");
}
