//! The compute queue's submissions: per frame slot a command buffer on the compute family, and a
//! compute timeline semaphore. Frame f's compute work signals the compute timeline with the frame's
//! value; it may wait on the graphics timeline first (before overwriting a slot that graphics
//! still samples). On a device with one queue (lavapipe) this is the graphics queue, and the same
//! semaphores order the two submissions.

use std::sync::Arc;

use ash::vk;

use super::buffer::Buffer;
use super::command::Recorder;
use super::context::Context;
use super::error::{GpuResult, VkResultExt};
use super::frame::{command_slot, FRAMES_IN_FLIGHT};
use super::garbage::Garbage;
use super::submit::{self, SemaphoreOp};

pub struct ComputeQueue {
    ctx: Arc<Context>,
    /// Per slot: command pool and its command buffer.
    slots: Vec<(vk::CommandPool, vk::CommandBuffer)>,
    /// Per slot: the timeline value its last submission signals (0: none yet). `submit` waits
    /// for it before resetting the slot, whatever slot the caller names.
    slot_values: Vec<u64>,
    /// The last value submitted (values must increase: the timeline only moves up).
    last_value: u64,
    /// Signalled with frame values by compute submissions.
    pub(super) timeline: vk::Semaphore,
}

impl ComputeQueue {
    pub fn new(ctx: &Arc<Context>) -> GpuResult<ComputeQueue> {
        // Starts where the frame timeline is: an earlier frame loop on this context used the
        // values below, and `wait_for_slot` waits for value − FRAMES_IN_FLIGHT.
        let mut timeline_type = vk::SemaphoreTypeCreateInfo::default()
            .semaphore_type(vk::SemaphoreType::TIMELINE)
            .initial_value(ctx.signaled_value());
        let info = vk::SemaphoreCreateInfo::default().push_next(&mut timeline_type);
        // SAFETY: valid create info on a live device.
        let timeline =
            unsafe { ctx.device.create_semaphore(&info, None) }.vk("vkCreateSemaphore")?;
        ctx.count_created(1);
        ctx.name(timeline, "compute timeline");
        // Pushed as made: an error drops (and frees) what exists.
        let mut queue = ComputeQueue {
            ctx: ctx.clone(),
            slots: Vec::new(),
            slot_values: vec![0; FRAMES_IN_FLIGHT],
            last_value: ctx.signaled_value(),
            timeline,
        };
        for i in 0..FRAMES_IN_FLIGHT {
            let (pool, [cmd]) =
                command_slot(ctx, ctx.compute.family, &format!("compute slot {i}"))?;
            queue.slots.push((pool, cmd));
        }
        Ok(queue)
    }
    /// Records compute work for the frame with timeline `value` in `slot` and submits it to the
    /// compute queue: waits for the graphics timeline to reach `wait_graphics` (if any) at the
    /// compute stage, and signals the compute timeline with `value`.
    pub fn submit(
        &mut self,
        slot: usize,
        value: u64,
        wait_graphics: Option<u64>,
        record: impl FnOnce(&Recorder) -> GpuResult<()>,
    ) -> GpuResult<()> {
        assert!(
            value > self.last_value,
            "compute value {value} after {}: a timeline only moves up",
            self.last_value
        );
        self.wait_for_slot(value)?;
        // Whatever slot is named, its previous submission is done before its reset.
        self.ctx
            .wait_timeline(self.timeline, self.slot_values[slot])?;
        let (pool, cmd) = self.slots[slot];
        // SAFETY: the slot's previous submission has completed (waited above); the reset puts
        // its command buffer in the initial state.
        unsafe {
            submit::reset_pool(&self.ctx, pool)?;
            submit::begin_one_time(&self.ctx, &[cmd])?;
        }
        {
            let rec = Recorder::new(&self.ctx, cmd, self.ctx.compute.family);
            rec.begin_label(&format!("compute frame value {value}"));
            let recorded = record(&rec);
            rec.end_label();
            if let Err(e) = recorded {
                // SAFETY: recording began above; the command buffer is never submitted.
                let _ = unsafe { self.ctx.device.end_command_buffer(cmd) };
                return Err(e);
            }
        }
        let waits: Vec<_> = wait_graphics
            .map(|v| {
                vk::SemaphoreSubmitInfo::default()
                    .semaphore(self.ctx.frame_timeline)
                    .value(v)
                    .stage_mask(vk::PipelineStageFlags2::COMPUTE_SHADER)
            })
            .into_iter()
            .collect();
        // Signalled once every command of the submission is done (not only its dispatches: the
        // timestamp writes and anything recorded later count too).
        let signals = [vk::SemaphoreSubmitInfo::default()
            .semaphore(self.timeline)
            .value(value)
            .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)];
        let queue = self.ctx.compute.raw;
        // SAFETY: recording began above, on a pool of the compute family; the semaphores are
        // live; one submitting thread.
        unsafe {
            submit::end_and_submit(&self.ctx, queue, cmd, &waits, &signals, vk::Fence::null())?
        };
        self.slot_values[slot] = value;
        self.last_value = value;
        Ok(())
    }

    /// Waits until the compute work of the frame two before `value` (the previous user of the
    /// same slot) has finished, so the slot's command buffer and per-slot buffers are free. The
    /// frame loop already waited for that frame's graphics work, which waited for this compute
    /// work; the wait here keeps the type correct on its own.
    pub fn wait_for_slot(&self, value: u64) -> GpuResult<()> {
        if value > FRAMES_IN_FLIGHT as u64 {
            self.ctx
                .wait_timeline(self.timeline, value - FRAMES_IN_FLIGHT as u64)?;
        }
        Ok(())
    }

    /// Waits until every submitted compute work has finished (once, after the first frame's
    /// warm-up, whose steps used both slots' per-slot buffers).
    pub fn wait_for_last(&self) -> GpuResult<()> {
        if self.last_value > 0 {
            self.ctx.wait_timeline(self.timeline, self.last_value)?;
        }
        Ok(())
    }

    /// The first `len` bytes of the host-visible `buffer` as the submission that signalled
    /// `value` left them, if the compute timeline has reached `value` (no wait; `None` if not
    /// yet). That submission must have ended with `Use::HostRead` of the buffer (the barrier
    /// that makes its writes available to the host), and no later submitted work may write it:
    /// the caller's ring of buffers keeps those (`ocean::simulation::queries`). Crate-only: a
    /// caller breaking that would read bytes the GPU is writing.
    pub(crate) fn read_if_done(
        &self,
        buffer: &Buffer,
        value: u64,
        len: usize,
    ) -> GpuResult<Option<Vec<u8>>> {
        // SAFETY: the semaphore is a live timeline semaphore of this device.
        let done = unsafe { self.ctx.device.get_semaphore_counter_value(self.timeline) }
            .vk("vkGetSemaphoreCounterValue")?;
        if done < value {
            return Ok(None);
        }
        // The spec orders host reads after a semaphore's signal through a host wait
        // (vkWaitSemaphores), not through vkGetSemaphoreCounterValue: the wait, which returns at
        // once now, makes the submission's host-available writes visible to this read.
        self.ctx.wait_timeline(self.timeline, value)?;
        // gpu-allocator maps host-visible memory HOST_COHERENT: nothing to invalidate.
        let bytes = buffer
            .mapped()
            .unwrap_or_else(|| panic!("read_if_done of a buffer that is not host-visible"));
        Ok(Some(bytes[..len].to_vec()))
    }

    /// The wait a graphics submission adds to sample this frame's compute results.
    pub fn graphics_wait(&self, value: u64, stages: vk::PipelineStageFlags2) -> SemaphoreOp {
        SemaphoreOp(
            vk::SemaphoreSubmitInfo::default()
                .semaphore(self.timeline)
                .value(value)
                .stage_mask(stages),
        )
    }
}

impl Drop for ComputeQueue {
    fn drop(&mut self) {
        for (pool, _) in self.slots.drain(..) {
            self.ctx.defer(Garbage::CommandPool(pool));
        }
        self.ctx.defer(Garbage::Semaphore(self.timeline));
    }
}
