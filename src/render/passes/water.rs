//! Water pass: the ocean as tessellated patches (shaders/surface/water.vert/.tesc/.tese/.frag,
//! layout in shaders/common/water.glsl). The control shader picks each edge's level from its
//! screen size and culls patches outside the frustum; the evaluation shader displaces the
//! vertices by the simulation's images; the fragment shader shades with the reflection and
//! refraction textures (set 1, rewritten on resize), the DU/DV map and the sky cube. The same
//! set feeds the texture debug views (`--view reflection|refraction|dudv`,
//! shaders/post/textures.frag), drawn over the whole main target.

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
use crate::shaders;

/// Patches per side (shared with water.vert).
pub use crate::shared::PATCHES;

/// Samplers the water's textures use.
pub struct WaterSamplers {
    /// Linear, clamped: reflection and refraction colour.
    pub clamp: vk::Sampler,
    /// Nearest, clamped: refraction depth.
    pub depth: vk::Sampler,
    /// Linear, repeating: the DU/DV map.
    pub repeat: vk::Sampler,
}

pub struct WaterPass {
    ctx: Arc<Context>,
    _set_layout: DescriptorSetLayout,
    layout: PipelineLayout,
    fill: Pipeline,
    /// Line rendering (`--view wireframe`), when the device has fillModeNonSolid.
    wireframe: Option<Pipeline>,
    /// A texture of the set over the whole main target (debug views).
    textures_view: Pipeline,
    _pool: DescriptorPool,
    set: vk::DescriptorSet,
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
        let sampled = vk::DescriptorType::COMBINED_IMAGE_SAMPLER;
        let fragment = vk::ShaderStageFlags::FRAGMENT;
        let set_layout = DescriptorSetLayout::new(
            ctx,
            "water textures layout",
            &[
                (0, sampled, fragment),
                (1, sampled, fragment),
                (2, sampled, fragment),
                (3, sampled, fragment),
            ],
        )?;
        let layout = scene_layout(ctx, "water layout", frame_layout, &[&set_layout])?;
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
        let pipeline = |name, polygon_mode| {
            scene_pipeline(
                ctx,
                &layout,
                GraphicsDesc {
                    name,
                    stages: &stages,
                    topology: vk::PrimitiveTopology::PATCH_LIST,
                    patch_control_points: 4,
                    polygon_mode,
                    constants: &[cascades, manual_filter as u32],
                    ..Default::default()
                },
                Depth::TestWrite,
                target,
            )
        };
        let fill = pipeline("water", vk::PolygonMode::FILL)?;
        let wireframe = if ctx.info.fill_mode_non_solid {
            Some(pipeline("water wireframe", vk::PolygonMode::LINE)?)
        } else {
            None
        };
        let textures_view = scene_pipeline(
            ctx,
            &layout,
            GraphicsDesc {
                name: "water textures view",
                stages: &[
                    (
                        vk::ShaderStageFlags::VERTEX,
                        shaders::COMMON_FULLSCREEN_VERT,
                    ),
                    (vk::ShaderStageFlags::FRAGMENT, shaders::POST_TEXTURES_FRAG),
                ],
                ..Default::default()
            },
            Depth::None,
            target,
        )?;
        let pool = DescriptorPool::new(ctx, "water descriptors", 1, &[(sampled, 4)])?;
        let set = pool.allocate(&set_layout, "water textures set")?;
        let pass = WaterPass {
            ctx: ctx.clone(),
            _set_layout: set_layout,
            layout,
            fill,
            wireframe,
            textures_view,
            _pool: pool,
            set,
        };
        pass.resize(targets, dudv, samplers);
        Ok(pass)
    }

    /// Points the pass at new targets. The caller makes sure no frame in flight uses the set.
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

    /// Whether `--view wireframe` can draw lines on this device.
    pub fn has_wireframe(&self) -> bool {
        self.wireframe.is_some()
    }

    /// Draws the ocean patches inside the main rendering scope.
    pub fn record(&self, rec: &Recorder, frame_set: vk::DescriptorSet, wireframe: bool) {
        let pipeline = match (&self.wireframe, wireframe) {
            (Some(lines), true) => lines,
            _ => &self.fill,
        };
        bind_scene(
            rec,
            pipeline,
            &self.layout,
            &[frame_set, self.set],
            ViewIndex::Main,
        );
        // One instance per row of patches (see water.vert).
        rec.draw(PATCHES * 4, PATCHES);
    }

    /// Draws `--view reflection|refraction|dudv` over the whole main target, inside a rendering
    /// scope with the main colour attachment only.
    pub fn record_textures_view(&self, rec: &Recorder, frame_set: vk::DescriptorSet) {
        bind_scene(
            rec,
            &self.textures_view,
            &self.layout,
            &[frame_set, self.set],
            ViewIndex::Main,
        );
        rec.draw(3, 1);
    }
}
