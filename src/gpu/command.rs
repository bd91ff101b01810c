//! `Recorder`: the safe face of a command buffer in the recording state. Passes outside the GPU
//! layer record through it (no `unsafe` above src/gpu). Barriers are synchronization2 only.

use ash::vk;

use super::buffer::Buffer;
use super::context::Context;

use super::pipeline::Pipeline;
pub use super::track::Access;

/// An image layout transition / dependency (made by `track`).
#[derive(Clone, Copy, Debug)]
pub(super) struct ImageBarrier {
    pub image: vk::Image,
    pub range: vk::ImageSubresourceRange,
    pub old_layout: vk::ImageLayout,
    pub new_layout: vk::ImageLayout,
    pub src: Access,
    pub dst: Access,
}

/// How a rendering scope starts on an attachment.
#[derive(Clone, Copy)]
pub enum Load {
    /// Clear to this value (an attachment write).
    Clear(vk::ClearValue),
    /// Keep the previous contents (an attachment read: the barrier before must cover it).
    Keep,
    /// The pass overwrites every pixel; previous contents are undefined.
    DontCare,
}

/// A colour or depth attachment of a rendering scope.
#[derive(Clone, Copy)]
pub(super) struct Attachment {
    pub view: vk::ImageView,
    pub layout: vk::ImageLayout,
    /// What happens to the previous contents at the start of rendering.
    pub load: Load,
}

/// A [`super::pass::Bindings`]' identity (its pipeline and sets), to tell a declared draw
/// from another.
#[derive(Clone, PartialEq, Eq)]
pub(super) struct BindingsKey(pub u64, pub Vec<vk::DescriptorSet>);

/// The semaphore waits a command buffer's reads rely on: (semaphore name, stages).
pub(super) type RequiredWaits = std::cell::RefCell<Vec<(&'static str, vk::PipelineStageFlags2)>>;

/// A command buffer in the recording state.
pub struct Recorder<'a> {
    pub(super) ctx: &'a Context,
    pub(super) cmd: vk::CommandBuffer,
    /// The queue family it records for (graphics commands need the graphics family).
    family: u32,
    /// The index buffer bound last and its size in indices (indexed draws stay within it).
    index_count: std::cell::Cell<Option<u32>>,
    /// Where the semaphore waits its reads rely on go (the frame's submission checks it has
    /// them): (semaphore name, stages). `None`: a submission that may rely on none.
    pub(super) required_waits: Option<&'a RequiredWaits>,
    /// The bind point of the bound pipeline (draws and dispatches need one).
    pub(super) bound: std::cell::Cell<Option<vk::PipelineBindPoint>>,
    /// Inside a rendering scope: what `Recorder::rendering` derived its barriers from (a draw
    /// inside the scope must use one of them).
    pub(super) scope: std::cell::RefCell<Option<Vec<BindingsKey>>>,
    /// What `Recorder::bind` bound last.
    pub(super) bound_key: std::cell::RefCell<Option<BindingsKey>>,
    /// A pipeline made on first use failed to be made in a bind: no draw or dispatch is
    /// recorded after it (the error waits in the context for the submission).
    failed: std::cell::Cell<bool>,
}

impl<'a> Recorder<'a> {
    /// Wraps `cmd`. Invariant: `cmd` is in the recording state for the recorder's lifetime
    /// (only `Frames` and one-shot helpers in this layer create recorders).
    pub(super) fn new(ctx: &'a Context, cmd: vk::CommandBuffer, family: u32) -> Self {
        Recorder {
            ctx,
            cmd,
            family,
            index_count: std::cell::Cell::new(None),
            required_waits: None,
            bound: std::cell::Cell::new(None),
            scope: std::cell::RefCell::new(None),
            bound_key: std::cell::RefCell::new(None),
            failed: std::cell::Cell::new(false),
        }
    }

    pub fn ctx(&self) -> &Context {
        self.ctx
    }

    pub(super) fn raw(&self) -> vk::CommandBuffer {
        self.cmd
    }

    /// Opens a debug label (RenderDoc, validation messages).
    pub fn begin_label(&self, name: &str) {
        self.ctx.journal_label(name);
        self.ctx.debug.begin_label(self.cmd, name);
    }

    pub fn end_label(&self) {
        self.ctx.debug.end_label(self.cmd);
    }

    /// Notes that a read relies on the submission waiting for semaphore `by` at `stages`
    /// (`Order::Wait`); panics where this command buffer's submission waits for nothing.
    pub(super) fn require_wait(&self, by: &'static str, stages: vk::PipelineStageFlags2) {
        let sink = self
            .required_waits
            .unwrap_or_else(|| panic!("a read ordered by {by} in a submission without waits"));
        sink.borrow_mut().push((by, stages));
    }

    /// Panics inside a rendering scope: barriers, transfers, dispatches and another scope
    /// belong outside one (Vulkan spec: they are not allowed, or only with restrictions, while
    /// dynamic rendering is active).
    pub(super) fn expect_outside_scope(&self, what: &str) {
        assert!(
            self.scope.borrow().is_none(),
            "{what} inside a rendering scope"
        );
    }

    /// Panics unless this command buffer is for the graphics queue's family (rendering and
    /// blits need a graphics-capable queue).
    pub(super) fn expect_graphics(&self, what: &str) {
        assert!(
            self.family == self.ctx.graphics.family,
            "{what} on queue family {}, which is not the graphics family",
            self.family
        );
    }

    /// Records one `vkCmdPipelineBarrier2` with the given image and buffer barriers. Only
    /// `track` (and the deliberate hazard's test) call it: passes declare uses instead.
    pub(super) fn barrier(
        &self,
        images: &[ImageBarrier],
        buffers: &[(vk::Buffer, Access, Access)],
    ) {
        self.expect_outside_scope("a pipeline barrier");
        let image_barriers: Vec<_> = images
            .iter()
            .map(|b| {
                vk::ImageMemoryBarrier2::default()
                    .src_stage_mask(b.src.stage)
                    .src_access_mask(b.src.access)
                    .dst_stage_mask(b.dst.stage)
                    .dst_access_mask(b.dst.access)
                    .old_layout(b.old_layout)
                    .new_layout(b.new_layout)
                    .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                    .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                    .image(b.image)
                    .subresource_range(b.range)
            })
            .collect();
        let buffer_barriers: Vec<_> = buffers
            .iter()
            .map(|(buffer, src, dst)| {
                vk::BufferMemoryBarrier2::default()
                    .src_stage_mask(src.stage)
                    .src_access_mask(src.access)
                    .dst_stage_mask(dst.stage)
                    .dst_access_mask(dst.access)
                    .src_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                    .dst_queue_family_index(vk::QUEUE_FAMILY_IGNORED)
                    .buffer(*buffer)
                    .offset(0)
                    .size(vk::WHOLE_SIZE)
            })
            .collect();
        let info = vk::DependencyInfo::default()
            .image_memory_barriers(&image_barriers)
            .buffer_memory_barriers(&buffer_barriers);
        // SAFETY: recording-state invariant; the handles are live (owned by the caller's passes).
        unsafe { self.ctx.device.cmd_pipeline_barrier2(self.cmd, &info) };
    }

    /// Begins dynamic rendering over `extent` and sets the viewport and scissor to it.
    pub(super) fn begin_rendering(
        &self,
        extent: vk::Extent2D,
        colour: &[Attachment],
        depth: Option<Attachment>,
    ) {
        let to_info = |a: &Attachment| {
            vk::RenderingAttachmentInfo::default()
                .image_view(a.view)
                .image_layout(a.layout)
                .load_op(match a.load {
                    Load::Clear(_) => vk::AttachmentLoadOp::CLEAR,
                    Load::Keep => vk::AttachmentLoadOp::LOAD,
                    Load::DontCare => vk::AttachmentLoadOp::DONT_CARE,
                })
                .store_op(vk::AttachmentStoreOp::STORE)
                .clear_value(match a.load {
                    Load::Clear(value) => value,
                    _ => vk::ClearValue::default(),
                })
        };
        let colour_infos: Vec<_> = colour.iter().map(to_info).collect();
        let depth_info = depth.as_ref().map(to_info);
        let area = vk::Rect2D {
            offset: vk::Offset2D::default(),
            extent,
        };
        let mut info = vk::RenderingInfo::default()
            .render_area(area)
            .layer_count(1)
            .color_attachments(&colour_infos);
        if let Some(d) = depth_info.as_ref() {
            info = info.depth_attachment(d);
        }
        let viewport = vk::Viewport {
            x: 0.0,
            y: 0.0,
            width: extent.width as f32,
            height: extent.height as f32,
            min_depth: 0.0,
            max_depth: 1.0,
        };
        // SAFETY: recording-state invariant; the views are live and in the given layouts.
        unsafe {
            self.ctx.device.cmd_begin_rendering(self.cmd, &info);
            self.ctx.device.cmd_set_viewport(self.cmd, 0, &[viewport]);
            self.ctx.device.cmd_set_scissor(self.cmd, 0, &[area]);
        }
    }

    pub(super) fn end_rendering(&self) {
        // SAFETY: recording-state invariant; paired with `begin_rendering`.
        unsafe { self.ctx.device.cmd_end_rendering(self.cmd) };
    }

    /// Binds `pipeline`, made now if it is made on first use. If making it fails, the error
    /// waits in the context for the submission ([`Context::fail_recording`]) and the draws
    /// and dispatches recorded after it are left out.
    pub(super) fn bind_pipeline(&self, pipeline: &Pipeline) {
        let raw = match pipeline.handle() {
            Ok(raw) => raw,
            Err(e) => {
                self.ctx.fail_recording(self.cmd, e);
                self.failed.set(true);
                self.bound.set(None);
                return;
            }
        };
        self.bound.set(Some(pipeline.bind_point));
        // SAFETY: recording-state invariant; the pipeline is live.
        unsafe {
            self.ctx
                .device
                .cmd_bind_pipeline(self.cmd, pipeline.bind_point, raw)
        };
    }

    /// Binds `sets` (starting at set 0) with `pipeline`'s own layout, so they cannot be bound
    /// with a layout they were not made for.
    pub(super) fn bind_sets(&self, pipeline: &Pipeline, sets: &[vk::DescriptorSet]) {
        // SAFETY: recording-state invariant; the sets were written at creation and are kept
        // alive by their owners (and the deletion queue) past this command buffer's execution.
        unsafe {
            self.ctx.device.cmd_bind_descriptor_sets(
                self.cmd,
                pipeline.bind_point,
                pipeline.layout.raw(),
                0,
                sets,
                &[],
            )
        };
    }

    /// Pushes `data` at offset 0 of `pipeline`'s push-constant range. Panics if the range is
    /// smaller than `T` (a programming error: the layout and the shader's block disagree).
    pub fn push_constants<T: bytemuck::Pod>(&self, pipeline: &Pipeline, data: &T) {
        let (stages, size) = pipeline.layout.push();
        let bytes = bytemuck::bytes_of(data);
        assert!(
            bytes.len() as u32 <= size && !stages.is_empty(),
            "pipeline {}: {} bytes of push constants into a range of {size}",
            pipeline.name,
            bytes.len()
        );
        // SAFETY: recording-state invariant; the layout's range covers the bytes (asserted).
        unsafe {
            self.ctx
                .device
                .cmd_push_constants(self.cmd, pipeline.layout.raw(), stages, 0, bytes)
        };
    }

    pub fn draw(&self, vertices: u32, instances: u32) {
        if !self.may_record(vk::PipelineBindPoint::GRAPHICS) {
            return;
        }
        // SAFETY: recording-state invariant; inside a rendering scope with a bound pipeline.
        unsafe {
            self.ctx
                .device
                .cmd_draw(self.cmd, vertices, instances, 0, 0)
        };
    }

    /// `instances` instances of `vertices` vertices, from instance `first` (gl_InstanceIndex
    /// counts from it).
    pub fn draw_instances(&self, vertices: u32, instances: u32, first: u32) {
        if !self.may_record(vk::PipelineBindPoint::GRAPHICS) {
            return;
        }
        // SAFETY: recording-state invariant; inside a rendering scope with a bound pipeline.
        unsafe {
            self.ctx
                .device
                .cmd_draw(self.cmd, vertices, instances, 0, first)
        };
    }

    /// Binds a buffer of u32 indices for `draw_indexed`.
    /// Binds `buffer` (u32 indices) for `draw_indexed`; panics without INDEX_BUFFER usage. Its
    /// contents must be visible to index reads: upload it with `Use::IndexRead` after
    /// (`oneshot::upload_then`).
    pub fn bind_index_buffer(&self, buffer: &Buffer) {
        buffer.expect_usage(vk::BufferUsageFlags::INDEX_BUFFER, "an index buffer");
        self.index_count.set(Some((buffer.size() / 4) as u32));
        // SAFETY: recording-state invariant; the buffer is live and was made with INDEX_BUFFER.
        unsafe {
            self.ctx
                .device
                .cmd_bind_index_buffer(self.cmd, buffer.raw(), 0, vk::IndexType::UINT32)
        };
    }

    pub fn draw_indexed(&self, indices: u32, instances: u32) {
        if !self.may_record(vk::PipelineBindPoint::GRAPHICS) {
            return;
        }
        assert!(
            self.index_count.get().is_some_and(|n| indices <= n),
            "an indexed draw of {indices} indices beyond the bound index buffer"
        );
        // SAFETY: recording-state invariant; inside a rendering scope with a bound pipeline and
        // an index buffer holding at least `indices` entries.
        unsafe {
            self.ctx
                .device
                .cmd_draw_indexed(self.cmd, indices, instances, 0, 0, 0)
        };
    }

    /// Whether to record a draw or dispatch: not after a pipeline failed to be made (the
    /// submission returns that error). Otherwise panics unless a pipeline of `point` is bound
    /// (and, for graphics, a rendering scope is open): a draw or dispatch without one is
    /// undefined behaviour in Vulkan.
    fn may_record(&self, point: vk::PipelineBindPoint) -> bool {
        if self.failed.get() {
            return false;
        }
        assert_eq!(
            self.bound.get(),
            Some(point),
            "a draw or dispatch without a bound {point:?} pipeline"
        );
        if point == vk::PipelineBindPoint::GRAPHICS {
            let scope = self.scope.borrow();
            let declared = scope.as_ref().expect("a draw outside a rendering scope");
            // The scope's barriers were derived from its declared draws: a draw with anything
            // else could read what no barrier waited for.
            let bound = self.bound_key.borrow();
            assert!(
                bound.as_ref().is_some_and(|b| declared.contains(b)),
                "a draw with a pipeline and sets its rendering scope did not declare"
            );
        }
        true
    }

    pub(super) fn dispatch_indirect_raw(&self, args: &Buffer, offset: vk::DeviceSize) {
        self.expect_outside_scope("a dispatch");
        if !self.may_record(vk::PipelineBindPoint::COMPUTE) {
            return;
        }
        assert!(
            offset + 12 <= args.size(),
            "indirect dispatch arguments past the buffer's end"
        );
        // SAFETY: recording-state invariant; a compute pipeline is bound and the arguments lie
        // within the buffer, which has INDIRECT_BUFFER usage (checked by the caller).
        unsafe {
            self.ctx
                .device
                .cmd_dispatch_indirect(self.cmd, args.raw(), offset)
        };
    }

    pub(super) fn draw_indirect_raw(&self, args: &Buffer, offset: vk::DeviceSize) {
        if !self.may_record(vk::PipelineBindPoint::GRAPHICS) {
            return;
        }
        assert!(
            offset + 16 <= args.size(),
            "indirect draw arguments past the buffer's end"
        );
        // SAFETY: recording-state invariant; inside a rendering scope with a bound pipeline,
        // the arguments within the buffer, which has INDIRECT_BUFFER usage (checked by the
        // caller); one draw, so the stride is unused.
        unsafe {
            self.ctx
                .device
                .cmd_draw_indirect(self.cmd, args.raw(), offset, 1, 16)
        };
    }

    pub(super) fn dispatch(&self, x: u32, y: u32, z: u32) {
        self.expect_outside_scope("a dispatch");
        if !self.may_record(vk::PipelineBindPoint::COMPUTE) {
            return;
        }
        // SAFETY: recording-state invariant; a compute pipeline is bound.
        unsafe { self.ctx.device.cmd_dispatch(self.cmd, x, y, z) };
    }

    pub(super) fn reset_queries(&self, pool: vk::QueryPool, count: u32) {
        // SAFETY: recording-state invariant; outside any rendering scope.
        unsafe {
            self.ctx
                .device
                .cmd_reset_query_pool(self.cmd, pool, 0, count)
        };
    }

    pub(super) fn begin_query(
        &self,
        pool: vk::QueryPool,
        query: u32,
        flags: vk::QueryControlFlags,
    ) {
        // SAFETY: recording-state invariant; the query is unavailable when this executes: see
        // `write_timestamp` (the statistics and occlusion pools are reset beside the timestamp
        // pool); PRECISE only on occlusion pools of devices with occlusionQueryPrecise.
        unsafe {
            self.ctx
                .device
                .cmd_begin_query(self.cmd, pool, query, flags)
        };
    }

    pub(super) fn end_query(&self, pool: vk::QueryPool, query: u32) {
        // SAFETY: recording-state invariant; paired with `begin_query` in the same scope.
        unsafe { self.ctx.device.cmd_end_query(self.cmd, pool, query) };
    }

    /// `write_timestamp` where a span begins (a frame, a submission's share of it, a pass),
    /// then an execution dependency from it to every later command. A timestamp's second
    /// synchronization scope is its own write alone (Vulkan spec, vkCmdWriteTimestamp2), so the
    /// commands after it may start before it is written, and Mesa 25's lavapipe starts them:
    /// without the barrier the water pass read 0.3 ms there, its 10 ms falling before its
    /// opening timestamp (README, Profile JSON). The span's closing timestamp needs none: it
    /// waits for all earlier commands (`ALL_COMMANDS`).
    pub(super) fn write_opening_timestamp(&self, pool: vk::QueryPool, query: u32) {
        self.expect_outside_scope("an opening timestamp's barrier");
        self.write_timestamp(pool, query);
        let order = [vk::MemoryBarrier2::default()
            .src_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)
            .dst_stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS)];
        let dependency = vk::DependencyInfo::default().memory_barriers(&order);
        // SAFETY: recording-state invariant, outside a rendering scope (checked above); an
        // execution dependency only: no access masks, no layout transition.
        unsafe { self.ctx.device.cmd_pipeline_barrier2(self.cmd, &dependency) };
    }

    pub(super) fn write_timestamp(&self, pool: vk::QueryPool, query: u32) {
        // SAFETY: recording-state invariant. The query is unavailable when this executes: the
        // only caller, `Profiler` (timestamps.rs), resets the slot's whole pool in `begin_frame`,
        // recorded at the start of the frame's first command buffer on this profiler's queue
        // (graphics 1, or the compute submission), and writes each query at most once after
        // that; a later command buffer of the frame (graphics 2, after `resume`) runs after the
        // reset by submission order on the same queue. Not reset in every command buffer.
        unsafe {
            self.ctx.device.cmd_write_timestamp2(
                self.cmd,
                vk::PipelineStageFlags2::ALL_COMMANDS,
                pool,
                query,
            )
        };
    }
}
