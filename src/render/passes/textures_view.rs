//! Texture debug views (`--view reflection|refraction|dudv`, shaders/post/textures.frag): the
//! reflection or refraction texture, or the DU/DV map tiled, over the whole main target. Reads
//! the water's textures set ([`WaterTextures`]).

use std::sync::Arc;

use ash::vk;

use super::water::WaterTextures;
use super::{bind_scene, scene_layout, scene_pipeline, Depth, SceneTarget};
use crate::gpu::{
    Bindings, BoundSet, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Pipeline, Recorder,
};
use crate::render::uniforms::ViewIndex;
use crate::render::ViewMode;
use crate::shaders;

pub struct TexturesViewPass {
    pipeline: Pipeline,
}

impl TexturesViewPass {
    /// Draws into the main target (`display_format`).
    pub fn new(
        ctx: &Arc<Context>,
        frame_layout: &DescriptorSetLayout,
        textures: &WaterTextures,
        display_format: vk::Format,
    ) -> GpuResult<TexturesViewPass> {
        let layout = scene_layout(
            ctx,
            "textures view layout",
            frame_layout,
            &[&textures.layout],
        )?;
        let pipeline = scene_pipeline(
            ctx,
            &layout,
            GraphicsDesc {
                name: "textures view",
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
            SceneTarget::Display(display_format),
        )?;
        Ok(TexturesViewPass { pipeline })
    }

    /// Whether `view` is one this pass draws.
    pub fn shows(view: ViewMode) -> bool {
        matches!(
            view,
            ViewMode::Reflection | ViewMode::Refraction | ViewMode::Dudv
        )
    }

    /// What `record` binds: its pipeline with `sets` (the frame set, the water's textures).
    pub fn draw<'a>(&'a self, sets: &'a [&'a BoundSet]) -> Bindings<'a> {
        Bindings {
            pipeline: &self.pipeline,
            sets,
        }
    }

    /// Draws the texture `--view` names over the whole main target, inside a rendering scope
    /// with the main colour attachment only that declared `draw(sets)`.
    pub fn record(&self, rec: &Recorder, sets: &[&BoundSet]) {
        bind_scene(rec, &self.draw(sets), ViewIndex::Main);
        rec.draw(3, 1);
    }
}
