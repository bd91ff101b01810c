//! The CLI's defaults and refusals.

use super::*;

#[test]
fn headless_defaults() {
    let cli = Cli::parse_from(["vkocean", "--headless"]);
    assert_eq!(cli.settings().unwrap().frames, Some(1));
    let cli = Cli::parse_from(["vkocean", "--headless", "--profile", "p.json"]);
    assert_eq!(cli.settings().unwrap().frames, Some(60));
    let cli = Cli::parse_from([
        "vkocean",
        "--headless",
        "--profile",
        "p.json",
        "--frames",
        "5",
    ]);
    assert!(cli.settings().is_err());
    let cli = Cli::parse_from(["vkocean", "--screenshot", "s.jpg"]);
    assert!(cli.settings().is_err());
}

#[test]
fn screenshot_every_needs_a_headless_screenshot() {
    let every = |extra: &[&str]| {
        let mut args = vec!["vkocean", "--screenshot-every", "6"];
        args.extend_from_slice(extra);
        Cli::try_parse_from(args)
            .map_err(|e| e.to_string())?
            .settings()
            .map_err(|e| e.0)
    };
    let ok = every(&["--headless", "--screenshot", "s.png"]).unwrap();
    assert_eq!(ok.screenshot_every, Some(6));
    for extra in [&["--headless"][..], &["--screenshot", "s.png"]] {
        let err = every(extra).unwrap_err();
        assert_eq!(err, "--screenshot-every needs --headless and --screenshot");
    }
    let zero = Cli::try_parse_from(["vkocean", "--headless", "--screenshot-every", "0"]);
    assert!(zero.is_err(), "0 frames apart is refused");
}

/// `--shadows` and the caustics in the refraction view follow the quality level unless given:
/// off at low (what they cost lavapipe there, README), on at medium and high; `--caustics off`
/// takes the caustics from every view, `--caustics on` puts them in the refraction at low too.
#[test]
fn shadows_and_the_refraction_caustics_follow_the_quality_unless_given() {
    let scene = |args: &[&str]| {
        let mut all = vec!["vkocean", "--headless"];
        all.extend_from_slice(args);
        let scene = Cli::parse_from(all).settings().unwrap().scene;
        (scene.shadows, scene.caustics, scene.refraction_caustics)
    };
    assert_eq!(scene(&["--quality", "low"]), (false, true, false));
    assert_eq!(scene(&["--quality", "medium"]), (true, true, true));
    assert_eq!(scene(&["--quality", "high"]), (true, true, true));
    assert_eq!(
        scene(&["--quality", "low", "--caustics", "on", "--shadows", "on"]),
        (true, true, true)
    );
    assert_eq!(
        scene(&["--quality", "high", "--caustics", "off", "--shadows", "off"]),
        (false, false, false)
    );
    assert_eq!(
        scene(&["--quality", "medium", "--caustics", "off"]),
        (true, false, false)
    );
}

/// FXAA runs at Lottes' fastest preset at low only (what his default's search cost lavapipe
/// there, README).
#[test]
fn the_fast_fxaa_preset_follows_the_quality() {
    let fast = |quality: &str| {
        Cli::parse_from(["vkocean", "--headless", "--quality", quality])
            .settings()
            .unwrap()
            .scene
            .fxaa_fast
    };
    assert_eq!(
        [fast("low"), fast("medium"), fast("high")],
        [true, false, false]
    );
}

/// `--sharpen` follows the scale unless given: DEFAULT_SHARPEN where the scene target is scaled
/// up (low and medium), none at full size; given with `--aa off` it is a usage error (the
/// anti-aliasing pass sharpens), not given it is simply off there.
#[test]
fn the_sharpening_follows_the_render_scale_unless_given() {
    let sharpen = |args: &[&str]| {
        let mut all = vec!["vkocean", "--headless"];
        all.extend_from_slice(args);
        Cli::parse_from(all).settings().map(|s| s.scene.sharpen)
    };
    let default = DEFAULT_SHARPEN as f32;
    assert_eq!(sharpen(&["--quality", "low"]).unwrap(), default);
    assert_eq!(sharpen(&["--quality", "medium"]).unwrap(), default);
    assert_eq!(sharpen(&["--quality", "high"]).unwrap(), 0.0);
    assert_eq!(
        sharpen(&["--quality", "high", "--render-scale", "0.5"]).unwrap(),
        default
    );
    assert_eq!(
        sharpen(&["--quality", "low", "--sharpen", "0.2"]).unwrap(),
        0.2
    );
    assert_eq!(sharpen(&["--quality", "low", "--aa", "off"]).unwrap(), 0.0);
    let refused = sharpen(&["--aa", "off", "--sharpen", "0.5"]).unwrap_err();
    assert!(refused.0.contains("--aa fxaa"), "{}", refused.0);
    assert!(Cli::try_parse_from(["vkocean", "--sharpen", "1.5"]).is_err());
}

/// A live `aa = off` (the overlay, `--live-set`) after `--sharpen` was given drops the
/// sharpening with its pass instead of being refused.
#[test]
fn a_live_aa_off_takes_a_given_sharpening_with_it() {
    let cli = Cli::parse_from([
        "vkocean",
        "--headless",
        "--quality",
        "low",
        "--sharpen",
        "0.5",
    ]);
    let mut t = cli.tunables();
    t.aa = AntiAliasing::Off;
    let scene = cli.retuned(&t).settings().unwrap().scene;
    assert_eq!((scene.aa, scene.sharpen), (AntiAliasing::Off, 0.0));
    t.aa = AntiAliasing::Fxaa;
    assert_eq!(cli.retuned(&t).settings().unwrap().scene.sharpen, 0.5);
}

/// `--upscale` follows the device unless given: bilinear on a CPU device, edge-directed on the
/// others and where the device is not known.
#[test]
fn the_upscale_follows_the_device_unless_given() {
    let upscale = |args: &[&str], cpu: Option<bool>| {
        let mut all = vec!["vkocean", "--headless"];
        all.extend_from_slice(args);
        let mut cli = Cli::parse_from(all);
        cli.cpu_device = cpu;
        cli.settings().unwrap().scene.upscale
    };
    assert_eq!(upscale(&[], Some(true)), Upscale::Bilinear);
    assert_eq!(upscale(&[], Some(false)), Upscale::Edge);
    assert_eq!(upscale(&[], None), Upscale::Edge);
    assert_eq!(upscale(&["--upscale", "edge"], Some(true)), Upscale::Edge);
    assert_eq!(
        upscale(&["--upscale", "bilinear"], Some(false)),
        Upscale::Bilinear
    );
}
