//! Terrain pass: the procedural island (shaders/terrain/terrain.vert, heights from
//! shaders/common/terrain.glsl) and the objects standing in the water (objects.vert: capped
//! cylinders, one instance each), lit by terrain.frag. Drawn in every view, with the view's clip
//! plane.

use std::sync::Arc;

use ash::vk;

use super::{bind_scene, scene_layout, scene_pipeline};
use crate::gpu::{
    Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Pipeline, PipelineLayout, Recorder,
};
use crate::render::camera::ViewIndex;
use crate::shaders;

/// Grid quads per side (`TERRAIN_QUADS` in shaders/common/terrain.glsl).
pub const TERRAIN_QUADS: u32 = 160;
/// Cylinder segments of an object (`SEGMENTS` in objects.vert), 9 vertices each.
const OBJECT_SEGMENTS: u32 = 20;
/// Entries of `FrameUniforms::objects`.
const OBJECTS: u32 = 4;

pub struct TerrainPass {
    layout: PipelineLayout,
    terrain: Pipeline,
    objects: Pipeline,
}

impl TerrainPass {
    pub fn new(ctx: &Arc<Context>, frame_layout: &DescriptorSetLayout) -> GpuResult<TerrainPass> {
        let layout = scene_layout(ctx, "terrain layout", frame_layout, &[])?;
        let pipeline = |name, vert| {
            scene_pipeline(
                ctx,
                &layout,
                GraphicsDesc {
                    name,
                    stages: &[
                        (vk::ShaderStageFlags::VERTEX, vert),
                        (
                            vk::ShaderStageFlags::FRAGMENT,
                            shaders::TERRAIN_TERRAIN_FRAG,
                        ),
                    ],
                    ..Default::default()
                },
                true,
            )
        };
        let terrain = pipeline("terrain", shaders::TERRAIN_TERRAIN_VERT)?;
        let objects = pipeline("objects", shaders::TERRAIN_OBJECTS_VERT)?;
        Ok(TerrainPass {
            layout,
            terrain,
            objects,
        })
    }

    /// Draws the island and the objects inside a scene rendering scope.
    pub fn record(&self, rec: &Recorder, frame_set: vk::DescriptorSet, view: ViewIndex) {
        bind_scene(rec, &self.terrain, &self.layout, &[frame_set], view);
        rec.draw(TERRAIN_QUADS * TERRAIN_QUADS * 6, 1);
        bind_scene(rec, &self.objects, &self.layout, &[frame_set], view);
        rec.draw(OBJECT_SEGMENTS * 9, OBJECTS);
    }
}
