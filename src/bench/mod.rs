//! Benchmarks. Times are GPU timestamps (and wall-clock frame times), reported as medians after
//! a warm-up, with any reference measured in the same process.
//!
//! - [`fft`]: our GPU FFT against rustfft on the same transforms (`vkocean bench fft`).
//! - [`frames`]: the whole sample, headless, per pass and per frame (`vkocean bench frames`).
//! - [`gerstner`]: seed 004's experiment, FPS against wave count and grid width
//!   (`vkocean bench gerstner`).

mod fft;
pub mod frames;
pub mod gerstner;

pub use fft::{fft, test_signal, FftBenchSettings, FftRow};
