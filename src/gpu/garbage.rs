//! The deferred-deletion queue's items. An owner's `Drop` turns its handles into a [`Garbage`]
//! and hands it to `Context::defer`; the context destroys it after the GPU finished the frames
//! that may still use it (see `Context::collect_garbage`). This file knows the device and the
//! allocator only, not the context.

use ash::vk;
use gpu_allocator::vulkan::{Allocation, Allocator};

/// A Vulkan object waiting for the GPU to finish with it.
pub(crate) enum Garbage {
    /// An object this layer does not own (egui-ash-renderer's textures): `release` runs once
    /// the GPU finished the frames that may use it and hands it back to its owner to destroy.
    Release(Box<dyn FnOnce() + Send>),
    Buffer(vk::Buffer, Allocation),
    Image {
        image: vk::Image,
        views: Vec<vk::ImageView>,
        allocation: Allocation,
    },
    Sampler(vk::Sampler),
    BufferView(vk::BufferView),
    Pipeline(vk::Pipeline),
    PipelineLayout(vk::PipelineLayout),
    DescriptorSetLayout(vk::DescriptorSetLayout),
    DescriptorPool(vk::DescriptorPool),
    CommandPool(vk::CommandPool),
    Semaphore(vk::Semaphore),
    QueryPool(vk::QueryPool),
}

impl Garbage {
    /// Destroys the object (and frees its memory through `allocator`); returns how many
    /// Vulkan objects that was (an image counts its views).
    pub(super) fn destroy(self, d: &ash::Device, allocator: &mut Allocator) -> u64 {
        let count = match &self {
            Garbage::Image { views, .. } => 1 + views.len() as u64,
            Garbage::Release(_) => 0,
            _ => 1,
        };
        let garbage = match self {
            Garbage::Release(release) => {
                release();
                return count;
            }
            garbage => garbage,
        };
        // SAFETY: the object was created from `d`, its owner is gone, and the frame
        // timeline says the GPU finished every submission that could reference it.
        unsafe {
            match garbage {
                Garbage::Release(_) => unreachable!("released above"),
                Garbage::Buffer(buffer, allocation) => {
                    d.destroy_buffer(buffer, None);
                    free(allocator, allocation);
                }
                Garbage::Image {
                    image,
                    views,
                    allocation,
                } => {
                    for view in views {
                        d.destroy_image_view(view, None);
                    }
                    d.destroy_image(image, None);
                    free(allocator, allocation);
                }
                Garbage::Sampler(s) => d.destroy_sampler(s, None),
                Garbage::BufferView(v) => d.destroy_buffer_view(v, None),
                Garbage::Pipeline(p) => d.destroy_pipeline(p, None),
                Garbage::PipelineLayout(l) => d.destroy_pipeline_layout(l, None),
                Garbage::DescriptorSetLayout(l) => d.destroy_descriptor_set_layout(l, None),
                Garbage::DescriptorPool(p) => d.destroy_descriptor_pool(p, None),
                Garbage::CommandPool(p) => d.destroy_command_pool(p, None),
                Garbage::Semaphore(s) => d.destroy_semaphore(s, None),
                Garbage::QueryPool(q) => d.destroy_query_pool(q, None),
            }
        }
        count
    }
}

fn free(allocator: &mut Allocator, allocation: Allocation) {
    if let Err(e) = allocator.free(allocation) {
        log::error!("freeing GPU memory: {e}");
    }
}
