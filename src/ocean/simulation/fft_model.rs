//! The FFT wave model (Tessendorf 2001): h0 and each element's ω quantum uploaded once; per
//! frame evolve (shaders/ocean/evolve.comp) → inverse FFT (`ocean::fft`) → assemble
//! (assemble.comp: sign correction, Jacobian, exact normal, the surface's foam) into the slot's images.

use std::sync::Arc;

use ash::vk;

use super::foam_sim::{FoamSim, Wind};
use super::spray_sim::{SprayBuffers, SpraySim};
use super::{scope, Kernel, ModelFrame, SlotImages, Timer, WaveModel};
use crate::gpu::oneshot::upload_on;
use crate::gpu::{
    Bind, Bindings, BoundSet, Buffer, Context, Image, MemoryLocation, Order, Recorder,
};
use crate::ocean::fft::{Direction, GpuFft};
use crate::ocean::foam;
use crate::ocean::moments::{Component, SeaMoments};
use crate::ocean::params::OceanSettings;
use crate::ocean::spectrum::{
    dispersion, h0, omega_steps_grid, time_ticks, wave_vector, wind_vector, Cascade,
};
use crate::pass_names as names;
use crate::shaders;

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct EvolveParams {
    patch_m: [f32; 4],
    /// `spectrum::time_ticks` of the frame's time.
    ticks: u32,
    n: u32,
}

#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct AssembleParams {
    patch_m: [f32; 4],
    choppiness: f32,
    dt_s: f32,
    foam_threshold: f32,
    foam_decay_s: f32,
    foam_gain: f32,
    n: u32,
    cascades: u32,
    /// 1: write each cascade's derivatives for the foam step (only when it runs).
    derivatives: u32,
}

pub(super) struct FftModel {
    /// h0 of every cascade, (K, N, N) complex.
    h0: Buffer,
    /// Every element's quantized frequency ω/ω0 (`spectrum::omega_steps`), (K, N, N) u32
    /// (bound by `evolve_set`).
    _omega_steps: Buffer,
    fft: GpuFft,
    evolve: Kernel,
    assemble: Kernel,
    evolve_set: BoundSet,
    /// Per slot: writes that slot's images, reads the other slot's normals (foam).
    assemble_sets: Vec<BoundSet>,
    /// The foam near the camera, after assemble from the same FFT output.
    foam: FoamSim,
    /// The spray, after the foam (`--spray on`).
    spray: Option<SpraySim>,
}

impl FftModel {
    /// The model's buffers, kernels and sets; `images` are bound at bindings 1–3 of the
    /// assemble sets, `foam` (per slot) is the foam simulation's. Also returns a bound on the
    /// displacement (m) and the sea's height.
    pub(super) fn new(
        ctx: &Arc<Context>,
        settings: &OceanSettings,
        cascades: &[Cascade],
        images: &SlotImages,
        derivatives: &Image,
        foam: &[Image],
    ) -> anyhow::Result<(FftModel, f64, SeaMoments)> {
        let fft = GpuFft::new(ctx, settings.fft_size, 4 * cascades.len())?;
        let (h0_buffer, steps_buffer, max_displacement_m, sea) =
            upload_spectrum(ctx, settings, cascades)?;
        let storage = vk::DescriptorType::STORAGE_BUFFER;
        let evolve = Kernel::new(
            ctx,
            names::OCEAN_EVOLVE,
            shaders::OCEAN_EVOLVE_COMP,
            &[storage, storage, storage],
            std::mem::size_of::<EvolveParams>(),
        )?;
        // An image writer's bindings (0–3), and the derivatives it writes for the foam (4).
        let image = vk::DescriptorType::STORAGE_IMAGE;
        let assemble = Kernel::new(
            ctx,
            names::OCEAN_ASSEMBLE,
            shaders::OCEAN_ASSEMBLE_COMP,
            &[storage, image, image, image, image],
            std::mem::size_of::<AssembleParams>(),
        )?;
        let t = Order::Tracked;
        let evolve_set = BoundSet::new(
            ctx,
            &evolve.set_layout,
            "ocean evolve set",
            &[
                (0, Bind::Storage(&h0_buffer, t)),
                (1, Bind::Storage(&fft.data, t)),
                (2, Bind::Storage(&steps_buffer, t)),
            ],
        )?;
        let assemble_sets = assemble.slot_sets(
            ctx,
            names::OCEAN_ASSEMBLE,
            |_| Bind::Storage(&fft.data, t),
            images,
            &[(4, Bind::StorageImage(derivatives, t))],
        )?;
        let wind = Wind {
            dir: wind_vector(&settings.sea),
            u10: settings.sea.wind_speed_m_s,
        };
        let spray = settings
            .spray
            .then(|| SpraySim::new(ctx, &fft.data, foam, wind))
            .transpose()?;
        let foam = FoamSim::new(ctx, derivatives, foam, wind)?;
        let model = FftModel {
            foam,
            spray,
            h0: h0_buffer,
            _omega_steps: steps_buffer,
            fft,
            evolve,
            assemble,
            evolve_set,
            assemble_sets,
        };
        Ok((model, max_displacement_m, sea))
    }
}

/// h0 of every cascade and every element's ω quantum, uploaded on the compute queue; a bound
/// on the displacement (m) from the spectrum's variance; the sea's Hs and mean frequency.
fn upload_spectrum(
    ctx: &Arc<Context>,
    settings: &OceanSettings,
    cascades: &[Cascade],
) -> anyhow::Result<(Buffer, Buffer, f64, SeaMoments)> {
    let n = settings.fft_size;
    let h0_values: Vec<[f32; 2]> = cascades
        .iter()
        .enumerate()
        .flat_map(|(c, cascade)| h0(&settings.sea, n, cascade, c as u32, settings.seed))
        .collect();
    // Parseval: the height variance is Σ_k E|h(k,t)|² = 2 Σ_k |h0(k)|² (item 3's two terms),
    // each element's energy at its wave vector in its cascade's grid: Hs = 4σ, the mean
    // frequency and each cascade's mean-square slope. Crests rarely pass 4σ, and choppiness
    // moves points sideways by about λ times the height's scale.
    let depth = settings.sea.depth_m;
    let components = || {
        cascades.iter().enumerate().flat_map(|(c, cascade)| {
            let h0 = &h0_values[c * n * n..(c + 1) * n * n];
            h0.iter().enumerate().map(move |(i, [re, im])| {
                let k = wave_vector(i % n, i / n, n, cascade.patch_m);
                Component {
                    energy: 2.0 * (*re as f64 * *re as f64 + *im as f64 * *im as f64),
                    omega: dispersion(k[0].hypot(k[1]), depth).0,
                    k,
                    layer: c,
                }
            })
        })
    };
    // Each cascade's image is its patch over N texels.
    let texel_m = std::array::from_fn(|c| cascades.get(c).map_or(1.0, |l| l.patch_m / n as f64));
    let sea = SeaMoments::from_waves(components(), depth).with_mip_gains(components(), texel_m);
    let max_displacement_m = sea.hs_m * (1.0 + settings.choppiness) + 0.5;
    // Uploaded, read and (--dump) downloaded on the compute queue only: it never crosses
    // queue families.
    let h0_bytes: &[u8] = bytemuck::cast_slice(&h0_values);
    let h0_buffer = Buffer::new(
        ctx,
        "h0 (all cascades)",
        h0_bytes.len() as u64,
        vk::BufferUsageFlags::STORAGE_BUFFER
            | vk::BufferUsageFlags::TRANSFER_DST
            | vk::BufferUsageFlags::TRANSFER_SRC,
        MemoryLocation::GpuOnly,
    )?;
    upload_on(ctx, ctx.compute, &h0_buffer, h0_bytes)?;
    let steps: Vec<u32> = cascades
        .iter()
        .flat_map(|c| omega_steps_grid(n, c.patch_m, settings.sea.depth_m))
        .collect();
    let steps_buffer = Buffer::new(
        ctx,
        "omega steps (all cascades)",
        (steps.len() * 4) as u64,
        vk::BufferUsageFlags::STORAGE_BUFFER | vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuOnly,
    )?;
    upload_on(
        ctx,
        ctx.compute,
        &steps_buffer,
        bytemuck::cast_slice(&steps),
    )?;
    Ok((h0_buffer, steps_buffer, max_displacement_m, sea))
}

impl WaveModel for FftModel {
    fn prepare(&mut self, f: &ModelFrame) {
        self.foam.prepare(f);
        if let Some(spray) = &mut self.spray {
            spray.prepare(f);
        }
    }

    fn record(&self, rec: &Recorder, timer: &mut Timer, f: &ModelFrame) {
        let groups = f.n.div_ceil(8);
        let evolve_params = EvolveParams {
            patch_m: f.patch_m,
            ticks: time_ticks(f.time_s),
            n: f.n,
        };
        let assemble_params = AssembleParams {
            patch_m: f.patch_m,
            choppiness: f.choppiness,
            dt_s: f.dt_s,
            foam_threshold: f.foam_threshold,
            foam_decay_s: foam::DECAY_S,
            foam_gain: foam::GAIN,
            n: f.n,
            cascades: f.layers,
            derivatives: u32::from(f.foam.count > 0),
        };
        let (evolve, assemble) = (&self.evolve, &self.assemble);
        scope(timer, rec, names::OCEAN_EVOLVE, || {
            // h(k, t) from h0 into the FFT data (the previous frame's FFT and assemble used it).
            rec.push_constants(&evolve.pipeline, &evolve_params);
            let b = Bindings {
                pipeline: &evolve.pipeline,
                sets: &[&self.evolve_set],
            };
            rec.dispatch_with(&b, [groups, groups, f.layers]);
        });
        scope(timer, rec, names::OCEAN_FFT, || {
            self.fft.record(rec, Direction::Inverse)
        });
        scope(timer, rec, names::OCEAN_ASSEMBLE, || {
            rec.push_constants(&assemble.pipeline, &assemble_params);
            let b = Bindings {
                pipeline: &assemble.pipeline,
                sets: &[&self.assemble_sets[f.slot]],
            };
            rec.dispatch_with(&b, [groups, groups, f.layers]);
        });
        self.foam.record(rec, timer, f);
        if let Some(spray) = self.spray.as_ref().filter(|_| f.spray) {
            spray.record(rec, timer, f);
        }
    }

    fn spray(&self) -> Option<&SprayBuffers> {
        self.spray.as_ref().map(SpraySim::buffers)
    }

    fn h0(&self) -> Option<&Buffer> {
        Some(&self.h0)
    }
}
