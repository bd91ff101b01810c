//! `Buffer`: a `VkBuffer` with its memory, destroyed through the deletion queue.

use std::ptr::NonNull;
use std::rc::Rc;
use std::sync::Arc;

use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;

use super::context::Context;
use super::error::{GpuError, GpuResult, VkResultExt};
use super::garbage::Garbage;
use super::queues::QueueUsers;
use super::track::{Handle, State, StateCell, Tracked};

/// A buffer and its memory. The host reaches a mapped buffer's bytes through `&mut self`
/// (`write`, `mapped_mut`) or after the GPU is done (`Frames::read_back`); descriptor sets that
/// bind it keep its handle alive (a shared core) but never touch its memory.
pub struct Buffer {
    core: Rc<BufferCore>,
    /// The mapping of a host-visible buffer (`size` bytes), valid while `core` lives.
    mapped: Option<NonNull<u8>>,
}

/// What a [`Buffer`] shares with the descriptor sets that bind it.
pub(super) struct BufferCore {
    ctx: Arc<Context>,
    pub(super) raw: vk::Buffer,
    /// Always `Some` until `Drop` moves it into the deletion queue.
    allocation: Option<Allocation>,
    pub(super) size: vk::DeviceSize,
    usage: vk::BufferUsageFlags,
    name: String,
    /// Created for both queues (`Buffer::shared`): CONCURRENT where the families differ.
    both_queues: bool,
    /// What the last recorded use left (`track`).
    pub(super) state: StateCell,
}

impl Buffer {
    /// Creates a named buffer used on one queue family: EXCLUSIVE (buffers never cross
    /// families; see `oneshot::upload_on`). `location` picks the memory: `GpuOnly`,
    /// `CpuToGpu` (mapped, for uploads and uniforms) or `GpuToCpu` (mapped, for readback).
    pub fn new(
        ctx: &Arc<Context>,
        name: &str,
        size: vk::DeviceSize,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
    ) -> GpuResult<Buffer> {
        Buffer::create(ctx, name, size, usage, location, QueueUsers::Graphics)
    }

    /// A device-local buffer both queues use: written on the compute queue, read by graphics
    /// through the compute timeline's wait (the spray's particles and indirect arguments).
    /// CONCURRENT across the two families where they differ, like the simulation images, so no
    /// ownership transfer is needed; [`Buffer::share`] hands its handle to the renderer.
    pub fn shared(
        ctx: &Arc<Context>,
        name: &str,
        size: vk::DeviceSize,
        usage: vk::BufferUsageFlags,
    ) -> GpuResult<Buffer> {
        let location = MemoryLocation::GpuOnly;
        let buffer = Buffer::create(ctx, name, size, usage, location, QueueUsers::Both)?;
        // Device memory may be host-visible (a CPU driver maps it): the host never touches
        // these, so the handles can be shared.
        Ok(Buffer {
            mapped: None,
            ..buffer
        })
    }

    fn create(
        ctx: &Arc<Context>,
        name: &str,
        size: vk::DeviceSize,
        usage: vk::BufferUsageFlags,
        location: MemoryLocation,
        users: QueueUsers,
    ) -> GpuResult<Buffer> {
        if size == 0 {
            return Err(GpuError::Unsupported(format!("buffer {name}: 0 bytes")));
        }
        let sharing = ctx.sharing(users);
        let info = vk::BufferCreateInfo::default()
            .size(size)
            .usage(usage)
            .sharing_mode(sharing.mode)
            .queue_family_indices(&sharing.families);
        // SAFETY: valid create info on a live device.
        let raw = unsafe { ctx.device.create_buffer(&info, None) }.vk("vkCreateBuffer")?;
        ctx.count_created(1);
        // SAFETY: `raw` is a live buffer of this device.
        let requirements = unsafe { ctx.device.get_buffer_memory_requirements(raw) };
        let allocation = ctx.allocator().allocate(&AllocationCreateDesc {
            name,
            requirements,
            location,
            linear: true,
            allocation_scheme: AllocationScheme::GpuAllocatorManaged,
        });
        let allocation = match allocation {
            Ok(a) => a,
            Err(source) => {
                // SAFETY: the buffer was never used or bound.
                unsafe { ctx.device.destroy_buffer(raw, None) };
                ctx.count_destroyed(1);
                return Err(GpuError::Alloc {
                    name: name.to_string(),
                    source,
                });
            }
        };
        // SAFETY: the allocation satisfies the buffer's requirements and is bound once.
        let bound = unsafe {
            ctx.device
                .bind_buffer_memory(raw, allocation.memory(), allocation.offset())
        };
        let mapped = allocation.mapped_ptr().map(|p| p.cast::<u8>());
        let core = BufferCore {
            ctx: ctx.clone(),
            raw,
            allocation: Some(allocation),
            size,
            usage,
            name: name.to_string(),
            both_queues: users == QueueUsers::Both,
            state: StateCell::new(State::NEW),
        };
        bound.map_err(|result| GpuError::Bind {
            name: name.to_string(),
            call: "vkBindBufferMemory",
            result,
        })?;
        ctx.name(raw, name);
        Ok(Buffer {
            core: Rc::new(core),
            mapped,
        })
    }

    /// Another handle to this device-local buffer (the renderer's sets bind the simulation's
    /// shared buffers). Panics on a mapped buffer: the host writes those through `&mut`, so
    /// they have one owner.
    pub fn share(&self) -> Buffer {
        assert!(
            self.mapped.is_none(),
            "buffer {}: a mapped buffer has one owner",
            self.core.name
        );
        Buffer {
            core: self.core.clone(),
            mapped: None,
        }
    }

    /// Whether `self` and `other` are the same buffer.
    pub fn is(&self, other: &Buffer) -> bool {
        Rc::ptr_eq(&self.core, &other.core)
    }

    /// Size in bytes.
    pub fn size(&self) -> vk::DeviceSize {
        self.core.size
    }

    pub(super) fn raw(&self) -> vk::Buffer {
        self.core.raw
    }

    /// Panics unless the buffer was created with `usage` (for `what`): the GPU layer's safe
    /// functions refuse what would be invalid usage.
    pub(super) fn expect_usage(&self, usage: vk::BufferUsageFlags, what: &str) {
        self.core.expect_usage(usage, what);
    }

    /// Panics unless the buffer was made for both queues (`Buffer::shared`): a read on the
    /// graphics queue of what the compute queue wrote needs CONCURRENT sharing where the
    /// families differ (vkocean transfers no buffer's ownership).
    pub(super) fn expect_both_queues(&self, what: &str) {
        self.core.expect_both_queues(what);
    }

    /// The handle descriptor sets keep alive.
    pub(super) fn core(&self) -> &Rc<BufferCore> {
        &self.core
    }

    /// The mapped bytes of a host-visible buffer (`None` for `GpuOnly`).
    /// Outside this layer use `Frames::read_back`, which first waits for the GPU.
    pub(super) fn mapped(&self) -> Option<&[u8]> {
        // SAFETY: the mapping covers `size` bytes and lives as long as `core`, which `self`
        // holds; the host writes only through `&mut self`, so no `&mut` alias exists now.
        self.mapped
            .map(|p| unsafe { std::slice::from_raw_parts(p.as_ptr(), self.core.size as usize) })
    }

    /// The mapped bytes of a host-visible buffer, to write. Panics if the buffer is not mapped
    /// (a programming error).
    pub fn mapped_mut(&mut self) -> &mut [u8] {
        let p = self.mapped.expect("buffer is host-visible");
        // SAFETY: as in `mapped`; `&mut self` makes this the only view of the bytes (the
        // descriptor sets sharing `core` never read the mapping).
        unsafe { std::slice::from_raw_parts_mut(p.as_ptr(), self.core.size as usize) }
    }

    /// Copies `bytes` to the start of a host-visible buffer. Panics if the buffer is not mapped
    /// or too small (both are programming errors).
    pub fn write(&mut self, bytes: &[u8]) {
        let slice = self.mapped_mut();
        assert!(
            bytes.len() <= slice.len(),
            "write of {} bytes into a {}-byte buffer",
            bytes.len(),
            slice.len()
        );
        slice[..bytes.len()].copy_from_slice(bytes);
    }
}

impl BufferCore {
    fn expect_usage(&self, usage: vk::BufferUsageFlags, what: &str) {
        assert!(
            self.usage.contains(usage),
            "buffer {} lacks {usage:?} usage, which {what} needs",
            self.name
        );
    }

    /// See [`Buffer::expect_both_queues`].
    pub(super) fn expect_both_queues(&self, what: &str) {
        assert!(
            self.both_queues,
            "buffer {}: {what} reads it on the graphics queue after the compute queue wrote it, \
             so it must be made with Buffer::shared",
            self.name
        );
    }
}

impl Drop for BufferCore {
    fn drop(&mut self) {
        if let Some(allocation) = self.allocation.take() {
            self.ctx.defer(Garbage::Buffer(self.raw, allocation));
        }
    }
}

/// A typed view of a buffer for texel-buffer descriptors (`samplerBuffer` / `imageBuffer`); a
/// shared handle that keeps its buffer's handle alive.
#[derive(Clone)]
pub struct BufferView(Rc<BufferViewCore>);

struct BufferViewCore {
    ctx: Arc<Context>,
    raw: vk::BufferView,
    buffer: Rc<BufferCore>,
}

impl BufferView {
    /// Views the whole of `buffer` as texels of `format`. The buffer must have been created with
    /// the matching UNIFORM_/STORAGE_TEXEL_BUFFER usage and fit in maxTexelBufferElements.
    pub fn new(
        ctx: &Arc<Context>,
        name: &str,
        buffer: &Buffer,
        format: vk::Format,
    ) -> GpuResult<BufferView> {
        use vk::BufferUsageFlags as U;
        use vk::FormatFeatureFlags as F;
        // Every texel-buffer use the buffer has must be a feature of the format, and the view
        // within maxTexelBufferElements: otherwise one line, not invalid usage.
        let usage = buffer.core.usage;
        let features = ctx.buffer_format_features(format);
        let needs = [
            (U::UNIFORM_TEXEL_BUFFER, F::UNIFORM_TEXEL_BUFFER),
            (U::STORAGE_TEXEL_BUFFER, F::STORAGE_TEXEL_BUFFER),
        ];
        let texel = U::UNIFORM_TEXEL_BUFFER | U::STORAGE_TEXEL_BUFFER;
        let missing = needs
            .iter()
            .any(|(u, f)| usage.contains(*u) && !features.contains(*f));
        let texel_bytes: u64 = match format {
            vk::Format::R32G32B32A32_SFLOAT => 16,
            vk::Format::R32G32_SFLOAT => 8,
            vk::Format::R32_SFLOAT | vk::Format::R8G8B8A8_UNORM => 4,
            _ => 0,
        };
        let elements = buffer
            .core
            .size
            .checked_div(texel_bytes)
            .unwrap_or(u64::MAX);
        let limit = ctx.info.limits.max_texel_buffer_elements as u64;
        if !usage.intersects(texel) || missing || elements > limit {
            return Err(GpuError::Unsupported(format!(
                "buffer view {name} of {} ({} bytes) as {format:?}: needs a texel-buffer usage the format supports and at most {limit} texels",
                buffer.core.name, buffer.core.size
            )));
        }
        let info = vk::BufferViewCreateInfo::default()
            .buffer(buffer.raw())
            .format(format)
            .offset(0)
            .range(vk::WHOLE_SIZE);
        // SAFETY: `buffer` is live, has a texel-buffer usage the format supports and fits in
        // maxTexelBufferElements (all checked above).
        let raw = unsafe { ctx.device.create_buffer_view(&info, None) }.vk("vkCreateBufferView")?;
        ctx.count_created(1);
        ctx.name(raw, name);
        Ok(BufferView(Rc::new(BufferViewCore {
            ctx: ctx.clone(),
            raw,
            buffer: buffer.core.clone(),
        })))
    }

    pub(super) fn raw(&self) -> vk::BufferView {
        self.0.raw
    }

    /// Panics unless the viewed buffer has `usage` (for `what`).
    pub(super) fn expect_usage(&self, usage: vk::BufferUsageFlags, what: &str) {
        self.0.buffer.expect_usage(usage, what);
    }

    /// The viewed buffer (tracked).
    pub(super) fn buffer(&self) -> &Rc<BufferCore> {
        &self.0.buffer
    }
}

impl Drop for BufferViewCore {
    fn drop(&mut self) {
        self.ctx.defer(Garbage::BufferView(self.raw));
    }
}

impl super::track::sealed::Sealed for Buffer {}
impl super::track::sealed::Sealed for BufferCore {}

impl Tracked for Buffer {
    fn handle(&self) -> Handle {
        Handle::buffer(self.core.raw)
    }
    fn name(&self) -> &str {
        &self.core.name
    }
    fn state(&self) -> &StateCell {
        &self.core.state
    }
}

impl Tracked for BufferCore {
    fn handle(&self) -> Handle {
        Handle::buffer(self.raw)
    }
    fn name(&self) -> &str {
        &self.name
    }
    fn state(&self) -> &StateCell {
        &self.state
    }
}
