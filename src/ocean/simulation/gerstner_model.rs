//! The Gerstner wave model: a sum of analytic trochoidal waves with exact normals
//! (shaders/ocean/gerstner.comp), evaluated over a window that follows the camera. The waves'
//! phases at the window origin are reduced in f64 on the CPU every frame.

use std::sync::Arc;

use ash::vk;

use super::{scope, Kernel, ModelFrame, SlotImages, Timer, WaveModel};
use crate::gpu::{Bind, Bindings, BoundSet, Buffer, Context, MemoryLocation, Order, Recorder};
use crate::ocean::foam;
use crate::ocean::gerstner::{Wave, G_SEED};
use crate::ocean::moments::{Component, SeaMoments};
use crate::pass_names as names;
use crate::shaders;

/// One wave as gerstner.comp reads it.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GpuWave {
    wave: [f32; 4],
    extra: [f32; 4],
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct GerstnerParams {
    window_m: f32,
    dt_s: f32,
    foam_threshold: f32,
    foam_decay_s: f32,
    foam_gain: f32,
    n: u32,
    count: u32,
    /// Whole texels the window moved since the previous frame.
    shift: [i32; 2],
}

pub(super) struct GerstnerModel {
    pub(super) waves: Vec<Wave>,
    /// Per slot: the waves as the slot's frame sees them (θ at the window origin changes every
    /// frame), written by the host.
    buffers: Vec<Buffer>,
    kernel: Kernel,
    /// Per slot, like the FFT model's assemble sets.
    sets: Vec<BoundSet>,
}

impl GerstnerModel {
    /// The model's buffers, kernel and sets; `images` are bound at bindings 1–3, their texels
    /// `texel_m` apart. Also returns a bound on the displacement (m) and the sea's height.
    pub(super) fn new(
        ctx: &Arc<Context>,
        waves: &[Wave],
        images: &SlotImages,
        texel_m: f64,
    ) -> anyhow::Result<(GerstnerModel, f64, SeaMoments)> {
        anyhow::ensure!(!waves.is_empty(), "Gerstner mode needs at least one wave");
        let kernel = Kernel::image_writer(
            ctx,
            names::OCEAN_GERSTNER,
            shaders::OCEAN_GERSTNER_COMP,
            std::mem::size_of::<GerstnerParams>(),
        )?;
        let buffers = (0..super::FRAMES_IN_FLIGHT)
            .map(|slot| {
                Buffer::new(
                    ctx,
                    &format!("gerstner waves slot {slot}"),
                    (waves.len() * std::mem::size_of::<GpuWave>()) as u64,
                    vk::BufferUsageFlags::STORAGE_BUFFER,
                    MemoryLocation::CpuToGpu,
                )
            })
            .collect::<Result<Vec<_>, _>>()?;
        // The host writes a slot's waves once the slot's previous compute work is done.
        let sets = kernel.slot_sets(
            ctx,
            names::OCEAN_GERSTNER,
            |slot| Bind::Storage(&buffers[slot], Order::Host),
            images,
            &[],
        )?;
        // Each wave moves a point by at most a vertically and Q·a sideways.
        let max_displacement_m = waves
            .iter()
            .map(|w| w.amplitude.abs() * (1.0 + w.steepness.abs()))
            .sum::<f64>()
            + 0.5;
        // A wave of amplitude a holds a²/2 of the height variance (deep water, g of seed 000).
        let components = || {
            waves.iter().map(|w| Component {
                energy: 0.5 * w.amplitude * w.amplitude,
                omega: (G_SEED * w.kx.hypot(w.kz)).sqrt(),
                k: [w.kx, w.kz],
                layer: 0,
            })
        };
        let sea =
            SeaMoments::from_waves(components(), None).with_mip_gains(components(), [texel_m; 4]);
        let model = GerstnerModel {
            waves: waves.to_vec(),
            buffers,
            kernel,
            sets,
        };
        Ok((model, max_displacement_m, sea))
    }
}

impl WaveModel for GerstnerModel {
    fn prepare(&mut self, f: &ModelFrame) {
        let gpu_waves: Vec<GpuWave> = self
            .waves
            .iter()
            .map(|w| {
                let k = (w.kx * w.kx + w.kz * w.kz).sqrt();
                let omega = (G_SEED * k).sqrt();
                // θ at the origin, reduced in f64 so the shader's float phase stays exact.
                let theta0 =
                    (w.kx * f.origin_m[0] + w.kz * f.origin_m[1] - omega * f.time_s - w.phase)
                        .rem_euclid(2.0 * std::f64::consts::PI);
                GpuWave {
                    wave: [w.kx as f32, w.kz as f32, w.amplitude as f32, theta0 as f32],
                    extra: [w.steepness as f32, omega as f32, k as f32, 0.0],
                }
            })
            .collect();
        self.buffers[f.slot].write(bytemuck::cast_slice(&gpu_waves));
    }

    fn record(&self, rec: &Recorder, timer: &mut Timer, f: &ModelFrame) {
        let params = GerstnerParams {
            window_m: f.window_m as f32,
            dt_s: f.dt_s,
            foam_threshold: f.foam_threshold,
            foam_decay_s: foam::DECAY_S,
            foam_gain: foam::GAIN,
            n: f.n,
            count: self.waves.len() as u32,
            shift: f.window_shift,
        };
        let kernel = &self.kernel;
        scope(timer, rec, names::OCEAN_GERSTNER, || {
            rec.push_constants(&kernel.pipeline, &params);
            let b = Bindings {
                pipeline: &kernel.pipeline,
                sets: &[&self.sets[f.slot]],
            };
            let groups = f.n.div_ceil(8);
            rec.dispatch_with(&b, [groups, groups, 1]);
        });
    }

    fn gerstner_waves(&self) -> Option<&[Wave]> {
        Some(&self.waves)
    }
}
