//! `Image` (a `VkImage`, its memory and a default view) and `Sampler`, both destroyed through the
//! deletion queue.

use std::ops::Deref;
use std::rc::Rc;
use std::sync::Arc;

use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;

use super::context::Context;
use super::error::{GpuError, GpuResult, VkResultExt};
use super::garbage::Garbage;
use super::queues::QueueUsers;
use super::track::{ExternalImage, Handle, State, StateCell, Tracked};

/// How to create an [`Image`].
#[derive(Clone, Copy, Debug)]
pub struct ImageDesc<'a> {
    pub name: &'a str,
    pub extent: vk::Extent2D,
    pub format: vk::Format,
    pub usage: vk::ImageUsageFlags,
    /// Array layers (1 for a plain 2D image; the view is a 2D array when > 1).
    pub layers: u32,
    /// View all layers as a 2D array even when there is one (shaders declaring arrays).
    pub array_view: bool,
    /// Used by both the graphics and the compute queue: CONCURRENT sharing when their families
    /// differ (correct by construction, no ownership transfers; `QueuePlan::sharing`).
    pub shared: bool,
    /// A cubemap: 6 layers (+x, -x, +y, -y, +z, -z), a cube view for sampling and one 2D view
    /// per face for rendering into it (`Image::layer_views`). A colour attachment with more
    /// than one layer gets the 2D views of its layers too.
    pub cube: bool,
    /// Mip levels (1: none). The default view holds them all, for sampling; a storage image
    /// with more than one also gets a view of each level (`Bind::StorageImage` binds level 0,
    /// `Bind::StorageLevel` another), since a storage descriptor addresses one level.
    pub levels: u32,
}

impl<'a> ImageDesc<'a> {
    /// A plain 2D image: one layer, one level, used by one queue family. The others set the
    /// fields that differ over it (`ImageDesc { layers: 6, cube: true, ..ImageDesc::new(…) }`).
    pub fn new(
        name: &'a str,
        extent: vk::Extent2D,
        format: vk::Format,
        usage: vk::ImageUsageFlags,
    ) -> ImageDesc<'a> {
        ImageDesc {
            name,
            extent,
            format,
            usage,
            layers: 1,
            array_view: false,
            shared: false,
            cube: false,
            levels: 1,
        }
    }
}

/// A 2D (array) image in device memory with a view of all its layers (none for an image with
/// transfer usage only). A shared handle: a clone is the same image (descriptor sets hold one,
/// so an image lives as long as a set that binds it), destroyed through the deletion queue when
/// the last clone is dropped. Its Vulkan handles stay inside the GPU layer.
#[derive(Clone)]
pub struct Image(Rc<ImageCore>);

/// What an [`Image`] holds; its handles are visible to the GPU layer only.
pub struct ImageCore {
    ctx: Arc<Context>,
    pub(super) raw: vk::Image,
    pub(super) view: vk::ImageView,
    /// One 2D view per layer (cubemaps and layered colour attachments: render targets of the
    /// faces or layers).
    pub(super) layer_views: Vec<vk::ImageView>,
    /// One array view per mip level (storage images with more than one level).
    pub(super) level_views: Vec<vk::ImageView>,
    allocation: Option<Allocation>,
    pub(super) format: vk::Format,
    pub(super) extent: vk::Extent2D,
    pub(super) layers: u32,
    pub(super) levels: u32,
    pub(super) aspect: vk::ImageAspectFlags,
    pub(super) usage: vk::ImageUsageFlags,
    name: String,
    /// What the last recorded use left (`track`), on the queue that uses the image.
    pub(super) state: StateCell,
}

impl std::fmt::Debug for Image {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "Image({:?})", self.name)
    }
}

impl Deref for Image {
    type Target = ImageCore;
    fn deref(&self) -> &ImageCore {
        &self.0
    }
}

/// A B8G8R8A8 format: bytes in blue, green, red, alpha order (swapchains often use one).
pub fn is_bgra(format: vk::Format) -> bool {
    matches!(
        format,
        vk::Format::B8G8R8A8_SRGB | vk::Format::B8G8R8A8_UNORM
    )
}

/// The aspect a format's views and barriers use.
pub fn aspect_of(format: vk::Format) -> vk::ImageAspectFlags {
    match format {
        vk::Format::D16_UNORM | vk::Format::D32_SFLOAT | vk::Format::X8_D24_UNORM_PACK32 => {
            vk::ImageAspectFlags::DEPTH
        }
        vk::Format::D24_UNORM_S8_UINT
        | vk::Format::D32_SFLOAT_S8_UINT
        | vk::Format::D16_UNORM_S8_UINT => {
            vk::ImageAspectFlags::DEPTH | vk::ImageAspectFlags::STENCIL
        }
        _ => vk::ImageAspectFlags::COLOR,
    }
}

impl Image {
    /// Creates a named image (optimal tiling, device-local) and its view.
    // Long: create, allocate, bind and make views, each failure freeing what came before.
    pub fn new(ctx: &Arc<Context>, desc: &ImageDesc) -> GpuResult<Image> {
        let e = desc.extent;
        if e.width == 0 || e.height == 0 || (desc.cube && e.width != e.height) {
            return Err(GpuError::Unsupported(format!(
                "image {}: {}x{} is empty{}",
                desc.name,
                e.width,
                e.height,
                if desc.cube {
                    " or not square (a cube)"
                } else {
                    ""
                }
            )));
        }
        let layers = if desc.cube { 6 } else { desc.layers.max(1) };
        let levels = desc.levels.max(1);
        let info = vk::ImageCreateInfo::default()
            .flags(if desc.cube {
                vk::ImageCreateFlags::CUBE_COMPATIBLE
            } else {
                vk::ImageCreateFlags::empty()
            })
            .image_type(vk::ImageType::TYPE_2D)
            .format(desc.format)
            .extent(vk::Extent3D {
                width: desc.extent.width,
                height: desc.extent.height,
                depth: 1,
            })
            .mip_levels(levels)
            .array_layers(layers)
            .samples(vk::SampleCountFlags::TYPE_1)
            .tiling(vk::ImageTiling::OPTIMAL)
            .usage(desc.usage)
            .initial_layout(vk::ImageLayout::UNDEFINED);
        let sharing = ctx.sharing(if desc.shared {
            QueueUsers::Both
        } else {
            QueueUsers::Graphics
        });
        let info = info
            .sharing_mode(sharing.mode)
            .queue_family_indices(&sharing.families);
        // SAFETY: valid create info on a live device.
        let raw = unsafe { ctx.device.create_image(&info, None) }.vk("vkCreateImage")?;
        ctx.count_created(1);
        // SAFETY: `raw` is a live image of this device.
        let requirements = unsafe { ctx.device.get_image_memory_requirements(raw) };
        let allocation = match ctx.allocator().allocate(&AllocationCreateDesc {
            name: desc.name,
            requirements,
            location: MemoryLocation::GpuOnly,
            linear: false,
            allocation_scheme: AllocationScheme::GpuAllocatorManaged,
        }) {
            Ok(a) => a,
            Err(source) => {
                // SAFETY: the image was never used or bound.
                unsafe { ctx.device.destroy_image(raw, None) };
                ctx.count_destroyed(1);
                return Err(GpuError::Alloc {
                    name: desc.name.to_string(),
                    source,
                });
            }
        };
        let aspect = aspect_of(desc.format);
        let mut image = ImageCore {
            ctx: ctx.clone(),
            raw,
            view: vk::ImageView::null(),
            layer_views: Vec::new(),
            level_views: Vec::new(),
            allocation: Some(allocation),
            format: desc.format,
            extent: desc.extent,
            layers,
            levels,
            aspect,
            usage: desc.usage,
            name: desc.name.to_string(),
            state: StateCell::new(State::NEW),
        };
        let allocation = image.allocation.as_ref().expect("just set");
        // SAFETY: the allocation satisfies the image's requirements and is bound once.
        unsafe {
            ctx.device
                .bind_image_memory(raw, allocation.memory(), allocation.offset())
        }
        .map_err(|result| GpuError::Bind {
            name: desc.name.to_string(),
            call: "vkBindImageMemory",
            result,
        })?;
        ctx.name(raw, desc.name);
        // Copy-only images (transfer usage alone) cannot have views; `view` stays null.
        let viewable = vk::ImageUsageFlags::SAMPLED
            | vk::ImageUsageFlags::STORAGE
            | vk::ImageUsageFlags::COLOR_ATTACHMENT
            | vk::ImageUsageFlags::DEPTH_STENCIL_ATTACHMENT;
        if !desc.usage.intersects(viewable) {
            return Ok(Image(Rc::new(image)));
        }
        let view_info = vk::ImageViewCreateInfo::default()
            .image(raw)
            .view_type(if desc.cube {
                vk::ImageViewType::CUBE
            } else if layers > 1 || desc.array_view {
                vk::ImageViewType::TYPE_2D_ARRAY
            } else {
                vk::ImageViewType::TYPE_2D
            })
            .format(desc.format)
            .subresource_range(vk::ImageSubresourceRange {
                level_count: levels,
                ..full_range(aspect, layers)
            });
        // SAFETY: the image is live and bound; the range is within it.
        image.view =
            unsafe { ctx.device.create_image_view(&view_info, None) }.vk("vkCreateImageView")?;
        ctx.count_created(1);
        ctx.name(image.view, &format!("{} view", desc.name));
        let layered_target =
            layers > 1 && desc.usage.contains(vk::ImageUsageFlags::COLOR_ATTACHMENT);
        if desc.cube || layered_target {
            for layer in 0..layers {
                let info = view_info
                    .view_type(vk::ImageViewType::TYPE_2D)
                    .subresource_range(vk::ImageSubresourceRange {
                        base_array_layer: layer,
                        layer_count: 1,
                        ..full_range(aspect, 1)
                    });
                // SAFETY: as above; the range is one layer of the image.
                let view =
                    unsafe { ctx.device.create_image_view(&info, None) }.vk("vkCreateImageView")?;
                ctx.count_created(1);
                let part = if desc.cube { "face" } else { "layer" };
                ctx.name(view, &format!("{} {part} {layer}", desc.name));
                image.layer_views.push(view);
            }
        }
        if levels > 1 && desc.usage.contains(vk::ImageUsageFlags::STORAGE) {
            for level in 0..levels {
                let info = view_info.subresource_range(vk::ImageSubresourceRange {
                    base_mip_level: level,
                    ..full_range(aspect, layers)
                });
                // SAFETY: as above; the range is one level of the image.
                let view =
                    unsafe { ctx.device.create_image_view(&info, None) }.vk("vkCreateImageView")?;
                ctx.count_created(1);
                ctx.name(view, &format!("{} level {level}", desc.name));
                image.level_views.push(view);
            }
        }
        Ok(Image(Rc::new(image)))
    }

    /// Whether `self` and `other` are the same image.
    pub fn same(&self, other: &Image) -> bool {
        Rc::ptr_eq(&self.0, &other.0)
    }
}

impl ImageCore {
    /// The whole subresource range (all layers, all levels).
    pub fn range(&self) -> vk::ImageSubresourceRange {
        vk::ImageSubresourceRange {
            level_count: self.levels,
            ..full_range(self.aspect, self.layers)
        }
    }

    /// Mip levels (1: none).
    pub fn levels(&self) -> u32 {
        self.levels
    }

    /// The view a storage descriptor binds for mip level `level`: the default view when the
    /// image has one level.
    pub(super) fn storage_view(&self, level: u32) -> vk::ImageView {
        assert!(
            level < self.levels,
            "image {} has no mip level {level}",
            self.name
        );
        self.level_views
            .get(level as usize)
            .copied()
            .unwrap_or(self.view)
    }

    pub fn extent(&self) -> vk::Extent2D {
        self.extent
    }

    pub fn format(&self) -> vk::Format {
        self.format
    }

    /// Array layers (6 for a cube).
    pub fn layers(&self) -> u32 {
        self.layers
    }

    /// The name it was created with (debug names, the frame graph).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Panics unless the image was created with `usage` (for `what`): using it otherwise is
    /// invalid usage, so the GPU layer's safe functions refuse it.
    pub(super) fn expect_usage(&self, usage: vk::ImageUsageFlags, what: &str) {
        expect_usage(&self.name, self.usage, usage, what);
    }
}

/// Panics unless `have` contains `want` (a programming error, named).
pub(super) fn expect_usage(
    name: &str,
    have: vk::ImageUsageFlags,
    want: vk::ImageUsageFlags,
    what: &str,
) {
    assert!(
        have.contains(want),
        "image {name} lacks {want:?} usage, which {what} needs"
    );
}

/// Every layer of the first mip level.
pub fn full_range(aspect: vk::ImageAspectFlags, layers: u32) -> vk::ImageSubresourceRange {
    vk::ImageSubresourceRange {
        aspect_mask: aspect,
        base_mip_level: 0,
        level_count: 1,
        base_array_layer: 0,
        layer_count: layers,
    }
}

impl Drop for ImageCore {
    fn drop(&mut self) {
        if let Some(allocation) = self.allocation.take() {
            let mut views = std::mem::take(&mut self.layer_views);
            views.append(&mut self.level_views);
            if self.view != vk::ImageView::null() {
                views.push(self.view);
            }
            self.ctx.defer(Garbage::Image {
                image: self.raw,
                views,
                allocation,
            });
        }
    }
}

/// A sampler; a shared handle (descriptor sets keep the samplers they bind alive).
#[derive(Clone)]
pub struct Sampler(Rc<SamplerCore>);

struct SamplerCore {
    ctx: Arc<Context>,
    raw: vk::Sampler,
}

impl Sampler {
    /// Linear filtering with the given addressing (clamp for render targets, repeat for tiles).
    pub fn linear(
        ctx: &Arc<Context>,
        name: &str,
        address: vk::SamplerAddressMode,
    ) -> GpuResult<Sampler> {
        Sampler::new(ctx, name, vk::Filter::LINEAR, address)
    }

    /// Nearest or linear filtering with the given addressing (nearest for depth textures, whose
    /// formats need not support linear filtering).
    pub fn new(
        ctx: &Arc<Context>,
        name: &str,
        filter: vk::Filter,
        address: vk::SamplerAddressMode,
    ) -> GpuResult<Sampler> {
        let info = vk::SamplerCreateInfo::default()
            .mag_filter(filter)
            .min_filter(filter)
            .mipmap_mode(if filter == vk::Filter::NEAREST {
                vk::SamplerMipmapMode::NEAREST
            } else {
                vk::SamplerMipmapMode::LINEAR
            })
            .address_mode_u(address)
            .address_mode_v(address)
            .address_mode_w(address)
            .max_lod(vk::LOD_CLAMP_NONE);
        // SAFETY: valid create info on a live device.
        let raw = unsafe { ctx.device.create_sampler(&info, None) }.vk("vkCreateSampler")?;
        ctx.count_created(1);
        ctx.name(raw, name);
        Ok(Sampler(Rc::new(SamplerCore {
            ctx: ctx.clone(),
            raw,
        })))
    }

    pub(super) fn raw(&self) -> vk::Sampler {
        self.0.raw
    }
}

impl Drop for SamplerCore {
    fn drop(&mut self) {
        self.ctx.defer(Garbage::Sampler(self.raw));
    }
}

impl super::track::sealed::Sealed for Image {}

impl Tracked for Image {
    fn handle(&self) -> Handle {
        Handle::image(self.raw, self.range())
    }
    fn name(&self) -> &str {
        &self.name
    }
    fn state(&self) -> &StateCell {
        &self.state
    }
}

/// The image a frame ends in: one the program owns (headless) or a swapchain's.
#[derive(Clone, Copy)]
pub enum Output<'a> {
    Image(&'a Image),
    External(&'a ExternalImage),
}

impl<'a> Output<'a> {
    pub fn extent(self) -> vk::Extent2D {
        match self {
            Output::Image(i) => i.extent,
            Output::External(e) => e.extent,
        }
    }
    pub fn format(self) -> vk::Format {
        match self {
            Output::Image(i) => i.format,
            Output::External(e) => e.format,
        }
    }
    pub fn tracked(self) -> &'a dyn Tracked {
        match self {
            Output::Image(i) => i,
            Output::External(e) => e,
        }
    }
    pub(super) fn raw(self) -> vk::Image {
        match self {
            Output::Image(i) => i.raw,
            Output::External(e) => e.raw,
        }
    }
    /// Whether it is `image`.
    pub(super) fn is(self, image: &Image) -> bool {
        matches!(self, Output::Image(i) if i.same(image))
    }
    pub(super) fn view(self) -> vk::ImageView {
        match self {
            Output::Image(i) => i.view,
            Output::External(e) => e.view,
        }
    }
    /// Panics unless the image has `usage` (for `what`).
    pub(super) fn expect_usage(self, usage: vk::ImageUsageFlags, what: &str) {
        match self {
            Output::Image(i) => i.expect_usage(usage, what),
            Output::External(e) => expect_usage(&e.name, e.usage, usage, what),
        }
    }
}
