//! GPU timestamp profiler. One pass name drives the debug label and a timestamp scope. Each frame
//! slot has its own query pool; a slot's results are read when the slot comes round again (its
//! frame has finished by then, see `Frames::begin`), so reading never stalls the GPU.

use std::sync::Arc;

use ash::vk;

use super::command::Recorder;
use super::context::Context;
use super::error::{GpuResult, VkResultExt};
use super::frame::{Frame, FRAMES_IN_FLIGHT};
use super::garbage::Garbage;

/// The counters `Profiler::statistics` reads; the results come in bit order: primitives out
/// of clipping, fragment-shader invocations, and (where the device has tessellation shaders,
/// which the tessellation counters need) tessellation-control patches and
/// tessellation-evaluation invocations.
fn statistics_flags(tessellation: bool) -> vk::QueryPipelineStatisticFlags {
    let mut flags = vk::QueryPipelineStatisticFlags::CLIPPING_PRIMITIVES
        | vk::QueryPipelineStatisticFlags::FRAGMENT_SHADER_INVOCATIONS;
    if tessellation {
        flags |= vk::QueryPipelineStatisticFlags::TESSELLATION_CONTROL_SHADER_PATCHES
            | vk::QueryPipelineStatisticFlags::TESSELLATION_EVALUATION_SHADER_INVOCATIONS;
    }
    flags
}

/// One frame's counts in the scope of `Profiler::statistics` (the water draw).
#[derive(Clone, Copy, Debug, Default)]
pub struct DrawStatistics {
    pub patches: u64,
    pub tess_eval_invocations: u64,
    /// Primitives that reach the rasterizer (after clipping).
    pub primitives: u64,
    /// Fragment-shader invocations: covered pixels plus what the device shades besides
    /// (helper lanes, partly covered blocks; a measure of rasterization work, overdraw).
    pub fragment_invocations: u64,
    /// Samples that passed the depth test (a precise occlusion query): the pixels the draw
    /// covers in the picture; `None` where the device has no precise occlusion queries.
    pub covered_samples: Option<u64>,
}

/// The compute queue's submission (the simulation).
pub const COMPUTE: &str = "compute";
/// The first graphics submission: passes that read no simulation output (sky cube,
/// reflection, refraction, scene); on a device with a compute queue it overlaps the simulation.
pub const GRAPHICS_SCENE: &str = "graphics 1";
/// The second graphics submission, after the wait for the compute timeline: water, sky,
/// textures view, output.
pub const GRAPHICS_OCEAN: &str = "graphics 2";

impl GpuTimings {
    /// The submission pass `name` ran in (`COMPUTE`, `GRAPHICS_SCENE`, `GRAPHICS_OCEAN`).
    pub fn submission_of(&self, name: &str) -> Option<&'static str> {
        self.submissions
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, s)| *s)
    }
}

/// Timestamps per frame: frame begin/end plus two per pass.
const QUERIES_PER_FRAME: u32 = 128;

/// What a slot recorded in its last frame: (pass name, submission, begin query, end query).
#[derive(Default)]
struct SlotRecord {
    frame_index: Option<u64>,
    passes: Vec<(&'static str, &'static str, u32, u32)>,
    used: u32,
    /// Queries around the gap between two submissions of the frame (`pause` / `resume`): what
    /// ran in between (the compute submission, on a device with one queue) is not the frame's.
    gap: Option<(u32, u32)>,
    /// The pipeline-statistics query was written.
    statistics: bool,
}

/// GPU times per pass and per frame, in milliseconds, in the order passes first appeared.
#[derive(Clone, Debug, Default)]
pub struct GpuTimings {
    pub passes: Vec<(&'static str, Vec<f64>)>,
    /// The submission each pass was recorded in (`Profiler::set_submission`), by pass name.
    pub submissions: Vec<(&'static str, &'static str)>,
    pub frames: Vec<f64>,
    /// The same samples frame by frame (`bench frames --csv`), in frame order.
    pub per_frame: Vec<FrameTimes>,
    /// Per frame, the counts in the scope of `Profiler::statistics`.
    pub statistics: Vec<DrawStatistics>,
}

/// One measured frame of one queue's submission.
#[derive(Clone, Debug)]
pub struct FrameTimes {
    /// The frame's index (0 = the first frame of the run).
    pub index: u64,
    /// Begin to end of the submission (ms).
    pub total_ms: f64,
    /// (pass, ms) in recording order.
    pub passes: Vec<(&'static str, f64)>,
}

/// A span's opening timestamp: ordered before what follows when `ordered` ([`Profiler::ordered`]).
fn write_opening(rec: &Recorder, ordered: bool, pool: vk::QueryPool, query: u32) {
    if ordered {
        rec.write_opening_timestamp(pool, query);
    } else {
        rec.write_timestamp(pool, query);
    }
}

/// Timestamp queries around passes; disabled (labels only) when the queue has no timestamps.
pub struct Profiler {
    ctx: Arc<Context>,
    /// One pool per frame slot (empty when timestamps are unsupported).
    pools: Vec<vk::QueryPool>,
    /// One pipeline-statistics query per frame slot (empty unless asked for and supported, and
    /// for compute).
    statistics_pools: Vec<vk::QueryPool>,
    /// One precise occlusion query per frame slot beside each statistics query (where the
    /// device has occlusionQueryPrecise).
    occlusion_pools: Vec<vk::QueryPool>,
    records: Vec<SlotRecord>,
    /// Slot of the frame being recorded.
    current: usize,
    /// Open pass scopes: (name, begin query).
    open: Vec<(&'static str, u32)>,
    /// Frames with an index below this are warm-up and not recorded.
    warmup_frames: u64,
    /// The submission passes are being recorded into (`set_submission`).
    submission: &'static str,
    period_ns: f64,
    valid_mask: u64,
    timings: GpuTimings,
    /// Keep the last finished frame's times, warm-up or not (`latest`; the overlay).
    pub live: bool,
    /// Order each span's opening timestamp before the commands that follow it
    /// (`Recorder::write_opening_timestamp`): `--profile` and `bench frames`, whose per-pass
    /// times are the point. Without it (the window, a plain headless run) a pass's draws may
    /// start before its opening timestamp on drivers that start later commands early (Mesa
    /// 25's lavapipe), and nothing waits for the sake of the measurement.
    pub ordered: bool,
    latest: Option<FrameTimes>,
}

impl Profiler {
    /// `warmup_frames`: leading frames whose timings are discarded (pipeline JIT, first uploads).
    /// `draw_statistics`: also count the work of the `statistics` scope (`--profile`). Only
    /// when asked: an active pipeline-statistics query made the water pass 5–7 % slower on
    /// lavapipe (it counts every fragment), which every frame would pay.
    pub fn new(
        ctx: &Arc<Context>,
        warmup_frames: u64,
        draw_statistics: bool,
    ) -> GpuResult<Profiler> {
        Self::for_queue(
            ctx,
            warmup_frames,
            ctx.info.timestamp_valid_bits,
            "graphics",
        )
        .and_then(|mut profiler| {
            profiler.submission = GRAPHICS_SCENE;
            if draw_statistics && ctx.info.pipeline_statistics_query {
                let flags = statistics_flags(ctx.info.tessellation_shader);
                for i in 0..FRAMES_IN_FLIGHT {
                    let info = vk::QueryPoolCreateInfo::default()
                        .query_type(vk::QueryType::PIPELINE_STATISTICS)
                        .pipeline_statistics(flags)
                        .query_count(1);
                    // SAFETY: valid create info on a live device with pipelineStatisticsQuery
                    // (and tessellationShader for the tessellation counters).
                    let pool = unsafe { ctx.device.create_query_pool(&info, None) }
                        .vk("vkCreateQueryPool")?;
                    ctx.count_created(1);
                    ctx.name(pool, &format!("draw statistics slot {i}"));
                    profiler.statistics_pools.push(pool);
                    if ctx.info.occlusion_query_precise {
                        let info = vk::QueryPoolCreateInfo::default()
                            .query_type(vk::QueryType::OCCLUSION)
                            .query_count(1);
                        // SAFETY: valid create info on a live device.
                        let pool = unsafe { ctx.device.create_query_pool(&info, None) }
                            .vk("vkCreateQueryPool")?;
                        ctx.count_created(1);
                        ctx.name(pool, &format!("draw coverage slot {i}"));
                        profiler.occlusion_pools.push(pool);
                    }
                }
            }
            Ok(profiler)
        })
    }

    /// A profiler for the compute queue's command buffers (its own query pools, reset in the
    /// compute submission; slots are read back on the same schedule as the graphics ones).
    pub fn for_compute(ctx: &Arc<Context>, warmup_frames: u64) -> GpuResult<Profiler> {
        Self::for_queue(
            ctx,
            warmup_frames,
            ctx.info.compute_timestamp_valid_bits,
            "compute",
        )
    }

    fn for_queue(
        ctx: &Arc<Context>,
        warmup_frames: u64,
        bits: u32,
        queue: &str,
    ) -> GpuResult<Profiler> {
        // Pools are pushed as they are made, so an error drops (and frees) the earlier ones.
        let mut profiler = Profiler {
            ctx: ctx.clone(),
            pools: Vec::new(),
            statistics_pools: Vec::new(),
            occlusion_pools: Vec::new(),
            records: (0..FRAMES_IN_FLIGHT)
                .map(|_| SlotRecord::default())
                .collect(),
            current: 0,
            open: Vec::new(),
            warmup_frames,
            submission: COMPUTE,
            period_ns: ctx.info.limits.timestamp_period as f64,
            valid_mask: if bits >= 64 {
                u64::MAX
            } else {
                (1u64 << bits) - 1
            },
            timings: GpuTimings::default(),
            live: false,
            ordered: false,
            latest: None,
        };
        if bits > 0 {
            for i in 0..FRAMES_IN_FLIGHT {
                let info = vk::QueryPoolCreateInfo::default()
                    .query_type(vk::QueryType::TIMESTAMP)
                    .query_count(QUERIES_PER_FRAME);
                // SAFETY: valid create info on a live device.
                let pool =
                    unsafe { ctx.device.create_query_pool(&info, None) }.vk("vkCreateQueryPool")?;
                ctx.count_created(1);
                ctx.name(pool, &format!("{queue} timestamps slot {i}"));
                profiler.pools.push(pool);
            }
        }
        Ok(profiler)
    }

    /// The last finished frame's pass times (kept while `live`).
    pub fn latest(&self) -> Option<&FrameTimes> {
        self.latest.as_ref()
    }

    /// Discards the results of frames with an index below `frames` (warm-up), including frames
    /// already submitted but not yet collected.
    pub fn set_warmup(&mut self, frames: u64) {
        self.warmup_frames = frames;
    }

    /// Names the submission the following passes are recorded into ([`COMPUTE`],
    /// [`GRAPHICS_SCENE`], [`GRAPHICS_OCEAN`]); `--profile` reports it per pass. One frame's
    /// queries may span several submissions of one queue (they run in submission order).
    pub fn set_submission(&mut self, submission: &'static str) {
        self.submission = submission;
    }

    /// Whether the device can time passes.
    pub fn enabled(&self) -> bool {
        !self.pools.is_empty()
    }

    /// Starts a frame: collects the finished results of this slot's previous frame, resets the
    /// slot's queries and writes the frame-begin timestamp (query 0).
    pub fn begin_frame(&mut self, rec: &Recorder, frame: &Frame) -> GpuResult<()> {
        self.current = frame.slot;
        self.collect(frame.slot)?;
        let record = &mut self.records[frame.slot];
        record.frame_index = Some(frame.index);
        record.passes.clear();
        record.used = 0;
        record.gap = None;
        record.statistics = false;
        for pools in [&self.statistics_pools, &self.occlusion_pools] {
            if let Some(&pool) = pools.get(frame.slot) {
                rec.reset_queries(pool, 1);
            }
        }
        if let Some(&pool) = self.pools.get(frame.slot) {
            rec.reset_queries(pool, QUERIES_PER_FRAME);
            write_opening(rec, self.ordered, pool, 0);
            record.used = 2; // query 1 is the frame end
        }
        Ok(())
    }

    /// Ends the frame's first submission: a timestamp where its GPU time pauses (see `resume`).
    pub fn pause(&mut self, rec: &Recorder) {
        let record = &mut self.records[self.current];
        if let Some(&pool) = self.pools.get(self.current) {
            if record.gap.is_none() && record.used + 2 <= QUERIES_PER_FRAME {
                rec.write_timestamp(pool, record.used);
                record.gap = Some((record.used, record.used + 1));
                record.used += 2;
            }
        }
    }

    /// Starts the frame's next submission, `submission`, after `pause`: the time between the
    /// two timestamps is left out of the frame's total.
    pub fn resume(&mut self, rec: &Recorder, submission: &'static str) {
        self.submission = submission;
        if let (Some(&pool), Some((_, end))) =
            (self.pools.get(self.current), self.records[self.current].gap)
        {
            write_opening(rec, self.ordered, pool, end);
        }
    }

    /// Ends a frame with the frame-end timestamp (query 1).
    pub fn end_frame(&mut self, rec: &Recorder) {
        assert!(
            self.open.is_empty(),
            "pass {:?} was not ended",
            self.open.last().map(|p| p.0)
        );
        if let Some(&pool) = self.pools.get(self.current) {
            rec.write_timestamp(pool, 1);
        }
    }

    /// Opens a named pass: a debug label and, when there is room, a timestamp.
    pub fn begin_pass(&mut self, rec: &Recorder, name: &'static str) {
        rec.pass(name);
        rec.begin_label(name);
        let record = &mut self.records[self.current];
        if let Some(&pool) = self.pools.get(self.current) {
            if record.used + 2 <= QUERIES_PER_FRAME {
                write_opening(rec, self.ordered, pool, record.used);
                self.open.push((name, record.used));
                record.used += 2;
                return;
            }
        }
        self.open.push((name, u32::MAX));
    }

    /// Closes the innermost pass.
    pub fn end_pass(&mut self, rec: &Recorder) {
        let (name, begin) = self.open.pop().expect("end_pass without begin_pass");
        if begin != u32::MAX {
            let pool = self.pools[self.current];
            rec.write_timestamp(pool, begin + 1);
            self.records[self.current]
                .passes
                .push((name, self.submission, begin, begin + 1));
        }
        rec.end_label();
    }

    /// Counts the work of `body` ([`DrawStatistics`]; once per frame, inside or outside a
    /// rendering scope). A no-op unless the profiler was made with `draw_statistics` on a device
    /// with pipeline-statistics queries.
    pub fn statistics<R>(&mut self, rec: &Recorder, body: impl FnOnce() -> R) -> R {
        let pool = self.statistics_pools.get(self.current).copied();
        let occlusion = self.occlusion_pools.get(self.current).copied();
        let record = &mut self.records[self.current];
        match pool {
            Some(pool) if !record.statistics => {
                record.statistics = true;
                rec.begin_query(pool, 0, vk::QueryControlFlags::empty());
                if let Some(occlusion) = occlusion {
                    rec.begin_query(occlusion, 0, vk::QueryControlFlags::PRECISE);
                }
                let result = body();
                if let Some(occlusion) = occlusion {
                    rec.end_query(occlusion, 0);
                }
                rec.end_query(pool, 0);
                result
            }
            _ => body(),
        }
    }

    /// Runs `body` inside a named pass.
    pub fn pass<R>(&mut self, rec: &Recorder, name: &'static str, body: impl FnOnce() -> R) -> R {
        self.begin_pass(rec, name);
        let result = body();
        self.end_pass(rec);
        result
    }

    /// Reads the finished results of `slot` (its frame must have completed on the GPU).
    fn collect(&mut self, slot: usize) -> GpuResult<()> {
        let record = &mut self.records[slot];
        let Some(index) = record.frame_index.take() else {
            return Ok(());
        };
        let Some(&pool) = self.pools.get(slot) else {
            return Ok(());
        };
        let measured = index >= self.warmup_frames;
        if record.used == 0 || !(measured || self.live) {
            return Ok(());
        }
        if let (true, true, Some(&stats_pool)) =
            (measured, record.statistics, self.statistics_pools.get(slot))
        {
            let mut counts = [0u64; 4];
            // SAFETY: as below; the query holds the counters of `statistics_flags` in bit order:
            // four, or two without tessellation shaders (the rest of `counts` stays 0; its
            // 32-byte stride covers either).
            unsafe {
                self.ctx.device.get_query_pool_results(
                    stats_pool,
                    0,
                    std::slice::from_mut(&mut counts),
                    vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
                )
            }
            .vk("vkGetQueryPoolResults")?;
            let [primitives, fragment_invocations, patches, tess_eval_invocations] = counts;
            let covered_samples = match self.occlusion_pools.get(slot) {
                None => None,
                Some(&pool) => {
                    let mut samples = 0u64;
                    // SAFETY: as below; one 64-bit result of the slot's occlusion query.
                    unsafe {
                        self.ctx.device.get_query_pool_results(
                            pool,
                            0,
                            std::slice::from_mut(&mut samples),
                            vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
                        )
                    }
                    .vk("vkGetQueryPoolResults")?;
                    Some(samples)
                }
            };
            self.timings.statistics.push(DrawStatistics {
                patches,
                tess_eval_invocations,
                primitives,
                fragment_invocations,
                covered_samples,
            });
        }
        let mut ticks = vec![0u64; record.used as usize];
        // SAFETY: the frame that wrote these queries has completed (the caller waited on the
        // timeline), every query in 0..used was written, and `ticks` holds `used` u64 values.
        unsafe {
            self.ctx.device.get_query_pool_results(
                pool,
                0,
                &mut ticks,
                vk::QueryResultFlags::TYPE_64 | vk::QueryResultFlags::WAIT,
            )
        }
        .vk("vkGetQueryPoolResults")?;
        let ms = |a: u32, b: u32| {
            let delta = ticks[b as usize].wrapping_sub(ticks[a as usize]) & self.valid_mask;
            delta as f64 * self.period_ns / 1.0e6
        };
        let total = ms(0, 1) - record.gap.map_or(0.0, |(a, b)| ms(a, b));
        let mut frame = FrameTimes {
            index,
            total_ms: total,
            passes: Vec::with_capacity(record.passes.len()),
        };
        for &(name, _, a, b) in &record.passes {
            frame.passes.push((name, ms(a, b)));
        }
        if self.live {
            self.latest = Some(frame.clone());
        }
        if !measured {
            return Ok(());
        }
        self.timings.frames.push(total);
        for (&(name, submission, _, _), &(_, value)) in record.passes.iter().zip(&frame.passes) {
            match self.timings.passes.iter_mut().find(|(n, _)| *n == name) {
                Some((_, samples)) => samples.push(value),
                None => {
                    self.timings.passes.push((name, vec![value]));
                    self.timings.submissions.push((name, submission));
                }
            }
        }
        self.timings.per_frame.push(frame);
        Ok(())
    }

    /// Collects every outstanding result (call after waiting for all frames) and returns them.
    pub fn finish(&mut self) -> GpuResult<GpuTimings> {
        // Oldest slot first so samples stay in frame order.
        let mut slots: Vec<usize> = (0..FRAMES_IN_FLIGHT).collect();
        slots.sort_by_key(|&s| self.records[s].frame_index.unwrap_or(u64::MAX));
        for s in slots {
            self.collect(s)?;
        }
        Ok(std::mem::take(&mut self.timings))
    }
}

impl Drop for Profiler {
    fn drop(&mut self) {
        let pools = self.pools.drain(..).chain(self.statistics_pools.drain(..));
        for pool in pools.chain(self.occlusion_pools.drain(..)) {
            self.ctx.defer(Garbage::QueryPool(pool));
        }
    }
}

/// The frame's two profilers, one per queue, each with its own query pools and recorded into
/// its own queue's submissions: `graphics` (graphics 1 and 2) and `compute` (the simulation).
pub struct Profilers {
    pub graphics: Profiler,
    pub compute: Profiler,
}

impl Profilers {
    /// `draw_statistics`: as for [`Profiler::new`].
    pub fn new(
        ctx: &Arc<Context>,
        warmup_frames: u64,
        draw_statistics: bool,
    ) -> GpuResult<Profilers> {
        Ok(Profilers {
            graphics: Profiler::new(ctx, warmup_frames, draw_statistics)?,
            compute: Profiler::for_compute(ctx, warmup_frames)?,
        })
    }

    /// [`Profiler::ordered`] on both.
    pub fn set_ordered(&mut self, ordered: bool) {
        self.graphics.ordered = ordered;
        self.compute.ordered = ordered;
    }

    /// [`Profiler::set_warmup`] on both.
    pub fn set_warmup(&mut self, frames: u64) {
        self.graphics.set_warmup(frames);
        self.compute.set_warmup(frames);
    }

    /// [`Profiler::finish`] on both: (graphics, compute) timings.
    pub fn finish(&mut self) -> GpuResult<(GpuTimings, GpuTimings)> {
        Ok((self.graphics.finish()?, self.compute.finish()?))
    }
}
