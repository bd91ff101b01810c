//! The command-line contract: every bad input gives one clear line on stderr and its exit code
//! (2 bad usage, 1 runtime failure), never a panic, and no output file is left behind.

mod common;

use common::{assert_one_line, entries, run, run_with_env, scratch, stderr};

/// Asserts exit `code`, exactly one stderr line starting `vkocean: ` that contains `needle`
/// (`common::assert_one_line`), and nothing on stdout.
fn assert_fails(args: &[&str], env: &[(&str, &str)], code: i32, needle: &str) {
    let out = run_with_env(args, env);
    assert_one_line(&out, code, needle, &format!("{args:?}"));
    assert!(out.stdout.is_empty(), "{args:?}: stdout should be empty");
}

#[test]
fn bad_usage_exits_2_with_one_line() {
    let cases: &[(&[&str], &str)] = &[
        (&["--headless", "--frames", "0"], "--frames"),
        (&["--headless", "--frames", "-1"], "--frames"),
        (&["--headless", "--frames", "1e3"], "not a whole number"),
        (&["--headless", "--frames", "abc"], "not a whole number"),
        (&["--headless", "--size", "0x0"], "--size"),
        (&["--headless", "--size", "100000x10"], "from 1 to 16384"),
        (&["--headless", "--size", "1280"], "WIDTHxHEIGHT"),
        (&["--headless", "--size", "wxh"], "WIDTHxHEIGHT"),
        (
            &["--headless", "--present-mode", "bogus"],
            "possible values: fifo, mailbox, immediate",
        ),
        (&["--headless", "--gpu", "x"], "--gpu"),
        (&["--headless", "--no-such-flag"], "--no-such-flag"),
        (
            &["--headless", "--screenshot", "shot.jpg"],
            "must end in .png",
        ),
        (&["--headless", "--profile", "p.txt"], "must end in .json"),
        (
            &["--headless", "--profile", "p.json", "--frames", "5"],
            "warm-up",
        ),
        (
            &["--headless", "--spectrum", "bogus"],
            "possible values: phillips, jonswap, pierson-moskowitz",
        ),
        (&["--headless", "--wind-speed", "0"], "--wind-speed"),
        (&["--headless", "--wind-speed", "-3"], "greater than 0"),
        (&["--headless", "--wind-speed", "nan"], "--wind-speed"),
        (&["--headless", "--wind-speed", "fast"], "not a number"),
        (&["--headless", "--wind-dir", "inf"], "--wind-dir"),
        (&["--headless", "--fetch", "0"], "--fetch"),
        (&["--headless", "--depth", "0"], "--depth"),
        (&["--headless", "--depth", "-5"], "--depth"),
        (&["--headless", "--fft-size", "100"], "power of two"),
        (&["--headless", "--fft-size", "2048"], "power of two"),
        (&["--headless", "--patch-size", "0"], "--patch-size"),
        (&["--headless", "--choppiness", "-1"], "--choppiness"),
        (&["--headless", "--choppiness", "NaN"], "--choppiness"),
        (&["--headless", "--cascades", "0"], "--cascades"),
        (&["--headless", "--cascades", "5"], "from 1 to 4"),
        (&["--headless", "--seed", "-1"], "--seed"),
        (
            &["--headless", "--waves", "sines"],
            "possible values: fft, gerstner",
        ),
        (
            &[
                "--headless",
                "--waves",
                "gerstner",
                "--gerstner-count",
                "14",
            ],
            "only 13 waves",
        ),
        (
            &["--headless", "--waves", "gerstner", "--gerstner-count", "0"],
            "--gerstner-count",
        ),
        (
            &["--headless", "--gerstner-count", "3"],
            "need --waves gerstner",
        ),
        (
            &[
                "--headless",
                "--waves",
                "gerstner",
                "--gerstner-waves",
                "/nonexistent/waves.csv",
            ],
            "--gerstner-waves",
        ),
        (
            &["--headless", "--camera", "1,2"],
            "3 comma-separated numbers",
        ),
        (
            &["--headless", "--camera", "0,-61,0"],
            "at most 60 m under the water",
        ),
        (&["--headless", "--camera", "0,nan,0"], "--camera"),
        (&["--headless", "--look-at", "0,12,0"], "--look-at"),
        (&["--headless", "--look-at", "0,50,0"], "straight above"),
        (&["--headless", "--view", "sideways"], "--view"),
        (&["--headless", "--fresnel", "fake"], "--fresnel"),
        (&["--headless", "--rtt-scale", "0"], "--rtt-scale"),
        (&["--headless", "--tess-edge", "1"], "--tess-edge"),
        (&["--headless", "--render-scale", "0.2"], "--render-scale"),
        (&["--headless", "--render-scale", "inf"], "--render-scale"),
        (&["--headless", "--terrain-grid", "8"], "--terrain-grid"),
        (&["--headless", "--terrain-grid", "4096"], "--terrain-grid"),
        (&["--headless", "--sun", "0,95"], "elevation"),
        (
            &["--headless", "--dudv", "/nonexistent/d.png"],
            "no such file",
        ),
        (&["--headless", "--dudv", "d.jpg"], "must end in .png"),
        (
            &["--headless", "--skybox", "/nonexistent"],
            "no such directory",
        ),
        (&["--headless", "--sea-floor", "0"], "--sea-floor"),
        (&["--headless", "--dt", "0"], "--dt"),
        (&["--headless", "--time", "-1"], "--time"),
        (&["--headless", "--buoy", "1,inf"], "--buoy"),
        (&["--headless", "--boat", "12,0"], "from 0.5 to 10 m/s"),
        (&["--headless", "--boat", "3"], "--boat"),
        (&["--headless", "--boat", "3,nan"], "--boat"),
        (
            &["--headless", "--bodies", "256", "--boat", "3,0"],
            "the boat is a body too",
        ),
        (
            &["--headless", "--quality", "ultra"],
            "possible values: low, medium, high",
        ),
        (
            &["--headless", "--preset", "hurricane"],
            "possible values: calm, breeze, moderate, storm",
        ),
        (&["--headless", "--config", "c.txt"], "must end in .toml"),
        (
            &["--headless", "--config", "/nonexistent/c.toml"],
            "--config /nonexistent/c.toml",
        ),
    ];
    for (args, needle) in cases {
        assert_fails(args, &[], 2, needle);
    }
}

#[test]
fn gpu_index_out_of_range_is_usage_error() {
    assert_fails(&["--headless", "--gpu", "99"], &[], 2, "--gpu 99");
}

#[test]
fn unwritable_outputs_fail_before_rendering() {
    assert_fails(
        &["--headless", "--screenshot", "/nonexistent-dir/s.png"],
        &[],
        1,
        "cannot write --screenshot",
    );
    assert_fails(
        &["--headless", "--profile", "/nonexistent-dir/p.json"],
        &[],
        1,
        "cannot write --profile",
    );
}

#[test]
fn failed_run_leaves_no_partial_file() {
    let dir = scratch("no-partial");
    let shot = dir.join("shot.png");
    let profile = dir.join("p.json");
    // The output paths are fine, the run fails later (device choice).
    let args = [
        "--headless",
        "--screenshot",
        shot.to_str().unwrap(),
        "--profile",
        profile.to_str().unwrap(),
        "--gpu",
        "99",
    ];
    assert_fails(&args, &[], 2, "--gpu 99");
    assert!(entries(&dir).is_empty(), "left behind: {:?}", entries(&dir));
}

#[test]
fn missing_loader_is_reported() {
    assert_fails(
        &["--headless"],
        &[("VKOCEAN_VULKAN_LIBRARY", "/nonexistent/libvulkan.so.1")],
        1,
        "Vulkan loader",
    );
}

#[test]
fn missing_device_is_reported() {
    let env = [
        ("VK_ICD_FILENAMES", "/nonexistent/icd.json"),
        ("VK_DRIVER_FILES", "/nonexistent/icd.json"),
    ];
    assert_fails(&["--headless"], &env, 1, "no Vulkan device found");
}

#[test]
fn missing_validation_layer_is_reported() {
    let empty = scratch("no-layers");
    let env = [("VK_LAYER_PATH", empty.to_str().unwrap())];
    assert_fails(
        &["--headless", "--validation"],
        &env,
        1,
        "VK_LAYER_KHRONOS_validation is not installed",
    );
}

#[test]
fn unknown_validation_extra_is_usage_error() {
    for list in ["bogus", "best-practices,nope", ""] {
        let name = list.rsplit(',').next().unwrap_or_default();
        assert_fails(
            &["--headless", "--validation-extra", list],
            &[],
            2,
            &format!("unknown check '{name}' (known: best-practices, vendors, gpu-assisted)"),
        );
    }
    assert_fails(
        &["bench", "fft", "--validation-extra", "bogus"],
        &[],
        2,
        "unknown check 'bogus'",
    );
}

/// `--validation-extra best-practices` turns Best Practices on (`VkValidationFeaturesEXT`, in
/// every layer version). Under the newest layer (tools/newest-layer, fetched by
/// tools/validate-newest into target/newest-layer) the run must be clean; the installed layer
/// may report Best Practices advice only (Debian 12's 1.3.239 reports three ids that 1.4.364
/// no longer reports: README, Validation), never a core or synchronization message. The vendor
/// checks need VK_EXT_layer_settings: without it, one line saying so.
#[test]
fn validation_extra_best_practices() {
    let args = [
        "--validation-extra",
        "best-practices",
        "--headless",
        "--size",
        "160x90",
        "--frames",
        "3",
    ];
    let out = run(&args);
    let err = stderr(&out);
    match out.status.code() {
        Some(0) => {
            common::clean_run(&out, "best-practices, installed layer");
        }
        Some(3) => {
            assert_eq!(
                common::validation_counts(&err).map(|c| c.1),
                Some(0),
                "{err}"
            );
            for line in err.lines().filter(|l| l.starts_with('[')) {
                assert!(line.contains("BestPractices"), "not Best Practices: {line}");
            }
        }
        code => panic!("exit {code:?}: {err}"),
    }

    let newest = std::env::var("VKOCEAN_NEWEST_LAYER")
        .map(std::path::PathBuf::from)
        .unwrap_or_else(|_| {
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("target/newest-layer")
        });
    if newest.join("VkLayer_khronos_validation.json").is_file() {
        let env = [("VK_LAYER_PATH", newest.to_str().expect("a UTF-8 path"))];
        common::clean_run(&run_with_env(&args, &env), "best-practices, newest layer");
    } else {
        eprintln!(
            "no newest layer in {} (tools/newest-layer): its clean run not checked",
            newest.display()
        );
    }

    let vendors = run(&[
        "--validation-extra",
        "vendors",
        "--headless",
        "--size",
        "16x16",
    ]);
    if vendors.status.code() == Some(1) {
        assert_one_line(&vendors, 1, "has no VK_EXT_layer_settings", "vendors");
    } else {
        assert!(
            matches!(vendors.status.code(), Some(0 | 3)),
            "{}",
            stderr(&vendors)
        );
    }
}

#[test]
fn window_without_display_says_use_headless() {
    let out = std::process::Command::new(common::bin())
        .args(["--frames", "1"])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("runs");
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("--headless"), "{err}");
}

#[test]
fn help_and_device_list() {
    let out = run(&["--help"]);
    assert_eq!(out.status.code(), Some(0));
    let help = String::from_utf8_lossy(&out.stdout);
    for flag in [
        "--headless",
        "--frames",
        "--size",
        "--screenshot",
        "--validation",
        "--profile",
        "--gpu",
        "--list-gpus",
        "--present-mode",
        "--spectrum",
        "--wind-speed",
        "--wind-dir",
        "--fetch",
        "--depth",
        "--fft-size",
        "--patch-size",
        "--choppiness",
        "--cascades",
        "--seed",
        "--aa",
    ] {
        assert!(help.contains(flag), "help lacks {flag}");
    }
    assert!(
        !help.contains("inject-sync-hazard"),
        "test-only flag must stay hidden"
    );

    let out = run(&["--list-gpus"]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let list = String::from_utf8_lossy(&out.stdout);
    assert!(
        list.lines().next().is_some_and(|l| l.starts_with("0: ")),
        "{list}"
    );
}

#[test]
fn config_file_errors_name_the_key() {
    let dir = scratch("config-errors");
    let cases: &[(&str, &str)] = &[
        ("wind-speeed = 14\n", "unknown key 'wind-speeed'"),
        ("[ocean]\nwind-speed = 3\n", "unknown key 'ocean'"),
        (
            "wind-speed = \"fast\"\n",
            "'--wind-speed <M_S>': not a number",
        ),
        ("wind-speed = nan\n", "--wind-speed"),
        ("fft-size = 100\n", "--fft-size"),
        ("cascades = 9\n", "--cascades"),
        ("camera = [0, 12]\n", "--camera"),
        (
            "camera = [0, true, 1]\n",
            "key 'camera': expected a list of numbers",
        ),
        (
            "validation = 3\n",
            "key 'validation': expected true or false",
        ),
        ("quality = \"ultra\"\n", "--quality"),
        ("config = \"other.toml\"\n", "unknown key 'config'"),
        ("background = \"1,0,1\"\n", "unknown key 'background'"),
        (
            "wind-speed = \n",
            "line 1, column 14: string values must be quoted",
        ),
        ("a = 1\na = 2\n", "line 2, column 1: duplicate key"),
        (
            "wind-speed = 3\nwind_speed = 4\n",
            "keys 'wind-speed' and 'wind_speed' name the same setting",
        ),
        (
            "seed = 18446744073709551615\n",
            "write a larger seed as a string",
        ),
        ("spectrum = 3\n", "--spectrum"),
    ];
    for (i, (text, needle)) in cases.iter().enumerate() {
        let path = dir.join(format!("bad{i}.toml"));
        std::fs::write(&path, text).unwrap();
        let shown = format!("--config {}", path.display());
        assert_fails(
            &["--headless", "--config", path.to_str().unwrap()],
            &[],
            2,
            needle,
        );
        assert_fails(
            &["--headless", "--config", path.to_str().unwrap()],
            &[],
            2,
            &shown,
        );
    }
}

#[test]
fn config_and_presets_apply_and_the_command_line_wins() {
    let dir = scratch("config-apply");
    let config = dir.join("sea.toml");
    std::fs::write(
        &config,
        "# a storm, made lighter on the command line\npreset = \"storm\"\nfetch = 300\nheadless = true\nsize = \"32x32\"\nquality = \"low\"\n",
    )
    .unwrap();
    let dump = dir.join("dump");
    let out = run(&[
        "--config",
        config.to_str().unwrap(),
        "--wind-speed",
        "20",
        "--dump",
        dump.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
    let params: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dump.join("params.json")).unwrap()).unwrap();
    // The command line beats the preset; the file's own key beats the preset; the preset fills
    // the rest; --quality low sets the grid (FFT size 64; its 3 cascades are also the default).
    assert_eq!(params["wind_speed_m_s"], 20.0, "{params}");
    assert_eq!(params["fetch_km"], 300.0, "{params}");
    assert_eq!(params["choppiness"], 1.2, "{params}");
    assert_eq!(params["patch_sizes_m"][0], 1000.0, "{params}");
    assert_eq!(params["fft_size"], 64, "{params}");
    assert_eq!(params["cascades"], 3, "{params}");

    // Each preset is its Beaufort force's mid-range wind.
    for (preset, wind) in [
        ("calm", 2.5),
        ("breeze", 6.7),
        ("moderate", 12.3),
        ("storm", 26.5),
    ] {
        let out = run(&[
            "--headless",
            "--size",
            "16x16",
            "--fft-size",
            "64",
            "--cascades",
            "1",
            "--preset",
            preset,
            "--dump",
            dump.to_str().unwrap(),
        ]);
        assert_eq!(out.status.code(), Some(0), "{}", stderr(&out));
        let params: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dump.join("params.json")).unwrap())
                .unwrap();
        assert_eq!(params["wind_speed_m_s"], wind, "{preset}: {params}");
    }
}
