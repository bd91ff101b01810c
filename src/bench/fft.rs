//! `vkocean bench fft`: our GPU FFT against rustfft on the CPU, same transforms, same process.
//!
//! GPU: each measured "frame" restores the input (a copy outside the timed scope, so values never
//! grow without bound), then runs the batch of 2D inverse transforms inside one profiler pass,
//! submitted on the compute queue the simulation ships on (`ComputeQueue`, timed by
//! `Profiler::for_compute`: that family's `timestampValidBits`; on lavapipe the one queue);
//! an empty graphics frame waits for it, so frame pacing and deferred deletion run as in a
//! frame of the renderer; times are GPU timestamps, the first `WARMUP_FRAMES` frames (pipeline JIT) excluded, median of
//! the rest. CPU: rustfft (one thread) on the same data and batch: rows, transpose, rows,
//! transpose back, which is the work the GPU does. `rustfft_ms` (the ratio's denominator) counts
//! the 2·batch·N one-dimensional transforms only, the measure of the anchors in MEASURED.md
//! (VkFFT ≈ 9× rustfft at N = 256); `rustfft_2d_ms` adds the transposes. Medians of the same
//! number of runs: `--runs R`, or by default at least `MIN_RUNS` and as many more as fit in
//! `MIN_SECONDS` per size (this 2-core VM loses a core to steal time for tenths of a second at a
//! time, so a median over a few hundred milliseconds can land inside one such episode).

use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

use ash::vk;
use rustfft::num_complex::Complex32;
use rustfft::FftPlanner;
use serde_json::json;

use super::CpuTimes;
use crate::frontend::Outcome;
use crate::gpu::compute::ComputeQueue;
use crate::gpu::oneshot::upload_on;
use crate::gpu::{Buffer, Context, Frames, MemoryLocation, Needs, Profiler};
use crate::ocean::fft::{Direction, GpuFft, Kernel};
use crate::output::PendingFile;
use crate::profile::{Stats, WARMUP_FRAMES};

/// Settings of `bench fft`.
#[derive(Clone, Debug)]
pub struct FftBenchSettings {
    pub sizes: Vec<usize>,
    pub batch: usize,
    /// Measured runs per size (after warm-up); `None`: at least `MIN_RUNS`, more until
    /// `MIN_SECONDS` have passed (at most `MAX_RUNS`).
    pub runs: Option<usize>,
    pub json: Option<PathBuf>,
    pub validation: bool,
    pub validation_extras: crate::gpu::ValidationExtras,
    pub gpu: Option<usize>,
}

/// One line of the table.
#[derive(Clone, Debug)]
pub struct FftRow {
    pub n: usize,
    pub batch: usize,
    pub gpu_ms: f64,
    /// The 1D transforms only.
    pub rustfft_ms: f64,
    /// With the transposes between the axes.
    pub rustfft_2d_ms: f64,
    /// The GPU kernel, e.g. "registers, 1 lane per 2 columns".
    pub kernel: String,
    /// Time to create the kernel's pipeline (the driver's compile), ms.
    pub pipeline_ms: f64,
    /// Measured runs behind the medians.
    pub runs: usize,
    /// Share of the machine's CPU time the hypervisor took during the runs (Linux only).
    pub steal_pct: Option<f64>,
}

/// Default run count: at least this many runs per size...
const MIN_RUNS: usize = 30;
/// ... and more until this much time has passed ...
const MIN_SECONDS: f64 = 3.0;
/// ... but no more than this.
const MAX_RUNS: usize = 2000;

pub fn fft(s: &FftBenchSettings) -> anyhow::Result<Outcome> {
    let json_file = PendingFile::create_if("--json", s.json.as_deref())?;
    let ctx = Context::headless(s.validation, s.validation_extras, s.gpu, Needs::COMPUTE)?;
    let counters = ctx.counters();
    for &n in &s.sizes {
        crate::ocean::fft::check_plan(&ctx, n, s.batch).map_err(anyhow::Error::msg)?;
    }
    let runs = match s.runs {
        Some(r) => format!("{r} runs"),
        None => format!("at least {MIN_RUNS} runs over at least {MIN_SECONDS} s"),
    };
    crate::outln!(
        "FFT benchmark: {} ({}); batch of {} 2D complex transforms, median of {runs} per size",
        ctx.info.name,
        ctx.info.driver,
        s.batch,
    );
    crate::outln!(
        "{:>6} {:>6} {:>10} {:>12} {:>8} {:>14} {:>8} {:>11} {:>6} {:>7}  kernel",
        "N",
        "batch",
        "gpu_ms",
        "rustfft_ms",
        "ratio",
        "rustfft_2d_ms",
        "ratio_2d",
        "pipeline_ms",
        "runs",
        "steal%"
    );
    let mut rows = Vec::new();
    for &n in &s.sizes {
        let input = test_signal(s.batch * n * n, n as u64);
        let row = measure(&ctx, n, s.batch, s.runs, &input)?;
        crate::outln!(
            "{:>6} {:>6} {:>10.3} {:>12.3} {:>8.2} {:>14.3} {:>8.2} {:>11.1} {:>6} {:>7}  {}",
            n,
            s.batch,
            row.gpu_ms,
            row.rustfft_ms,
            row.gpu_ms / row.rustfft_ms,
            row.rustfft_2d_ms,
            row.gpu_ms / row.rustfft_2d_ms,
            row.pipeline_ms,
            row.runs,
            row.steal_pct.map_or("-".to_string(), |p| format!("{p:.1}")),
            row.kernel
        );
        rows.push(row);
    }
    drop(ctx);
    if let Some(file) = json_file {
        let value: Vec<_> = rows
            .iter()
            .map(|r| {
                json!({"n": r.n, "batch": r.batch, "gpu_ms": r.gpu_ms, "rustfft_ms": r.rustfft_ms,
                       "ratio": r.gpu_ms / r.rustfft_ms, "rustfft_2d_ms": r.rustfft_2d_ms,
                       "ratio_2d": r.gpu_ms / r.rustfft_2d_ms, "pipeline_ms": r.pipeline_ms,
                       "kernel": r.kernel, "runs": r.runs, "steal_pct": r.steal_pct})
            })
            .collect();
        // The table went to stdout row by row: a failed write fails the run before the JSON.
        crate::output::stdout_status()?;
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

/// One row: medians of the GPU transform and of rustfft (1D transforms only; with transposes),
/// in ms, the GPU kernel, the number of measured runs and the steal time meanwhile. Runs
/// alternate: one GPU frame, waited for, then one CPU run, so both see the same machine (this
/// 2-core VM's speed drifts by 2× over minutes).
fn measure(
    ctx: &Arc<Context>,
    n: usize,
    batch: usize,
    runs: Option<usize>,
    input: &[Complex32],
) -> anyhow::Result<FftRow> {
    let fft = GpuFft::new(ctx, n, batch)?;
    let mut cpu = RustFft::new(n, input);
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
    // Used on the compute queue only, like every simulation buffer (EXCLUSIVE there).
    upload_on(ctx, ctx.compute, &pristine, &bytes)?;
    let mut frames = Frames::new(ctx)?;
    let mut compute = ComputeQueue::new(ctx)?;
    // Disabled when the compute family's timestampValidBits is 0.
    let mut profiler = Profiler::for_compute(ctx, WARMUP_FRAMES)?;
    if !profiler.enabled() {
        anyhow::bail!(
            "{}'s compute queue family has no timestamp queries (timestampValidBits 0); \
             cannot time the GPU FFT",
            ctx.info.name
        );
    }
    let (min_runs, max_runs, min_time) = match runs {
        Some(r) => (r, r, Duration::ZERO),
        None => (MIN_RUNS, MAX_RUNS, Duration::from_secs_f64(MIN_SECONDS)),
    };
    let mut cpu_fft = Vec::new();
    let mut cpu_2d = Vec::new();
    let mut measuring_since = None;
    let mut cpu_times_before = None;
    for run in 0.. {
        crate::interrupt::check()?;
        let measured = cpu_fft.len();
        let elapsed = measuring_since.map_or(Duration::ZERO, |t: Instant| t.elapsed());
        if measured >= max_runs || (measured >= min_runs && elapsed >= min_time) {
            break;
        }
        if run == WARMUP_FRAMES as usize {
            measuring_since = Some(Instant::now());
            cpu_times_before = CpuTimes::now();
        }
        let frame = frames.begin()?;
        let value = frame.signal_value();
        // The previous run was waited for: nothing to wait on before the compute work.
        compute.submit(frame.slot, value, None, |rec| {
            profiler.begin_frame(rec, &frame)?;
            // After the previous frame's transform read and wrote `data` (the copy records its
            // barrier).
            rec.copy_buffer(&pristine, &fft.data, bytes.len() as u64);
            profiler.pass(rec, "fft", || fft.record(rec, Direction::Inverse));
            profiler.end_frame(rec);
            Ok(())
        })?;
        let wait = compute.graphics_wait(value, vk::PipelineStageFlags2::ALL_COMMANDS);
        frames.submit(frame, &[wait], &[])?;
        frames.wait_all()?;
        let (fft_ms, total_ms) = cpu.run();
        if run >= WARMUP_FRAMES as usize {
            cpu_fft.push(fft_ms);
            cpu_2d.push(total_ms);
        }
    }
    let timings = profiler.finish()?;
    let samples = timings
        .passes
        .iter()
        .find(|(name, _)| *name == "fft")
        .map(|(_, s)| s.clone())
        .unwrap_or_default();
    let median = Stats::of(&samples)
        .ok_or_else(|| anyhow::anyhow!("no GPU FFT timing was measured"))?
        .median;
    let cpu_median = |v: &[f64]| Stats::of(v).expect("runs > 0").median;
    let steal_pct = cpu_times_before
        .zip(CpuTimes::now())
        .map(|(before, after)| after.steal_percent_since(&before));
    Ok(FftRow {
        n,
        batch,
        gpu_ms: median,
        rustfft_ms: cpu_median(&cpu_fft),
        rustfft_2d_ms: cpu_median(&cpu_2d),
        kernel: kernel_name(fft.kernel),
        pipeline_ms: fft.pipeline_ms,
        runs: cpu_fft.len(),
        steal_pct,
    })
}

fn kernel_name(kernel: Kernel) -> String {
    match kernel {
        Kernel::Shared { threads } => format!("shared memory, {threads} invocations per row"),
        Kernel::Registers { log2_lanes } => {
            let lanes = 1u32 << log2_lanes;
            format!(
                "registers, {lanes} lane{} per 2 columns",
                if lanes == 1 { "" } else { "s" }
            )
        }
    }
}

/// rustfft (one thread) on the benchmark's batch: rows, transpose, rows, transpose back.
struct RustFft<'a> {
    fft: Arc<dyn rustfft::Fft<f32>>,
    n: usize,
    input: &'a [Complex32],
    data: Vec<Complex32>,
    transposed: Vec<Complex32>,
    scratch: Vec<Complex32>,
}

impl<'a> RustFft<'a> {
    fn new(n: usize, input: &'a [Complex32]) -> RustFft<'a> {
        let fft = FftPlanner::<f32>::new().plan_fft_inverse(n);
        let zero = Complex32::new(0.0, 0.0);
        RustFft {
            scratch: vec![zero; fft.get_inplace_scratch_len()],
            fft,
            n,
            input,
            data: input.to_vec(),
            transposed: vec![zero; n * n],
        }
    }

    /// One run: (1D transforms only, whole 2D transforms) in ms.
    fn run(&mut self) -> (f64, f64) {
        let n = self.n;
        self.data.copy_from_slice(self.input);
        let start = Instant::now();
        let mut fft_s = 0.0;
        for array in self.data.chunks_exact_mut(n * n) {
            let t = Instant::now();
            self.fft.process_with_scratch(array, &mut self.scratch);
            fft_s += t.elapsed().as_secs_f64();
            transpose(array, &mut self.transposed, n);
            let t = Instant::now();
            self.fft
                .process_with_scratch(&mut self.transposed, &mut self.scratch);
            fft_s += t.elapsed().as_secs_f64();
            transpose(&self.transposed, array, n);
        }
        let total_s = start.elapsed().as_secs_f64();
        std::hint::black_box(&self.data);
        (fft_s * 1e3, total_s * 1e3)
    }
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
