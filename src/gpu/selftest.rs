//! A deliberate synchronization hazard, recorded only when `--inject-sync-hazard` (a hidden,
//! test-only flag) is given: a buffer fill followed by a copy that reads the buffer, with no
//! barrier between them. Synchronization validation must report SYNC-HAZARD-READ-AFTER-WRITE;
//! the test that uses it proves validation is really on and the counters really count.

use std::sync::Arc;

use ash::vk;
use gpu_allocator::MemoryLocation;

use super::buffer::Buffer;
use super::command::Recorder;
use super::context::Context;
use super::error::GpuResult;

/// Two small buffers for the hazard.
pub struct SyncHazard {
    src: Buffer,
    dst: Buffer,
}

impl SyncHazard {
    pub fn new(ctx: &Arc<Context>) -> GpuResult<Self> {
        let usage = vk::BufferUsageFlags::TRANSFER_SRC | vk::BufferUsageFlags::TRANSFER_DST;
        Ok(SyncHazard {
            src: Buffer::new(
                ctx,
                "sync hazard source",
                256,
                usage,
                MemoryLocation::GpuOnly,
            )?,
            dst: Buffer::new(
                ctx,
                "sync hazard destination",
                256,
                usage,
                MemoryLocation::GpuOnly,
            )?,
        })
    }

    /// Records fill(src) then copy(src -> dst) without the barrier the copy needs.
    pub fn record(&self, rec: &Recorder) {
        rec.begin_label("deliberate sync hazard");
        rec.fill_buffer_unsynchronized(&self.src, 0x5eed_5eed);
        rec.copy_buffer_unsynchronized(&self.src, &self.dst, 256);
        rec.end_label();
    }
}
