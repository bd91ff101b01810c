//! The window's swapchain: creation and recreation (resize, out-of-date, suboptimal), image
//! acquisition and presentation. Acquire semaphores are per frame slot; "ready to present"
//! semaphores are per swapchain image (an image's previous present has consumed its semaphore
//! by the time the image is acquired again).
//!
//! The surface's capabilities are queried once per (re)creation, not per frame: the frontend
//! recreates on a resize event, an out-of-date or suboptimal acquire or present, and skips
//! frames while the window has zero size (minimised).
//!
//! Retiring a swapchain: `vkDeviceWaitIdle` does not cover the presentation engine's semaphore
//! waits (no present fences without VK_EXT_swapchain_maintenance1), so a retired swapchain and
//! its ready semaphores are kept until the new swapchain has presented `RETIRE_AFTER_PRESENTS`
//! times, by which point every present queued on the old one has been processed.

use std::sync::Arc;

use ash::vk;

use super::context::Context;
use super::error::{GpuError, GpuResult, VkResultExt};
use super::frame::{Frames, FRAMES_IN_FLIGHT};

/// Presents on a new swapchain after which a retired one is destroyed.
const RETIRE_AFTER_PRESENTS: u64 = 8;

/// Presentation mode requested on the command line (`--present-mode`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum PresentMode {
    /// Wait for vertical blank (always available).
    Fifo,
    /// Replace the queued image (no tearing, no waiting).
    Mailbox,
    /// Present at once (may tear).
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

/// The surface format to render to: 8-bit sRGB (B8G8R8A8 or R8G8B8A8) in the sRGB colour space,
/// whose attachment writes encode; else the same layouts in UNORM, where the shaders encode sRGB
/// themselves (`DISPLAY_TARGET` in shaders/common/display.glsl); `None` when neither is offered.
pub fn choose_surface_format(formats: &[vk::SurfaceFormatKHR]) -> Option<vk::SurfaceFormatKHR> {
    [
        vk::Format::B8G8R8A8_SRGB,
        vk::Format::R8G8B8A8_SRGB,
        vk::Format::B8G8R8A8_UNORM,
        vk::Format::R8G8B8A8_UNORM,
    ]
    .iter()
    .find_map(|f| {
        formats
            .iter()
            .find(|s| s.format == *f && s.color_space == vk::ColorSpaceKHR::SRGB_NONLINEAR)
    })
    .copied()
}

/// An acquired swapchain image (not `Copy`: its acquire semaphore is waited for once).
#[derive(Debug)]
pub struct AcquiredImage {
    pub(super) index: u32,
    pub(super) image: vk::Image,
    /// Its colour view (the overlay draws into the image).
    pub(super) view: vk::ImageView,
    /// Signalled when the image may be written (wait on it where the frame first touches the
    /// image: the output pass's copy, blit or draw).
    pub(super) acquired: vk::Semaphore,
    /// Signal this when rendering is done; presentation waits on it.
    pub(super) ready: vk::Semaphore,
    /// `acquire_wait` was taken (a binary semaphore's signal is waited for once).
    pub(super) waited: std::cell::Cell<bool>,
    /// The swapchain's image size, format and usage.
    pub(super) extent: vk::Extent2D,
    pub(super) format: vk::Format,
    pub(super) usage: vk::ImageUsageFlags,
}

impl AcquiredImage {
    /// The wait for the acquire, at `stage` (where the frame first writes the image).
    /// Panics the second time: the acquire's one signal can satisfy one wait.
    pub fn acquire_wait(&self, stage: vk::PipelineStageFlags2) -> super::SemaphoreOp {
        assert!(
            !self.waited.replace(true),
            "swapchain image {}: its acquire was already waited for",
            self.index
        );
        super::SemaphoreOp(
            vk::SemaphoreSubmitInfo::default()
                .semaphore(self.acquired)
                .stage_mask(stage),
        )
    }

    /// The signal the presentation waits for, after every command of the submission.
    pub fn ready_signal(&self) -> super::SemaphoreOp {
        super::SemaphoreOp(
            vk::SemaphoreSubmitInfo::default()
                .semaphore(self.ready)
                .stage_mask(vk::PipelineStageFlags2::ALL_COMMANDS),
        )
    }

    /// The image as a frame's output, free for writing once the acquire semaphore's wait at
    /// `after` is done.
    pub fn target(&self, after: vk::PipelineStageFlags2) -> super::ExternalImage {
        super::ExternalImage {
            raw: self.image,
            view: self.view,
            extent: self.extent,
            format: self.format,
            usage: self.usage,
            name: format!("swapchain image {}", self.index),
            state: super::track::StateCell::new(super::State::available_after(after)),
        }
    }
}

/// A retired swapchain waiting for its presents to drain.
struct Retired {
    raw: vk::SwapchainKHR,
    views: Vec<vk::ImageView>,
    ready: Vec<vk::Semaphore>,
    /// `presents` count at which it may be destroyed.
    destroy_at: u64,
}

pub struct Swapchain {
    ctx: Arc<Context>,
    fns: ash::khr::swapchain::Device,
    raw: vk::SwapchainKHR,
    images: Vec<vk::Image>,
    /// One colour view per image (the overlay pass renders into the image).
    views: Vec<vk::ImageView>,
    ready: Vec<vk::Semaphore>,
    acquire: Vec<vk::Semaphore>,
    retired: Vec<Retired>,
    /// Presents so far (all swapchains).
    presents: u64,
    pub format: vk::Format,
    pub extent: vk::Extent2D,
    pub present_mode: vk::PresentModeKHR,
    /// Whether images can be copied out (F12 / --screenshot).
    pub can_copy: bool,
    /// Whether images can be copied into; else the output pass draws into them.
    pub transfer_dst: bool,
    /// Number of swapchains created so far (reported at exit; the window test checks resizes).
    pub generation: u32,
    /// The images' usage (what `supportedUsageFlags` offered of what we ask).
    usage: vk::ImageUsageFlags,
}

impl Swapchain {
    /// Creates the swapchain for the context's surface at `size` (used when the surface leaves
    /// the extent to the application).
    pub fn new(ctx: &Arc<Context>, size: vk::Extent2D, mode: PresentMode) -> GpuResult<Swapchain> {
        let mut swapchain = Swapchain {
            ctx: ctx.clone(),
            fns: ash::khr::swapchain::Device::new(&ctx.instance, &ctx.device),
            raw: vk::SwapchainKHR::null(),
            images: Vec::new(),
            views: Vec::new(),
            ready: Vec::new(),
            acquire: Vec::new(),
            retired: Vec::new(),
            presents: 0,
            format: vk::Format::UNDEFINED,
            extent: vk::Extent2D::default(),
            present_mode: vk::PresentModeKHR::FIFO,
            can_copy: false,
            transfer_dst: false,
            generation: 0,
            usage: vk::ImageUsageFlags::empty(),
        };
        // Pushed one by one: an error drops (and frees) what exists so far.
        for i in 0..FRAMES_IN_FLIGHT {
            let s = swapchain.semaphore(&format!("swapchain acquire slot {i}"))?;
            swapchain.acquire.push(s);
        }
        if !swapchain.recreate(size, mode)? {
            return Err(GpuError::Unsupported(
                "the window's surface has zero size (minimised?); cannot create its swapchain"
                    .into(),
            ));
        }
        Ok(swapchain)
    }

    fn semaphore(&self, name: &str) -> GpuResult<vk::Semaphore> {
        // SAFETY: valid create info on a live device.
        let s = unsafe {
            self.ctx
                .device
                .create_semaphore(&vk::SemaphoreCreateInfo::default(), None)
        }
        .vk("vkCreateSemaphore")?;
        self.ctx.count_created(1);
        self.ctx.name(s, name);
        Ok(s)
    }

    fn view(&self, image: vk::Image, format: vk::Format, name: &str) -> GpuResult<vk::ImageView> {
        let info = vk::ImageViewCreateInfo::default()
            .image(image)
            .view_type(vk::ImageViewType::TYPE_2D)
            .format(format)
            .subresource_range(super::image::full_range(vk::ImageAspectFlags::COLOR, 1));
        // SAFETY: `image` is a live image of this device's swapchain, in `format`.
        let view =
            unsafe { self.ctx.device.create_image_view(&info, None) }.vk("vkCreateImageView")?;
        self.ctx.count_created(1);
        self.ctx.name(view, name);
        Ok(view)
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

    /// (Re)creates the swapchain at the surface's extent (`size`, the window's, where the surface
    /// leaves it to the application). Waits for the device to go idle first (resizes are rare);
    /// the old swapchain is retired (see the module comment). `Ok(false)`: the surface has zero
    /// size (a minimised window) and nothing changed; call again later.
    // Long: the swapchain's creation (capabilities, format, mode, extent, images, per-image
    // semaphores) with the old swapchain handed over; each step needs the previous one.
    pub fn recreate(&mut self, size: vk::Extent2D, mode: PresentMode) -> GpuResult<bool> {
        // The one query of the capabilities for this swapchain.
        let caps = self.capabilities()?;
        let extent = surface_extent(&caps, size);
        if extent.width == 0 || extent.height == 0 {
            return Ok(false);
        }
        self.ctx.wait_idle()?;
        let (surface_fns, surface) = self
            .ctx
            .surface
            .as_ref()
            .expect("a windowed context has a surface");
        // SAFETY: surface and physical device are live.
        let formats =
            unsafe { surface_fns.get_physical_device_surface_formats(self.ctx.physical, *surface) }
                .vk("vkGetPhysicalDeviceSurfaceFormatsKHR")?;
        // SAFETY: as above.
        let modes = unsafe {
            surface_fns.get_physical_device_surface_present_modes(self.ctx.physical, *surface)
        }
        .vk("vkGetPhysicalDeviceSurfacePresentModesKHR")?;
        let format = choose_surface_format(&formats).ok_or_else(|| {
            GpuError::Unsupported(
                "the window surface offers no 8-bit RGBA/BGRA format in the sRGB colour space"
                    .into(),
            )
        })?;
        if self.generation == 0 && format.format != formats[0].format {
            log::info!("surface formats offered: {formats:?}");
        }
        let present_mode = if modes.contains(&mode.vk()) {
            mode.vk()
        } else {
            if self.generation == 0 {
                log::warn!("present mode {mode:?} is not supported by this surface; using FIFO");
            }
            vk::PresentModeKHR::FIFO
        };
        let alpha = [
            vk::CompositeAlphaFlagsKHR::OPAQUE,
            vk::CompositeAlphaFlagsKHR::INHERIT,
            vk::CompositeAlphaFlagsKHR::PRE_MULTIPLIED,
            vk::CompositeAlphaFlagsKHR::POST_MULTIPLIED,
        ]
        .into_iter()
        .find(|a| caps.supported_composite_alpha.contains(*a))
        .unwrap_or(vk::CompositeAlphaFlagsKHR::OPAQUE);
        let mut image_count = caps.min_image_count + 1;
        if caps.max_image_count > 0 {
            image_count = image_count.min(caps.max_image_count);
        }
        // Only COLOR_ATTACHMENT is a guaranteed usage: the overlay pass draws into the image,
        // and so does the output pass where TRANSFER_DST (its copy or blit) is not offered.
        // Screenshots copy the image out and need TRANSFER_SRC (else F12 and --screenshot
        // say they cannot).
        let (usage, can_copy, transfer_dst) = swapchain_usage(caps.supported_usage_flags);
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
            .composite_alpha(alpha)
            .present_mode(present_mode)
            // Not clipped: F12 and --screenshot read the image back, and a clipped swapchain
            // leaves covered pixels undefined.
            .clipped(false)
            .old_swapchain(old);
        // SAFETY: valid create info; `old` (possibly null) is retired by this call.
        let raw = unsafe { self.fns.create_swapchain(&info, None) }.vk("vkCreateSwapchainKHR")?;
        self.ctx.count_created(1);
        self.images.clear();
        if old != vk::SwapchainKHR::null() {
            self.retired.push(Retired {
                raw: old,
                views: std::mem::take(&mut self.views),
                ready: std::mem::take(&mut self.ready),
                destroy_at: self.presents + RETIRE_AFTER_PRESENTS,
            });
        }
        self.raw = raw;
        self.generation += 1;
        self.ctx
            .name(raw, &format!("swapchain #{}", self.generation));
        // SAFETY: the swapchain is live.
        self.images =
            unsafe { self.fns.get_swapchain_images(raw) }.vk("vkGetSwapchainImagesKHR")?;
        for i in 0..self.images.len() {
            let image = self.images[i];
            self.ctx.name(image, &format!("swapchain image {i}"));
            let ready = self.semaphore(&format!("swapchain image {i} ready to present"))?;
            self.ready.push(ready);
            let view = self.view(image, format.format, &format!("swapchain image {i} view"))?;
            self.views.push(view);
        }
        self.format = format.format;
        self.extent = extent;
        self.present_mode = present_mode;
        self.can_copy = can_copy;
        self.transfer_dst = transfer_dst;
        self.usage = usage;
        log::info!(
            "swapchain #{}: {}x{} {:?} {:?}, {} images",
            self.generation,
            extent.width,
            extent.height,
            format.format,
            present_mode,
            self.images.len()
        );
        Ok(true)
    }

    /// Waits until the next frame's slot is free (its acquire semaphore then is unsignalled and
    /// unwaited) and acquires an image for it. `Ok(None)`: the swapchain is out of date and must
    /// be recreated. The flag is true when the image is usable but suboptimal.
    pub fn acquire(&self, frames: &Frames) -> GpuResult<Option<(AcquiredImage, bool)>> {
        frames.wait_for_slot()?;
        // A finite wait: a presentation engine that never hands an image back (a lost display)
        // becomes an error instead of a hang.
        let timeout_ns = self.ctx.wait_timeout_s * 1_000_000_000;
        let semaphore = self.acquire[frames.next_slot()];
        // SAFETY: the semaphore's previous wait (two frames ago) has completed (waited above)
        // and an out-of-date acquire leaves it unsignalled.
        match unsafe {
            self.fns
                .acquire_next_image(self.raw, timeout_ns, semaphore, vk::Fence::null())
        } {
            Ok((index, suboptimal)) => {
                let i = index as usize;
                let image = AcquiredImage {
                    index,
                    image: self.images[i],
                    view: self.views[i],
                    acquired: semaphore,
                    ready: self.ready[i],
                    waited: std::cell::Cell::new(false),
                    extent: self.extent,
                    format: self.format,
                    usage: self.usage,
                };
                Ok(Some((image, suboptimal)))
            }
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(None),
            Err(vk::Result::TIMEOUT | vk::Result::NOT_READY) => Err(GpuError::Timeout {
                seconds: self.ctx.wait_timeout_s,
            }),
            Err(result) => Err(GpuError::Vk {
                call: "vkAcquireNextImageKHR",
                result,
            }),
        }
    }

    /// Presents `image` after its `ready` semaphore. Returns true when the swapchain should be
    /// recreated (out of date or suboptimal).
    pub fn present(&mut self, image: &AcquiredImage) -> GpuResult<bool> {
        let waits = [image.ready];
        let swapchains = [self.raw];
        let indices = [image.index];
        let info = vk::PresentInfoKHR::default()
            .wait_semaphores(&waits)
            .swapchains(&swapchains)
            .image_indices(&indices);
        // SAFETY: the image was acquired from this swapchain and rendering signals `ready`.
        let result = match unsafe { self.fns.queue_present(self.ctx.graphics.raw, &info) } {
            Ok(suboptimal) => Ok(suboptimal),
            Err(vk::Result::ERROR_OUT_OF_DATE_KHR) => Ok(true),
            Err(result) => Err(GpuError::Vk {
                call: "vkQueuePresentKHR",
                result,
            }),
        };
        self.presents += 1;
        self.destroy_retired(false);
        result
    }

    /// Destroys retired swapchains whose presents have drained (all of them if `all`).
    fn destroy_retired(&mut self, all: bool) {
        let presents = self.presents;
        let (done, keep): (Vec<_>, Vec<_>) = self
            .retired
            .drain(..)
            .partition(|r| all || presents >= r.destroy_at);
        self.retired = keep;
        for r in done {
            // SAFETY: the swapchain was retired by a newer one and its presents have been
            // processed (module comment); the semaphores were only used by those presents.
            self.ctx
                .count_destroyed((r.ready.len() + r.views.len()) as u64 + 1);
            unsafe {
                for v in r.views {
                    self.ctx.device.destroy_image_view(v, None);
                }
                for s in r.ready {
                    self.ctx.device.destroy_semaphore(s, None);
                }
                self.fns.destroy_swapchain(r.raw, None);
            }
        }
    }
}

impl Drop for Swapchain {
    fn drop(&mut self) {
        if let Err(e) = self.ctx.wait_idle() {
            log::error!("swapchain shutdown: {e}");
        }
        self.destroy_retired(true);
        // SAFETY: the device is idle; at shutdown there is no later point to wait for pending
        // presents (without VK_EXT_swapchain_maintenance1), so this is the best available.
        unsafe {
            for v in self.views.drain(..) {
                self.ctx.device.destroy_image_view(v, None);
                self.ctx.count_destroyed(1);
            }
            for s in self.ready.drain(..).chain(self.acquire.drain(..)) {
                self.ctx.device.destroy_semaphore(s, None);
                self.ctx.count_destroyed(1);
            }
            if self.raw != vk::SwapchainKHR::null() {
                self.fns.destroy_swapchain(self.raw, None);
                self.ctx.count_destroyed(1);
            }
        }
    }
}

/// The surface's current extent, or `fallback` (the window size) clamped to the allowed range
/// when the surface lets the application choose (`currentExtent` 0xFFFFFFFF). A zero extent
/// means the window is minimised.
fn surface_extent(caps: &vk::SurfaceCapabilitiesKHR, fallback: vk::Extent2D) -> vk::Extent2D {
    if caps.current_extent.width != u32::MAX {
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
    }
}

/// The usage to request of swapchain images from the surface's `supportedUsageFlags`, and
/// whether it includes TRANSFER_SRC (screenshots) and TRANSFER_DST (the output's copy).
fn swapchain_usage(supported: vk::ImageUsageFlags) -> (vk::ImageUsageFlags, bool, bool) {
    let optional = vk::ImageUsageFlags::TRANSFER_SRC | vk::ImageUsageFlags::TRANSFER_DST;
    let usage = vk::ImageUsageFlags::COLOR_ATTACHMENT | (supported & optional);
    (
        usage,
        usage.contains(vk::ImageUsageFlags::TRANSFER_SRC),
        usage.contains(vk::ImageUsageFlags::TRANSFER_DST),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn swapchain_usage_asks_only_for_what_the_surface_offers() {
        use vk::ImageUsageFlags as U;
        let all = U::COLOR_ATTACHMENT | U::TRANSFER_SRC | U::TRANSFER_DST | U::STORAGE;
        assert_eq!(
            swapchain_usage(all),
            (
                U::COLOR_ATTACHMENT | U::TRANSFER_SRC | U::TRANSFER_DST,
                true,
                true
            )
        );
        // The guaranteed minimum: drawn output, no screenshots.
        assert_eq!(
            swapchain_usage(U::COLOR_ATTACHMENT),
            (U::COLOR_ATTACHMENT, false, false)
        );
        assert_eq!(
            swapchain_usage(U::COLOR_ATTACHMENT | U::TRANSFER_SRC),
            (U::COLOR_ATTACHMENT | U::TRANSFER_SRC, true, false)
        );
    }

    fn offer(formats: &[vk::Format]) -> Vec<vk::SurfaceFormatKHR> {
        formats
            .iter()
            .map(|&format| vk::SurfaceFormatKHR {
                format,
                color_space: vk::ColorSpaceKHR::SRGB_NONLINEAR,
            })
            .collect()
    }

    #[test]
    fn surface_format_prefers_srgb_then_unorm() {
        let pick = |f: &[vk::Format]| choose_surface_format(&offer(f)).map(|s| s.format);
        // lavapipe / most desktop drivers.
        let lavapipe = [vk::Format::B8G8R8A8_SRGB, vk::Format::B8G8R8A8_UNORM];
        assert_eq!(pick(&lavapipe), Some(vk::Format::B8G8R8A8_SRGB));
        // UNORM listed first: still the sRGB one.
        let unorm_first = [vk::Format::B8G8R8A8_UNORM, vk::Format::R8G8B8A8_SRGB];
        assert_eq!(pick(&unorm_first), Some(vk::Format::R8G8B8A8_SRGB));
        // No 8-bit sRGB format (some compositors): UNORM, encoded by the shaders.
        let no_srgb = [
            vk::Format::A2B10G10R10_UNORM_PACK32,
            vk::Format::R8G8B8A8_UNORM,
        ];
        assert_eq!(pick(&no_srgb), Some(vk::Format::R8G8B8A8_UNORM));
        assert_eq!(pick(&[vk::Format::R16G16B16A16_SFLOAT]), None);
        // The right format in another colour space does not count.
        let hdr = [vk::SurfaceFormatKHR {
            format: vk::Format::B8G8R8A8_SRGB,
            color_space: vk::ColorSpaceKHR::EXTENDED_SRGB_LINEAR_EXT,
        }];
        assert_eq!(choose_surface_format(&hdr), None);
    }
}
