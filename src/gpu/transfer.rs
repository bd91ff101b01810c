//! The transfer commands of [`Recorder`]: copies, blits, clears and fills. Each records its own
//! barriers (`Recorder::uses`) and checks what Vulkan would otherwise leave undefined: sizes,
//! usages, a source distinct from its destination, no rendering scope open.

use ash::vk;

use super::buffer::Buffer;
use super::command::Recorder;
use super::image::{Image, Output};
use super::track::Use;

impl Recorder<'_> {
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
        self.expect_outside_scope("a copy");
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
        self.expect_outside_scope("a copy");
        assert!(!dst.is(src), "a copy of {} onto itself", src.name());
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
        self.expect_outside_scope("a blit");
        self.expect_graphics("a blit");
        assert!(!dst.is(src), "a blit of {} onto itself", src.name());
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
    pub(super) fn blit_half_height(&self, image: &super::image::Image, layer: u32) {
        assert!(
            layer >= 1 && layer < image.layers,
            "blit into layer {layer}"
        );
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
        self.expect_outside_scope("a copy");
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
        self.expect_outside_scope("a copy");
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
        self.expect_outside_scope("a clear");
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
        self.expect_outside_scope("a fill");
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
        self.expect_outside_scope("a copy");
        assert!(!src.is(dst), "a copy of a buffer onto itself");
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
