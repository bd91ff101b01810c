//! Descriptor set layouts and [`BoundSet`]: a descriptor set written once, at creation, that
//! knows what it binds. Each binding names its resource and how the work that wrote it is
//! ordered before a read ([`Order`]), so a pass's barriers are derived from the shaders that
//! read the set (`pass.rs`), not written beside them. A set is never rewritten (a new one is
//! made, and the old one retired through the deletion queue), so no frame in flight can see a
//! set change, and a set keeps what it binds alive: every safe function here is sound.

use std::collections::BTreeMap;
use std::rc::Rc;
use std::sync::Arc;

use ash::vk;

use super::buffer::{Buffer, BufferCore, BufferView};
use super::context::Context;
use super::error::{GpuError, GpuResult, VkResultExt};
use super::garbage::Garbage;
use super::image::{Image, Sampler};

/// A descriptor set layout.
pub struct DescriptorSetLayout {
    ctx: Arc<Context>,
    pub(super) raw: vk::DescriptorSetLayout,
    /// (binding, type, stages), as created.
    pub(super) bindings: Vec<(u32, vk::DescriptorType, vk::ShaderStageFlags)>,
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
        let bindings = bindings
            .iter()
            .map(|b| (b.binding, b.descriptor_type, b.stage_flags))
            .collect();
        Ok(Self {
            ctx: ctx.clone(),
            raw,
            bindings,
        })
    }
}

impl Drop for DescriptorSetLayout {
    fn drop(&mut self) {
        self.ctx.defer(Garbage::DescriptorSetLayout(self.raw));
    }
}

/// How the work that last wrote a bound resource is ordered before a shader reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Order {
    /// Tracked on the queue that reads it: the reading pass records the barrier its shaders'
    /// stages need (`Recorder::rendering`, `Recorder::dispatch_with`).
    Tracked,
    /// Written by the host before the submission that reads it (uniforms): the submission
    /// makes host writes visible; no barrier.
    Host,
    /// Written on the compute queue and sampled in GENERAL; the reading submission's semaphore
    /// wait (`by`) at `stages` orders it, so every stage that reads it must be in `stages`.
    Wait {
        by: &'static str,
        stages: vk::PipelineStageFlags2,
    },
}

/// One binding of a [`BoundSet`].
#[derive(Clone, Copy)]
pub enum Bind<'a> {
    /// A uniform block the host writes before each submission (`Order::Host`).
    Uniform(&'a Buffer),
    /// A storage block.
    Storage(&'a Buffer, Order),
    /// A combined image sampler over the image's default view.
    Sampled(&'a Image, &'a Sampler, Order),
    /// A storage image (GENERAL): its default view, or its first level's with mip levels.
    StorageImage(&'a Image, Order),
    /// One mip level of a storage image (GENERAL).
    StorageLevel(&'a Image, u32, Order),
    /// `samplerBuffer` / `textureBuffer`.
    UniformTexel(&'a BufferView, Order),
    /// `imageBuffer`.
    StorageTexel(&'a BufferView, Order),
}

/// What a binding holds, kept alive with the set.
pub(super) enum Resource {
    Image(Image),
    Buffer(Rc<BufferCore>),
}

/// One written binding.
pub(super) struct Bound {
    pub order: Order,
    pub resource: Resource,
}

impl Bound {
    pub(super) fn name(&self) -> &str {
        use super::track::Tracked;
        match &self.resource {
            Resource::Image(i) => i.name(),
            Resource::Buffer(b) => b.name(),
        }
    }
}

/// A descriptor set written once from [`Bind`]s, with its own pool. It keeps every image,
/// buffer, view and sampler it binds alive; dropped, it goes through the deletion queue.
pub struct BoundSet {
    ctx: Arc<Context>,
    pool: vk::DescriptorPool,
    pub(super) raw: vk::DescriptorSet,
    pub(super) name: String,
    pub(super) bindings: BTreeMap<u32, Bound>,
    /// Its layout's bindings (a pipeline binds it only where its layout has the same).
    pub(super) layout: Vec<(u32, vk::DescriptorType, vk::ShaderStageFlags)>,
    _samplers: Vec<Sampler>,
    _views: Vec<BufferView>,
}

impl BoundSet {
    /// Allocates a set of `layout` and writes `binds` (binding, what) into it. Each bind's
    /// descriptor type must be the layout's at that binding (else an error naming both).
    // Long: check, pool, allocate, write and keep, in the binds' order; each step a few lines
    // over the same binds.
    pub fn new(
        ctx: &Arc<Context>,
        layout: &DescriptorSetLayout,
        name: &str,
        binds: &[(u32, Bind)],
    ) -> GpuResult<BoundSet> {
        let ty_of = |bind: &Bind| match bind {
            Bind::Uniform(_) => vk::DescriptorType::UNIFORM_BUFFER,
            Bind::Storage(..) => vk::DescriptorType::STORAGE_BUFFER,
            Bind::Sampled(..) => vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
            Bind::StorageImage(..) | Bind::StorageLevel(..) => vk::DescriptorType::STORAGE_IMAGE,
            Bind::UniformTexel(..) => vk::DescriptorType::UNIFORM_TEXEL_BUFFER,
            Bind::StorageTexel(..) => vk::DescriptorType::STORAGE_TEXEL_BUFFER,
        };
        let mut sizes: BTreeMap<i32, u32> = BTreeMap::new();
        for (binding, bind) in binds {
            expect_bind_usage(name, *binding, bind);
            let ty = ty_of(bind);
            let declared = layout.bindings.iter().find(|b| b.0 == *binding);
            if declared.map(|b| b.1) != Some(ty) {
                return Err(GpuError::Unsupported(format!(
                    "descriptor set {name}: binding {binding} is written as {ty:?} but its layout declares {:?}",
                    declared.map(|b| b.1)
                )));
            }
            *sizes.entry(ty.as_raw()).or_default() += 1;
        }
        let sizes: Vec<_> = sizes
            .iter()
            .map(|(&ty, &n)| vk::DescriptorPoolSize {
                ty: vk::DescriptorType::from_raw(ty),
                descriptor_count: n,
            })
            .collect();
        let info = vk::DescriptorPoolCreateInfo::default()
            .max_sets(1)
            .pool_sizes(&sizes);
        // SAFETY: valid create info on a live device.
        let pool = unsafe { ctx.device.create_descriptor_pool(&info, None) }
            .vk("vkCreateDescriptorPool")?;
        ctx.count_created(1);
        ctx.name(pool, &format!("{name} pool"));
        let mut set = BoundSet {
            ctx: ctx.clone(),
            pool,
            raw: vk::DescriptorSet::null(),
            name: name.to_string(),
            bindings: BTreeMap::new(),
            layout: layout.bindings.clone(),
            _samplers: Vec::new(),
            _views: Vec::new(),
        };
        let layouts = [layout.raw];
        let info = vk::DescriptorSetAllocateInfo::default()
            .descriptor_pool(pool)
            .set_layouts(&layouts);
        // SAFETY: pool and layout are live objects of this device; the pool has room for it.
        set.raw = unsafe { ctx.device.allocate_descriptor_sets(&info) }
            .vk("vkAllocateDescriptorSets")?[0];
        ctx.name(set.raw, name);

        let image_info = |bind: &Bind| match bind {
            Bind::Sampled(image, sampler, order) => vk::DescriptorImageInfo {
                sampler: sampler.raw(),
                image_view: image.view,
                image_layout: sampled_layout(*order),
            },
            Bind::StorageImage(image, _) => vk::DescriptorImageInfo {
                sampler: vk::Sampler::null(),
                image_view: image.storage_view(0),
                image_layout: vk::ImageLayout::GENERAL,
            },
            Bind::StorageLevel(image, level, _) => vk::DescriptorImageInfo {
                sampler: vk::Sampler::null(),
                image_view: image.storage_view(*level),
                image_layout: vk::ImageLayout::GENERAL,
            },
            _ => vk::DescriptorImageInfo::default(),
        };
        let buffer_info = |bind: &Bind| match bind {
            Bind::Uniform(b) | Bind::Storage(b, _) => vk::DescriptorBufferInfo {
                buffer: b.raw(),
                offset: 0,
                range: vk::WHOLE_SIZE,
            },
            _ => vk::DescriptorBufferInfo::default(),
        };
        let texel = |bind: &Bind| match bind {
            Bind::UniformTexel(v, _) | Bind::StorageTexel(v, _) => v.raw(),
            _ => vk::BufferView::null(),
        };
        let images: Vec<[vk::DescriptorImageInfo; 1]> =
            binds.iter().map(|(_, b)| [image_info(b)]).collect();
        let buffers: Vec<[vk::DescriptorBufferInfo; 1]> =
            binds.iter().map(|(_, b)| [buffer_info(b)]).collect();
        let texels: Vec<[vk::BufferView; 1]> = binds.iter().map(|(_, b)| [texel(b)]).collect();
        let writes: Vec<_> = binds
            .iter()
            .enumerate()
            .map(|(i, (binding, bind))| {
                let w = vk::WriteDescriptorSet::default()
                    .dst_set(set.raw)
                    .dst_binding(*binding)
                    .descriptor_type(ty_of(bind));
                match bind {
                    Bind::Uniform(_) | Bind::Storage(..) => w.buffer_info(&buffers[i]),
                    Bind::Sampled(..) | Bind::StorageImage(..) | Bind::StorageLevel(..) => {
                        w.image_info(&images[i])
                    }
                    Bind::UniformTexel(..) | Bind::StorageTexel(..) => {
                        w.texel_buffer_view(&texels[i])
                    }
                }
            })
            .collect();
        // SAFETY: the set was just allocated (no command buffer uses it); every handle written
        // is live and kept alive by the set (below) for as long as the set exists; the types
        // match the layout (checked above).
        unsafe { ctx.device.update_descriptor_sets(&writes, &[]) };
        for (binding, bind) in binds {
            let (order, resource) = match bind {
                Bind::Uniform(b) => (Order::Host, Resource::Buffer(b.core().clone())),
                Bind::Storage(b, o) => (*o, Resource::Buffer(b.core().clone())),
                Bind::Sampled(i, s, o) => {
                    set._samplers.push((*s).clone());
                    (*o, Resource::Image((*i).clone()))
                }
                Bind::StorageImage(i, o) | Bind::StorageLevel(i, _, o) => {
                    (*o, Resource::Image((*i).clone()))
                }
                Bind::UniformTexel(v, o) | Bind::StorageTexel(v, o) => {
                    set._views.push((*v).clone());
                    (*o, Resource::Buffer(v.buffer().clone()))
                }
            };
            let bound = Bound { order, resource };
            set.bindings.insert(*binding, bound);
        }
        Ok(set)
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    /// Whether `binding` binds `image`.
    pub fn binds_image(&self, binding: u32, image: &Image) -> bool {
        matches!(
            self.bindings.get(&binding).map(|b| &b.resource),
            Some(Resource::Image(i)) if i.same(image)
        )
    }
}

/// Panics unless what `bind` binds has the usage its descriptor type needs.
fn expect_bind_usage(set: &str, binding: u32, bind: &Bind) {
    use vk::BufferUsageFlags as B;
    use vk::ImageUsageFlags as I;
    let what = format!("set {set} binding {binding}");
    // Images are written by GPU work, which the host's order does not cover.
    let image_host = matches!(
        bind,
        Bind::Sampled(_, _, Order::Host)
            | Bind::StorageImage(_, Order::Host)
            | Bind::StorageLevel(_, _, Order::Host)
    );
    assert!(
        !image_host,
        "{what}: an image cannot be ordered by the host"
    );
    match bind {
        Bind::Uniform(b) => b.expect_usage(B::UNIFORM_BUFFER, &what),
        Bind::Storage(b, _) => b.expect_usage(B::STORAGE_BUFFER, &what),
        Bind::Sampled(i, _, _) => i.expect_usage(I::SAMPLED, &what),
        Bind::StorageImage(i, _) | Bind::StorageLevel(i, _, _) => i.expect_usage(I::STORAGE, &what),
        Bind::UniformTexel(v, _) => v.expect_usage(B::UNIFORM_TEXEL_BUFFER, &what),
        Bind::StorageTexel(v, _) => v.expect_usage(B::STORAGE_TEXEL_BUFFER, &what),
    }
}

/// The layout a sampled image is bound in: SHADER_READ_ONLY_OPTIMAL when tracked by its reader,
/// GENERAL when it stays where its compute writer left it.
pub(super) fn sampled_layout(order: Order) -> vk::ImageLayout {
    match order {
        Order::Wait { .. } => vk::ImageLayout::GENERAL,
        Order::Tracked | Order::Host => vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
    }
}

impl Drop for BoundSet {
    fn drop(&mut self) {
        // The set goes with its pool, once no frame in flight can use it.
        self.ctx.defer(Garbage::DescriptorPool(self.pool));
    }
}
