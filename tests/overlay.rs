//! The overlay (egui, F1 / `--overlay`) and the settings API it edits: the overlay draws only
//! inside its panel; a live change (`--live-set`, the overlay's path: tunables → the flags'
//! resolution → `Session::retune`) makes the same sea as the flag; saved settings read back.

mod common;

use common::*;

/// `vkocean: overlay drawn at X,Y size WxH` → (x, y, w, h).
fn overlay_rect(stderr: &str) -> Option<(u32, u32, u32, u32)> {
    let line = stderr
        .lines()
        .find_map(|l| l.strip_prefix("vkocean: overlay drawn at "))?;
    let (at, size) = line.split_once(" size ")?;
    let (x, y) = at.split_once(',')?;
    let (w, h) = size.split_once('x')?;
    Some((
        x.parse().ok()?,
        y.parse().ok()?,
        w.parse().ok()?,
        h.parse().ok()?,
    ))
}

#[test]
fn the_overlay_changes_only_its_panel_validation_clean() {
    let dir = scratch("overlay-region");
    let (w, h) = (640u32, 480u32);
    let shot = |name: &str, extra: &[&str]| {
        let png = dir.join(name);
        let mut args = vec![
            "--headless",
            "--validation",
            "--size",
            "640x480",
            "--frames",
            "3",
            "--screenshot",
            png.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let out = run(&args);
        let err = clean_run(&out, name);
        (read_png(&png).2, err)
    };
    let (plain, _) = shot("plain.png", &[]);
    let (with, err) = shot("overlay.png", &["--overlay"]);
    let (x0, y0, rw, rh) = overlay_rect(&err).expect("the run reports the panel's rectangle");
    assert!(rw > 100 && rh > 100, "a panel, not a speck: {rw}x{rh}");
    assert!((x0 + rw) < w && (y0 + rh) < h, "the panel fits the picture");
    // Outside the panel (and egui's 1-pixel feathering around it): the same bytes.
    let (mut inside_changed, mut outside_changed) = (0u64, 0u64);
    for y in 0..h {
        for x in 0..w {
            let i = ((y * w + x) * 4) as usize;
            let differs = plain[i..i + 3] != with[i..i + 3];
            let inside = x + 2 >= x0 && x <= x0 + rw + 2 && y + 2 >= y0 && y <= y0 + rh + 2;
            match (differs, inside) {
                (true, true) => inside_changed += 1,
                (true, false) => outside_changed += 1,
                _ => {}
            }
        }
    }
    assert_eq!(outside_changed, 0, "pixels changed outside the panel");
    // The panel is opaque: nearly every pixel in it differs from the ocean under it.
    let area = (rw * rh) as u64;
    assert!(
        inside_changed * 10 > area * 9,
        "{inside_changed} of {area} panel pixels changed"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The dump files of a headless run of 3 frames with `args`.
fn dump(name: &str, args: &[&str]) -> Vec<(String, Vec<u8>)> {
    let dir = scratch(name);
    let mut all = vec![
        "--headless",
        "--quality",
        "low",
        "--frames",
        "3",
        "--dump",
        dir.to_str().unwrap(),
    ];
    all.extend_from_slice(args);
    let out = run(&all);
    assert_eq!(out.status.code(), Some(0), "{all:?}: {}", stderr(&out));
    let files = entries(&dir)
        .into_iter()
        .map(|f| {
            let bytes = std::fs::read(dir.join(&f)).unwrap();
            (f, bytes)
        })
        .collect();
    let _ = std::fs::remove_dir_all(&dir);
    files
}

#[test]
fn a_live_change_makes_the_same_sea_as_the_flag() {
    // Wind, fetch, depth, choppiness, spectrum and seed rebuild h0; the cascades the grid.
    let flags = [
        "--wind-speed=15",
        "--fetch=300",
        "--depth=40",
        "--choppiness=1.5",
        "--spectrum=pierson-moskowitz",
        "--seed=7",
        "--cascades=2",
    ];
    let live = "wind-speed=15;fetch=300;depth=40;choppiness=1.5;spectrum=pierson-moskowitz;seed=7;cascades=2";
    let by_flag = dump("live-flag", &flags);
    let by_live = dump("live-set", &["--live-set", live]);
    let before = dump("live-none", &[]);
    let names: Vec<&String> = by_flag.iter().map(|f| &f.0).collect();
    assert_eq!(
        names,
        by_live.iter().map(|f| &f.0).collect::<Vec<_>>(),
        "the same files"
    );
    for ((name, a), (_, b)) in by_flag.iter().zip(&by_live) {
        match name.as_str() {
            // The foam (channel 3) accumulates over frames, and a live change starts it anew.
            "normals.npy" => {
                let (a, b) = (npy_f32(a).1, npy_f32(b).1);
                assert_eq!(a.len(), b.len());
                for (i, (x, y)) in a.iter().zip(&b).enumerate() {
                    if i % 4 != 3 {
                        assert_eq!(x, y, "normals.npy value {i}");
                    }
                }
            }
            // The spray's puffs, too, are the frames' history.
            "spray.npy" => {}
            _ => assert!(
                a == b,
                "{name} differs between the flag and the live change"
            ),
        }
    }
    // And the change did something: the sea differs from the unchanged run's.
    let displacement = |files: &[(String, Vec<u8>)]| {
        files
            .iter()
            .find(|f| f.0 == "displacement.npy")
            .unwrap()
            .1
            .clone()
    };
    assert!(displacement(&before) != displacement(&by_flag));
}

#[test]
fn a_live_change_of_the_look_matches_the_flag_in_the_picture() {
    let size = (320, 180);
    // The water geometry too: the live change makes a new water pass (the default here,
    // clipmap, becomes the tessellated one).
    let flags = [
        "--frames",
        "3",
        "--sun=40,25",
        "--clouds=0.7",
        "--slicks=0.6",
        "--render-scale=0.75",
        "--geometry=tessellated",
        "--gusts=off",
    ];
    let live = [
        "--frames",
        "3",
        "--live-set",
        "sun-azimuth=40;sun-elevation=25;clouds=0.7;slicks=0.6;render-scale=0.75;geometry=tessellated;gusts=off",
    ];
    let a = shot("look-flag", size, &flags, &[]);
    let b = shot("look-live", size, &live, &[]);
    let c = shot("look-none", size, &["--frames", "3"], &[]);
    assert!(a == b, "mean difference {}", mean_abs_diff(&a, &b));
    assert!(mean_abs_diff(&a, &c) > 2.0, "the change shows");
}

#[test]
fn gusts_turn_on_and_off_live_as_the_flag_does() {
    // A change of the gusts alone is a uniform (`Session::retune` keeps the renderer): both
    // ways, each against the flag, and the switch shows in the picture. The sun is given: a
    // live change passes every tunable as its flag, and the default sun's direction does not
    // come back bit for bit through its azimuth and elevation in degrees.
    let size = (320, 180);
    let frames = ["--frames", "3", "--sun=40,25"];
    let shot_with = |name: &str, extra: &[&str]| {
        let args: Vec<&str> = frames.iter().chain(extra).copied().collect();
        shot(name, size, &args, &[])
    };
    let off = shot_with("gusts-off-flag", &["--gusts=off"]);
    let on = shot_with("gusts-on-flag", &["--gusts=on"]);
    let diff = mean_abs_diff(&on, &off);
    assert!(
        diff > 0.05,
        "the gusts change the picture: mean difference {diff}"
    );
    let off_live = shot_with("gusts-off-live", &["--live-set", "gusts=off"]);
    assert!(
        off_live == off,
        "mean difference {}",
        mean_abs_diff(&off_live, &off)
    );
    let on_live = shot_with("gusts-on-live", &["--gusts=off", "--live-set", "gusts=on"]);
    assert!(
        on_live == on,
        "mean difference {}",
        mean_abs_diff(&on_live, &on)
    );
}

#[test]
fn a_bad_live_change_is_one_line_and_exit_2() {
    for (pair, says) in [
        ("wind-speed=500", "wind-speed=500: expected a number"),
        ("gusts=maybe", "gusts=maybe: expected on or off"),
    ] {
        let out = run(&["--headless", "--live-set", pair]);
        assert_eq!(out.status.code(), Some(2));
        let err = stderr(&out);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains(says), "{err}");
    }
}

#[test]
fn saved_settings_read_back_to_the_same_tunables() {
    use clap::Parser;
    use vkocean::cli::Cli;
    let dir = scratch("overlay-save");
    let cli = Cli::try_parse_from([
        "vkocean",
        "--preset",
        "storm",
        "--quality",
        "medium",
        "--depth",
        "35.5",
        "--seed",
        "18446744073709551615",
        "--sun=-20.25,7.5",
        "--view",
        "normals",
        "--fresnel",
        "exact",
        "--aa",
        "off",
        "--time-scale",
        "0.5",
        "--slicks",
        "0.25",
        "--waves",
        "gerstner",
        "--geometry",
        "tessellated",
        "--gusts",
        "off",
    ])
    .unwrap();
    let mut tunables = cli.tunables();
    tunables.camera = Some(([1.5, 20.0, -3.0], [10.0, 0.0, -100.0]));
    let path = dir.join("saved.toml");
    std::fs::write(&path, tunables.to_toml()).unwrap();
    let args = vkocean::cli::with_config(vec![
        "vkocean".into(),
        "--config".into(),
        path.clone().into_os_string(),
    ])
    .unwrap();
    let read = Cli::try_parse_from(args).unwrap();
    assert_eq!(read.tunables(), tunables);
    // The resolved settings agree too (what the run would do with them).
    let (a, b) = (
        cli.retuned(&tunables).settings().unwrap(),
        read.settings().unwrap(),
    );
    assert_eq!(a.ocean, b.ocean);
    assert_eq!(format!("{:?}", a.scene), format!("{:?}", b.scene));
    assert_eq!(a.time_scale, b.time_scale);
    let _ = std::fs::remove_dir_all(&dir);
}
