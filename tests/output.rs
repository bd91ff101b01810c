//! The output pass's drawn path (src/render/passes/output.rs): when it scales, or where the
//! output image takes no copies (a swapchain without TRANSFER_DST), the picture is drawn into
//! it as a colour attachment. `VKOCEAN_OUTPUT=draw` forces that path headless and
//! `VKOCEAN_OUTPUT=transfer` the copy or blit; on lavapipe the drawn picture equals the copy's
//! exactly at `--render-scale 1` (nearest sampling at texel centres, sRGB decoded and encoded
//! again) and the bilinear blit's within `SCALED_TOLERANCE` levels when it scales,
//! validation-clean, for an sRGB and a UNORM output.

mod common;

const SIZE: (u32, u32) = (240, 136);

/// Largest difference of one channel (0..255) allowed between the bilinear blit and the
/// bilinear sample that replaces it: both filter with 8-bit weights on lavapipe, rounded
/// differently.
const SCALED_TOLERANCE: i32 = 2;

/// A picture with `VKOCEAN_OUTPUT=mode` (`draw`, `transfer`; "" leaves it unset: the default).
fn shot(name: &str, args: &[&str], mode: &str) -> Vec<u8> {
    let mut all = vec!["--time", "5", "--fft-size", "64", "--quality", "low"];
    all.extend_from_slice(args);
    let env: &[(&str, &str)] = if mode.is_empty() {
        &[]
    } else {
        &[("VKOCEAN_OUTPUT", mode)]
    };
    common::shot(&format!("output-{name}-{mode}"), SIZE, &all, env)
}

/// (largest channel difference, pixels that differ at all).
fn difference(a: &[u8], b: &[u8]) -> (i32, usize) {
    assert_eq!(a.len(), b.len());
    let max = a
        .iter()
        .zip(b)
        .map(|(x, y)| (*x as i32 - *y as i32).abs())
        .max()
        .unwrap_or(0);
    let pixels = a
        .chunks(4)
        .zip(b.chunks(4))
        .filter(|(p, q)| p[..3] != q[..3])
        .count();
    (max, pixels)
}

/// Compares the transfer path with the drawn one; returns the drawn picture.
fn compare(name: &str, args: &[&str], tolerance: i32) -> Vec<u8> {
    let copied = shot(name, args, "transfer");
    let drawn = shot(name, args, "draw");
    let (max, pixels) = difference(&copied, &drawn);
    eprintln!("{name}: largest difference {max}, {pixels} pixels differ");
    assert!(
        max <= tolerance,
        "{name}: the drawn output differs from the copy by up to {max} (> {tolerance}) in \
         {pixels} pixels"
    );
    // Not a black or empty picture that would trivially match.
    assert!(copied.chunks(4).any(|p| p[..3] != copied[..3]));
    drawn
}

#[test]
fn the_drawn_output_equals_the_copy_at_full_scale() {
    compare("copy", &["--render-scale", "1", "--aa", "off"], 0);
    compare("copy-aa", &["--render-scale", "1", "--aa", "fxaa"], 0);
}

/// Scaling draws by default (the draw was faster than the blit on lavapipe: output.rs): the
/// default picture is the drawn one, bit for bit. `--upscale bilinear` (the default on a CPU
/// device) draws what the blit does; `--upscale edge` (tests/anti_aliasing.rs measures it)
/// differs.
#[test]
fn the_drawn_output_matches_the_blit_when_scaling() {
    let args = [
        "--render-scale",
        "0.5",
        "--aa",
        "fxaa",
        "--upscale",
        "bilinear",
    ];
    let drawn = compare("scaled", &args, SCALED_TOLERANCE);
    let default = shot("scaled", &args, "");
    let (max, pixels) = difference(&default, &drawn);
    assert_eq!(
        (max, pixels),
        (0, 0),
        "scaling by default differs from the drawn output"
    );
    let edge = shot(
        "scaled-edge",
        &["--render-scale", "0.5", "--aa", "fxaa", "--upscale", "edge"],
        "",
    );
    let (_, pixels) = difference(&edge, &drawn);
    assert!(
        pixels > 0,
        "--upscale edge draws what --upscale bilinear draws"
    );
}

#[test]
fn the_drawn_output_into_unorm_equals_the_copy() {
    compare(
        "unorm",
        &["--render-scale", "1", "--aa", "off", "--unorm-output"],
        0,
    );
}
