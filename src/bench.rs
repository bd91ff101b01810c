//! `vkocean bench fft`: our GPU FFT against rustfft on the CPU, same transforms, same process.
//!
//! GPU: each measured "frame" restores the input (a copy outside the timed scope, so values never
//! grow without bound), then runs the batch of 2D inverse transforms inside one profiler pass;
//! times are GPU timestamps, the first `WARMUP_FRAMES` frames (pipeline JIT) excluded, median of
//! the rest. CPU: rustfft (one thread) on the same data and batch — rows, transpose, rows,
//! transpose back, which is the work the GPU does — median of the same number of runs.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

use ash::vk;
use rustfft::num_complex::Complex32;
use rustfft::FftPlanner;
use serde_json::json;

use crate::frontend::Outcome;
use crate::gpu::oneshot::upload;
use crate::gpu::{Access, Buffer, Context, ContextDesc, Frames, MemoryLocation, Profiler};
use crate::ocean::fft::{Direction, GpuFft};
use crate::output::PendingFile;
use crate::profile::{Stats, WARMUP_FRAMES};

/// Settings of `bench fft`.
#[derive(Clone, Debug)]
pub struct FftBenchSettings {
    pub sizes: Vec<usize>,
    pub batch: usize,
    /// Measured runs per size (after warm-up).
    pub runs: usize,
    pub json: Option<PathBuf>,
    pub validation: bool,
    pub gpu: Option<usize>,
}

/// One line of the table.
#[derive(Clone, Copy, Debug)]
pub struct FftRow {
    pub n: usize,
    pub batch: usize,
    pub gpu_ms: f64,
    pub rustfft_ms: f64,
}

pub fn fft(s: &FftBenchSettings) -> anyhow::Result<Outcome> {
    let json_file = s
        .json
        .as_deref()
        .map(|p| PendingFile::create("--json", p))
        .transpose()?;
    let ctx = Context::new(&ContextDesc {
        validation: s.validation,
        gpu_index: s.gpu,
        window: None,
    })?;
    let counters = ctx.counters();
    for &n in &s.sizes {
        crate::ocean::fft::check_plan(&ctx, n, s.batch).map_err(anyhow::Error::msg)?;
    }
    println!(
        "FFT benchmark: {} ({}); batch of {} 2D complex transforms, median of {} runs",
        ctx.info.name, ctx.info.driver, s.batch, s.runs
    );
    println!(
        "{:>6} {:>6} {:>10} {:>12} {:>8}",
        "N", "batch", "gpu_ms", "rustfft_ms", "ratio"
    );
    let mut rows = Vec::new();
    for &n in &s.sizes {
        let input = test_signal(s.batch * n * n, n as u64);
        let gpu_ms = gpu_median(&ctx, n, s.batch, s.runs, &input)?;
        let rustfft_ms = rustfft_median(n, s.runs, &input);
        let row = FftRow {
            n,
            batch: s.batch,
            gpu_ms,
            rustfft_ms,
        };
        println!(
            "{:>6} {:>6} {:>10.3} {:>12.3} {:>8.2}",
            n,
            s.batch,
            gpu_ms,
            rustfft_ms,
            gpu_ms / rustfft_ms
        );
        rows.push(row);
    }
    drop(ctx);
    if let Some(file) = json_file {
        let value: Vec<_> = rows
            .iter()
            .map(|r| {
                json!({"n": r.n, "batch": r.batch, "gpu_ms": r.gpu_ms, "rustfft_ms": r.rustfft_ms,
                       "ratio": r.gpu_ms / r.rustfft_ms})
            })
            .collect();
        file.commit((serde_json::to_string_pretty(&value)? + "\n").as_bytes())?;
    }
    Ok(Outcome { counters })
}

/// Deterministic complex test signal in [-1, 1]² (also the FFT tests' input).
pub fn test_signal(len: usize, seed: u64) -> Vec<Complex32> {
    let mut state = seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 40) as f32 / (1u64 << 23) as f32 * 2.0 - 1.0
    };
    (0..len).map(|_| Complex32::new(next(), next())).collect()
}

fn gpu_median(
    ctx: &Arc<Context>,
    n: usize,
    batch: usize,
    runs: usize,
    input: &[Complex32],
) -> anyhow::Result<f64> {
    let fft = GpuFft::new(ctx, n, batch)?;
    let bytes: Vec<u8> = input
        .iter()
        .flat_map(|c| [c.re.to_ne_bytes(), c.im.to_ne_bytes()])
        .flatten()
        .collect();
    let pristine = Buffer::new(
        ctx,
        "fft bench input",
        bytes.len() as u64,
        vk::BufferUsageFlags::TRANSFER_SRC | vk::BufferUsageFlags::TRANSFER_DST,
        MemoryLocation::GpuOnly,
    )?;
    upload(ctx, &pristine, &bytes)?;
    let mut frames = Frames::new(ctx)?;
    let mut profiler = Profiler::new(ctx, WARMUP_FRAMES)?;
    if !profiler.enabled() {
        anyhow::bail!(
            "{} has no timestamp queries; cannot time the GPU FFT",
            ctx.info.name
        );
    }
    for _ in 0..WARMUP_FRAMES as usize + runs {
        let frame = frames.begin()?;
        {
            let rec = frame.recorder(ctx);
            profiler.begin_frame(&rec, &frame)?;
            // The previous frame's transform read and wrote `data`.
            rec.barrier(
                &[],
                &[(
                    fft.data.raw,
                    Access::COMPUTE_READ.or(Access::COMPUTE_WRITE),
                    Access::COPY_WRITE,
                )],
            );
            rec.copy_buffer(&pristine, &fft.data, bytes.len() as u64);
            profiler.pass(&rec, "fft", || {
                fft.record(&rec, Direction::Inverse, Access::COPY_WRITE)
            });
            profiler.end_frame(&rec);
        }
        frames.submit(frame, &[], &[])?;
    }
    frames.wait_all()?;
    let timings = profiler.finish()?;
    let samples = timings
        .passes
        .iter()
        .find(|(name, _)| *name == "fft")
        .map(|(_, s)| s.clone())
        .unwrap_or_default();
    Ok(Stats::of(&samples)
        .ok_or_else(|| anyhow::anyhow!("no GPU FFT timing was measured"))?
        .median)
}

fn rustfft_median(n: usize, runs: usize, input: &[Complex32]) -> f64 {
    let fft = FftPlanner::<f32>::new().plan_fft_inverse(n);
    let mut scratch = vec![Complex32::new(0.0, 0.0); fft.get_inplace_scratch_len()];
    let mut data = input.to_vec();
    let mut transposed = vec![Complex32::new(0.0, 0.0); n * n];
    let mut samples = Vec::with_capacity(runs);
    for run in 0..3 + runs {
        data.copy_from_slice(input);
        let start = Instant::now();
        for array in data.chunks_exact_mut(n * n) {
            fft.process_with_scratch(array, &mut scratch);
            transpose(array, &mut transposed, n);
            fft.process_with_scratch(&mut transposed, &mut scratch);
            transpose(&transposed, array, n);
        }
        if run >= 3 {
            samples.push(start.elapsed().as_secs_f64() * 1e3);
        }
        std::hint::black_box(&data);
    }
    Stats::of(&samples).expect("runs > 0").median
}

/// Blocked out-of-place transpose of an n×n array.
fn transpose(src: &[Complex32], dst: &mut [Complex32], n: usize) {
    const B: usize = 8;
    for bi in (0..n).step_by(B) {
        for bj in (0..n).step_by(B) {
            for i in bi..(bi + B).min(n) {
                for j in bj..(bj + B).min(n) {
                    dst[j * n + i] = src[i * n + j];
                }
            }
        }
    }
}
