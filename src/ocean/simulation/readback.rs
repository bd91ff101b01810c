//! Reading the simulation back to the host (`--dump`, `--stats`, tests): the images of a slot,
//! the spray's counts and h0, each on the compute queue that wrote or owns them (README, "Across queues").

use std::sync::Arc;

use super::{Simulation, Texels, COUNTS_BYTES, LIVE_INDEX, PARTICLE_BYTES};
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

    /// The spray's counts in `slot` as the last compute submission left them: (live particles,
    /// puffs born, puffs landed that frame); `None` without spray. Read on the compute queue
    /// that wrote them (the caller waited for the frame that drew them).
    pub fn spray_counts(&self, ctx: &Arc<Context>, slot: usize) -> GpuResult<Option<[u32; 3]>> {
        let Some(spray) = self.spray() else {
            return Ok(None);
        };
        let bytes = download_on(ctx, ctx.compute, &spray.counts[slot], COUNTS_BYTES as usize)?;
        let counts: &[u32] = bytemuck::cast_slice(&bytes);
        Ok(Some([counts[LIVE_INDEX], counts[9], counts[8]]))
    }

    /// The spray's live particles in `slot` (`None` without spray): 12 f32 each, as
    /// spray.comp's `Particle` holds them (position, age, velocity, drop radius, the water's
    /// height under it, 3 unused). Read on the compute queue that wrote them.
    pub fn spray_particles(&self, ctx: &Arc<Context>, slot: usize) -> GpuResult<Option<Vec<f32>>> {
        let Some([live, ..]) = self.spray_counts(ctx, slot)? else {
            return Ok(None);
        };
        if live == 0 {
            return Ok(Some(Vec::new()));
        }
        let buffer = &self.spray().expect("counts read").particles[slot];
        let bytes = download_on(
            ctx,
            ctx.compute,
            buffer,
            (live as u64 * PARTICLE_BYTES) as usize,
        )?;
        Ok(Some(bytemuck::cast_slice(&bytes).to_vec()))
    }

    /// h0 as uploaded, read back on the compute queue that owns it (FFT mode; for dumps):
    /// (K, N, N) complex f32 bytes.
    pub fn download_h0(&self, ctx: &Arc<Context>) -> GpuResult<Option<Vec<u8>>> {
        match self.model.h0() {
            Some(h0) => download_on(ctx, ctx.compute, h0, h0.size() as usize).map(Some),
            None => Ok(None),
        }
    }

    /// The wake's image of `slot` (`--boat`; `None` without): N × N texels (h, ∂h/∂x, ∂h/∂z, foam),
    /// rows along z, read on the compute queue that wrote it (the caller waited for the frame
    /// that sampled it).
    pub fn read_wake(&self, ctx: &Arc<Context>, slot: usize) -> GpuResult<Option<Texels>> {
        if self.wake.place_of().is_none() {
            return Ok(None);
        }
        ctx.wait_idle()?;
        let bytes = download_image_layers_on(
            ctx,
            ctx.compute,
            &[&self.wake.images[slot]],
            Use::ComputeRead,
        )?;
        Ok(Some(bytemuck::cast_slice(&bytes[0]).to_vec()))
    }
}
