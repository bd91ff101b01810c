//! The steps every submission shares: reset a slot's pool, begin one-time recording, end and
//! submit with timeline waits and signals. Used by the frame loop (`frame.rs`), the compute
//! queue (`compute.rs`) and one-shot work (`oneshot.rs`).

use ash::vk;

use super::context::Context;
use super::error::{GpuResult, VkResultExt};

/// Resets `pool`, returning its command buffers to the initial state.
///
/// # Safety
/// No command buffer of `pool` is pending execution (its last submission has completed) or
/// being recorded by another thread.
pub(super) unsafe fn reset_pool(ctx: &Context, pool: vk::CommandPool) -> GpuResult<()> {
    // SAFETY: the caller guarantees the pool's command buffers are idle.
    unsafe {
        ctx.device
            .reset_command_pool(pool, vk::CommandPoolResetFlags::empty())
    }
    .vk("vkResetCommandPool")
}

/// Begins recording each of `cmds` for a single submission.
///
/// # Safety
/// Each command buffer is in the initial state (freshly allocated or its pool reset).
pub(super) unsafe fn begin_one_time(ctx: &Context, cmds: &[vk::CommandBuffer]) -> GpuResult<()> {
    let begin =
        vk::CommandBufferBeginInfo::default().flags(vk::CommandBufferUsageFlags::ONE_TIME_SUBMIT);
    for &cmd in cmds {
        // SAFETY: the caller guarantees `cmd` is in the initial state.
        unsafe { ctx.device.begin_command_buffer(cmd, &begin) }.vk("vkBeginCommandBuffer")?;
        // An earlier recording of `cmd` that failed and was never submitted leaves no error.
        ctx.take_recording_failure(cmd);
    }
    Ok(())
}

/// Ends `cmd` and submits it to `queue`: it waits for `waits`, then signals `signals` and
/// `fence` (may be null).
///
/// # Safety
/// `cmd` is recording (begun, not ended) with commands valid for `queue`'s family; the
/// semaphores and `fence` are live, `fence` unsignalled; only this thread submits to `queue`.
pub(super) unsafe fn end_and_submit(
    ctx: &Context,
    queue: vk::Queue,
    cmd: vk::CommandBuffer,
    waits: &[vk::SemaphoreSubmitInfo],
    signals: &[vk::SemaphoreSubmitInfo],
    fence: vk::Fence,
) -> GpuResult<()> {
    // SAFETY: `cmd` is recording (caller).
    unsafe { ctx.device.end_command_buffer(cmd) }.vk("vkEndCommandBuffer")?;
    // A pipeline made on first use failed while `cmd` was recorded: its draws are missing.
    if let Some(failure) = ctx.take_recording_failure(cmd) {
        return Err(failure);
    }
    ctx.journal_submit(queue, waits, signals);
    let cmds = [vk::CommandBufferSubmitInfo::default().command_buffer(cmd)];
    let submit = vk::SubmitInfo2::default()
        .wait_semaphore_infos(waits)
        .command_buffer_infos(&cmds)
        .signal_semaphore_infos(signals);
    // SAFETY: `cmd` is now executable; semaphores and fence are live; one submitting thread
    // (caller).
    unsafe { ctx.device.queue_submit2(queue, &[submit], fence) }.vk("vkQueueSubmit2")
}

/// A semaphore wait or signal of a submission: which semaphore, which timeline value, at which
/// stages. Made by the GPU layer only (`ComputeQueue::graphics_wait`, `AcquiredImage`), so no
/// code above it holds a raw semaphore.
#[derive(Clone, Copy, Debug)]
pub struct SemaphoreOp(pub(super) vk::SemaphoreSubmitInfo<'static>);

/// The raw infos of `ops`.
pub(super) fn infos(ops: &[SemaphoreOp]) -> Vec<vk::SemaphoreSubmitInfo<'static>> {
    ops.iter().map(|op| op.0).collect()
}
