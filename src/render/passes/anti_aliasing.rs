//! Anti-aliasing pass (`--aa fxaa`): FXAA (Lottes 2009) over the main colour into the
//! anti-aliased colour, a target of the same size and format, which the output pass then copies
//! or scales into the output instead of the main colour. Two draws in one rendering scope:
//! `edges` (shaders/post/fxaa_edges.frag) copies every pixel, sharpened where it is not on an
//! edge (`--sharpen`, a contrast-adaptive sharpening for the upscale that follows), and marks
//! those on an edge in the main depth buffer (free once the sky is drawn), then `fxaa` (shaders/post/fxaa.frag),
//! depth-tested against the mark, anti-aliases only those. Lavapipe runs every pixel of a 4x4
//! block through the whole shader whatever its branches, but skips a block no pixel of which
//! passes the early depth test: one draw with FXAA's early exit cost 7.8 ms at 640x360, the two
//! 5.2–5.7 ms (README, Anti-aliasing).
//!
//! Why it runs at the main target's size (`--render-scale`), before the output pass scales up:
//! a full-screen pass at the output's 1280x720 cost 12–14 ms on lavapipe (passes/output.rs);
//! at `--quality low`'s 640x360 this one costs a quarter of that (README, Anti-aliasing).

use std::sync::Arc;

use ash::vk;

use super::SceneTarget;
use crate::gpu::{
    Bind, Bindings, BoundSet, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Image, Order,
    Pipeline, PipelineLayout, Recorder, Sampler,
};
use crate::render::targets::DEPTH_FORMAT;
use crate::shaders;

pub struct AntiAliasingPass {
    ctx: Arc<Context>,
    /// First draw: copies the main colour, writes depth 0 on edges and 1 elsewhere.
    edges: Pipeline,
    /// Second draw, depth-tested (GREATER_OR_EQUAL, at depth 0): FXAA where the first draw
    /// wrote 0. The compare keeps the scene's reversed-Z direction (GREATER): NVIDIA's Z-cull
    /// works in one direction per depth buffer (Best Practices' Zcull-LessGreaterRatio).
    fxaa: Pipeline,
    /// Binding 0: the main colour, sampled linearly and clamped. Kept: `resize` makes a set.
    set_layout: DescriptorSetLayout,
    /// Binds the main colour (remade on resize).
    set: BoundSet,
}

impl AntiAliasingPass {
    /// Reads `main` (the main colour, display colour in an 8-bit format) through `sampler`
    /// (linear, clamped) and draws into a target of `main`'s format; `fast`: Lottes' fastest
    /// preset (`SceneSettings::fxaa_fast`).
    pub fn new(ctx: &Arc<Context>, main: &Image, sampler: &Sampler, fast: bool) -> GpuResult<Self> {
        let set_layout = DescriptorSetLayout::new(
            ctx,
            "anti-aliasing set layout",
            &[(
                0,
                vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
                vk::ShaderStageFlags::FRAGMENT,
            )],
        )?;
        let set = Self::set(ctx, &set_layout, main, sampler)?;
        // The edges draw's push constant: the sharpening (`--sharpen`, 0 to 1).
        let layout = PipelineLayout::new(
            ctx,
            "anti-aliasing layout",
            &[&set_layout],
            Some((vk::ShaderStageFlags::FRAGMENT, 4)),
        )?;
        // The shaders' DISPLAY_TARGET (whether samples come decoded, sRGB, or encoded, UNORM)
        // and FXAA_FAST.
        let display_mode = SceneTarget::Display(main.format()).display_mode();
        let pipeline = |name, fragment, depth_compare, depth_write| {
            Pipeline::graphics(
                ctx,
                &layout,
                &GraphicsDesc {
                    name,
                    stages: &[
                        (
                            vk::ShaderStageFlags::VERTEX,
                            shaders::COMMON_FULLSCREEN_VERT,
                        ),
                        (vk::ShaderStageFlags::FRAGMENT, fragment),
                    ],
                    colour_formats: &[main.format()],
                    depth_format: Some(DEPTH_FORMAT),
                    depth_compare: Some(depth_compare),
                    depth_write,
                    constants: &[display_mode, fast as u32],
                    ..Default::default()
                },
            )
        };
        let edges = pipeline(
            "anti-aliasing edges",
            shaders::POST_FXAA_EDGES_FRAG,
            vk::CompareOp::ALWAYS,
            true,
        )?;
        // fullscreen.vert draws at depth 0: 0 >= 0 on the marked pixels only.
        let fxaa = pipeline(
            "anti-aliasing fxaa",
            shaders::POST_FXAA_FRAG,
            vk::CompareOp::GREATER_OR_EQUAL,
            false,
        )?;
        Ok(AntiAliasingPass {
            ctx: ctx.clone(),
            edges,
            fxaa,
            set_layout,
            set,
        })
    }

    fn set(
        ctx: &Arc<Context>,
        layout: &DescriptorSetLayout,
        main: &Image,
        sampler: &Sampler,
    ) -> GpuResult<BoundSet> {
        let bind = Bind::Sampled(main, sampler, Order::Tracked);
        BoundSet::new(ctx, layout, "anti-aliasing set (main colour)", &[(0, bind)])
    }

    /// Points the pass at a new main colour (a new set; the old one retires with its frames).
    pub fn resize(&mut self, main: &Image, sampler: &Sampler) -> GpuResult<()> {
        self.set = Self::set(&self.ctx, &self.set_layout, main, sampler)?;
        Ok(())
    }

    /// Its two draws: edges, then FXAA, each with the main colour's set.
    pub fn draws<'a>(&'a self, sets: &'a [&'a BoundSet; 1]) -> [Bindings<'a>; 2] {
        [&self.edges, &self.fxaa].map(|pipeline| Bindings { pipeline, sets })
    }

    /// The set `draws` takes.
    pub fn set_ref(&self) -> [&BoundSet; 1] {
        [&self.set]
    }

    /// Draws the anti-aliased picture, inside a rendering scope whose colour attachment is the
    /// anti-aliased colour and whose depth attachment (contents not loaded) has its size, and
    /// which declared `draws`; the pixels off the edges sharpened by `sharpen` (0 to 1: a copy
    /// at 0).
    pub fn record(&self, rec: &Recorder, draws: &[Bindings; 2], sharpen: f32) {
        for (i, draw) in draws.iter().enumerate() {
            rec.bind(draw);
            if i == 0 {
                rec.push_constants(&self.edges, &sharpen);
            }
            rec.draw(3, 1);
        }
    }
}
