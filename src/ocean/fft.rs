//! Our GPU FFT: 2D complex transforms of a batch of N×N arrays by Stockham radix-2 autosort
//! passes. One dispatch per axis covers the whole batch (every packed field of every cascade);
//! each dispatch transforms one axis without a round trip through global memory between stages
//! and writes the result transposed, so the second dispatch does the other axis and leaves the
//! result in the original orientation.
//!
//! Two kernels share the butterfly code (shaders/common/fft.glsl), picked per device by
//! [`Kernel::for_device`]:
//! - [`Kernel::Shared`] (shaders/ocean/fft.comp), for GPUs: a workgroup per row, radix-8/16
//!   groups in registers exchanged through shared memory, coalesced loads.
//! - [`Kernel::Registers`] (shaders/ocean/fft_rows.comp), for CPU drivers (lavapipe): two
//!   columns per SIMD lane (one lane pair per column pair, joined by subgroup shuffles, for
//!   N = 512), all passes in registers, strided RGBA32F texel fetches in and contiguous 32-byte
//!   stores out. On llvmpipe a storage-buffer store costs a branch per lane and component while
//!   arithmetic is 8-wide and texel fetches are gathers, so this kernel is built around its
//!   stores; it is 8× faster there than the shared-memory one (`vkocean bench fft`, README).
//!
//! Transforms are unnormalized: inverse out[j] = Σ_n in[n] e^{+2πi nj/N} per axis (rustfft's
//! convention); forward uses e^{−2πi nj/N}.

use std::sync::Arc;

use ash::vk;

use crate::gpu::{
    Bind, Bindings, BoundSet, Buffer, BufferView, Context, DescriptorSetLayout, MemoryLocation,
    Order, Pipeline, PipelineLayout, Recorder,
};
use crate::shaders;

/// Smallest and largest supported N.
pub const MIN_N: usize = 64;
pub const MAX_N: usize = 1024;

/// Environment variable overriding the invocations per workgroup of the shared-memory kernel
/// (tuning experiments).
pub const THREADS_ENV: &str = "VKOCEAN_FFT_THREADS";
/// Environment variable forcing a kernel: `shared` or `registers` (experiments, comparisons).
pub const KERNEL_ENV: &str = "VKOCEAN_FFT_KERNEL";

/// Checks `VKOCEAN_FFT_KERNEL` and `VKOCEAN_FFT_THREADS` when set: a value that would be
/// ignored is an error (the message names the variable), not a silent fallback.
pub fn check_env() -> Result<(), String> {
    if let Some(v) = std::env::var_os(KERNEL_ENV) {
        let v = v.to_string_lossy();
        if v != "shared" && v != "registers" {
            return Err(format!("{KERNEL_ENV}={v}: must be shared or registers"));
        }
    }
    if let Some(v) = std::env::var_os(THREADS_ENV) {
        let v = v.to_string_lossy();
        match v.trim().parse::<u32>() {
            Ok(n) if n.is_power_of_two() && n <= 1024 => {}
            _ => {
                return Err(format!(
                    "{THREADS_ENV}={v}: must be a power of two from 1 to 1024 (the device's limit and N/8 cap it further)"
                ))
            }
        }
    }
    Ok(())
}

/// Column pairs per workgroup of the register kernel (one SIMD vector of lanes).
const REGISTER_PAIRS: u32 = 8;
/// Longest column the register kernel keeps in the registers of one invocation (which holds
/// two); longer columns are split over 2 (N = 512) or 4 (N = 1024) subgroup lanes. 2 lanes of
/// 2 × 512 values for N = 1024 took llvmpipe tens of seconds to compile; 4 lanes of 2 × 256
/// compile as fast as N = 512.
const REGISTER_MAX_M: usize = 256;
const REGISTER_MAX_N: usize = 4 * REGISTER_MAX_M;

/// Direction of a transform.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Direction {
    /// e^{+2πi nj/N}: spectrum → field.
    Inverse,
    /// e^{−2πi nj/N}.
    Forward,
}

/// Which shader does the transforms.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// fft.comp: a workgroup of `threads` invocations per row, shared memory between passes.
    Shared { threads: u32 },
    /// fft_rows.comp: 2^`log2_lanes` invocations (subgroup lanes) per pair of columns,
    /// registers only.
    Registers { log2_lanes: u32 },
}

impl Kernel {
    /// The kernel for this device and size: the register kernel on CPU drivers when it applies
    /// (see [`Kernel::registers`]), the shared-memory kernel otherwise. `VKOCEAN_FFT_KERNEL`
    /// overrides the choice when the forced kernel can run.
    pub fn for_device(ctx: &Context, n: usize, batch: usize) -> Kernel {
        let shared = Kernel::Shared {
            threads: threads_for(ctx, n),
        };
        let registers = Kernel::registers(ctx, n, batch);
        match std::env::var(KERNEL_ENV).as_deref() {
            Ok("shared") => return shared,
            Ok("registers") => return registers.unwrap_or(shared),
            _ => {}
        }
        match registers {
            Some(kernel) if ctx.info.device_type == vk::PhysicalDeviceType::CPU => kernel,
            _ => shared,
        }
    }

    /// The register kernel, if the device can run it for N and this batch: N ≤ 1024, 64-bit
    /// integers (its stores), RGBA32F uniform texel buffers (its loads), subgroup shuffles in
    /// subgroups of at least N/256 lanes (the lanes of one column above N = 256) and the batch
    /// within maxTexelBufferElements.
    pub fn registers(ctx: &Context, n: usize, batch: usize) -> Option<Kernel> {
        let lanes = n.div_ceil(REGISTER_MAX_M).max(1);
        let info = &ctx.info;
        let texels = batch * n * n / 2;
        let fits = n <= REGISTER_MAX_N
            && info.shader_int64
            // It reads its input as RGBA32F uniform texel buffers (not guaranteed by the spec).
            && ctx
                .buffer_format_features(vk::Format::R32G32B32A32_SFLOAT)
                .contains(vk::FormatFeatureFlags::UNIFORM_TEXEL_BUFFER)
            && texels <= info.limits.max_texel_buffer_elements as usize
            && (lanes == 1
                || (info.compute_subgroup_shuffle && info.subgroup_size as usize >= lanes));
        fits.then_some(Kernel::Registers {
            log2_lanes: lanes.trailing_zeros(),
        })
    }
}

/// Checks N (a power of two in MIN_N..=MAX_N) and the device limits for a batch.
pub fn check_plan(ctx: &Context, n: usize, batch: usize) -> Result<(), String> {
    if !n.is_power_of_two() || !(MIN_N..=MAX_N).contains(&n) {
        return Err(format!(
            "FFT size {n} is not a power of two from {MIN_N} to {MAX_N}"
        ));
    }
    let limits = &ctx.info.limits;
    let shared = 2 * n * 8;
    if shared > limits.max_compute_shared_memory_size as usize {
        return Err(format!(
            "FFT size {n} needs {shared} bytes of shared memory; {} allows {}",
            ctx.info.name, limits.max_compute_shared_memory_size
        ));
    }
    let bytes = (batch * n * n * 8) as u64;
    if bytes > limits.max_storage_buffer_range as u64 {
        return Err(format!(
            "FFT size {n} with {batch} fields needs a {} MiB buffer; {} allows {} MiB",
            bytes >> 20,
            ctx.info.name,
            limits.max_storage_buffer_range >> 20
        ));
    }
    if n > limits.max_compute_work_group_count[0] as usize
        || batch > limits.max_compute_work_group_count[1] as usize
    {
        return Err(format!(
            "FFT size {n} x {batch} exceeds the dispatch limits of {}",
            ctx.info.name
        ));
    }
    Ok(())
}

/// Invocations per workgroup of the shared-memory kernel. GPUs: one per group of 16 values
/// (N/16), so every thread of the 16-point passes has one group and the 8-point passes two. CPU
/// drivers: 8, one SIMD vector of lanes, which measured fastest for this kernel (N = 256,
/// batch 4: 1 → 85 ms, 4 → 34, 8 → 23, 16 → 29, 32 → 43). Capped by the device;
/// `VKOCEAN_FFT_THREADS` overrides it for experiments.
pub fn threads_for(ctx: &Context, n: usize) -> u32 {
    let limits = &ctx.info.limits;
    let cap = limits
        .max_compute_work_group_invocations
        .min(limits.max_compute_work_group_size[0]);
    let wanted = std::env::var(THREADS_ENV)
        .ok()
        .and_then(|v| v.parse::<u32>().ok())
        .unwrap_or(if ctx.info.device_type == vk::PhysicalDeviceType::CPU {
            8
        } else {
            (n / 16) as u32
        });
    wanted.clamp(1, cap).min((n / 8) as u32).next_power_of_two()
}

/// A batch of N×N 2D transforms on the GPU: buffers, the kernel's pipeline and descriptors.
pub struct GpuFft {
    pub n: usize,
    pub batch: usize,
    pub kernel: Kernel,
    /// Wall time vkCreateComputePipelines took for the kernel (the driver's shader compile;
    /// `bench fft` prints it).
    pub pipeline_ms: f64,
    /// Input and output, (batch, N, N) complex f32 (vec2).
    pub data: Buffer,
    /// The intermediate (row-transformed, transposed) arrays (bound by `sets`).
    _scratch: Buffer,
    /// The shared kernel's e^{+2πi m/N}, m < N, computed once in f64 (the register kernel's
    /// are compile-time constants; its sets read `data` and `scratch` through RGBA32F views).
    _twiddles: Option<Buffer>,
    _set_layout: DescriptorSetLayout,
    pipeline: Pipeline,
    /// data → scratch, scratch → data.
    sets: [BoundSet; 2],
    /// Workgroups per batch entry along x.
    groups_x: u32,
}

/// Push constants of both kernels.
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
struct FftParams {
    direction: f32,
}

impl GpuFft {
    /// Plans transforms of `batch` N×N arrays with the device's kernel ([`Kernel::for_device`]).
    pub fn new(ctx: &Arc<Context>, n: usize, batch: usize) -> anyhow::Result<GpuFft> {
        GpuFft::with_kernel(ctx, n, batch, Kernel::for_device(ctx, n, batch))
    }

    /// Plans transforms with a given kernel (tests run both on every device that can).
    // Long: both kernels' buffers, views, descriptor sets and pipelines; the kernel decides
    // each binding, so the steps stay side by side.
    pub fn with_kernel(
        ctx: &Arc<Context>,
        n: usize,
        batch: usize,
        kernel: Kernel,
    ) -> anyhow::Result<GpuFft> {
        check_plan(ctx, n, batch).map_err(anyhow::Error::msg)?;
        let bytes = (batch * n * n * 8) as u64;
        let usage = vk::BufferUsageFlags::STORAGE_BUFFER
            | vk::BufferUsageFlags::UNIFORM_TEXEL_BUFFER
            | vk::BufferUsageFlags::TRANSFER_SRC
            | vk::BufferUsageFlags::TRANSFER_DST;
        let data = Buffer::new(ctx, "fft data", bytes, usage, MemoryLocation::GpuOnly)?;
        let scratch = Buffer::new(ctx, "fft scratch", bytes, usage, MemoryLocation::GpuOnly)?;
        let storage = vk::DescriptorType::STORAGE_BUFFER;
        let texel = vk::DescriptorType::UNIFORM_TEXEL_BUFFER;
        let stage = vk::ShaderStageFlags::COMPUTE;
        let log2_n = n.trailing_zeros();

        let mut twiddles = None;
        let (bindings, spirv, constants, groups_x): (Vec<_>, _, Vec<u32>, u32) = match kernel {
            Kernel::Shared { threads } => (
                vec![
                    (0, storage, stage),
                    (1, storage, stage),
                    (2, storage, stage),
                ],
                shaders::OCEAN_FFT_COMP,
                vec![log2_n, threads],
                n as u32,
            ),
            Kernel::Registers { log2_lanes } => (
                vec![(0, texel, stage), (1, storage, stage)],
                shaders::OCEAN_FFT_ROWS_COMP,
                vec![
                    log2_n,
                    log2_lanes,
                    REGISTER_PAIRS,
                    REGISTER_PAIRS << log2_lanes,
                ],
                n as u32 / (2 * REGISTER_PAIRS),
            ),
        };
        let set_layout = DescriptorSetLayout::new(ctx, "fft set layout", &bindings)?;
        let layout = PipelineLayout::new(
            ctx,
            "fft layout",
            &[&set_layout],
            Some((stage, std::mem::size_of::<FftParams>() as u32)),
        )?;
        let compile = std::time::Instant::now();
        let pipeline = Pipeline::compute(
            ctx,
            &layout,
            &format!("fft N={n} {kernel:?}"),
            spirv,
            &constants,
        )?;
        let pipeline_ms = compile.elapsed().as_secs_f64() * 1e3;
        let t = Order::Tracked;
        let names = ["fft rows: data -> scratch", "fft columns: scratch -> data"];
        let sets = match kernel {
            Kernel::Shared { .. } => {
                let values: Vec<f32> = (0..n)
                    .flat_map(|j| {
                        let a = 2.0 * std::f64::consts::PI * j as f64 / n as f64;
                        [a.cos() as f32, a.sin() as f32]
                    })
                    .collect();
                let mut buffer = Buffer::new(
                    ctx,
                    &format!("fft twiddles N={n}"),
                    (n * 8) as u64,
                    vk::BufferUsageFlags::STORAGE_BUFFER,
                    MemoryLocation::CpuToGpu,
                )?;
                buffer.write(bytemuck::cast_slice(&values));
                let set = |name, from, to| {
                    BoundSet::new(
                        ctx,
                        &set_layout,
                        name,
                        &[
                            (0, Bind::Storage(from, t)),
                            (1, Bind::Storage(to, t)),
                            (2, Bind::Storage(&buffer, Order::Host)),
                        ],
                    )
                };
                let sets = [
                    set(names[0], &data, &scratch)?,
                    set(names[1], &scratch, &data)?,
                ];
                twiddles = Some(buffer);
                sets
            }
            Kernel::Registers { .. } => {
                let rgba = vk::Format::R32G32B32A32_SFLOAT;
                let data_view = BufferView::new(ctx, "fft data as RGBA32F", &data, rgba)?;
                let scratch_view = BufferView::new(ctx, "fft scratch as RGBA32F", &scratch, rgba)?;
                let set = |name, from, to| {
                    BoundSet::new(
                        ctx,
                        &set_layout,
                        name,
                        &[(0, Bind::UniformTexel(from, t)), (1, Bind::Storage(to, t))],
                    )
                };
                [
                    set(names[0], &data_view, &scratch)?,
                    set(names[1], &scratch_view, &data)?,
                ]
            }
        };
        Ok(GpuFft {
            n,
            batch,
            kernel,
            pipeline_ms,
            data,
            _scratch: scratch,
            _twiddles: twiddles,
            _set_layout: set_layout,
            pipeline,
            sets,
            groups_x,
        })
    }

    /// Size of `data` in bytes.
    pub fn byte_len(&self) -> usize {
        self.batch * self.n * self.n * 8
    }

    /// Records the 2D transform of `data` in place (its state says who wrote it last; `track`).
    pub fn record(&self, rec: &Recorder, direction: Direction) {
        let sign = match direction {
            Direction::Inverse => 1.0,
            Direction::Forward => -1.0,
        };
        // Rows: data → scratch; columns: scratch → data. The barriers between them come from
        // the kernel's `readonly` / `writeonly` bindings.
        for set in &self.sets {
            let b = Bindings {
                pipeline: &self.pipeline,
                sets: &[set],
            };
            rec.push_constants(&self.pipeline, &FftParams { direction: sign });
            rec.dispatch_with(&b, [self.groups_x, self.batch as u32, 1]);
        }
    }
}

/// How many radix-2 stages each pass fuses in registers, for N = 2^log2_n (6 ≤ log2_n ≤ 10):
/// ceil(log2_n / 4) passes of 3 or 4 stages (8- or 16-point groups), the larger first.
pub fn pass_schedule(log2_n: u32) -> Vec<u32> {
    let passes = log2_n.div_ceil(4);
    let base = log2_n / passes;
    let extra = log2_n % passes;
    (0..passes).map(|p| base + u32::from(p < extra)).collect()
}

/// The shader's algorithm on the CPU (one row): the executable specification of the index
/// arithmetic in fft.comp, checked against rustfft in the tests below.
///
/// A pass with R = 2^r (Ns = product of the earlier passes' R): for j < N/R, k = j mod Ns,
/// v_q = x[j + q N/R] · w^{qk} (w = e^{±2πi/(Ns R)}), v = DFT_R(v) computed by r radix-2 Stockham
/// stages on the R values, y[(j − k) R + k + q Ns] = v_q.
pub fn stockham_model(x: &mut [rustfft::num_complex::Complex64], direction: Direction) {
    use rustfft::num_complex::Complex64;
    let n = x.len();
    let sign = if direction == Direction::Inverse {
        1.0
    } else {
        -1.0
    };
    let root = |m: usize, of: usize| {
        Complex64::from_polar(
            1.0,
            sign * 2.0 * std::f64::consts::PI * m as f64 / of as f64,
        )
    };
    let mut from = x.to_vec();
    let mut to = vec![Complex64::new(0.0, 0.0); n];
    let mut ns = 1;
    for r in pass_schedule(n.trailing_zeros()) {
        let radix = 1usize << r;
        for j in 0..n / radix {
            let k = j % ns;
            let mut v: Vec<Complex64> = (0..radix)
                .map(|q| from[j + q * n / radix] * root(q * k * (n / (ns * radix)), n))
                .collect();
            // DFT_R by radix-2 Stockham stages on the registers.
            for ls in 0..r {
                let s = 1usize << ls;
                let mut u = vec![Complex64::new(0.0, 0.0); radix];
                for jj in 0..radix / 2 {
                    let kk = jj % s;
                    let a = v[jj];
                    let b = v[jj + radix / 2] * root(kk * (radix / (2 * s)), radix);
                    u[2 * jj - kk] = a + b;
                    u[2 * jj - kk + s] = a - b;
                }
                v = u;
            }
            for (q, value) in v.into_iter().enumerate() {
                to[(j - k) * radix + k + q * ns] = value;
            }
        }
        std::mem::swap(&mut from, &mut to);
        ns *= radix;
    }
    x.copy_from_slice(&from);
}

#[cfg(test)]
mod tests {
    use super::*;
    use rustfft::num_complex::Complex64;
    use rustfft::FftPlanner;

    #[test]
    fn stockham_model_matches_rustfft() {
        let mut planner = FftPlanner::<f64>::new();
        for log2 in 6..=10 {
            let n = 1usize << log2;
            let input: Vec<Complex64> = (0..n)
                .map(|i| Complex64::new((i as f64 * 0.37).sin(), (i as f64 * 1.3).cos() - 0.2))
                .collect();
            for direction in [Direction::Inverse, Direction::Forward] {
                let mut ours = input.clone();
                stockham_model(&mut ours, direction);
                let mut reference = input.clone();
                match direction {
                    Direction::Inverse => planner.plan_fft_inverse(n).process(&mut reference),
                    Direction::Forward => planner.plan_fft_forward(n).process(&mut reference),
                }
                let err: f64 = ours
                    .iter()
                    .zip(&reference)
                    .map(|(a, b)| (a - b).norm_sqr())
                    .sum();
                let norm: f64 = reference.iter().map(|b| b.norm_sqr()).sum();
                assert!((err / norm).sqrt() < 1e-12, "N = {n} {direction:?}");
            }
        }
    }
}
