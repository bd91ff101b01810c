//! One-shot command submission outside the frame loop (uploads, readbacks, tests, benchmarks):
//! record, submit to a queue (the graphics queue unless said otherwise), wait on a fence, done.
//!
//! A fence orders the host, not another queue's memory accesses: data a one-shot writes for the
//! compute queue (h0) is therefore uploaded by a one-shot on the compute queue itself
//! ([`upload_on`]), and read back there ([`download_on`]), so it never crosses families.

use std::sync::Arc;

use ash::vk;
use gpu_allocator::MemoryLocation;

use super::buffer::Buffer;
use super::command::Recorder;
use super::context::{Context, Queue};
use super::error::{GpuError, GpuResult, VkResultExt};
use super::image::Image;
use super::submit;
use super::track::Use;

/// Records commands with `record`, submits them and blocks until the GPU has finished.
pub fn run_once<R>(
    ctx: &Arc<Context>,
    name: &str,
    record: impl FnOnce(&Recorder) -> R,
) -> GpuResult<R> {
    run_once_on(ctx, ctx.graphics, name, &[], record)
}

/// `run_once` on a given queue (`ctx.graphics` or `ctx.compute`), first waiting on `waits`.
pub fn run_once_on<R>(
    ctx: &Arc<Context>,
    queue: Queue,
    name: &str,
    waits: &[super::SemaphoreOp],
    record: impl FnOnce(&Recorder) -> R,
) -> GpuResult<R> {
    assert!(
        queue.raw == ctx.graphics.raw || queue.raw == ctx.compute.raw,
        "a one-shot on a queue of another context"
    );
    let pool_info = vk::CommandPoolCreateInfo::default()
        .queue_family_index(queue.family)
        .flags(vk::CommandPoolCreateFlags::TRANSIENT);
    // SAFETY: valid create info on a live device; destroyed below after the wait.
    let pool =
        unsafe { ctx.device.create_command_pool(&pool_info, None) }.vk("vkCreateCommandPool")?;
    ctx.count_created(1);
    let result = (|| {
        let alloc = vk::CommandBufferAllocateInfo::default()
            .command_pool(pool)
            .level(vk::CommandBufferLevel::PRIMARY)
            .command_buffer_count(1);
        // SAFETY: the pool is live and used by this thread only.
        let cmd = unsafe { ctx.device.allocate_command_buffers(&alloc) }
            .vk("vkAllocateCommandBuffers")?[0];
        ctx.name(cmd, name);
        // SAFETY: a freshly allocated command buffer.
        unsafe { submit::begin_one_time(ctx, &[cmd])? };
        let value = {
            let rec = Recorder::new(ctx, cmd, queue.family);
            rec.begin_label(name);
            let value = record(&rec);
            rec.end_label();
            value
        };
        // SAFETY: valid create info on a live device.
        let fence = unsafe {
            ctx.device
                .create_fence(&vk::FenceCreateInfo::default(), None)
        }
        .vk("vkCreateFence")?;
        ctx.count_created(1);
        // SAFETY: recording began above, on a pool of `queue`'s family; the fence is new and
        // unsignalled; the sample submits from one thread.
        let waits = submit::infos(waits);
        let submitted = unsafe { submit::end_and_submit(ctx, queue.raw, cmd, &waits, &[], fence) };
        // SAFETY: the fence was submitted (or the submit failed and it stays unsignalled, in which
        // case we do not wait on it).
        let waited = submitted.and_then(|()| {
            match unsafe {
                ctx.device
                    .wait_for_fences(&[fence], true, ctx.wait_timeout_s * 1_000_000_000)
            } {
                Ok(()) => Ok(()),
                Err(vk::Result::TIMEOUT) => Err(GpuError::Timeout {
                    seconds: ctx.wait_timeout_s,
                }),
                Err(result) => Err(GpuError::Vk {
                    call: "vkWaitForFences",
                    result,
                }),
            }
        });
        // SAFETY: the fence is no longer in use (waited, or never submitted).
        unsafe { ctx.device.destroy_fence(fence, None) };
        ctx.count_destroyed(1);
        waited.map(|()| value)
    })();
    // SAFETY: the submission (if any) has completed, so the pool's command buffer is idle.
    unsafe { ctx.device.destroy_command_pool(pool, None) };
    ctx.count_destroyed(1);
    result
}

/// Copies `bytes` into the start of a device buffer (through a staging buffer) and waits.
pub fn upload(ctx: &Arc<Context>, dst: &Buffer, bytes: &[u8]) -> GpuResult<()> {
    upload_on(ctx, ctx.graphics, dst, bytes)
}

/// `upload` then a barrier that makes the bytes visible to `then` (e.g. `Use::IndexRead` for
/// an index buffer, which no tracked pass declares).
pub fn upload_then(ctx: &Arc<Context>, dst: &Buffer, bytes: &[u8], then: Use) -> GpuResult<()> {
    upload(ctx, dst, bytes)?;
    run_once(ctx, "upload: visible to its reader", |rec| {
        rec.uses(&[(dst, then)])
    })
}

/// `upload` on the queue that will use the buffer (`ctx.compute` for the simulation's inputs).
pub fn upload_on(ctx: &Arc<Context>, queue: Queue, dst: &Buffer, bytes: &[u8]) -> GpuResult<()> {
    let mut staging = Buffer::new(
        ctx,
        "upload staging",
        bytes.len().max(4) as u64,
        vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::CpuToGpu,
    )?;
    staging.write(bytes);
    run_once_on(ctx, queue, "upload", &[], |rec| {
        // The buffer's state says it was copied to: its next user's barrier waits for that
        // (on this queue, where a barrier's first scope covers this submission).
        rec.copy_buffer(&staging, dst, bytes.len() as u64);
    })
}

/// Fills every layer of a colour image from tightly packed texels (layer after layer), leaving it
/// in SHADER_READ_ONLY_OPTIMAL for fragment shaders. Waits.
pub fn upload_image(ctx: &Arc<Context>, image: &Image, bytes: &[u8]) -> GpuResult<()> {
    upload_image_with(ctx, image, bytes.len(), |staging| {
        staging.copy_from_slice(bytes);
        Ok(())
    })
}

/// [`upload_image`] of `len` bytes that `fill` writes straight into the mapped staging buffer
/// (a decoder, so the texels exist once on the host); `fill`'s error ends the upload.
pub fn upload_image_with<E: From<GpuError>>(
    ctx: &Arc<Context>,
    image: &Image,
    len: usize,
    fill: impl FnOnce(&mut [u8]) -> Result<(), E>,
) -> Result<(), E> {
    let mut staging = Buffer::new(
        ctx,
        "image upload staging",
        len.max(4) as u64,
        vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::CpuToGpu,
    )?;
    fill(&mut staging.mapped_mut()[..len])?;
    run_once(ctx, "image upload", |rec| {
        // Left in TRANSFER_DST_OPTIMAL: the first pass that samples it moves it to
        // SHADER_READ_ONLY_OPTIMAL, waiting at the stages its shaders read it in.
        rec.copy_buffer_to_image_layers(&staging, image);
    })?;
    Ok(())
}

/// Reads the first `len` bytes of a device buffer (through a staging buffer).
pub fn download(ctx: &Arc<Context>, src: &Buffer, len: usize) -> GpuResult<Vec<u8>> {
    download_on(ctx, ctx.graphics, src, len)
}

/// `download` on the queue that used the buffer (`ctx.compute` for the simulation's).
pub fn download_on(
    ctx: &Arc<Context>,
    queue: Queue,
    src: &Buffer,
    len: usize,
) -> GpuResult<Vec<u8>> {
    let staging = Buffer::new(
        ctx,
        "download staging",
        len.max(4) as u64,
        vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuToCpu,
    )?;
    run_once_on(ctx, queue, "download", &[], |rec| {
        rec.copy_buffer(src, &staging, len as u64);
        rec.uses(&[(&staging, Use::HostRead)]);
    })?;
    Ok(staging.mapped().expect("staging is host-visible")[..len].to_vec())
}

/// Reads every layer of each of `images` (tightly packed, layer after layer) on `queue`, the
/// queue whose tracked state they are in, and leaves each in the state `then` asks for (e.g.
/// `Use::ComputeRead`: back in GENERAL for the compute queue). Returns the bytes of each.
pub fn download_image_layers_on(
    ctx: &Arc<Context>,
    queue: Queue,
    images: &[&Image],
    then: Use,
) -> GpuResult<Vec<Vec<u8>>> {
    let buffers = images
        .iter()
        .map(|image| {
            let e = image.extent;
            // RGBA32F (the simulation's) or RGBA8: the copy asserts the size it needs.
            let texel = if image.format == vk::Format::R32G32B32A32_SFLOAT {
                16
            } else {
                4
            };
            let bytes = e.width as u64 * e.height as u64 * image.layers as u64 * texel;
            Buffer::new(
                ctx,
                &format!("{} readback", image.name()),
                bytes,
                vk::BufferUsageFlags::TRANSFER_DST,
                MemoryLocation::GpuToCpu,
            )
        })
        .collect::<GpuResult<Vec<_>>>()?;
    run_once_on(ctx, queue, "image readback", &[], |rec| {
        for (image, buffer) in images.iter().zip(&buffers) {
            rec.copy_image_layers_to_buffer(image, buffer);
            rec.uses(&[(*image, then), (buffer, Use::HostRead)]);
        }
    })?;
    // The one-shot waited for its fence: the GPU is done with the buffers.
    Ok(buffers
        .iter()
        .map(|b| b.mapped().expect("readback is host-visible").to_vec())
        .collect())
}
