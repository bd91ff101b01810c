//! The overlay's painter: egui's triangles drawn by egui-ash-renderer (dynamic rendering, our
//! allocator, one mesh buffer per frame in flight) into a rendering scope the caller opened.
//!
//! Two things are done here rather than by the crate, for correctness by the spec:
//! - **Texture patches are uploaded whole.** The crate updates a patch of a live texture after a
//!   transition from `UNDEFINED`, which lets a driver discard the rest of the texture (egui
//!   patches its font atlas when new glyphs appear). The painter keeps a CPU copy of each
//!   texture, applies the patch there and uploads the whole image as a new texture.
//! - **Freed textures are retired through the deletion queue.** egui frees a texture after the
//!   frame that last draws with it; the crate would destroy it at once. The painter keeps the
//!   freed ids until it records the next frame's overlay (the frame that may still draw them,
//!   egui's `TexturesDelta::free` contract), then hands them to `Context::defer`
//!   (`Garbage::Release`); once the frame timeline passes that frame they come back and the
//!   crate destroys them. A replaced texture (new glyphs, a new DPI) needs no wait of ours: the
//!   crate's upload ends in `vkQueueWaitIdle` on the graphics queue, so every frame drawn with
//!   the old texture has finished before the crate destroys it. Both are rare: the first
//!   frame's font atlas, new glyphs, a new DPI.

use std::collections::HashMap;
use std::mem::ManuallyDrop;
use std::sync::{Arc, Mutex};

use ash::vk;
use egui::epaint::{ClippedPrimitive, ColorImage, ImageData, ImageDelta, TextureId};
use egui_ash_renderer::allocator::GpuAllocator;
use egui_ash_renderer::{DynamicRendering, Options, RenderMode, Renderer};

use super::error::VkResultExt;
use super::garbage::Garbage;
use super::{Context, GpuError, GpuResult, Recorder, FRAMES_IN_FLIGHT};

/// egui-ash-renderer's errors as ours.
fn egui_error(e: egui_ash_renderer::RendererError) -> GpuError {
    GpuError::Unsupported(format!("the overlay's egui renderer: {e}"))
}

pub struct EguiPainter {
    ctx: Arc<Context>,
    /// Dropped by hand in `Drop`, after the device is idle (it destroys its objects at once).
    renderer: ManuallyDrop<Renderer<GpuAllocator>>,
    /// Command buffers of the renderer's texture uploads (graphics family).
    pool: vk::CommandPool,
    /// The colour format it draws into.
    pub format: vk::Format,
    /// CPU copies of egui's textures (patches are applied here, then uploaded whole).
    textures: HashMap<TextureId, ColorImage>,
    /// Freed by egui, possibly drawn by the next frame: deferred when that frame is recorded.
    freed: Vec<TextureId>,
    /// Retired through the deletion queue and now unused by the GPU: destroyed at the next
    /// `update_textures` or `draw`.
    released: Arc<Mutex<Vec<TextureId>>>,
}

impl EguiPainter {
    /// A painter for colour attachments of `format` (8-bit; sRGB formats encode its output).
    pub fn new(ctx: &Arc<Context>, format: vk::Format) -> GpuResult<EguiPainter> {
        let srgb = matches!(
            format,
            vk::Format::R8G8B8A8_SRGB | vk::Format::B8G8R8A8_SRGB
        );
        let renderer = Renderer::with_gpu_allocator(
            ctx.shared_allocator(),
            ctx.device.clone(),
            RenderMode::DynamicRendering(DynamicRendering {
                color_attachment_format: format,
                depth_attachment_format: None,
                stencil_attachment_format: None,
            }),
            Options {
                in_flight_frames: FRAMES_IN_FLIGHT,
                enable_depth_test: false,
                enable_depth_write: false,
                srgb_framebuffer: srgb,
            },
        )
        .map_err(egui_error)?;
        let info = vk::CommandPoolCreateInfo::default()
            .queue_family_index(ctx.graphics.family)
            .flags(vk::CommandPoolCreateFlags::TRANSIENT);
        // SAFETY: valid create info on a live device.
        let pool =
            unsafe { ctx.device.create_command_pool(&info, None) }.vk("vkCreateCommandPool")?;
        ctx.count_created(1);
        ctx.name(pool, "overlay texture uploads");
        Ok(EguiPainter {
            ctx: ctx.clone(),
            renderer: ManuallyDrop::new(renderer),
            pool,
            format,
            textures: HashMap::new(),
            freed: Vec::new(),
            released: Arc::default(),
        })
    }

    /// Applies egui's texture changes. Call between frames, before the frame that draws this
    /// delta's primitives; frees are retired through the deletion queue (module comment).
    pub fn update_textures(
        &mut self,
        set: &[(TextureId, ImageDelta)],
        free: &[TextureId],
    ) -> GpuResult<()> {
        self.destroy_released()?;
        for (id, delta) in set {
            let ImageData::Color(patch) = &delta.image;
            let whole = match (delta.pos, self.textures.get_mut(id)) {
                (None, _) => {
                    self.textures.insert(*id, (**patch).clone());
                    &self.textures[id]
                }
                (Some([x0, y0]), Some(image)) => {
                    let w = image.size[0];
                    for (row, line) in patch.pixels.chunks(patch.size[0].max(1)).enumerate() {
                        let start = (y0 + row) * w + x0;
                        image.pixels[start..start + line.len()].copy_from_slice(line);
                    }
                    &*image
                }
                (Some(_), None) => {
                    return Err(GpuError::Unsupported(format!(
                        "the overlay: egui patched texture {id:?}, which it never set"
                    )))
                }
            };
            let full = ImageDelta::full(whole.clone(), delta.options);
            self.renderer
                .set_texture(self.ctx.graphics.raw, self.pool, *id, &full)
                .map_err(egui_error)?;
        }
        for id in free {
            self.textures.remove(id);
            self.freed.push(*id);
        }
        Ok(())
    }

    /// Destroys the textures the deletion queue handed back (the GPU is done with them).
    fn destroy_released(&mut self) -> GpuResult<()> {
        let released =
            std::mem::take(&mut *self.released.lock().unwrap_or_else(|p| p.into_inner()));
        for id in released {
            self.renderer.free_texture(id).map_err(egui_error)?;
        }
        Ok(())
    }

    /// Draws `primitives` inside the rendering scope `rec` has open, over `extent`.
    pub fn draw(
        &mut self,
        rec: &Recorder,
        extent: vk::Extent2D,
        pixels_per_point: f32,
        primitives: &[ClippedPrimitive],
    ) -> GpuResult<()> {
        // egui's renderer draws into the open scope (dynamic rendering, one colour attachment).
        assert!(
            rec.scope.borrow().is_some(),
            "the overlay draws inside a rendering scope"
        );
        self.destroy_released()?;
        self.renderer
            .cmd_draw(rec.raw(), extent, pixels_per_point, primitives)
            .map_err(egui_error)?;
        // Freed before this frame: it is the last that may draw them; tagged with its value.
        for id in self.freed.drain(..) {
            let released = self.released.clone();
            self.ctx.defer(Garbage::Release(Box::new(move || {
                released.lock().unwrap_or_else(|p| p.into_inner()).push(id);
            })));
        }
        Ok(())
    }
}

impl Drop for EguiPainter {
    fn drop(&mut self) {
        // The renderer destroys its pipeline, buffers and textures at once.
        if let Err(e) = self.ctx.wait_idle() {
            log::error!("overlay shutdown: {e}");
        }
        // SAFETY: the device is idle, so no submission uses the renderer's objects or the pool;
        // the renderer is dropped exactly once, here.
        unsafe {
            ManuallyDrop::drop(&mut self.renderer);
            self.ctx.device.destroy_command_pool(self.pool, None);
        }
        self.ctx.count_destroyed(1);
    }
}
