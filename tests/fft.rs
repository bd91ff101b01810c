//! Our GPU Stockham FFT against rustfft (f64) on random complex input, for every supported N and
//! a few batch sizes, plus a forward/inverse round trip; validation-clean throughout.

mod common;

use std::sync::Arc;

use rustfft::num_complex::Complex64;
use vkocean::gpu::oneshot::{download, run_once, upload};
use vkocean::gpu::Context;
use vkocean::ocean::cpu::inverse_2d;
use vkocean::ocean::fft::{check_plan, threads_for, Direction, GpuFft, Kernel};

/// Deterministic pseudo-random complex values in [-1, 1]² (the benchmark's signal).
fn random_input(len: usize, seed: u64) -> Vec<[f32; 2]> {
    vkocean::bench::test_signal(len, seed)
        .iter()
        .map(|c| [c.re, c.im])
        .collect()
}

fn run_gpu(
    ctx: &Arc<Context>,
    fft: &GpuFft,
    input: &[[f32; 2]],
    directions: &[Direction],
) -> Vec<[f32; 2]> {
    upload(ctx, &fft.data, bytemuck::cast_slice(input)).unwrap();
    run_once(ctx, "fft test", |rec| {
        for &d in directions {
            fft.record(rec, d);
        }
    })
    .unwrap();
    let bytes = download(ctx, &fft.data, fft.byte_len()).unwrap();
    bytemuck::cast_slice(&bytes).to_vec()
}

fn relative_l2(ours: &[[f32; 2]], reference: &[Complex64]) -> f64 {
    common::relative_l2(
        ours.iter()
            .zip(reference)
            .flat_map(|(a, b)| [(a[0] as f64, b.re), (a[1] as f64, b.im)]),
    )
}

/// Every (N, batch, kernel) to test: both kernels wherever the device can run them, the
/// shared-memory one (for GPUs) always, the register one (for CPU drivers) where it applies.
fn plans(ctx: &Context, sizes: &[usize], batches: &[usize]) -> Vec<(usize, usize, Kernel)> {
    let mut all = Vec::new();
    for &n in sizes {
        for &batch in batches {
            let shared = Kernel::Shared {
                threads: threads_for(ctx, n),
            };
            for kernel in std::iter::once(shared).chain(Kernel::registers(ctx, n, batch)) {
                all.push((n, batch, kernel));
            }
        }
    }
    all
}

#[test]
fn lavapipe_gets_the_register_kernel_at_every_size() {
    let ctx = common::gpu_context();
    if ctx.info.device_type != vkocean::gpu::vk::PhysicalDeviceType::CPU {
        return; // GPUs keep the shared-memory kernel; nothing to check
    }
    for log2 in 6..=10 {
        let n = 1usize << log2;
        let kernel = Kernel::for_device(&ctx, n, 12);
        match kernel {
            Kernel::Registers { log2_lanes } => {
                // 256 values per lane: 1 lane up to N = 256, 2 for 512, 4 for 1024.
                assert_eq!(1usize << log2_lanes, n.div_ceil(256), "N = {n}");
            }
            Kernel::Shared { .. } => panic!("N = {n}: the shared-memory kernel on lavapipe"),
        }
    }
}

#[test]
fn inverse_fft_matches_rustfft_for_every_size() {
    let ctx = common::gpu_context();
    let sizes = [64usize, 128, 256, 512, 1024];
    for n in sizes {
        if let Err(e) = check_plan(&ctx, n, 3) {
            panic!("N = {n} should be supported on lavapipe: {e}");
        }
    }
    for (n, batch, kernel) in plans(&ctx, &sizes, &[1, 3]) {
        let fft = GpuFft::with_kernel(&ctx, n, batch, kernel).unwrap();
        let input = random_input(batch * n * n, (n * 31 + batch) as u64);
        let ours = run_gpu(&ctx, &fft, &input, &[Direction::Inverse]);
        let mut reference: Vec<Complex64> = input
            .iter()
            .map(|c| Complex64::new(c[0] as f64, c[1] as f64))
            .collect();
        for array in reference.chunks_exact_mut(n * n) {
            inverse_2d(array, n);
        }
        let err = relative_l2(&ours, &reference);
        assert!(
            err < 1e-5,
            "N = {n}, batch {batch}, {kernel:?}: relative L2 error {err:e}"
        );
    }
    common::assert_validation_clean(ctx);
}

#[test]
fn forward_then_inverse_is_identity() {
    let ctx = common::gpu_context();
    for (n, batch, kernel) in plans(&ctx, &[64, 256, 512, 1024], &[2]) {
        let fft = GpuFft::with_kernel(&ctx, n, batch, kernel).unwrap();
        let input = random_input(batch * n * n, n as u64);
        let out = run_gpu(
            &ctx,
            &fft,
            &input,
            &[Direction::Forward, Direction::Inverse],
        );
        let scale = 1.0 / (n * n) as f64;
        let reference: Vec<Complex64> = input
            .iter()
            .map(|c| Complex64::new(c[0] as f64, c[1] as f64) / scale)
            .collect();
        let err = relative_l2(&out, &reference);
        assert!(
            err < 1e-5,
            "N = {n}, {kernel:?}: round trip relative L2 error {err:e}"
        );
    }
    common::assert_validation_clean(ctx);
}

#[test]
fn unsupported_sizes_are_refused_with_a_reason() {
    let ctx = common::gpu_context();
    for n in [0usize, 32, 100, 2048] {
        let err = check_plan(&ctx, n, 1).unwrap_err();
        assert!(err.contains(&n.to_string()), "{err}");
    }
    // lavapipe allows 128 MiB per storage buffer: 1024² x 17 arrays of 8 bytes do not fit.
    assert!(check_plan(&ctx, 1024, 17).unwrap_err().contains("MiB"));
}
