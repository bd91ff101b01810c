//! The GPU layer's safe functions are sound whatever their arguments (issue 31): what would be
//! invalid usage in Vulkan is refused before it reaches the driver, as an error or, for a
//! programming error, a panic naming what is wrong.

mod common;

use common::{assert_validation_clean, gpu_context, test_image};
use vkocean::gpu::oneshot::run_once;
use vkocean::gpu::{vk, Buffer, BufferView, Load, MemoryLocation, Target};

fn buffer(
    ctx: &std::sync::Arc<vkocean::gpu::Context>,
    size: u64,
    usage: vk::BufferUsageFlags,
) -> Buffer {
    Buffer::new(ctx, "test buffer", size, usage, MemoryLocation::GpuOnly).unwrap()
}

#[test]
#[should_panic(expected = "lacks COLOR_ATTACHMENT usage")]
fn an_image_without_attachment_usage_is_no_render_target() {
    let ctx = gpu_context();
    let image = test_image(&ctx, "sampled-only image", vk::ImageUsageFlags::SAMPLED);
    let _ = Target::new(&image, Load::DontCare);
}

#[test]
#[should_panic(expected = "copy of 512 bytes between buffers of 256 and 1024 bytes")]
fn a_copy_larger_than_its_source_is_refused() {
    let ctx = gpu_context();
    let transfer = vk::BufferUsageFlags::TRANSFER_SRC | vk::BufferUsageFlags::TRANSFER_DST;
    let small = buffer(&ctx, 256, transfer);
    let large = buffer(&ctx, 1024, transfer);
    let _ = run_once(&ctx, "oversized copy", |rec| {
        rec.copy_buffer(&small, &large, 512)
    });
}

#[test]
#[should_panic(expected = "lacks TRANSFER_SRC usage")]
fn a_copy_from_a_buffer_without_transfer_usage_is_refused() {
    let ctx = gpu_context();
    let storage = buffer(&ctx, 256, vk::BufferUsageFlags::STORAGE_BUFFER);
    let dst = buffer(&ctx, 256, vk::BufferUsageFlags::TRANSFER_DST);
    let _ = run_once(&ctx, "copy without usage", |rec| {
        rec.copy_buffer(&storage, &dst, 256)
    });
}

#[test]
fn a_texel_view_of_a_buffer_without_texel_usage_is_an_error() {
    let ctx = gpu_context();
    let storage = buffer(&ctx, 256, vk::BufferUsageFlags::STORAGE_BUFFER);
    let error = BufferView::new(&ctx, "test view", &storage, vk::Format::R32G32B32A32_SFLOAT)
        .err()
        .expect("refused")
        .to_string();
    assert!(error.contains("texel-buffer usage"), "{error}");
    // With the usage, the same view is made.
    let texel = buffer(&ctx, 256, vk::BufferUsageFlags::UNIFORM_TEXEL_BUFFER);
    let view = BufferView::new(&ctx, "test view", &texel, vk::Format::R32G32B32A32_SFLOAT).unwrap();
    drop((view, texel, storage));
    assert_validation_clean(ctx);
}
