//! Water pass: the ocean as tessellated patches (shaders/surface/water.vert/.tesc/.tese/.frag,
//! layout in shaders/common/water.glsl). The control shader picks each edge's level from its
//! screen size and culls patches outside the frustum; the evaluation shader displaces the
//! vertices by the simulation's images; the fragment shader shades with the reflection and
//! refraction textures (set 1, [`WaterTextures`], rewritten on resize), the DU/DV map and the
//! sky cube. The same set feeds the texture debug views (`textures_view.rs`).

use std::sync::Arc;

use ash::vk;

use super::{bind_scene, scene_layout, scene_pipeline, Depth, SceneTarget};
use crate::gpu::{
    Bind, Bindings, BoundSet, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Image, Order,
    Pipeline, Recorder, Sampler,
};
use crate::render::targets::Targets;
use crate::render::uniforms::ViewIndex;
use crate::render::ViewMode;
use crate::shaders;

/// Patches per side (shared with water.vert).
pub use crate::shared::PATCHES;

/// Samplers the water's textures use.
pub struct WaterSamplers<'a> {
    /// Linear, clamped: reflection (all its layers) and refraction colour.
    pub clamp: &'a Sampler,
    /// Nearest, clamped: refraction depth.
    pub depth: &'a Sampler,
    /// Linear, repeating: the DU/DV map.
    pub repeat: &'a Sampler,
}

/// The water's textures (set 1 of the water and of the textures view): reflection colour,
/// refraction colour and depth, the DU/DV map.
pub struct WaterTextures {
    ctx: Arc<Context>,
    pub layout: DescriptorSetLayout,
    /// Remade on resize (a set is never rewritten; the old one retires with its frames).
    pub set: BoundSet,
}

impl WaterTextures {
    pub fn new(
        ctx: &Arc<Context>,
        targets: &Targets,
        dudv: &Image,
        samplers: &WaterSamplers,
    ) -> GpuResult<WaterTextures> {
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        let fragment = vk::ShaderStageFlags::FRAGMENT;
        let layout = DescriptorSetLayout::new(
            ctx,
            "water textures layout",
            &[
                (0, sampled, fragment),
                (1, sampled, fragment),
                (2, sampled, fragment),
                (3, sampled, fragment),
            ],
        )?;
        let set = Self::set(ctx, &layout, targets, dudv, samplers)?;
        Ok(WaterTextures {
            ctx: ctx.clone(),
            layout,
            set,
        })
    }

    fn set(
        ctx: &Arc<Context>,
        layout: &DescriptorSetLayout,
        targets: &Targets,
        dudv: &Image,
        samplers: &WaterSamplers,
    ) -> GpuResult<BoundSet> {
        // Each tracked: the passes that sample them wait for their writers (graphics 1's
        // reflection and refraction passes, the DU/DV map's upload).
        let t = Order::Tracked;
        BoundSet::new(
            ctx,
            layout,
            "water textures set",
            &[
                (
                    0,
                    Bind::Sampled(&targets.reflection.colour, samplers.clamp, t),
                ),
                (
                    1,
                    Bind::Sampled(&targets.refraction.colour, samplers.clamp, t),
                ),
                (
                    2,
                    Bind::Sampled(&targets.refraction.depth, samplers.depth, t),
                ),
                (3, Bind::Sampled(dudv, samplers.repeat, t)),
            ],
        )
    }

    /// Binds new targets: a new set (the old one is retired through the deletion queue).
    pub fn resize(
        &mut self,
        targets: &Targets,
        dudv: &Image,
        samplers: &WaterSamplers,
    ) -> GpuResult<()> {
        self.set = Self::set(&self.ctx, &self.layout, targets, dudv, samplers)?;
        Ok(())
    }
}

pub struct WaterPass {
    fill: Pipeline,
    /// The surface seen from under the water (the camera below it): its own pipeline
    /// (specialization constant 2 of water.frag), because lavapipe pays for a branch it does
    /// not take (6 ms a frame at --quality low when one shader held both views).
    from_below: Pipeline,
    /// Line rendering (`--view wireframe`), when the device has fillModeNonSolid.
    wireframe: Option<Pipeline>,
    textures: WaterTextures,
}

impl WaterPass {
    /// `cascades`: layers of the ocean images (a specialization constant: the loop bound of the
    /// evaluation and fragment shaders); `manual_filter`: the ocean images are bound with a
    /// nearest sampler and the shaders filter them bilinearly by hand (devices without linear
    /// filtering of RGBA32F). Draws into the main target (`targets.display_format`).
    pub fn new(
        ctx: &Arc<Context>,
        frame_layout: &DescriptorSetLayout,
        targets: &Targets,
        dudv: &Image,
        samplers: &WaterSamplers,
        cascades: u32,
        manual_filter: bool,
    ) -> GpuResult<WaterPass> {
        let target = SceneTarget::Display(targets.display_format());
        let textures = WaterTextures::new(ctx, targets, dudv, samplers)?;
        let layout = scene_layout(ctx, "water layout", frame_layout, &[&textures.layout])?;
        let stages = [
            (vk::ShaderStageFlags::VERTEX, shaders::SURFACE_WATER_VERT),
            (
                vk::ShaderStageFlags::TESSELLATION_CONTROL,
                shaders::SURFACE_WATER_TESC,
            ),
            (
                vk::ShaderStageFlags::TESSELLATION_EVALUATION,
                shaders::SURFACE_WATER_TESE,
            ),
            (vk::ShaderStageFlags::FRAGMENT, shaders::SURFACE_WATER_FRAG),
        ];
        let pipeline = |name, polygon_mode, underwater: bool| {
            scene_pipeline(
                ctx,
                &layout,
                GraphicsDesc {
                    name,
                    stages: &stages,
                    topology: vk::PrimitiveTopology::PATCH_LIST,
                    patch_control_points: 4,
                    polygon_mode,
                    constants: &[cascades, manual_filter as u32, underwater as u32],
                    ..Default::default()
                },
                Depth::TestWrite,
                target,
            )
        };
        let fill = pipeline("water", vk::PolygonMode::FILL, false)?;
        let from_below = pipeline("water from below", vk::PolygonMode::FILL, true)?;
        let wireframe = if ctx.info.fill_mode_non_solid {
            Some(pipeline("water wireframe", vk::PolygonMode::LINE, false)?)
        } else {
            None
        };
        Ok(WaterPass {
            fill,
            from_below,
            wireframe,
            textures,
        })
    }

    /// The reflection, refraction and DU/DV textures the water samples.
    pub fn textures(&self) -> &WaterTextures {
        &self.textures
    }

    /// Points the pass at new targets (a new textures set).
    pub fn resize(
        &mut self,
        targets: &Targets,
        dudv: &Image,
        samplers: &WaterSamplers,
    ) -> GpuResult<()> {
        self.textures.resize(targets, dudv, samplers)
    }

    /// Its pipelines (the renderer checks their bindings at creation).
    pub fn pipelines(&self) -> impl Iterator<Item = &Pipeline> {
        [&self.fill, &self.from_below]
            .into_iter()
            .chain(self.wireframe.as_ref())
    }

    /// Whether `--view wireframe` can draw lines on this device.
    pub fn has_wireframe(&self) -> bool {
        self.wireframe.is_some()
    }

    /// What `record` binds: the pipeline for `view` (lines for `ViewMode::Wireframe` where the
    /// device draws lines, from below when the camera is `underwater`, filled otherwise) with
    /// `sets` (the frame set and [`WaterPass::textures`]' set).
    pub fn draw<'a>(
        &'a self,
        sets: &'a [&'a BoundSet],
        view: ViewMode,
        underwater: bool,
    ) -> Bindings<'a> {
        let pipeline = match (&self.wireframe, view) {
            (Some(lines), ViewMode::Wireframe) => lines,
            _ if underwater => &self.from_below,
            _ => &self.fill,
        };
        Bindings { pipeline, sets }
    }

    /// Draws the ocean patches inside the main rendering scope, which declared
    /// `draw(sets, view, underwater)`.
    pub fn record(&self, rec: &Recorder, sets: &[&BoundSet], view: ViewMode, underwater: bool) {
        bind_scene(rec, &self.draw(sets, view, underwater), ViewIndex::Main);
        // One instance per row of patches (see water.vert).
        rec.draw(PATCHES * 4, PATCHES);
    }
}
