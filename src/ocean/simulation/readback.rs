//! Reading the simulation back to the host (`--dump`, `--stats`, tests): the images of a slot
//! and h0, each on the compute queue that wrote or owns them (README, "Across queues").

use std::sync::Arc;

use ash::vk;

use super::{Simulation, Texels};
use crate::gpu::oneshot::{download_on, run_once_on};
use crate::gpu::{Buffer, Context, GpuResult, MemoryLocation, Tracked, Use};

impl Simulation {
    /// Reads both images of `slot` as the last compute submission left them (tests, dumps):
    /// (displacement, normals), each cascade after cascade, `[m][n]` RGBA f32. No graphics frame
    /// may still be sampling the slot (wait for it first).
    pub fn read_back(&self, ctx: &Arc<Context>, slot: usize) -> GpuResult<(Texels, Texels)> {
        let images = [&self.displacement[slot], &self.normals[slot]];
        let n = self.settings.fft_size;
        let bytes = (self.cascades.len() * n * n * 16) as u64;
        let buffers = [
            Buffer::new(
                ctx,
                "ocean displacement readback",
                bytes,
                vk::BufferUsageFlags::TRANSFER_DST,
                MemoryLocation::GpuToCpu,
            )?,
            Buffer::new(
                ctx,
                "ocean normals readback",
                bytes,
                vk::BufferUsageFlags::TRANSFER_DST,
                MemoryLocation::GpuToCpu,
            )?,
        ];
        // On the compute queue, after the submission that wrote the images: a pipeline barrier's
        // first scope covers everything submitted earlier to the same queue, so the layout
        // transition chains with the writes (a semaphore wait on another queue at COPY would
        // not have chained with a barrier whose first scope is COMPUTE_SHADER). The images go
        // back to GENERAL before later compute submissions (same queue again) and graphics
        // frames (through the compute timeline, whose later signals cover this) touch them.
        // The caller makes sure no graphics frame still samples the slot (it waited for it).
        run_once_on(ctx, ctx.compute, "ocean readback", &[], |rec| {
            let uses = |image_use, buffer_use| -> Vec<(&dyn Tracked, Use)> {
                let images = images.iter().map(|&img| (img as &dyn Tracked, image_use));
                let buffers = buffers.iter().map(|b| (b as &dyn Tracked, buffer_use));
                images.chain(buffers).collect()
            };
            rec.uses(&uses(Use::CopySrc, Use::CopyDst));
            for (img, buffer) in images.iter().zip(&buffers) {
                rec.copy_image_layers_to_buffer(img, vk::ImageLayout::TRANSFER_SRC_OPTIMAL, buffer);
            }
            rec.uses(&uses(Use::ComputeRead, Use::HostRead));
        })?;
        let read = |b: &Buffer| -> Texels {
            bytemuck::cast_slice(b.mapped().expect("readback is host-visible")).to_vec()
        };
        Ok((read(&buffers[0]), read(&buffers[1])))
    }

    /// h0 as uploaded, read back on the compute queue that owns it (FFT mode; for dumps):
    /// (K, N, N) complex f32 bytes.
    pub fn download_h0(&self, ctx: &Arc<Context>) -> GpuResult<Option<Vec<u8>>> {
        match self.model.h0() {
            Some(h0) => download_on(ctx, ctx.compute, h0, h0.size as usize).map(Some),
            None => Ok(None),
        }
    }
}
