//! Output pass: puts the main target (display colour at `--render-scale` of the output's size),
//! or with `--aa fxaa` the anti-aliased target of the same size and format, into the output
//! image (a swapchain image or the headless target). A copy when the two have the same size and
//! format and the output takes copies; otherwise drawn: a full-screen triangle samples the
//! picture into the output as a colour attachment (shaders/post/output.frag; nearest at the
//! same size, bilinear or edge-directed when scaling up: `--upscale`), which also converts between RGBA and BGRA byte orders (a
//! recreated swapchain may change it). Only COLOR_ATTACHMENT is a guaranteed usage of swapchain
//! images (`supportedUsageFlags`), so the draw works into every output.
//!
//! Why a draw rather than a blit when scaling: on lavapipe at `--quality low` (640x360 to
//! 1280x720) the draw took 6.3–7.1 ms against the blit's 7.7–8.0 (medians of `bench frames`,
//! runs alternating; 2026-12-01, a day this VM ran about 1.8 times slower than README's
//! numbers), and a GPU blits with a draw of its own anyway. `VKOCEAN_OUTPUT=draw` draws even
//! where a copy would do, `VKOCEAN_OUTPUT=transfer` copies or blits wherever the output takes
//! transfers (tests/output.rs compares the paths). The drawn path's pipeline and descriptor set
//! are made at the first drawn frame and remade when the output's format, the way of scaling
//! (the edge-directed pipeline is a specialization of its own) or the sampled picture changes
//! (the old ones go to the deletion queue).
//!
//! Why the tone map is not a pass of its own here: at 1280x720 on lavapipe a full-screen
//! tone-map pass at the output's size cost 12–14 ms, the blit from a half-size main target
//! 3.2–3.6 ms. The scene shaders tone-map per fragment at the main target's size instead
//! (shaders/common/display.glsl), and the sRGB attachment format encodes.

use std::cell::RefCell;
use std::sync::Arc;

use ash::vk;

use crate::gpu::{
    Bind, Bindings, BoundSet, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Image, Load,
    Order, Pipeline, PipelineLayout, Recorder, Sampler, Target,
};
use crate::pass_names as names;
use crate::render::OutputTarget;
use crate::shaders;

/// `draw` draws the output even where a copy would do; `transfer` copies or blits wherever the
/// output takes transfers (tests, experiments).
pub const OUTPUT_ENV: &str = "VKOCEAN_OUTPUT";

/// How the picture gets into the output (`VKOCEAN_OUTPUT`).
#[derive(Clone, Copy, PartialEq, Eq)]
enum Path {
    /// A copy where the sizes and formats match, else a draw.
    Auto,
    /// Always a draw.
    Draw,
    /// A copy or a blit where the output takes transfers.
    Transfer,
}

/// The output pass: a copy, or (`Drawn`, made when first needed) a draw; a blit on request.
pub struct OutputPass {
    ctx: Arc<Context>,
    path: Path,
    /// The drawing pipeline, and its set for the picture it last sampled.
    drawn: RefCell<Option<Drawn>>,
}

/// What drawing the output needs, for one output format and way of scaling.
struct Drawn {
    format: vk::Format,
    /// Scaling up edge-directed (shaders/post/output.frag's EDGE).
    edge: bool,
    pipeline: Pipeline,
    /// Binding 0: the picture. Kept: sets are allocated from it.
    set_layout: DescriptorSetLayout,
    /// Nearest (same size) and linear (scaling), clamped.
    nearest: Sampler,
    linear: Sampler,
    /// The set and the filter it samples with; remade when the picture or the filter changes
    /// (a set is never rewritten; the old one retires with the frames that bind it).
    set: Option<(BoundSet, vk::Filter)>,
}

impl OutputPass {
    pub fn new(ctx: &Arc<Context>) -> OutputPass {
        OutputPass {
            ctx: ctx.clone(),
            path: match std::env::var(OUTPUT_ENV).as_deref() {
                Ok("draw") => Path::Draw,
                Ok("transfer") => Path::Transfer,
                _ => Path::Auto,
            },
            drawn: RefCell::new(None),
        }
    }

    /// Forgets the drawn path's set: the picture it sampled is about to be replaced (the set
    /// would keep the old one alive). Called by `Renderer::resize`.
    pub fn resize(&self) {
        if let Some(drawn) = self.drawn.borrow_mut().as_mut() {
            drawn.set = None;
        }
    }

    /// Records the copy, blit or draw of `main` (the main or the anti-aliased colour, last
    /// written as a colour attachment) into `output`. Outside any rendering scope. Scaling
    /// filters with `scale_filter`; with `edge` (`--upscale edge`) a linear scaling up is drawn
    /// edge-directed (shaders/post/output.frag), else bilinearly.
    pub fn record(
        &self,
        rec: &Recorder,
        main: &Image,
        output: &OutputTarget,
        scale_filter: vk::Filter,
        edge: bool,
    ) -> GpuResult<()> {
        let filter = if main.extent() == output.extent {
            vk::Filter::NEAREST
        } else {
            scale_filter
        };
        let same = main.extent() == output.extent && main.format() == output.format;
        let draw = match self.path {
            Path::Draw => true,
            Path::Transfer => !output.transfer_dst,
            Path::Auto => !output.transfer_dst || !same,
        };
        if draw {
            self.draw(rec, main, output, filter, edge)?;
        } else if same {
            rec.copy_image(main, output.image);
        } else {
            rec.blit_image(main, output.image, filter);
        }
        Ok(())
    }

    /// The drawn output: a full-screen triangle sampling `main` with `filter`, edge-directed
    /// with `edge` where it scales up linearly.
    fn draw(
        &self,
        rec: &Recorder,
        main: &Image,
        output: &OutputTarget,
        filter: vk::Filter,
        edge: bool,
    ) -> GpuResult<()> {
        let up = main.extent().width < output.extent.width;
        let edge = edge && up && filter == vk::Filter::LINEAR;
        let mut slot = self.drawn.borrow_mut();
        if slot
            .as_ref()
            .is_none_or(|d| d.format != output.format || d.edge != edge)
        {
            *slot = Some(Drawn::new(&self.ctx, output.format, edge)?);
        }
        let drawn = slot.as_mut().expect("made above");
        drawn.set_for(&self.ctx, main, filter)?;
        let drawn = &*drawn;
        let sets = [&drawn.set.as_ref().expect("made by set_for").0];
        let draw = Bindings {
            pipeline: &drawn.pipeline,
            sets: &sets,
        };
        let target = [Target::output(output.image, Load::DontCare)];
        rec.rendering(names::OUTPUT, &target, None, &[draw])
            .record(|| {
                rec.bind(&draw);
                rec.draw(3, 1);
            });
        Ok(())
    }
}

impl Drawn {
    fn new(ctx: &Arc<Context>, format: vk::Format, edge: bool) -> GpuResult<Drawn> {
        let set_layout = DescriptorSetLayout::new(
            ctx,
            "output set layout",
            &[(
                0,
                vk::DescriptorType::COMBINED_IMAGE_SAMPLER,
                vk::ShaderStageFlags::FRAGMENT,
            )],
        )?;
        let layout = PipelineLayout::new(ctx, "output layout", &[&set_layout], None)?;
        let pipeline = Pipeline::graphics(
            ctx,
            &layout,
            &GraphicsDesc {
                name: if edge {
                    "output (drawn, edge-directed)"
                } else {
                    "output (drawn)"
                },
                stages: &[
                    (
                        vk::ShaderStageFlags::VERTEX,
                        shaders::COMMON_FULLSCREEN_VERT,
                    ),
                    (vk::ShaderStageFlags::FRAGMENT, shaders::POST_OUTPUT_FRAG),
                ],
                colour_formats: &[format],
                constants: &[u32::from(edge)],
                ..Default::default()
            },
        )?;
        let clamp = vk::SamplerAddressMode::CLAMP_TO_EDGE;
        Ok(Drawn {
            format,
            edge,
            pipeline,
            set_layout,
            nearest: Sampler::new(ctx, "output sampler (nearest)", vk::Filter::NEAREST, clamp)?,
            linear: Sampler::linear(ctx, "output sampler (linear)", clamp)?,
            set: None,
        })
    }

    /// Makes `set` sample `picture` with `filter`: keeps the last one, or makes a new one (the
    /// old one, which a frame in flight may still bind, goes to the deletion queue).
    fn set_for(
        &mut self,
        ctx: &Arc<Context>,
        picture: &Image,
        filter: vk::Filter,
    ) -> GpuResult<()> {
        let current = self
            .set
            .as_ref()
            .is_some_and(|(set, f)| *f == filter && set.binds_image(0, picture));
        if !current {
            let sampler = if filter == vk::Filter::LINEAR {
                &self.linear
            } else {
                &self.nearest
            };
            let bind = Bind::Sampled(picture, sampler, Order::Tracked);
            let set = BoundSet::new(ctx, &self.set_layout, "output set (picture)", &[(0, bind)])?;
            self.set = Some((set, filter));
        }
        Ok(())
    }
}
