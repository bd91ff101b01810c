//! `--profile PATH`: GPU timestamps per pass (compute passes first, then graphics) and per frame
//! (`frame_gpu_ms`: the two graphics submissions, without the time between them; `compute_gpu_ms`:
//! the compute submission), CPU frame times, as JSON:
//! `{"device","driver","frames","warmup_frames","size":[w,h],"passes":[{"name","submission","gpu_ms":{min,median,mean,p95,max},"samples"}],
//!   "frame_gpu_ms":{..},"compute_gpu_ms":{..},"gpu_total_ms":{..},"frame_cpu_ms":{..}}`
//! (`gpu_total_ms`: compute + graphics per frame). The first `WARMUP_FRAMES` frames are excluded.

use serde_json::{json, Value};

use crate::gpu::{DeviceInfo, DrawStatistics, GpuTimings};

/// Frames excluded from statistics (pipeline JIT, first-use allocations).
pub const WARMUP_FRAMES: u64 = 5;

/// min, median, mean, p95, max of a sample set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Stats {
    pub min: f64,
    pub median: f64,
    pub mean: f64,
    pub p95: f64,
    pub max: f64,
}

impl Stats {
    /// `None` for an empty sample set. Percentiles by linear interpolation between ranks.
    pub fn of(samples: &[f64]) -> Option<Stats> {
        if samples.is_empty() {
            return None;
        }
        let mut sorted = samples.to_vec();
        sorted.sort_by(f64::total_cmp);
        let pct = |p: f64| {
            let rank = p * (sorted.len() - 1) as f64;
            let (lo, hi) = (rank.floor() as usize, rank.ceil() as usize);
            sorted[lo] + (sorted[hi] - sorted[lo]) * (rank - lo as f64)
        };
        Some(Stats {
            min: sorted[0],
            median: pct(0.5),
            mean: sorted.iter().sum::<f64>() / sorted.len() as f64,
            p95: pct(0.95),
            max: sorted[sorted.len() - 1],
        })
    }

    fn json(samples: &[f64]) -> Value {
        match Stats::of(samples) {
            Some(s) => {
                json!({"min": s.min, "median": s.median, "mean": s.mean, "p95": s.p95, "max": s.max})
            }
            None => Value::Null,
        }
    }
}

/// Everything a profile report says.
pub struct ProfileReport<'a> {
    pub device: &'a DeviceInfo,
    pub frames: u64,
    /// Leading frames left out of the statistics.
    pub warmup_frames: u64,
    pub size: (u32, u32),
    pub gpu: &'a GpuTimings,
    /// The compute submission's passes (the simulation), timed in its own query pools.
    pub compute: &'a GpuTimings,
    /// CPU frame times (ms) after warm-up: wall time from one frame's start to the next.
    pub cpu_frame_ms: &'a [f64],
}

/// Per frame both submissions timed: (frame index, compute ms, graphics ms). Frames without a
/// compute submission count 0 for it.
pub fn gpu_per_frame(graphics: &GpuTimings, compute: &GpuTimings) -> Vec<(u64, f64, f64)> {
    let compute: std::collections::BTreeMap<u64, f64> = compute
        .per_frame
        .iter()
        .map(|f| (f.index, f.total_ms))
        .collect();
    graphics
        .per_frame
        .iter()
        .map(|f| {
            (
                f.index,
                compute.get(&f.index).copied().unwrap_or(0.0),
                f.total_ms,
            )
        })
        .collect()
}

/// Compute + graphics GPU ms per frame (one queue on lavapipe: they run back to back).
pub fn gpu_total_ms(graphics: &GpuTimings, compute: &GpuTimings) -> Vec<f64> {
    gpu_per_frame(graphics, compute)
        .iter()
        .map(|f| f.1 + f.2)
        .collect()
}

impl ProfileReport<'_> {
    pub fn gpu_total_ms(&self) -> Vec<f64> {
        gpu_total_ms(self.gpu, self.compute)
    }

    pub fn to_json(&self) -> String {
        serde_json::to_string_pretty(&self.to_value()).expect("a JSON value always serializes")
            + "\n"
    }

    pub fn to_value(&self) -> Value {
        let passes: Vec<Value> = self
            .compute
            .passes
            .iter()
            .chain(&self.gpu.passes)
            .map(|(name, samples)| json!({"name": name, "submission": self.submission_of(name), "gpu_ms": Stats::json(samples), "samples": samples.len()}))
            .collect();
        let report = json!({
            "device": self.device.name,
            "driver": self.device.driver,
            "frames": self.frames,
            "warmup_frames": self.warmup_frames,
            "size": [self.size.0, self.size.1],
            "passes": passes,
            "frame_gpu_ms": Stats::json(&self.gpu.frames),
            "compute_gpu_ms": Stats::json(&self.compute.frames),
            "gpu_total_ms": Stats::json(&self.gpu_total_ms()),
            "frame_cpu_ms": Stats::json(self.cpu_frame_ms),
        });
        let mut report = report;
        if !self.gpu.statistics.is_empty() {
            let column = |f| self.statistics_column(f);
            report["water_tessellation"] = json!({
                "patches": Stats::json(&column(|c| c.patches)),
                "tess_eval_invocations": Stats::json(&column(|c| c.tess_eval_invocations)),
                "primitives": Stats::json(&column(|c| c.primitives)),
                "fragment_invocations": Stats::json(&column(|c| c.fragment_invocations)),
                "samples": self.gpu.statistics.len(),
            });
            if let Some(coverage) = self.water_coverage_json() {
                report["water_coverage"] = coverage;
            }
        }
        report
    }

    /// The submission a pass ran in (compute, graphics 1, graphics 2).
    fn submission_of(&self, name: &str) -> &'static str {
        self.compute
            .submission_of(name)
            .or_else(|| self.gpu.submission_of(name))
            .unwrap_or("?")
    }

    /// The water draw's fragment-shader invocations per covered pixel and its covered pixels
    /// (samples that passed the depth test), frame by frame; `None` without precise occlusion
    /// queries.
    pub fn water_coverage(&self) -> Option<(Vec<f64>, Vec<f64>)> {
        let frames: Option<Vec<(f64, f64)>> = self
            .gpu
            .statistics
            .iter()
            .map(|c| {
                let covered = c.covered_samples? as f64;
                Some((c.fragment_invocations as f64 / covered.max(1.0), covered))
            })
            .collect();
        let frames = frames.filter(|f| !f.is_empty())?;
        Some(frames.into_iter().unzip())
    }

    /// `water_coverage` of the profile JSON: statistics of both columns.
    pub fn water_coverage_json(&self) -> Option<Value> {
        let (per_pixel, covered) = self.water_coverage()?;
        Some(json!({
            "invocations_per_pixel": Stats::json(&per_pixel),
            "covered_pixels": Stats::json(&covered),
        }))
    }

    /// The summary's line of the water's coverage (medians).
    pub fn water_coverage_line(&self) -> Option<String> {
        let (per_pixel, covered) = self.water_coverage()?;
        let (i, c) = (Stats::of(&per_pixel)?, Stats::of(&covered)?);
        Some(format!(
            "median {:.2} fragment invocations per covered pixel (p95 {:.2}), {:.0} pixels covered",
            i.median, i.p95, c.median
        ))
    }

    /// One counter of the water draw's statistics, frame by frame.
    fn statistics_column(&self, counter: fn(&DrawStatistics) -> u64) -> Vec<f64> {
        self.gpu
            .statistics
            .iter()
            .map(|c| counter(c) as f64)
            .collect()
    }

    /// A short human-readable table (logged at the end of a profiled run).
    pub fn summary(&self) -> String {
        let mut out = String::new();
        for (name, samples) in self.compute.passes.iter().chain(&self.gpu.passes) {
            if let Some(s) = Stats::of(samples) {
                out += &format!(
                    "  {name:<16} median {:7.3} ms  p95 {:7.3} ms  ({})\n",
                    s.median,
                    s.p95,
                    self.submission_of(name)
                );
            }
        }
        if let Some(s) = Stats::of(&self.compute.frames) {
            out += &format!(
                "  {:<16} median {:7.3} ms  p95 {:7.3} ms\n",
                "compute (GPU)", s.median, s.p95
            );
        }
        let median = |f| Stats::of(&self.statistics_column(f)).map(|s| s.median);
        if let (Some(p), Some(e), Some(t), Some(f)) = (
            median(|c| c.patches),
            median(|c| c.tess_eval_invocations),
            median(|c| c.primitives),
            median(|c| c.fragment_invocations),
        ) {
            out += &format!(
                "  {:<16} median {p:.0} patches, {e:.0} tess-eval invocations, {t:.0} triangles, {f:.0} fragments\n",
                "water draw"
            );
        }
        if let Some(line) = self.water_coverage_line() {
            out += &format!("  {:<16} {line}\n", "water coverage");
        }
        if let Some(s) = Stats::of(&self.gpu.frames) {
            out += &format!(
                "  {:<16} median {:7.3} ms  p95 {:7.3} ms\n",
                "frame (GPU)", s.median, s.p95
            );
        }
        if let Some(s) = Stats::of(&self.gpu_total_ms()) {
            out += &format!(
                "  {:<16} median {:7.3} ms  p95 {:7.3} ms\n",
                "compute + frame", s.median, s.p95
            );
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stats_of_known_samples() {
        let s = Stats::of(&[5.0, 1.0, 3.0, 2.0, 4.0]).unwrap();
        assert_eq!((s.min, s.median, s.mean, s.max), (1.0, 3.0, 3.0, 5.0));
        assert!((s.p95 - 4.8).abs() < 1e-12, "p95 {}", s.p95);
        assert_eq!(Stats::of(&[]), None);
        let one = Stats::of(&[2.5]).unwrap();
        assert_eq!(
            (one.min, one.median, one.p95, one.max),
            (2.5, 2.5, 2.5, 2.5)
        );
    }
}
