//! The normal images' mip levels (shaders/ocean/slope_mips.comp), after the wave model wrote
//! level 0: each level the mean of 2x2 texels of the one below. water.frag samples each
//! cascade at the level the pixel's footprint asks for, along the view and across it (LEAN
//! mapping's idea, Olano & Baker 2010: filtered slopes, and the variance the filter took off
//! returned to the unresolved slopes: `moments::slope_mip_gains`). Without them a cascade's
//! slopes faded out as a whole once the footprint passed its shortest waves, its longer waves
//! with them.
//!
//! Only above a 64² grid (`slope_levels`): at `--quality low` the water keeps that fade, which
//! costs nothing, for the frame's budget.

use std::sync::Arc;

use ash::vk;

use super::{scope, Kernel, Timer};
use crate::gpu::{Bind, Bindings, BoundSet, Context, GpuResult, Image, Order, Recorder};
use crate::pass_names as names;
use crate::shaders;
use crate::shared::SLOPE_LEVELS;

/// Mip levels of the normal images for a grid of `fft_size` texels a side: `SLOPE_LEVELS`
/// above 64 (one workgroup reduces 32x32 texels to level 5), else none.
pub fn slope_levels(fft_size: usize) -> u32 {
    if fft_size > 64 {
        SLOPE_LEVELS
    } else {
        1
    }
}

/// The kernel and one set per slot (its normal image's levels).
pub(super) struct SlopeMips {
    kernel: Kernel,
    sets: Vec<BoundSet>,
}

impl SlopeMips {
    /// For the slots' `normals`; `None` when they have no mip levels.
    pub(super) fn new(ctx: &Arc<Context>, normals: &[Image]) -> GpuResult<Option<SlopeMips>> {
        if normals.first().is_none_or(|n| n.levels() == 1) {
            return Ok(None);
        }
        let bindings = [vk::DescriptorType::STORAGE_IMAGE; SLOPE_LEVELS as usize];
        let kernel = Kernel::new(
            ctx,
            names::OCEAN_SLOPE_MIPS,
            shaders::OCEAN_SLOPE_MIPS_COMP,
            &bindings,
            0,
        )?;
        let sets = normals
            .iter()
            .enumerate()
            .map(|(slot, image)| {
                let binds: Vec<_> = (0..SLOPE_LEVELS)
                    .map(|l| (l, Bind::StorageLevel(image, l, Order::Tracked)))
                    .collect();
                let name = format!("{} set slot {slot}", names::OCEAN_SLOPE_MIPS);
                BoundSet::new(ctx, &kernel.set_layout, &name, &binds)
            })
            .collect::<GpuResult<_>>()?;
        Ok(Some(SlopeMips { kernel, sets }))
    }

    /// Records the levels of `slot`'s normal image (`n` texels a side, `layers` cascades),
    /// once the wave model has written level 0.
    pub(super) fn record(
        &self,
        rec: &Recorder,
        timer: &mut Timer,
        slot: usize,
        n: u32,
        layers: u32,
    ) {
        scope(timer, rec, names::OCEAN_SLOPE_MIPS, || {
            let b = Bindings {
                pipeline: &self.kernel.pipeline,
                sets: &[&self.sets[slot]],
            };
            rec.dispatch_with(&b, [n / 32, n / 32, layers]);
        });
    }
}
