//! The output pass's drawn path (src/render/passes/output.rs): where the output image takes no
//! copies (a swapchain without TRANSFER_DST), the picture is drawn into it as a colour
//! attachment. `VKOCEAN_OUTPUT=draw` forces that path headless; on lavapipe its picture equals
//! the copy's exactly at `--render-scale 1` (nearest sampling at texel centres, sRGB decoded and
//! encoded again) and the bilinear blit's within `SCALED_TOLERANCE` levels when it scales,
//! validation-clean, for an sRGB and a UNORM output.

mod common;

const SIZE: (u32, u32) = (240, 136);

/// Largest difference of one channel (0..255) allowed between the bilinear blit and the
/// bilinear sample that replaces it: both filter with 8-bit weights on lavapipe, rounded
/// differently.
const SCALED_TOLERANCE: i32 = 2;

fn shot(name: &str, args: &[&str], draw: bool) -> Vec<u8> {
    let mut all = vec!["--time", "5", "--fft-size", "64", "--quality", "low"];
    all.extend_from_slice(args);
    let mode = if draw { "draw" } else { "copy" };
    common::shot(
        &format!("output-{name}-{mode}"),
        SIZE,
        &all,
        &[("VKOCEAN_OUTPUT", mode)],
    )
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

fn compare(name: &str, args: &[&str], tolerance: i32) {
    let copied = shot(name, args, false);
    let drawn = shot(name, args, true);
    let (max, pixels) = difference(&copied, &drawn);
    eprintln!("{name}: largest difference {max}, {pixels} pixels differ");
    assert!(
        max <= tolerance,
        "{name}: the drawn output differs from the copy by up to {max} (> {tolerance}) in \
         {pixels} pixels"
    );
    // Not a black or empty picture that would trivially match.
    assert!(copied.chunks(4).any(|p| p[..3] != copied[..3]));
}

#[test]
fn the_drawn_output_equals_the_copy_at_full_scale() {
    compare("copy", &["--render-scale", "1", "--aa", "off"], 0);
    compare("copy-aa", &["--render-scale", "1", "--aa", "fxaa"], 0);
}

#[test]
fn the_drawn_output_matches_the_blit_when_scaling() {
    compare(
        "scaled",
        &["--render-scale", "0.5", "--aa", "fxaa"],
        SCALED_TOLERANCE,
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
