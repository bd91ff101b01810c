//! The reflection's distances (shaders/post/reflection_distance.frag): from the reflection's
//! depth, per texel the share of objects (1, or 0 for the sky) and that share times the log2 of
//! their distance, into layer 0 of `Targets::reflection_distance`; the frame then blurs its
//! layers down as it blurs the reflection's colour (`Recorder::halve_down_layers`). The water
//! reads both at the same place and layer: the blurred pair is the share of objects under its
//! lookup's kernel and their mean log distance, exactly the objects whose colour the kernel
//! mixed in, which it takes out where they stand nearer than the sea point
//! (shaders/common/reflection.glsl). Three taps of the depth itself had stood for the kernel
//! before, and missed the buoy, a few texels wide, in the blurred layers' tall kernels.

use std::sync::Arc;

use ash::vk;

use crate::gpu::{
    Bind, Bindings, BoundSet, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Image, Order,
    Pipeline, PipelineLayout, Recorder, Sampler,
};
use crate::render::targets::DISTANCE_FORMAT;
use crate::shaders;

pub struct ReflectionDistancePass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    /// Binding 0: the reflection's depth. Kept: `resize` makes a set.
    set_layout: DescriptorSetLayout,
    /// Binds the reflection's depth (remade on resize).
    set: BoundSet,
}

impl ReflectionDistancePass {
    /// Reads `depth` (the reflection's, texel by texel through `sampler`).
    pub fn new(ctx: &Arc<Context>, depth: &Image, sampler: &Sampler) -> GpuResult<Self> {
        let set_layout = DescriptorSetLayout::new(
            ctx,
            "reflection distance set layout",
            &[(
                0,
                vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
                vk::ShaderStageFlags::FRAGMENT,
            )],
        )?;
        let set = Self::set(ctx, &set_layout, depth, sampler)?;
        let layout = PipelineLayout::new(ctx, "reflection distance layout", &[&set_layout], None)?;
        let pipeline = Pipeline::graphics(
            ctx,
            &layout,
            &GraphicsDesc {
                name: "reflection distance",
                stages: &[
                    (
                        vk::ShaderStageFlags::VERTEX,
                        shaders::COMMON_FULLSCREEN_VERT,
                    ),
                    (
                        vk::ShaderStageFlags::FRAGMENT,
                        shaders::POST_REFLECTION_DISTANCE_FRAG,
                    ),
                ],
                colour_formats: &[DISTANCE_FORMAT],
                ..Default::default()
            },
        )?;
        Ok(ReflectionDistancePass {
            ctx: ctx.clone(),
            pipeline,
            set_layout,
            set,
        })
    }

    fn set(
        ctx: &Arc<Context>,
        layout: &DescriptorSetLayout,
        depth: &Image,
        sampler: &Sampler,
    ) -> GpuResult<BoundSet> {
        let bind = Bind::Sampled(depth, sampler, Order::Tracked);
        let name = "reflection distance set (reflection depth)";
        BoundSet::new(ctx, layout, name, &[(0, bind)])
    }

    /// Points the pass at a new reflection depth (a new set; the old one retires with its
    /// frames).
    pub fn resize(&mut self, depth: &Image, sampler: &Sampler) -> GpuResult<()> {
        self.set = Self::set(&self.ctx, &self.set_layout, depth, sampler)?;
        Ok(())
    }

    /// Its draw, with the set `set_ref` gives.
    pub fn draw<'a>(&'a self, sets: &'a [&'a BoundSet; 1]) -> Bindings<'a> {
        Bindings {
            pipeline: &self.pipeline,
            sets,
        }
    }

    /// The set `draw` takes.
    pub fn set_ref(&self) -> [&BoundSet; 1] {
        [&self.set]
    }

    /// Draws the distances, inside a rendering scope into layer 0 of
    /// `Targets::reflection_distance` that declared `draw`.
    pub fn record(&self, rec: &Recorder, draw: &Bindings) {
        rec.bind(draw);
        rec.draw(3, 1);
    }
}
