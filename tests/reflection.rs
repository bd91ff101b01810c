//! The reflection's blurred layers (`Recorder::halve_down_layers`, read by water.frag to blur
//! what the water reflects by the slopes it does not resolve): on lavapipe, layer l of an image
//! against a CPU reference, layer l − 1's rows averaged in pairs, columns kept; validation-clean.

mod common;

use vkocean::gpu::oneshot::{download, run_once, upload_image};
use vkocean::gpu::{vk, Buffer, Image, ImageDesc, MemoryLocation};

const W: usize = 24;
const H: usize = 64;
const LAYERS: usize = 5;

/// Pseudo-random texels (a fixed LCG): every row and column differs from its neighbours.
fn texels() -> Vec<u8> {
    let mut state = 0x2545_f491_u32;
    (0..W * H * 4 * LAYERS)
        .map(|_| {
            state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
            (state >> 24) as u8
        })
        .collect()
}

#[test]
fn each_layer_averages_the_rows_of_the_one_before_in_pairs() {
    let ctx = common::gpu_context();
    let format = vk::Format::R8G8B8A8_UNORM;
    let image = Image::new(
        &ctx,
        &ImageDesc {
            name: "blurred layers",
            extent: vk::Extent2D {
                width: W as u32,
                height: H as u32,
            },
            format,
            usage: vk::ImageUsageFlags::SAMPLED
                | vk::ImageUsageFlags::TRANSFER_SRC
                | vk::ImageUsageFlags::TRANSFER_DST,
            layers: LAYERS as u32,
            array_view: true,
            shared: false,
            cube: false,
        },
    )
    .unwrap();
    // Every layer starts out random: layers 1.. must be overwritten, not blended with it.
    let input = texels();
    upload_image(&ctx, &image, &input).unwrap();
    let len = input.len();
    let readback = Buffer::new(
        &ctx,
        "blurred layers readback",
        len as u64,
        vk::BufferUsageFlags::TRANSFER_SRC | vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuOnly,
    )
    .unwrap();
    run_once(&ctx, "halve down layers", |rec| {
        rec.halve_down_layers(&image);
        rec.copy_image_layers_to_buffer(&image, &readback);
    })
    .unwrap();
    let out = download(&ctx, &readback, len).unwrap();

    let at = |data: &[u8], layer: usize, x: usize, y: usize, c: usize| {
        data[((layer * H + y) * W + x) * 4 + c] as f64
    };
    // Layer 0 is untouched.
    assert_eq!(out[..W * H * 4], input[..W * H * 4], "layer 0 changed");
    // Layer l's top H / 2^l rows: the mean of layer l − 1's rows 2y and 2y + 1, within the
    // rounding of two 8-bit values (each blit rounds once).
    let mut worst: f64 = 0.0;
    for layer in 1..LAYERS {
        let rows = H >> layer;
        for y in 0..rows {
            for x in 0..W {
                for c in 0..4 {
                    let expected = 0.5
                        * (at(&out, layer - 1, x, 2 * y, c) + at(&out, layer - 1, x, 2 * y + 1, c));
                    worst = worst.max((at(&out, layer, x, y, c) - expected).abs());
                }
            }
        }
    }
    assert!(
        worst <= 1.0,
        "a layer's texel is {worst} levels off its rows' mean"
    );
    // And against layer 0 directly: layer l is the mean of 2^l rows (rounding accumulates).
    let layer = LAYERS - 1;
    let span = 1 << layer;
    let mut far: f64 = 0.0;
    for y in 0..H >> layer {
        for x in 0..W {
            let mean: f64 = (0..span)
                .map(|r| at(&input, 0, x, y * span + r, 1))
                .sum::<f64>()
                / span as f64;
            far = far.max((at(&out, layer, x, y, 1) - mean).abs());
        }
    }
    assert!(
        far <= 2.5,
        "layer {layer} is {far} levels off the mean of {span} rows"
    );
    drop(readback);
    drop(image);
    common::assert_validation_clean(ctx);
}
