//! The compute kernels' common shape: a pipeline with its set layout, and the sets of the
//! kernels that write a slot's images.

use std::sync::Arc;

use ash::vk;

use crate::gpu::{
    Bind, BoundSet, Context, DescriptorSetLayout, GpuResult, Image, Order, Pipeline,
    PipelineLayout, FRAMES_IN_FLIGHT,
};

/// A compute pipeline with its set layout.
pub(super) struct Kernel {
    pub(super) set_layout: DescriptorSetLayout,
    pub(super) pipeline: Pipeline,
}

impl Kernel {
    pub(super) fn new(
        ctx: &Arc<Context>,
        name: &str,
        spirv: &[u8],
        bindings: &[vk::DescriptorType],
        push_size: usize,
    ) -> GpuResult<Kernel> {
        let entries: Vec<_> = bindings
            .iter()
            .enumerate()
            .map(|(i, &ty)| (i as u32, ty, vk::ShaderStageFlags::COMPUTE))
            .collect();
        let set_layout = DescriptorSetLayout::new(ctx, &format!("{name} set layout"), &entries)?;
        let layout = PipelineLayout::new(
            ctx,
            &format!("{name} layout"),
            &[&set_layout],
            (push_size > 0).then_some((vk::ShaderStageFlags::COMPUTE, push_size as u32)),
        )?;
        let pipeline = Pipeline::compute(ctx, &layout, name, spirv, &[])?;
        Ok(Kernel {
            set_layout,
            pipeline,
        })
    }
}

impl Kernel {
    /// A kernel that writes a slot's images: binding 0 is its input (a storage buffer), 1–3
    /// the slot's displacement and normals and the previous slot's normals.
    pub(super) fn image_writer(
        ctx: &Arc<Context>,
        name: &str,
        spirv: &[u8],
        push_size: usize,
    ) -> GpuResult<Kernel> {
        let image = vk::DescriptorType::STORAGE_IMAGE;
        let bindings = [vk::DescriptorType::STORAGE_BUFFER, image, image, image];
        Kernel::new(ctx, name, spirv, &bindings, push_size)
    }

    /// One set per slot for an `image_writer` kernel: `input(slot)` at binding 0,
    /// `images(slot)` at 1–3 and `more` (the same in every slot) after them.
    pub(super) fn slot_sets<'a>(
        &self,
        ctx: &Arc<Context>,
        name: &str,
        input: impl Fn(usize) -> Bind<'a>,
        images: &SlotImages,
        more: &[(u32, Bind<'a>)],
    ) -> GpuResult<Vec<BoundSet>> {
        (0..FRAMES_IN_FLIGHT)
            .map(|slot| {
                let mut binds = vec![(0, input(slot))];
                binds.extend(images.binds(slot));
                binds.extend(more.iter().cloned());
                BoundSet::new(
                    ctx,
                    &self.set_layout,
                    &format!("{name} set slot {slot}"),
                    &binds,
                )
            })
            .collect()
    }
}

/// The images a slot's kernel writes and reads: that slot's displacement and normals, the
/// other slot's normals (foam decays and is advected from there).
pub(super) struct SlotImages<'a> {
    pub(super) displacement: &'a [Image],
    pub(super) normals: &'a [Image],
}

impl SlotImages<'_> {
    /// Bindings 1–3 of a slot's set; the kernels' `writeonly` and `readonly` qualifiers make
    /// the barriers (tracked on the compute queue).
    fn binds(&self, slot: usize) -> [(u32, Bind<'_>); 3] {
        let previous = (slot + FRAMES_IN_FLIGHT - 1) % FRAMES_IN_FLIGHT;
        let t = Order::Tracked;
        [
            (1, Bind::StorageImage(&self.displacement[slot], t)),
            (2, Bind::StorageImage(&self.normals[slot], t)),
            (3, Bind::StorageImage(&self.normals[previous], t)),
        ]
    }
}
