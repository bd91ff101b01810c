//! `Recorder`: the safe face of a command buffer in the recording state. Passes outside the GPU
//! layer record through it (no `unsafe` above src/gpu). Barriers are synchronization2 only.

use ash::vk;

use super::buffer::Buffer;
use super::context::Context;
use super::image::{Image, Output};
use super::pipeline::Pipeline;
pub use super::track::Access;
use super::track::Use;

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
pub(super) struct BindingsKey(pub vk::Pipeline, pub Vec<vk::DescriptorSet>);

/// A command buffer in the recording state.
pub struct Recorder<'a> {
    pub(super) ctx: &'a Context,
    cmd: vk::CommandBuffer,
    /// The bind point of the bound pipeline (draws and dispatches need one).
    pub(super) bound: std::cell::Cell<Option<vk::PipelineBindPoint>>,
    /// Inside a rendering scope: what `Recorder::rendering` derived its barriers from (a draw
    /// inside the scope must use one of them).
    pub(super) scope: std::cell::RefCell<Option<Vec<BindingsKey>>>,
    /// What `Recorder::bind` bound last.
    pub(super) bound_key: std::cell::RefCell<Option<BindingsKey>>,
}

impl<'a> Recorder<'a> {
    /// Wraps `cmd`. Invariant: `cmd` is in the recording state for the recorder's lifetime
    /// (only `Frames` and one-shot helpers in this layer create recorders).
    pub(crate) fn new(ctx: &'a Context, cmd: vk::CommandBuffer) -> Self {
        Recorder {
            ctx,
            cmd,
            bound: std::cell::Cell::new(None),
            scope: std::cell::RefCell::new(None),
            bound_key: std::cell::RefCell::new(None),
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

    /// Records one `vkCmdPipelineBarrier2` with the given image and buffer barriers. Only
    /// `track` (and the deliberate hazard's test) call it: passes declare uses instead.
    pub(super) fn barrier(
        &self,
        images: &[ImageBarrier],
        buffers: &[(vk::Buffer, Access, Access)],
    ) {
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

    pub(super) fn bind_pipeline(&self, pipeline: &Pipeline) {
        self.bound.set(Some(pipeline.bind_point));
        // SAFETY: recording-state invariant; the pipeline is live.
        unsafe {
            self.ctx
                .device
                .cmd_bind_pipeline(self.cmd, pipeline.bind_point, pipeline.raw)
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
        self.expect_bound(vk::PipelineBindPoint::GRAPHICS);
        // SAFETY: recording-state invariant; inside a rendering scope with a bound pipeline.
        unsafe {
            self.ctx
                .device
                .cmd_draw(self.cmd, vertices, instances, 0, 0)
        };
    }

    /// Binds a buffer of u32 indices for `draw_indexed`.
    pub fn bind_index_buffer(&self, buffer: &Buffer) {
        // SAFETY: recording-state invariant; the buffer is live and was made with INDEX_BUFFER.
        unsafe {
            self.ctx
                .device
                .cmd_bind_index_buffer(self.cmd, buffer.raw(), 0, vk::IndexType::UINT32)
        };
    }

    pub fn draw_indexed(&self, indices: u32, instances: u32) {
        self.expect_bound(vk::PipelineBindPoint::GRAPHICS);
        // SAFETY: recording-state invariant; inside a rendering scope with a bound pipeline and
        // an index buffer holding at least `indices` entries.
        unsafe {
            self.ctx
                .device
                .cmd_draw_indexed(self.cmd, indices, instances, 0, 0, 0)
        };
    }

    /// Panics unless a pipeline of `point` is bound (and, for graphics, a rendering scope is
    /// open): a draw or dispatch without one is undefined behaviour in Vulkan.
    fn expect_bound(&self, point: vk::PipelineBindPoint) {
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
    }

    pub(super) fn dispatch(&self, x: u32, y: u32, z: u32) {
        self.expect_bound(vk::PipelineBindPoint::COMPUTE);
        // SAFETY: recording-state invariant; a compute pipeline is bound.
        unsafe { self.ctx.device.cmd_dispatch(self.cmd, x, y, z) };
    }

    /// Copies the output image (layer 0) into a tightly packed buffer, with its barriers.
    /// Panics if the buffer is too small (a programming error).
    pub fn copy_image_to_buffer(&self, image: Output, buffer: &Buffer) {
        let extent = image.extent();
        let need = texel_bytes(image.format()) * extent.width as u64 * extent.height as u64;
        assert!(
            buffer.size() >= need,
            "copy of {need} bytes into a {}-byte buffer",
            buffer.size()
        );
        image.expect_usage(vk::ImageUsageFlags::TRANSFER_SRC, "a copy to a buffer");
        buffer.expect_usage(vk::BufferUsageFlags::TRANSFER_DST, "a copy from an image");
        self.uses(&[(image.tracked(), Use::CopySrc), (buffer, Use::CopyDst)]);
        let region = packed_region(extent, 1);
        // SAFETY: recording-state invariant; the image is in TRANSFER_SRC_OPTIMAL (the barrier
        // above) and the buffer holds its texels (asserted).
        unsafe {
            self.ctx.device.cmd_copy_image_to_buffer(
                self.cmd,
                image.raw(),
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                buffer.raw(),
                &[region],
            )
        };
    }

    /// Copies a single-layer colour image into the output image of the same extent and texel
    /// size, bit for bit (e.g. UNORM bytes into an sRGB image), with its barriers. Panics if
    /// the extents or texel sizes differ.
    pub fn copy_image(&self, src: &Image, dst: Output) {
        let extent = src.extent;
        assert!(
            extent == dst.extent() && texel_bytes(src.format) == texel_bytes(dst.format()),
            "copy between images of other sizes or texels ({:?} {:?} to {:?} {:?})",
            extent,
            src.format,
            dst.extent(),
            dst.format()
        );
        src.expect_usage(vk::ImageUsageFlags::TRANSFER_SRC, "a copy's source");
        dst.expect_usage(vk::ImageUsageFlags::TRANSFER_DST, "a copy's destination");
        self.uses(&[(src, Use::TransferSrc), (dst.tracked(), Use::TransferDst)]);
        let layer = packed_region(extent, 1).image_subresource;
        let region = vk::ImageCopy {
            src_subresource: layer,
            src_offset: vk::Offset3D::default(),
            dst_subresource: layer,
            dst_offset: vk::Offset3D::default(),
            extent: vk::Extent3D {
                width: extent.width,
                height: extent.height,
                depth: 1,
            },
        };
        // SAFETY: recording-state invariant; both images are in the layouts the barrier above
        // left and have `extent` texels of the same size (asserted).
        unsafe {
            self.ctx.device.cmd_copy_image(
                self.cmd,
                src.raw,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                dst.raw(),
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &[region],
            )
        };
    }

    /// Blits the whole of `src` onto the whole of the output image, scaling with `filter` and
    /// converting between the two formats (sRGB decoded before filtering and encoded after;
    /// channel order followed), with its barriers. The formats' BLIT_SRC / BLIT_DST and linear
    /// filtering are checked by the renderer's format check at creation.
    pub fn blit_image(&self, src: &Image, dst: Output, filter: vk::Filter) {
        src.expect_usage(vk::ImageUsageFlags::TRANSFER_SRC, "a blit's source");
        dst.expect_usage(vk::ImageUsageFlags::TRANSFER_DST, "a blit's destination");
        self.uses(&[(src, Use::TransferSrc), (dst.tracked(), Use::TransferDst)]);
        let layer = packed_region(src.extent, 1).image_subresource;
        let corners = |e: vk::Extent2D| {
            [
                vk::Offset3D::default(),
                vk::Offset3D {
                    x: e.width as i32,
                    y: e.height as i32,
                    z: 1,
                },
            ]
        };
        let region = vk::ImageBlit {
            src_subresource: layer,
            src_offsets: corners(src.extent),
            dst_subresource: layer,
            dst_offsets: corners(dst.extent()),
        };
        // SAFETY: recording-state invariant; both images are in the layouts the barrier above
        // left, the regions are their whole extents and their formats support BLIT_SRC /
        // BLIT_DST (and linear filtering when `filter` is LINEAR; the renderer's format check).
        unsafe {
            self.ctx.device.cmd_blit_image(
                self.cmd,
                src.raw,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                dst.raw(),
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &[region],
                filter,
            )
        };
    }

    /// Blits the top `half_height(layer − 1)` rows of layer `layer − 1` of a colour image
    /// (TRANSFER_SRC_OPTIMAL) onto the top `half_height(layer)` rows of layer `layer`
    /// (TRANSFER_DST_OPTIMAL), full width, with a linear filter: each row the mean of two.
    pub fn blit_half_height(&self, image: &super::image::Image, layer: u32) {
        image.expect_usage(
            vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST,
            "blits between its layers",
        );
        let rows = |layer| {
            [
                vk::Offset3D::default(),
                vk::Offset3D {
                    x: image.extent.width as i32,
                    y: half_height(image.extent.height, layer) as i32,
                    z: 1,
                },
            ]
        };
        let subresource = |base_array_layer| vk::ImageSubresourceLayers {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            mip_level: 0,
            base_array_layer,
            layer_count: 1,
        };
        let region = vk::ImageBlit {
            src_subresource: subresource(layer - 1),
            src_offsets: rows(layer - 1),
            dst_subresource: subresource(layer),
            dst_offsets: rows(layer),
        };
        // SAFETY: recording-state invariant; the two layers are in the layouts named above (the
        // caller's barriers, which made layer − 1's contents visible to transfer reads), exist
        // and are distinct subresources, the regions lie within them, and the format supports
        // BLIT_SRC / BLIT_DST and linear filtering (the renderer's format check).
        unsafe {
            self.ctx.device.cmd_blit_image(
                self.cmd,
                image.raw,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                image.raw,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &[region],
                vk::Filter::LINEAR,
            )
        };
    }

    /// Bytes of every layer of `image`, tightly packed.
    fn layers_bytes(image: &Image) -> u64 {
        let e = image.extent;
        texel_bytes(image.format) * e.width as u64 * e.height as u64 * image.layers as u64
    }

    /// Copies every layer of a colour image into a buffer, tightly packed, layer after layer,
    /// with its barriers. Panics if the buffer is too small.
    pub fn copy_image_layers_to_buffer(&self, image: &Image, buffer: &Buffer) {
        assert!(
            buffer.size() >= Self::layers_bytes(image),
            "readback buffer too small"
        );
        image.expect_usage(vk::ImageUsageFlags::TRANSFER_SRC, "a copy to a buffer");
        buffer.expect_usage(vk::BufferUsageFlags::TRANSFER_DST, "a copy from an image");
        self.uses(&[(image, Use::CopySrc), (buffer, Use::CopyDst)]);
        let region = packed_region(image.extent, image.layers);
        // SAFETY: recording-state invariant; the image is in TRANSFER_SRC_OPTIMAL (the barrier
        // above) and the buffer holds all layers (asserted).
        unsafe {
            self.ctx.device.cmd_copy_image_to_buffer(
                self.cmd,
                image.raw,
                vk::ImageLayout::TRANSFER_SRC_OPTIMAL,
                buffer.raw(),
                &[region],
            )
        };
    }

    /// Copies a tightly packed buffer into every layer of a colour image (discarding what it
    /// held), with its barriers. Panics if the buffer is too small.
    pub fn copy_buffer_to_image_layers(&self, buffer: &Buffer, image: &Image) {
        assert!(
            buffer.size() >= Self::layers_bytes(image),
            "upload buffer too small"
        );
        buffer.expect_usage(vk::BufferUsageFlags::TRANSFER_SRC, "a copy to an image");
        image.expect_usage(vk::ImageUsageFlags::TRANSFER_DST, "a copy from a buffer");
        self.uses(&[(buffer, Use::CopySrc), (image, Use::CopyDst)]);
        let region = packed_region(image.extent, image.layers);
        // SAFETY: recording-state invariant; the image is in TRANSFER_DST_OPTIMAL (the barrier
        // above) and the buffer holds all layers (asserted).
        unsafe {
            self.ctx.device.cmd_copy_buffer_to_image(
                self.cmd,
                buffer.raw(),
                image.raw,
                vk::ImageLayout::TRANSFER_DST_OPTIMAL,
                &[region],
            )
        };
    }

    /// Clears every layer of a colour image to zero (in GENERAL), with its barrier.
    pub fn clear_image(&self, image: &Image) {
        image.expect_usage(vk::ImageUsageFlags::TRANSFER_DST, "a clear");
        self.uses(&[(image, Use::Clear)]);
        let range = image.range();
        // SAFETY: recording-state invariant; the image has TRANSFER_DST usage (a validation
        // error otherwise, not undefined behaviour of this program) and is in GENERAL.
        unsafe {
            self.ctx.device.cmd_clear_color_image(
                self.cmd,
                image.raw,
                vk::ImageLayout::GENERAL,
                &vk::ClearColorValue::default(),
                &[range],
            )
        };
    }

    /// Fills a whole buffer with a 32-bit value, without a barrier (the deliberate hazard of
    /// `selftest` only).
    pub(super) fn fill_buffer_unsynchronized(&self, buffer: &Buffer, value: u32) {
        buffer.expect_usage(vk::BufferUsageFlags::TRANSFER_DST, "a fill");
        // SAFETY: recording-state invariant; the buffer has TRANSFER_DST usage.
        unsafe {
            self.ctx
                .device
                .cmd_fill_buffer(self.cmd, buffer.raw(), 0, vk::WHOLE_SIZE, value)
        };
    }

    /// Copies `size` bytes from the start of `src` to the start of `dst`, without a barrier
    /// (`copy_buffer` and the deliberate hazard of `selftest`). Panics if either is smaller.
    pub(super) fn copy_buffer_unsynchronized(&self, src: &Buffer, dst: &Buffer, size: u64) {
        src.expect_usage(vk::BufferUsageFlags::TRANSFER_SRC, "a copy's source");
        dst.expect_usage(vk::BufferUsageFlags::TRANSFER_DST, "a copy's destination");
        assert!(
            size <= src.size() && size <= dst.size(),
            "copy of {size} bytes between buffers of {} and {} bytes",
            src.size(),
            dst.size()
        );
        let region = vk::BufferCopy {
            src_offset: 0,
            dst_offset: 0,
            size,
        };
        // SAFETY: recording-state invariant; both buffers hold at least `size` bytes (asserted).
        unsafe {
            self.ctx
                .device
                .cmd_copy_buffer(self.cmd, src.raw(), dst.raw(), &[region])
        };
    }

    /// Copies `size` bytes from the start of `src` to the start of `dst`, with its barriers
    /// (`dst` is overwritten whole: pass its size). Panics if either buffer is smaller.
    pub fn copy_buffer(&self, src: &Buffer, dst: &Buffer, size: vk::DeviceSize) {
        self.uses(&[(src, Use::CopySrc), (dst, Use::CopyDst)]);
        self.copy_buffer_unsynchronized(src, dst, size);
    }

    pub(crate) fn reset_queries(&self, pool: vk::QueryPool, count: u32) {
        // SAFETY: recording-state invariant; outside any rendering scope.
        unsafe {
            self.ctx
                .device
                .cmd_reset_query_pool(self.cmd, pool, 0, count)
        };
    }

    pub(crate) fn begin_query(&self, pool: vk::QueryPool, query: u32) {
        // SAFETY: recording-state invariant; the query is unavailable when this executes: see
        // `write_timestamp` (the statistics pool is reset beside the timestamp pool).
        unsafe {
            self.ctx
                .device
                .cmd_begin_query(self.cmd, pool, query, vk::QueryControlFlags::empty())
        };
    }

    pub(crate) fn end_query(&self, pool: vk::QueryPool, query: u32) {
        // SAFETY: recording-state invariant; paired with `begin_query` in the same scope.
        unsafe { self.ctx.device.cmd_end_query(self.cmd, pool, query) };
    }

    pub(crate) fn write_timestamp(&self, pool: vk::QueryPool, query: u32) {
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

/// Bytes per texel of the colour formats copied here (panics on another: a programming error).
fn texel_bytes(format: vk::Format) -> u64 {
    use vk::Format as F;
    match format {
        F::R8G8B8A8_UNORM | F::R8G8B8A8_SRGB | F::B8G8R8A8_UNORM | F::B8G8R8A8_SRGB => 4,
        F::R16G16B16A16_SFLOAT => 8,
        F::R32G32B32A32_SFLOAT => 16,
        F::R32_SFLOAT | F::D32_SFLOAT => 4,
        other => panic!("texel size of {other:?} unknown to the copies"),
    }
}

/// The rows of layer `layer` that `Recorder::halve_down_layers` fills in an image `height`
/// rows high: the height halved `layer` times (at least 1).
pub fn half_height(height: u32, layer: u32) -> u32 {
    (height >> layer).max(1)
}

/// A copy of the first `layers` layers of a colour image of `extent` to or from a tightly
/// packed buffer, layer after layer.
fn packed_region(extent: vk::Extent2D, layers: u32) -> vk::BufferImageCopy {
    vk::BufferImageCopy {
        buffer_offset: 0,
        buffer_row_length: 0,
        buffer_image_height: 0,
        image_subresource: vk::ImageSubresourceLayers {
            aspect_mask: vk::ImageAspectFlags::COLOR,
            mip_level: 0,
            base_array_layer: 0,
            layer_count: layers,
        },
        image_offset: vk::Offset3D::default(),
        image_extent: vk::Extent3D {
            width: extent.width,
            height: extent.height,
            depth: 1,
        },
    }
}
