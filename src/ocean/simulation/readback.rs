//! Reading the simulation back to the host (`--dump`, `--stats`, tests): the images of a slot
//! and h0, each on the compute queue that wrote or owns them (README, "Across queues").

use std::sync::Arc;

use super::{Simulation, Texels};
use crate::gpu::oneshot::{download_image_layers_on, download_on};
use crate::gpu::{Context, GpuResult, Use};

impl Simulation {
    /// Reads both images of `slot` as the last compute submission left them (tests, dumps):
    /// (displacement, normals), each cascade after cascade, `[m][n]` RGBA f32. Waits for the
    /// device first: no frame may still be sampling the slot while its images change layout
    /// for the copy.
    pub fn read_back(&self, ctx: &Arc<Context>, slot: usize) -> GpuResult<(Texels, Texels)> {
        ctx.wait_idle()?;
        let images = [&self.displacement[slot], &self.normals[slot]];
        // On the compute queue, after the submission that wrote the images: a pipeline barrier's
        // first scope covers everything submitted earlier to the same queue, so the layout
        // transition chains with the writes (a semaphore wait on another queue at COPY would
        // not have chained with a barrier whose first scope is COMPUTE_SHADER). The images go
        // back to GENERAL before later compute submissions (same queue again) and graphics
        // frames (through the compute timeline, whose later signals cover this) touch them.
        // The caller makes sure no graphics frame still samples the slot (it waited for it).
        let bytes = download_image_layers_on(ctx, ctx.compute, &images, Use::ComputeRead)?;
        let texels = |b: &[u8]| -> Texels { bytemuck::cast_slice(b).to_vec() };
        Ok((texels(&bytes[0]), texels(&bytes[1])))
    }

    /// h0 as uploaded, read back on the compute queue that owns it (FFT mode; for dumps):
    /// (K, N, N) complex f32 bytes.
    pub fn download_h0(&self, ctx: &Arc<Context>) -> GpuResult<Option<Vec<u8>>> {
        match self.model.h0() {
            Some(h0) => download_on(ctx, ctx.compute, h0, h0.size() as usize).map(Some),
            None => Ok(None),
        }
    }
}
