//! Water pass: the ocean as tessellated patches (shaders/surface/water.vert/.tesc/.tese/.frag,
//! layout in shaders/common/water.glsl). The control shader picks each edge's level from its
//! screen size and culls patches outside the frustum; the evaluation shader displaces the
//! vertices by the simulation's images; the fragment shader shades with the reflection and
//! refraction textures (set 1, [`WaterTextures`], rewritten on resize), the DU/DV map and the
//! sky cube. The same set feeds the texture debug views (`textures_view.rs`).

use std::sync::Arc;

use ash::vk;

use super::{bind_scene, scene_layout, scene_pipeline, Depth, SceneTarget};
use crate::gpu::descriptors::{self, Write};
use crate::gpu::{
    Context, DescriptorPool, DescriptorSetLayout, GpuResult, GraphicsDesc, Pipeline,
    PipelineLayout, Recorder,
};
use crate::render::targets::Targets;
use crate::render::uniforms::ViewIndex;
use crate::render::ViewMode;
use crate::shaders;

/// Patches per side (shared with water.vert).
pub use crate::shared::PATCHES;

/// Samplers the water's textures use.
pub struct WaterSamplers {
    /// Linear, clamped: reflection (all its layers) and refraction colour.
    pub clamp: vk::Sampler,
    /// Nearest, clamped: refraction depth.
    pub depth: vk::Sampler,
    /// Linear, repeating: the DU/DV map.
    pub repeat: vk::Sampler,
}

/// The water's textures (set 1 of the water and of the textures view): reflection colour,
/// refraction colour and depth, the DU/DV map.
pub struct WaterTextures {
    ctx: Arc<Context>,
    pub layout: DescriptorSetLayout,
    _pool: DescriptorPool,
    pub set: vk::DescriptorSet,
}

impl WaterTextures {
    pub fn new(
        ctx: &Arc<Context>,
        targets: &Targets,
        dudv: vk::ImageView,
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
        let pool = DescriptorPool::new(ctx, "water descriptors", 1, &[(sampled, 4)])?;
        let set = pool.allocate(&layout, "water textures set")?;
        let textures = WaterTextures {
            ctx: ctx.clone(),
            layout,
            _pool: pool,
            set,
        };
        textures.resize(targets, dudv, samplers);
        Ok(textures)
    }

    /// Points the set at new targets. The caller makes sure no frame in flight uses the set.
    pub fn resize(&self, targets: &Targets, dudv: vk::ImageView, samplers: &WaterSamplers) {
        let read = vk::ImageLayout::SHADER_READ_ONLY_OPTIMAL;
        descriptors::update(
            &self.ctx,
            self.set,
            &[
                Write::SampledImage {
                    binding: 0,
                    view: targets.reflection.colour.view,
                    sampler: samplers.clamp,
                    layout: read,
                },
                Write::SampledImage {
                    binding: 1,
                    view: targets.refraction.colour.view,
                    sampler: samplers.clamp,
                    layout: read,
                },
                Write::SampledImage {
                    binding: 2,
                    view: targets.refraction.depth.view,
                    sampler: samplers.depth,
                    layout: read,
                },
                Write::SampledImage {
                    binding: 3,
                    view: dudv,
                    sampler: samplers.repeat,
                    layout: read,
                },
            ],
        );
    }
}

pub struct WaterPass {
    layout: PipelineLayout,
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
        dudv: vk::ImageView,
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
            layout,
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

    /// Points the pass at new targets. The caller makes sure no frame in flight uses the set.
    pub fn resize(&self, targets: &Targets, dudv: vk::ImageView, samplers: &WaterSamplers) {
        self.textures.resize(targets, dudv, samplers);
    }

    /// Whether `--view wireframe` can draw lines on this device.
    pub fn has_wireframe(&self) -> bool {
        self.wireframe.is_some()
    }

    /// Draws the ocean patches inside the main rendering scope: as lines for
    /// `ViewMode::Wireframe` (where the device draws lines), filled otherwise, from below when
    /// the camera is `underwater`.
    pub fn record(
        &self,
        rec: &Recorder,
        frame_set: vk::DescriptorSet,
        view: ViewMode,
        underwater: bool,
    ) {
        let pipeline = match (&self.wireframe, view) {
            (Some(lines), ViewMode::Wireframe) => lines,
            _ if underwater => &self.from_below,
            _ => &self.fill,
        };
        bind_scene(
            rec,
            pipeline,
            &self.layout,
            &[frame_set, self.textures.set],
            ViewIndex::Main,
        );
        // One instance per row of patches (see water.vert).
        rec.draw(PATCHES * 4, PATCHES);
    }
}
