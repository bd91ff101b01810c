//! Anti-aliasing pass (`--aa fxaa`): FXAA (Lottes 2009) over the main colour into the
//! anti-aliased colour, a target of the same size and format, which the output pass then copies
//! or scales into the output instead of the main colour. Two draws in one rendering scope:
//! `edges` (shaders/post/fxaa_edges.frag) copies every pixel and marks those on an edge in the
//! main depth buffer (free once the sky is drawn), then `fxaa` (shaders/post/fxaa.frag),
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
use crate::gpu::descriptors::{self, Write};
use crate::gpu::{
    Context, DescriptorPool, DescriptorSetLayout, GpuResult, GraphicsDesc, Image, Pipeline,
    PipelineLayout, Recorder,
};
use crate::render::targets::DEPTH_FORMAT;
use crate::shaders;

pub struct AntiAliasingPass {
    ctx: Arc<Context>,
    layout: PipelineLayout,
    /// First draw: copies the main colour, writes depth 1 on edges and 0 elsewhere.
    edges: Pipeline,
    /// Second draw, depth-tested (LESS, at depth 0): FXAA where the first draw wrote 1.
    fxaa: Pipeline,
    /// Binding 0: the main colour, sampled linearly and clamped. Kept: `resize` updates the set.
    _set_layout: DescriptorSetLayout,
    /// Holds `set`.
    _pool: DescriptorPool,
    /// Points at the main colour (rewritten on resize).
    set: vk::DescriptorSet,
}

impl AntiAliasingPass {
    /// Reads `main` (the main colour, display colour in an 8-bit format) through `sampler`
    /// (linear, clamped) and draws into a target of `main`'s format.
    pub fn new(ctx: &Arc<Context>, main: &Image, sampler: vk::Sampler) -> GpuResult<Self> {
        let set_layout = DescriptorSetLayout::new(
            ctx,
            "anti-aliasing set layout",
            &[(
                0,
                vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
                vk::ShaderStageFlags::FRAGMENT,
            )],
        )?;
        let pool = DescriptorPool::new(
            ctx,
            "anti-aliasing descriptors",
            1,
            &[(vk::DescriptorType::COMBINED_IMAGE_SAMPLER, 1)],
        )?;
        let set = pool.allocate(&set_layout, "anti-aliasing set (main colour)")?;
        let layout = PipelineLayout::new(ctx, "anti-aliasing layout", &[&set_layout], None)?;
        // The shaders' DISPLAY_TARGET: whether samples come decoded (sRGB) or encoded (UNORM).
        let display_mode = SceneTarget::Display(main.format).display_mode();
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
                    colour_formats: &[main.format],
                    depth_format: Some(DEPTH_FORMAT),
                    depth_compare: Some(depth_compare),
                    depth_write,
                    constants: &[display_mode],
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
        // fullscreen.vert draws at depth 0: 0 < 1 on the marked pixels only.
        let fxaa = pipeline(
            "anti-aliasing fxaa",
            shaders::POST_FXAA_FRAG,
            vk::CompareOp::LESS,
            false,
        )?;
        let pass = AntiAliasingPass {
            ctx: ctx.clone(),
            layout,
            edges,
            fxaa,
            _set_layout: set_layout,
            _pool: pool,
            set,
        };
        pass.resize(main, sampler);
        Ok(pass)
    }

    /// Points the pass at a new main colour. The caller makes sure no frame in flight uses the
    /// set.
    pub fn resize(&self, main: &Image, sampler: vk::Sampler) {
        descriptors::update(
            &self.ctx,
            self.set,
            &[Write::SampledImage {
                binding: 0,
                view: main.view,
                sampler,
                layout: vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL,
            }],
        );
    }

    /// Draws the anti-aliased picture, inside a rendering scope whose colour attachment is the
    /// anti-aliased colour and whose depth attachment (contents not loaded) has its size, and
    /// which samples the main colour.
    pub fn record(&self, rec: &Recorder) {
        for pipeline in [&self.edges, &self.fxaa] {
            rec.bind_pipeline(pipeline);
            rec.bind_sets(pipeline, &self.layout, &[self.set]);
            rec.draw(3, 1);
        }
    }
}
