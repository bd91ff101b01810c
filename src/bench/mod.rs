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

/// The machine's CPU time counters (Linux `/proc/stat`, first line), in clock ticks: how much
/// time the hypervisor took from a virtual machine ("steal") over an interval, which explains a
/// benchmark that runs slower than the one before it.
#[derive(Clone, Copy, Debug)]
pub struct CpuTimes {
    steal: u64,
    total: u64,
}

impl CpuTimes {
    /// Now, or `None` where `/proc/stat` is missing or unreadable.
    pub fn now() -> Option<CpuTimes> {
        let stat = std::fs::read_to_string("/proc/stat").ok()?;
        // cpu  user nice system idle iowait irq softirq steal guest guest_nice
        let fields: Vec<u64> = stat
            .lines()
            .next()?
            .strip_prefix("cpu ")?
            .split_whitespace()
            .take(8)
            .map(|f| f.parse().ok())
            .collect::<Option<_>>()?;
        (fields.len() == 8).then(|| CpuTimes {
            steal: fields[7],
            total: fields.iter().sum(),
        })
    }

    /// Percentage of all CPU time stolen since `earlier` (0 when no time passed).
    pub fn steal_percent_since(&self, earlier: &CpuTimes) -> f64 {
        let total = self.total.saturating_sub(earlier.total);
        let steal = self.steal.saturating_sub(earlier.steal);
        if total == 0 {
            0.0
        } else {
            100.0 * steal as f64 / total as f64
        }
    }
}
