//! `Buffer`: a `VkBuffer` with its memory, destroyed through the deletion queue.

use std::cell::Cell;
use std::sync::Arc;

use ash::vk;
use gpu_allocator::vulkan::{Allocation, AllocationCreateDesc, AllocationScheme};
use gpu_allocator::MemoryLocation;

use super::context::Context;
use super::error::{GpuError, GpuResult, VkResultExt};
use super::garbage::Garbage;
use super::track::{Handle, State, Tracked};

/// A buffer and its memory.
pub struct Buffer {
    ctx: Arc<Context>,
    pub raw: vk::Buffer,
    /// Always `Some` until `Drop` moves it into the deletion queue.
    allocation: Option<Allocation>,
    pub size: vk::DeviceSize,
    /// What the last recorded use left (`track`).
    pub(crate) state: Cell<State>,
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
        let info = vk::BufferCreateInfo::default()
            .size(size)
            .usage(usage)
            .sharing_mode(vk::SharingMode::EXCLUSIVE);
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
        let buffer = Buffer {
            ctx: ctx.clone(),
            raw,
            allocation: Some(allocation),
            size,
            state: Cell::new(State::NEW),
        };
        bound.map_err(|result| GpuError::Bind {
            name: name.to_string(),
            call: "vkBindBufferMemory",
            result,
        })?;
        ctx.name(raw, name);
        Ok(buffer)
    }

    /// The mapped bytes of a host-visible buffer (`None` for `GpuOnly`).
    /// Outside this layer use `Frames::read_back`, which first waits for the GPU.
    pub(crate) fn mapped(&self) -> Option<&[u8]> {
        self.allocation
            .as_ref()
            .and_then(|a| a.mapped_slice())
            .map(|s| &s[..self.size as usize])
    }

    /// The mapped bytes of a host-visible buffer, to write. Panics if the buffer is not mapped
    /// (a programming error).
    pub fn mapped_mut(&mut self) -> &mut [u8] {
        let size = self.size as usize;
        &mut self
            .allocation
            .as_mut()
            .and_then(|a| a.mapped_slice_mut())
            .expect("buffer is host-visible")[..size]
    }

    /// Copies `bytes` to the start of a host-visible buffer. Panics if the buffer is not mapped
    /// or too small (both are programming errors).
    pub fn write(&mut self, bytes: &[u8]) {
        let size = self.size as usize;
        let slice = self
            .allocation
            .as_mut()
            .and_then(|a| a.mapped_slice_mut())
            .expect("buffer is host-visible");
        assert!(
            bytes.len() <= size,
            "write of {} bytes into a {size}-byte buffer",
            bytes.len()
        );
        slice[..bytes.len()].copy_from_slice(bytes);
    }
}

impl Drop for Buffer {
    fn drop(&mut self) {
        if let Some(allocation) = self.allocation.take() {
            self.ctx.defer(Garbage::Buffer(self.raw, allocation));
        }
    }
}

/// A typed view of a buffer for texel-buffer descriptors (`samplerBuffer` / `imageBuffer`).
pub struct BufferView {
    ctx: Arc<Context>,
    pub raw: vk::BufferView,
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
        let info = vk::BufferViewCreateInfo::default()
            .buffer(buffer.raw)
            .format(format)
            .offset(0)
            .range(vk::WHOLE_SIZE);
        // SAFETY: `buffer` is live and the create info is valid for it (caller's usage contract).
        let raw = unsafe { ctx.device.create_buffer_view(&info, None) }.vk("vkCreateBufferView")?;
        ctx.count_created(1);
        ctx.name(raw, name);
        Ok(BufferView {
            ctx: ctx.clone(),
            raw,
        })
    }
}

impl Drop for BufferView {
    fn drop(&mut self) {
        self.ctx.defer(Garbage::BufferView(self.raw));
    }
}

impl Tracked for Buffer {
    fn handle(&self) -> Handle {
        Handle::Buffer(self.raw)
    }
    fn state(&self) -> &Cell<State> {
        &self.state
    }
}
