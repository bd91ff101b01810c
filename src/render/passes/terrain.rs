//! Terrain pass: the procedural island (shaders/terrain/terrain.vert, heights from
//! shaders/common/terrain.glsl) and the objects standing in the water (objects.vert: capped
//! cylinders, one instance each), lit by terrain.frag. Drawn in every view, with the view's clip
//! plane.

use std::sync::Arc;

use ash::vk;

use super::{bind_scene, scene_layout, scene_pipeline, Depth};
use crate::gpu::oneshot::upload;
use crate::gpu::{
    Buffer, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, MemoryLocation, Pipeline,
    PipelineLayout, Recorder,
};
use crate::render::camera::ViewIndex;
use crate::shaders;

/// Cylinder segments of an object (`SEGMENTS` in objects.vert), 9 vertices each.
const OBJECT_SEGMENTS: u32 = 20;
/// Entries of `FrameUniforms::objects`.
const OBJECTS: u32 = 4;

pub struct TerrainPass {
    /// Grid quads per side (`--terrain-grid`; `TERRAIN_QUADS`, specialization constant 0 of
    /// shaders/common/terrain.glsl).
    quads: u32,
    /// Two triangles per grid quad over the (quads + 1)² lattice, row by row: each lattice
    /// vertex is shaded once per batch instead of six times (lavapipe's vertex stage runs on
    /// one CPU thread, so this matters in every view).
    indices: Buffer,
    layout: PipelineLayout,
    terrain: Pipeline,
    objects: Pipeline,
}

impl TerrainPass {
    /// `quads`: grid quads per side of the island's lattice.
    pub fn new(
        ctx: &Arc<Context>,
        frame_layout: &DescriptorSetLayout,
        quads: u32,
    ) -> GpuResult<TerrainPass> {
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
                    constants: &[quads],
                    ..Default::default()
                },
                Depth::TestWrite,
            )
        };
        let terrain = pipeline("terrain", shaders::TERRAIN_TERRAIN_VERT)?;
        let objects = pipeline("objects", shaders::TERRAIN_OBJECTS_VERT)?;
        let lattice = |x: u32, z: u32| z * (quads + 1) + x;
        let mut list = Vec::with_capacity((quads * quads * 6) as usize);
        for z in 0..quads {
            for x in 0..quads {
                // The corners of terrain.vert's former CORNERS table: (0,0) (1,1) (1,0), (0,0) (0,1) (1,1).
                list.extend([
                    lattice(x, z),
                    lattice(x + 1, z + 1),
                    lattice(x + 1, z),
                    lattice(x, z),
                    lattice(x, z + 1),
                    lattice(x + 1, z + 1),
                ]);
            }
        }
        let bytes: &[u8] = bytemuck::cast_slice(&list);
        let indices = Buffer::new(
            ctx,
            "terrain indices",
            bytes.len() as u64,
            vk::BufferUsageFlags::INDEX_BUFFER | vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuOnly,
        )?;
        upload(ctx, &indices, bytes)?;
        Ok(TerrainPass {
            quads,
            indices,
            layout,
            terrain,
            objects,
        })
    }

    /// Draws the island and the objects inside a scene rendering scope.
    pub fn record(&self, rec: &Recorder, frame_set: vk::DescriptorSet, view: ViewIndex) {
        bind_scene(rec, &self.terrain, &self.layout, &[frame_set], view);
        rec.bind_index_buffer(&self.indices);
        rec.draw_indexed(self.quads * self.quads * 6, 1);
        bind_scene(rec, &self.objects, &self.layout, &[frame_set], view);
        rec.draw(OBJECT_SEGMENTS * 9, OBJECTS);
    }
}
