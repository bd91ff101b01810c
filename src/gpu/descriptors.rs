//! Descriptor set layouts, a descriptor pool that frees its sets with itself, and the writes a
//! pass needs (uniform buffer, sampled image, storage image).

use std::sync::Arc;

use ash::vk;

use super::context::Context;
use super::error::{GpuResult, VkResultExt};
use super::garbage::Garbage;

/// A descriptor set layout.
pub struct DescriptorSetLayout {
    ctx: Arc<Context>,
    pub raw: vk::DescriptorSetLayout,
}

impl DescriptorSetLayout {
    /// One binding per entry: (binding, type, stages).
    pub fn new(
        ctx: &Arc<Context>,
        name: &str,
        bindings: &[(u32, vk::DescriptorType, vk::ShaderStageFlags)],
    ) -> GpuResult<Self> {
        let bindings: Vec<_> = bindings
            .iter()
            .map(|&(binding, ty, stages)| {
                vk::DescriptorSetLayoutBinding::default()
                    .binding(binding)
                    .descriptor_type(ty)
                    .descriptor_count(1)
                    .stage_flags(stages)
            })
            .collect();
        let info = vk::DescriptorSetLayoutCreateInfo::default().bindings(&bindings);
        // SAFETY: valid create info on a live device.
        let raw = unsafe { ctx.device.create_descriptor_set_layout(&info, None) }
            .vk("vkCreateDescriptorSetLayout")?;
        ctx.count_created(1);
        ctx.name(raw, name);
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }
}

impl Drop for DescriptorSetLayout {
    fn drop(&mut self) {
        self.ctx.defer(Garbage::DescriptorSetLayout(self.raw));
    }
}

/// A descriptor pool; its sets live as long as it does.
pub struct DescriptorPool {
    ctx: Arc<Context>,
    pub raw: vk::DescriptorPool,
}

impl DescriptorPool {
    /// A pool for `max_sets` sets holding at most the given descriptor counts.
    pub fn new(
        ctx: &Arc<Context>,
        name: &str,
        max_sets: u32,
        sizes: &[(vk::DescriptorType, u32)],
    ) -> GpuResult<Self> {
        let sizes: Vec<_> = sizes
            .iter()
            .map(|&(ty, n)| vk::DescriptorPoolSize {
                ty,
                descriptor_count: n,
            })
            .collect();
        let info = vk::DescriptorPoolCreateInfo::default()
            .max_sets(max_sets)
            .pool_sizes(&sizes);
        // SAFETY: valid create info on a live device.
        let raw = unsafe { ctx.device.create_descriptor_pool(&info, None) }
            .vk("vkCreateDescriptorPool")?;
        ctx.count_created(1);
        ctx.name(raw, name);
        Ok(Self {
            ctx: ctx.clone(),
            raw,
        })
    }

    /// Allocates one named set of `layout`.
    pub fn allocate(
        &self,
        layout: &DescriptorSetLayout,
        name: &str,
    ) -> GpuResult<vk::DescriptorSet> {
        let layouts = [layout.raw];
        let info = vk::DescriptorSetAllocateInfo::default()
            .descriptor_pool(self.raw)
            .set_layouts(&layouts);
        // SAFETY: pool and layout are live objects of this device.
        let set = unsafe { self.ctx.device.allocate_descriptor_sets(&info) }
            .vk("vkAllocateDescriptorSets")?[0];
        self.ctx.name(set, name);
        Ok(set)
    }
}

impl Drop for DescriptorPool {
    fn drop(&mut self) {
        self.ctx.defer(Garbage::DescriptorPool(self.raw));
    }
}

/// One descriptor write.
pub enum Write {
    UniformBuffer {
        binding: u32,
        buffer: vk::Buffer,
    },
    StorageBuffer {
        binding: u32,
        buffer: vk::Buffer,
    },
    SampledImage {
        binding: u32,
        view: vk::ImageView,
        sampler: vk::Sampler,
        /// Layout the image is in when sampled (SHADER_READ_ONLY_OPTIMAL or GENERAL).
        layout: vk::ImageLayout,
    },
    StorageImage {
        binding: u32,
        view: vk::ImageView,
    },
    /// `samplerBuffer` / `textureBuffer`.
    UniformTexelBuffer {
        binding: u32,
        view: vk::BufferView,
    },
    /// `imageBuffer`.
    StorageTexelBuffer {
        binding: u32,
        view: vk::BufferView,
    },
}

/// Writes descriptors into `set`. The caller guarantees the set is not in use by pending GPU work
/// (sets are per frame slot, or rewritten only after a device wait on resize).
pub fn update(ctx: &Context, set: vk::DescriptorSet, writes: &[Write]) {
    let buffer_infos: Vec<[vk::DescriptorBufferInfo; 1]> = writes
        .iter()
        .map(|w| match w {
            Write::UniformBuffer { buffer, .. } | Write::StorageBuffer { buffer, .. } => {
                [vk::DescriptorBufferInfo {
                    buffer: *buffer,
                    offset: 0,
                    range: vk::WHOLE_SIZE,
                }]
            }
            _ => [vk::DescriptorBufferInfo::default()],
        })
        .collect();
    let image_infos: Vec<[vk::DescriptorImageInfo; 1]> = writes
        .iter()
        .map(|w| match w {
            Write::SampledImage {
                view,
                sampler,
                layout,
                ..
            } => [vk::DescriptorImageInfo {
                sampler: *sampler,
                image_view: *view,
                image_layout: *layout,
            }],
            Write::StorageImage { view, .. } => [vk::DescriptorImageInfo {
                sampler: vk::Sampler::null(),
                image_view: *view,
                image_layout: vk::ImageLayout::GENERAL,
            }],
            _ => [vk::DescriptorImageInfo::default()],
        })
        .collect();
    let texel_views: Vec<[vk::BufferView; 1]> = writes
        .iter()
        .map(|w| match w {
            Write::UniformTexelBuffer { view, .. } | Write::StorageTexelBuffer { view, .. } => {
                [*view]
            }
            _ => [vk::BufferView::null()],
        })
        .collect();
    let vk_writes: Vec<_> = writes
        .iter()
        .enumerate()
        .map(|(i, w)| {
            let base = vk::WriteDescriptorSet::default().dst_set(set);
            match w {
                Write::UniformBuffer { binding, .. } => base
                    .dst_binding(*binding)
                    .descriptor_type(vk::DescriptorType::UNIFORM_BUFFER)
                    .buffer_info(&buffer_infos[i]),
                Write::StorageBuffer { binding, .. } => base
                    .dst_binding(*binding)
                    .descriptor_type(vk::DescriptorType::STORAGE_BUFFER)
                    .buffer_info(&buffer_infos[i]),
                Write::SampledImage { binding, .. } => base
                    .dst_binding(*binding)
                    .descriptor_type(vk::DescriptorType::COMBINED_IMAGE_SAMPLER)
                    .image_info(&image_infos[i]),
                Write::StorageImage { binding, .. } => base
                    .dst_binding(*binding)
                    .descriptor_type(vk::DescriptorType::STORAGE_IMAGE)
                    .image_info(&image_infos[i]),
                Write::UniformTexelBuffer { binding, .. } => base
                    .dst_binding(*binding)
                    .descriptor_type(vk::DescriptorType::UNIFORM_TEXEL_BUFFER)
                    .texel_buffer_view(&texel_views[i]),
                Write::StorageTexelBuffer { binding, .. } => base
                    .dst_binding(*binding)
                    .descriptor_type(vk::DescriptorType::STORAGE_TEXEL_BUFFER)
                    .texel_buffer_view(&texel_views[i]),
            }
        })
        .collect();
    // SAFETY: all handles are live; the set is not in use by the GPU (caller's contract).
    unsafe { ctx.device.update_descriptor_sets(&vk_writes, &[]) };
}
