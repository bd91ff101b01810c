//! Terrain pass: the procedural island (shaders/terrain/terrain.vert, heights from
//! shaders/common/terrain.glsl), the objects standing in the water (objects.vert: capped
//! cylinders, one instance each) and the floating bodies (bodies.vert, `--bodies`), lit by
//! terrain.frag. Drawn in every view, with the view's clip
//! plane. The reflection and refraction views draw a coarser mesh over the same lattice (every
//! other lattice point): they render at `--rtt-scale`, blurred by the waves' distortion, and a
//! CPU driver pays for every triangle on one thread.

use std::sync::Arc;

use ash::vk;

use super::water::WaterKind;
use super::{
    bind_scene, lattice_triangles, scene_layout, scene_pipeline, Depth, Mesh, PerTarget,
    SceneTarget,
};
use crate::gpu::{
    Bindings, BoundSet, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Pipeline, Recorder,
};
use crate::render::uniforms::ViewIndex;
use crate::shaders;

/// Cylinder segments of an object (`SEGMENTS` in objects.vert), 9 vertices each.
const OBJECT_SEGMENTS: u32 = 20;
/// Entries of `FrameUniforms::objects`.
const OBJECTS: u32 = 4;
/// Vertices of each shape of floating body (bodies.vert): a box, a boat, a buoy's 12-sided
/// prism.
const BODY_VERTICES: [u32; 3] = [36, 54, 144];

pub struct TerrainPass {
    /// Index buffers over the (quads + 1)² lattice, two triangles per cell, row by row: each
    /// lattice vertex is shaded once per batch instead of six times (lavapipe's vertex stage
    /// runs on one CPU thread, so this matters in every view). The main view's cells are one
    /// lattice step wide, the HDR views' (reflection, refraction) two.
    meshes: PerTarget<Mesh>,
    /// Island and objects with the caustics (terrain_caustics.frag): into HDR (refraction;
    /// terrain.frag when it draws none, `WaterKind::refraction_caustics`) and into the main
    /// target (from under the water). They sample the simulation's images.
    caustics: PerTarget<[Pipeline; 3]>,
    /// Island and objects without them (terrain.frag): the reflection, which reads nothing the
    /// simulation wrote, so it draws before the simulation is waited for (graphics 1), and the
    /// main view from above the water, where the drowned terrain lies under the water's
    /// surface (the caustic shader's untaken branch cost lavapipe 1.4 ms there at low).
    plain: PerTarget<[Pipeline; 3]>,
}

impl TerrainPass {
    /// `quads`: grid quads per side of the island's lattice; `display_format`: the main
    /// target's; `ocean`: how terrain.frag samples the ocean images for the caustics (its
    /// cascades and filter; the geometry is the water's own).
    pub fn new(
        ctx: &Arc<Context>,
        frame_layout: &DescriptorSetLayout,
        quads: u32,
        display_format: vk::Format,
        ocean: WaterKind,
    ) -> GpuResult<TerrainPass> {
        let layout = scene_layout(ctx, "terrain layout", frame_layout, &[])?;
        // `caustics`: terrain_caustics.frag or terrain.frag; `materials`: common/terrain_lit.glsl's
        // TERRAIN_MATERIALS. Its TERRAIN_UNDERWATER is on only for the one pipeline that can
        // see from under the water: the caustics' into the main target.
        let pipeline = |name: &str, vert: &[u8], target, caustics: bool, materials: bool| {
            let frag = if caustics {
                shaders::TERRAIN_TERRAIN_CAUSTICS_FRAG
            } else {
                shaders::TERRAIN_TERRAIN_FRAG
            };
            let underwater = caustics && matches!(target, SceneTarget::Display(_));
            scene_pipeline(
                ctx,
                &layout,
                GraphicsDesc {
                    name,
                    stages: &[
                        (vk::ShaderStageFlags::VERTEX, vert),
                        (vk::ShaderStageFlags::FRAGMENT, frag),
                    ],
                    // common/water.glsl's CASCADES and OCEAN_MANUAL_FILTER,
                    // common/terrain_lit.glsl's TERRAIN_MATERIALS, terrain.vert's
                    // TERRAIN_QUADS, common/shadow.glsl's SHADOWS,
                    // common/terrain_lit.glsl's TERRAIN_UNDERWATER, common/water.glsl's
                    // SLOPE_MIPS (the caustics' low-pass).
                    constants: &[
                        ocean.cascades,
                        ocean.manual_filter as u32,
                        materials as u32,
                        quads,
                        ocean.shadows as u32,
                        underwater as u32,
                        ocean.slope_mips as u32,
                    ],
                    ..Default::default()
                },
                Depth::TestWrite,
                target,
            )
        };
        let pair = |label: &str, target, caustics, materials| -> GpuResult<[Pipeline; 3]> {
            let [terrain, objects, bodies] = [
                ("terrain", shaders::TERRAIN_TERRAIN_VERT),
                ("objects", shaders::TERRAIN_OBJECTS_VERT),
                ("floating bodies", shaders::TERRAIN_BODIES_VERT),
            ]
            .map(|(what, vert)| {
                pipeline(
                    &format!("{what} ({label})"),
                    vert,
                    target,
                    caustics,
                    materials,
                )
            });
            Ok([terrain?, objects?, bodies?])
        };
        let caustics = PerTarget::new(display_format, |target| {
            let label = match target {
                SceneTarget::Hdr => "refraction",
                SceneTarget::Display(_) => "main view, under the water",
            };
            // The refraction view leaves the materials out: it sees the sea floor. Without its
            // caustics (`WaterKind::refraction_caustics`) it draws without the caustics'
            // shader, not with their branch off by a uniform: lavapipe runs a branch taken or
            // not (2 ms a frame at --quality low). The main view from under the water keeps
            // the shader (`--caustics off` there is the uniform's: its light shafts too).
            let display = matches!(target, SceneTarget::Display(_));
            pair(label, target, display || ocean.refraction_caustics, display)
        })?;
        let plain = PerTarget::new(display_format, |target| {
            let label = match target {
                SceneTarget::Hdr => "reflection",
                SceneTarget::Display(_) => "main view",
            };
            pair(label, target, false, true)
        })?;
        let meshes = PerTarget::new(display_format, |target| {
            let step = match target {
                SceneTarget::Hdr => 2,
                SceneTarget::Display(_) => 1,
            };
            let name = format!("terrain indices ({})", target.label());
            Mesh::new(ctx, &name, &lattice_triangles(quads, step))
        })?;
        Ok(TerrainPass {
            meshes,
            caustics,
            plain,
        })
    }

    /// What `record` binds for `view`: the island's, the objects' and the floating bodies'
    /// pipelines with `sets`
    /// (the frame set); the caustics in the refraction (where it draws them), and in the main
    /// view when the camera is `underwater`.
    pub fn draws<'a>(
        &'a self,
        sets: &'a [&'a BoundSet],
        view: ViewIndex,
        underwater: bool,
    ) -> [Bindings<'a>; 3] {
        let pipelines = match view {
            ViewIndex::Refraction => &self.caustics,
            ViewIndex::Main if underwater => &self.caustics,
            _ => &self.plain,
        }
        .for_view(view);
        pipelines
            .each_ref()
            .map(|pipeline| Bindings { pipeline, sets })
    }

    /// Draws the island, the objects and the floating bodies (`bodies`: how many of each
    /// shape, in that order in the bodies' block) inside a scene rendering scope that declared
    /// `draws(sets, view, underwater)`.
    pub fn record(
        &self,
        rec: &Recorder,
        sets: &[&BoundSet],
        view: ViewIndex,
        underwater: bool,
        bodies: [u32; 3],
    ) {
        let [terrain, objects, floating] = self.draws(sets, view, underwater);
        let mesh = self.meshes.for_view(view);
        bind_scene(rec, &terrain, view);
        rec.bind_index_buffer(&mesh.buffer);
        rec.draw_indexed(mesh.count, 1);
        bind_scene(rec, &objects, view);
        rec.draw(OBJECT_SEGMENTS * 9, OBJECTS);
        if bodies.iter().any(|&n| n > 0) {
            bind_scene(rec, &floating, view);
            let mut first = 0;
            for (n, vertices) in bodies.into_iter().zip(BODY_VERTICES) {
                if n > 0 {
                    rec.draw_instances(vertices, n, first);
                }
                first += n;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::lattice_triangles;

    /// Area of the triangles in lattice units (both windings count as positive).
    fn area(quads: u32, indices: &[u32]) -> f64 {
        let point = |i: u32| ((i % (quads + 1)) as f64, (i / (quads + 1)) as f64);
        indices
            .chunks_exact(3)
            .map(|t| {
                let (a, b, c) = (point(t[0]), point(t[1]), point(t[2]));
                ((b.0 - a.0) * (c.1 - a.1) - (c.0 - a.0) * (b.1 - a.1)).abs() / 2.0
            })
            .sum()
    }

    #[test]
    fn both_meshes_span_the_lattice_with_its_area_and_corner() {
        for quads in [16, 17, 64, 161] {
            let full = (quads * quads) as f64;
            let fine = lattice_triangles(quads, 1);
            let coarse = lattice_triangles(quads, 2);
            assert_eq!(fine.len() as u32, quads * quads * 6);
            assert_eq!(coarse.len() as u32, quads.div_ceil(2).pow(2) * 6);
            assert!((area(quads, &fine) - full).abs() < 1e-9, "quads {quads}");
            assert!((area(quads, &coarse) - full).abs() < 1e-9, "quads {quads}");
            let last = (quads + 1) * (quads + 1) - 1;
            assert!(coarse.iter().all(|&i| i <= last) && coarse.contains(&last));
        }
    }
}
