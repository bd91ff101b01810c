//! The reflection's distances and the sky its objects hide (shaders/post/reflection_distance.frag):
//! the sky along the mirrored view's ray, and as its alpha, from the reflection's depth, the
//! share of objects (1, or 0 for the sky) times the log2 of their distance, into layer 0 of
//! `Targets::reflection_sky`; the frame then blurs it down its layers as it blurs the
//! reflection's colour (`Recorder::halve_down_layers`), whose alpha is the share of objects
//! (the sky draws 0 there: shaders/sky/sky.frag). The water reads both at the same place and
//! layer: the blurred alphas are the share of objects under its lookup's kernel and that share
//! times their mean log distance, exactly the objects whose colour the kernel mixed in, and the
//! blurred sky is what stands behind them under that kernel, which replaces them where they
//! stand nearer than the sea point (shaders/common/reflection.glsl). Three taps of the depth
//! itself had stood for the kernel before, and missed the buoy, a few texels wide, in the
//! blurred layers' tall kernels; an image of the distances of its own, blurred alike, cost the
//! water two lookups more than the alphas.

use std::sync::Arc;

use ash::vk;

use super::{bind_scene, scene_layout};
use crate::gpu::{
    Bind, Bindings, BoundSet, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Image, Order,
    Pipeline, Recorder, Sampler,
};
use crate::render::targets::HDR_FORMAT;
use crate::render::uniforms::ViewIndex;
use crate::shaders;

pub struct ReflectionDistancePass {
    ctx: Arc<Context>,
    pipeline: Pipeline,
    /// Set 1, binding 0: the reflection's depth. Kept: `resize` makes a set.
    set_layout: DescriptorSetLayout,
    /// Binds the reflection's depth (remade on resize).
    set: BoundSet,
}

impl ReflectionDistancePass {
    /// Reads the frame's set (`frame_layout`: the reflection's view, the sky cube) and `depth`
    /// (the reflection's, texel by texel through `sampler`).
    pub fn new(
        ctx: &Arc<Context>,
        frame_layout: &DescriptorSetLayout,
        depth: &Image,
        sampler: &Sampler,
    ) -> GpuResult<Self> {
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
        let layout = scene_layout(
            ctx,
            "reflection distance layout",
            frame_layout,
            &[&set_layout],
        )?;
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
                colour_formats: &[HDR_FORMAT],
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

    /// Its draw, with the sets `sets` gives.
    pub fn draw<'a>(&'a self, sets: &'a [&'a BoundSet; 2]) -> Bindings<'a> {
        Bindings {
            pipeline: &self.pipeline,
            sets,
        }
    }

    /// The frame's set `frame` and this pass's own, which `draw` takes.
    pub fn sets<'a>(&'a self, frame: &'a BoundSet) -> [&'a BoundSet; 2] {
        [frame, &self.set]
    }

    /// Draws the sky and the distances, inside a rendering scope into layer 0 of
    /// `Targets::reflection_sky` that declared `draw`.
    pub fn record(&self, rec: &Recorder, draw: &Bindings) {
        bind_scene(rec, draw, ViewIndex::Reflection);
        rec.draw(3, 1);
    }
}
