//! The window's swapchain: creation and recreation (resize, out-of-date, suboptimal), image
//! acquisition and presentation. Acquire semaphores are per frame slot; "ready to present"
//! semaphores are per swapchain image (an image's previous present has consumed its semaphore
//! by the time the image is acquired again).

use std::sync::Arc;

use ash::vk;

use super::context::Context;
use super::error::{GpuError, GpuResult, VkResultExt};
use super::frame::FRAMES_IN_FLIGHT;

/// Presentation mode requested on the command line.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PresentMode {
    Fifo,
    Mailbox,
    Immediate,
}

impl PresentMode {
    fn vk(self) -> vk::PresentModeKHR {
        match self {
            PresentMode::Fifo => vk::PresentModeKHR::FIFO,
            PresentMode::Mailbox => vk::PresentModeKHR::MAILBOX,
            PresentMode::Immediate => vk::PresentModeKHR::IMMEDIATE,
        }
    }
}

/// An acquired swapchain image.
#[derive(Clone, Copy, Debug)]
pub struct AcquiredImage {
    pub index: u32,
    pub image: vk::Image,
    pub view: vk::ImageView,
    /// Signalled when the image may be written (wait on it at COLOR_ATTACHMENT_OUTPUT).
    pub acquired: vk::Semaphore,
    /// Signal this when rendering is done; presentation waits on it.
    pub ready: vk::Semaphore,
}

pub struct Swapchain {
    ctx: Arc<Context>,
    fns: ash::khr::swapchain::Device,
    raw: vk::SwapchainKHR,
    images: Vec<vk::Image>,
    views: Vec<vk::ImageView>,
    ready: Vec<vk::Semaphore>,
    acquire: Vec<vk::Semaphore>,
    pub format: vk::Format,
    pub extent: vk::Extent2D,
    pub present_mode: vk::PresentModeKHR,
    /// Whether images can be copied out (F12 / --screenshot).
    pub can_copy: bool,
    /// Number of swapchains created so far (reported at exit; the window test checks resizes).
    pub generation: u32,
}

impl Swapchain {
    /// Creates the swapchain for the context's surface at `size` (used when the surface leaves
    /// the extent to the application).
    pub fn new(ctx: &Arc<Context>, size: vk::Extent2D, mode: PresentMode) -> GpuResult<Swapchain> {
        let fns = ash::khr::swapchain::Device::new(&ctx.instance, &ctx.device);
        let mut acquire = Vec::new();
        for i in 0..FRAMES_IN_FLIGHT {
            // SAFETY: valid create info on a live device.
            let s = unsafe {
                ctx.device
                    .create_semaphore(&vk::SemaphoreCreateInfo::default(), None)
            }
            .vk("vkCreateSemaphore")?;
            ctx.name(s, &format!("swapchain acquire slot {i}"));
            acquire.push(s);
        }
        let mut swapchain = Swapchain {
            ctx: ctx.clone(),
            fns,
            raw: vk::SwapchainKHR::null(),
            images: Vec::new(),
            views: Vec::new(),
            ready: Vec::new(),
            acquire,
            format: vk::Format::UNDEFINED,
            extent: vk::Extent2D::default(),
            present_mode: vk::PresentModeKHR::FIFO,
            can_copy: false,
            generation: 0,
        };
        swapchain.recreate(size, mode)?;
        Ok(swapchain)
    }

    /// The surface's current extent, or `fallback` (the window size) when the surface lets the
    /// application choose. A zero extent means the window is minimised.
    pub fn surface_extent(&self, fallback: vk::Extent2D) -> GpuResult<vk::Extent2D> {
        let caps = self.capabilities()?;
        Ok(if caps.current_extent.width != u32::MAX {
            caps.current_extent
        } else {
            vk::Extent2D {
                width: fallback
                    .width
                    .clamp(caps.min_image_extent.width, caps.max_image_extent.width),
                height: fallback
                    .height
                    .clamp(caps.min_image_extent.height, caps.max_image_extent.height),
            }
        })
    }

    fn capabilities(&self) -> GpuResult<vk::SurfaceCapabilitiesKHR> {
        let (fns, surface) = self
            .ctx
            .surface
            .as_ref()
            .expect("a windowed context has a surface");
        // SAFETY: surface and physical device are live.
        unsafe { fns.get_physical_device_surface_capabilities(self.ctx.physical, *surface) }
            .vk("vkGetPhysicalDeviceSurfaceCapabilitiesKHR")
    }

    /// (Re)creates the swapchain. Waits for the device to go idle first: resizes are rare and
    /// this keeps the old images' destruction trivially safe.
    pub fn recreate(&mut self, size: vk::Extent2D, mode: PresentMode) -> GpuResult<()> {
        self.ctx.wait_idle()?;
        let (surface_fns, surface) = self
            .ctx
            .surface
            .as_ref()
            .expect("a windowed context has a surface");
        let caps = self.capabilities()?;
        // SAFETY: surface and physical device are live.
        let formats =
            unsafe { surface_fns.get_physical_device_surface_formats(self.ctx.physical, *surface) }
                .vk("vkGetPhysicalDeviceSurfaceFormatsKHR")?;
        // SAFETY: as above.
        let modes = unsafe {
            surface_fns.get_physical_device_surface_present_modes(self.ctx.physical, *surface)
        }
        .vk("vkGetPhysicalDeviceSurfacePresentModesKHR")?;
        let format = [vk::Format::B8G8R8A8_SRGB, vk::Format::R8G8B8A8_SRGB]
            .iter()
            .find_map(|f| {
                formats
                    .iter()
                    .find(|s| s.format == *f && s.color_space == vk::ColorSpaceKHR::SRGB_NONLINEAR)
            })
            .copied()
            .ok_or_else(|| {
                GpuError::Unsupported("the window surface offers no 8-bit sRGB format".into())
            })?;
        let present_mode = if modes.contains(&mode.vk()) {
            mode.vk()
        } else {
            log::warn!("present mode {mode:?} is not supported by this surface; using FIFO");
            vk::PresentModeKHR::FIFO
        };
        let extent = self.surface_extent(size)?;
        let mut image_count = caps.min_image_count + 1;
        if caps.max_image_count > 0 {
            image_count = image_count.min(caps.max_image_count);
        }
        let can_copy = caps
            .supported_usage_flags
            .contains(vk::ImageUsageFlags::TRANSFER_SRC);
        let mut usage = vk::ImageUsageFlags::COLOR_ATTACHMENT;
        if can_copy {
            usage |= vk::ImageUsageFlags::TRANSFER_SRC;
        }
        let old = self.raw;
        let info = vk::SwapchainCreateInfoKHR::default()
            .surface(*surface)
            .min_image_count(image_count)
            .image_format(format.format)
            .image_color_space(format.color_space)
            .image_extent(extent)
            .image_array_layers(1)
            .image_usage(usage)
            .image_sharing_mode(vk::SharingMode::EXCLUSIVE)
            .pre_transform(caps.current_transform)
            .composite_alpha(vk::CompositeAlphaFlagsKHR::OPAQUE)
            .present_mode(present_mode)
            .clipped(true)
            .old_swapchain(old);
        // SAFETY: valid create info; `old` (possibly null) is retired by this call.
        let raw = unsafe { self.fns.create_swapchain(&info, None) }.vk("vkCreateSwapchainKHR")?;
        self.destroy_images();
        if old != vk::SwapchainKHR::null() {
            // SAFETY: the device is idle, so nothing uses the old swapchain or its images.
            unsafe { self.fns.destroy_swapchain(old, None) };
        }
        self.raw = raw;
        self.generation += 1;
        self.ctx
            .name(raw, &format!("swapchain #{}", self.generation));
        // SAFETY: the swapchain is live.
        self.images =
            unsafe { self.fns.get_swapchain_images(raw) }.vk("vkGetSwapchainImagesKHR")?;
        for (i, &image) in self.images.iter().enumerate() {
            self.ctx.name(image, &format!("swapchain image {i}"));
            let view_info = vk::ImageViewCreateInfo::default()
                .image(image)
                .view_type(vk::ImageViewType::TYPE_2D)
                .format(format.format)
                .subresource_range(super::image::full_range(vk::ImageAspectFlags::COLOR, 1));
            // SAFETY: the image belongs to the live swapchain.
            let view = unsafe { self.ctx.device.create_image_view(&view_info, None) }
                .vk("vkCreateImageView")?;
            self.ctx.name(view, &format!("swapchain image {i} view"));
            self.views.push(view);
            // SAFETY: valid create info on a live device.
            let ready = unsafe {
                self.ctx
                    .device
                    .create_semaphore(&vk::SemaphoreCreateInfo::default(), None)
            }
            .vk("vkCreateSemaphore")?;
            self.ctx
                .name(ready, &format!("swapchain image {i} ready to present"));
            self.ready.push(ready);
        }
        self.format = format.format;
        self.extent = extent;
        self.present_mode = present_mode;
        self.can_copy = can_copy;
        log::info!(
            "swapchain #{}: {}x{} {:?} {:?}, {} images",
            self.generation,
            extent.width,
            extent.height,
            format.format,
            present_mode,
            self.images.len()
        );
        Ok(())
    }

    /// Acquires the next image for frame slot `slot`. `Ok(None)`: the swapchain is out of date
    /// and must be recreated. The flag is true when the image is usable but suboptimal.
    pub fn acquire(&self, slot: usize) -> GpuResult<Option<(AcquiredImage, bool)>> {
        let semaphore = self.acquire[slot];
        // SAFETY: the semaphore is unsignalled: its previous wait (frame slot - 2) has completed
        // because `Frames::begin` waited for that frame.
        match unsafe {
            self.fns
                .acquire_next_image(self.raw, u64::MAX, semaphore, vk::Fence::null())
        } {
            Ok((index, suboptimal)) => {
                let i = index as usize;
                Ok(Some((
                    AcquiredImage {
                        index,
                        image: self.images[i],
                        view: self.views[i],
                        acquired: semaphore,
                        ready: self.ready[i],
                    },
                    suboptimal,
                )))
            }
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(None),
            Err(result) => Err(GpuError::Vk {
                call: "vkAcquireNextImageKHR",
                result,
            }),
        }
    }

    /// Presents `image` after its `ready` semaphore. Returns true when the swapchain should be
    /// recreated (out of date or suboptimal).
    pub fn present(&self, image: &AcquiredImage) -> GpuResult<bool> {
        let waits = [image.ready];
        let swapchains = [self.raw];
        let indices = [image.index];
        let info = vk::PresentInfoKHR::default()
            .wait_semaphores(&waits)
            .swapchains(&swapchains)
            .image_indices(&indices);
        // SAFETY: the image was acquired from this swapchain and rendering signals `ready`.
        match unsafe { self.fns.queue_present(self.ctx.graphics.raw, &info) } {
            Ok(suboptimal) => Ok(suboptimal),
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(true),
            Err(result) => Err(GpuError::Vk {
                call: "vkQueuePresentKHR",
                result,
            }),
        }
    }

    fn destroy_images(&mut self) {
        // SAFETY: only called with the device idle; views and semaphores are ours.
        unsafe {
            for view in self.views.drain(..) {
                self.ctx.device.destroy_image_view(view, None);
            }
            for s in self.ready.drain(..) {
                self.ctx.device.destroy_semaphore(s, None);
            }
        }
        self.images.clear();
    }
}

impl Drop for Swapchain {
    fn drop(&mut self) {
        if let Err(e) = self.ctx.wait_idle() {
            log::error!("swapchain shutdown: {e}");
        }
        self.destroy_images();
        // SAFETY: the device is idle; the swapchain and acquire semaphores are ours.
        unsafe {
            for s in self.acquire.drain(..) {
                self.ctx.device.destroy_semaphore(s, None);
            }
            if self.raw != vk::SwapchainKHR::null() {
                self.fns.destroy_swapchain(self.raw, None);
            }
        }
    }
}
