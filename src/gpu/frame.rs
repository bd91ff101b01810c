//! Frames in flight, paced by the context's graphics timeline semaphore (no fences).
//!
//! Frame f (counting from 0) records into slot f % 2. Its graphics work is two submissions to
//! the graphics queue: the scene submission (passes that need no simulation output; it waits
//! for nothing and signals nothing) and the ocean submission (it waits for the compute timeline
//! and signals the graphics timeline with f + 1; a signal covers every command submitted
//! earlier to the queue, so it covers the scene submission too). Before slot s is reused for
//! frame f, the CPU waits for the value f - 1, i.e. for frame f - 2, the previous user of the
//! slot. The deletion queue is emptied there too.

use std::sync::Arc;

use ash::vk;

use super::buffer::Buffer;
use super::command::{Recorder, RequiredWaits};
use super::context::Context;
use super::error::{GpuError, GpuResult, VkResultExt};
use super::garbage::Garbage;
use super::submit::{self, SemaphoreOp};

/// Number of frames the CPU may record ahead of the GPU.
pub const FRAMES_IN_FLIGHT: usize = 2;

/// Creates a transient command pool on `family` with `N` primary command buffers, named after
/// `label` (frame slots here, compute slots in `compute.rs`).
pub(super) fn command_slot<const N: usize>(
    ctx: &Context,
    family: u32,
    label: &str,
) -> GpuResult<(vk::CommandPool, [vk::CommandBuffer; N])> {
    let info = vk::CommandPoolCreateInfo::default()
        .queue_family_index(family)
        .flags(vk::CommandPoolCreateFlags::TRANSIENT);
    // SAFETY: valid create info on a live device.
    let pool = unsafe { ctx.device.create_command_pool(&info, None) }.vk("vkCreateCommandPool")?;
    ctx.count_created(1);
    let alloc = vk::CommandBufferAllocateInfo::default()
        .command_pool(pool)
        .level(vk::CommandBufferLevel::PRIMARY)
        .command_buffer_count(N as u32);
    // SAFETY: the pool is live.
    let cmds: [vk::CommandBuffer; N] = match unsafe { ctx.device.allocate_command_buffers(&alloc) }
    {
        Ok(c) => c.try_into().expect("N command buffers"),
        Err(result) => {
            ctx.defer(Garbage::CommandPool(pool));
            return Err(GpuError::Vk {
                call: "vkAllocateCommandBuffers",
                result,
            });
        }
    };
    ctx.name(pool, &format!("{label} command pool"));
    for (i, &cmd) in cmds.iter().enumerate() {
        ctx.name(cmd, &format!("{label} commands {i}"));
    }
    Ok((pool, cmds))
}

/// Which of a frame's two graphics submissions a recorder writes into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Submission {
    /// Passes that read no simulation output; submitted first, waits for nothing.
    Scene = 0,
    /// Passes that sample the simulation images, and the output; waits for the compute timeline.
    Ocean = 1,
}

/// A command pool and the frame's two primary command buffers (`Submission`).
struct Slot {
    pool: vk::CommandPool,
    cmds: [vk::CommandBuffer; 2],
}

/// The frame loop's command buffers and pacing. After a submission of a frame failed (an error
/// from `submit_scene` or `submit`), the frame's other work may have gone to the GPU without
/// it: end the loop (as every caller does, passing the error up), do not begin another frame.
pub struct Frames {
    ctx: Arc<Context>,
    slots: Vec<Slot>,
    /// Timeline value before this frame loop's first frame (an earlier loop on the same context
    /// may have signalled values already; timeline values must keep increasing).
    base: u64,
    /// Index of the next frame to begin.
    next: u64,
}

/// The frame being recorded.
pub struct Frame {
    /// Frame number, from 0.
    pub index: u64,
    /// Frame-in-flight slot (`index % FRAMES_IN_FLIGHT`).
    pub slot: usize,
    cmds: [vk::CommandBuffer; 2],
    /// Timeline value its submission signals.
    value: u64,
    /// The scene submission went out (`Frames::submit_scene`).
    scene_submitted: bool,
    /// Per command buffer: the semaphore waits its reads rely on (`Order::Wait`), checked
    /// against the waits it is submitted with.
    required_waits: [RequiredWaits; 2],
    /// The device its command buffers belong to.
    ctx: Arc<Context>,
}

impl Frame {
    /// The timeline value this frame's graphics submission signals.
    pub fn signal_value(&self) -> u64 {
        self.value
    }

    /// The timeline value of the frame that used this slot before (frame f − 2), if any: the
    /// compute submission waits for it before overwriting the slot's images.
    pub fn previous_user(&self) -> Option<u64> {
        let n = FRAMES_IN_FLIGHT as u64;
        (self.value > n).then(|| self.value - n)
    }

    /// A recorder for one of this frame's command buffers. It borrows the frame, so it cannot
    /// outlive the recording state (`Frames::submit` consumes the frame).
    pub fn recorder<'a>(&'a self, ctx: &'a Context, submission: Submission) -> Recorder<'a> {
        assert!(
            !(submission == Submission::Scene && self.scene_submitted),
            "the scene submission was already submitted"
        );
        assert!(
            std::ptr::eq(ctx, &*self.ctx),
            "a frame's commands recorded with another device's context"
        );
        let mut rec = Recorder::new(ctx, self.cmds[submission as usize], ctx.graphics.family);
        rec.required_waits = Some(&self.required_waits[submission as usize]);
        rec
    }
}

impl Frames {
    pub fn new(ctx: &Arc<Context>) -> GpuResult<Frames> {
        // Slots are pushed as they are made, so an error drops (and frees) the earlier ones.
        let mut frames = Frames {
            ctx: ctx.clone(),
            slots: Vec::new(),
            base: ctx.signaled_value(),
            next: 0,
        };
        for i in 0..FRAMES_IN_FLIGHT {
            let (pool, cmds) = command_slot(ctx, ctx.graphics.family, &format!("frame slot {i}"))?;
            frames.slots.push(Slot { pool, cmds });
        }
        Ok(frames)
    }

    /// Slot the next frame will use.
    pub fn next_slot(&self) -> usize {
        (self.next % FRAMES_IN_FLIGHT as u64) as usize
    }

    /// Waits until the GPU finished the previous frame of the next frame's slot (so per-slot
    /// resources, e.g. a swapchain acquire semaphore, are free). `begin` does this too.
    pub fn wait_for_slot(&self) -> GpuResult<()> {
        if self.next >= FRAMES_IN_FLIGHT as u64 {
            self.wait_for(self.base + self.next + 1 - FRAMES_IN_FLIGHT as u64)?;
        }
        Ok(())
    }

    /// Waits until the slot of the next frame is free, collects garbage and begins recording.
    pub fn begin(&mut self) -> GpuResult<Frame> {
        let index = self.next;
        let slot = self.next_slot();
        self.wait_for_slot()?;
        let value = self.base + index + 1;
        self.ctx.set_pending_value(value);
        self.ctx.collect_garbage()?;
        let s = &self.slots[slot];
        // SAFETY: the slot's previous submission has completed (waited above), so its pool
        // and command buffers are idle; the reset puts them in the initial state.
        unsafe {
            submit::reset_pool(&self.ctx, s.pool)?;
            submit::begin_one_time(&self.ctx, &s.cmds)?;
        }
        Ok(Frame {
            index,
            slot,
            cmds: s.cmds,
            value,
            scene_submitted: false,
            required_waits: Default::default(),
            ctx: self.ctx.clone(),
        })
    }

    /// Ends and submits the frame's scene command buffer to the graphics queue: no waits, no
    /// signals (the ocean submission's signal covers it). Call once, before the compute
    /// submission, so a separate compute queue runs the simulation while this draws.
    pub fn submit_scene(&mut self, frame: &mut Frame) -> GpuResult<()> {
        assert!(
            !frame.scene_submitted,
            "the scene submission was already submitted"
        );
        assert!(
            Arc::ptr_eq(&frame.ctx, &self.ctx),
            "a frame of another context"
        );
        self.check_waits(
            &frame.required_waits[Submission::Scene as usize],
            &[],
            "graphics 1",
        );
        let cmd = frame.cmds[Submission::Scene as usize];
        let queue = self.ctx.graphics.raw;
        // SAFETY: `cmd` is recording (begun in `begin`, not yet ended) graphics commands; only
        // this thread submits.
        unsafe { submit::end_and_submit(&self.ctx, queue, cmd, &[], &[], vk::Fence::null())? };
        frame.scene_submitted = true;
        Ok(())
    }

    /// Ends recording and submits the frame's ocean command buffer to the graphics queue (after
    /// the scene one, if `submit_scene` was not called), waiting on `waits` and signalling the
    /// frame timeline with `frame.signal_value()` plus `signals`.
    pub fn submit(
        &mut self,
        mut frame: Frame,
        waits: &[SemaphoreOp],
        signals: &[SemaphoreOp],
    ) -> GpuResult<()> {
        if !frame.scene_submitted {
            self.submit_scene(&mut frame)?;
        }
        self.check_waits(
            &frame.required_waits[Submission::Ocean as usize],
            waits,
            "graphics 2",
        );
        let cmd = frame.cmds[Submission::Ocean as usize];
        let mut all_signals = vec![vk::SemaphoreSubmitInfo::default()
            .semaphore(self.ctx.frame_timeline)
            .value(frame.signal_value())
            .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)];
        all_signals.extend(submit::infos(signals));
        let queue = self.ctx.graphics.raw;
        // SAFETY: `cmd` is recording (begun in `begin`) graphics commands; the semaphores are
        // live; only this thread submits.
        unsafe {
            submit::end_and_submit(
                &self.ctx,
                queue,
                cmd,
                &submit::infos(waits),
                &all_signals,
                vk::Fence::null(),
            )?
        };
        // Only a submitted frame counts: waits for its value can then complete.
        self.next = frame.index + 1;
        self.ctx.set_signaled_value(frame.value);
        Ok(())
    }

    /// Panics unless `waits` hold, for each (semaphore, stages) a read of the command buffer
    /// relies on (`Order::Wait`), a wait for that semaphore covering those stages: a read the
    /// submission does not wait for is a race with the other queue's writes.
    fn check_waits(&self, required: &RequiredWaits, waits: &[SemaphoreOp], which: &str) {
        for (by, stages) in required.borrow().iter() {
            let covered = waits.iter().any(|w| {
                self.ctx.semaphore_name(w.0.semaphore).as_deref() == Some(*by)
                    && w.0.stage_mask.contains(*stages)
            });
            assert!(
                covered,
                "{which} reads what {by} orders at {stages:?}, but is not submitted with that wait"
            );
        }
    }

    /// A copy of the bytes of a host-visible buffer that submitted frames wrote (with a
    /// barrier making the write visible to HOST_READ, as `Recorder::uses` records for
    /// `Use::HostRead`). Waits for every submitted frame first, so no GPU work can still be
    /// writing it, and returns a copy, so no later frame can write under the caller's view.
    /// Panics if the buffer is not host-visible (a programming error).
    pub fn read_back(&self, buffer: &Buffer) -> GpuResult<Vec<u8>> {
        self.wait_all()?;
        Ok(buffer
            .mapped()
            .expect("read_back needs a host-visible buffer")
            .to_vec())
    }

    /// Blocks until the frame timeline reaches `value`.
    pub fn wait_for(&self, value: u64) -> GpuResult<()> {
        self.ctx.wait_timeline(self.ctx.frame_timeline, value)
    }

    /// Waits for every submitted frame.
    pub fn wait_all(&self) -> GpuResult<()> {
        if self.next > 0 {
            self.wait_for(self.base + self.next)?;
        }
        Ok(())
    }

    /// Number of frames submitted so far.
    pub fn submitted(&self) -> u64 {
        self.next
    }
}

impl Drop for Frames {
    fn drop(&mut self) {
        for slot in self.slots.drain(..) {
            // Freed with the pool, after the GPU is done with it.
            self.ctx.defer(Garbage::CommandPool(slot.pool));
        }
    }
}
