//! Water pass: the ocean surface in one of two geometries ([`Geometry`], `--geometry`), shaded
//! by one fragment shader (shaders/surface/water.frag) from one vertex routine
//! (shaders/common/water_vertex.glsl):
//! - tessellated: patches (shaders/surface/water.vert/.tesc/.tese, layout in
//!   shaders/common/water.glsl) whose control shader picks each edge's level from its screen
//!   size and culls patches outside the frustum; the evaluation shader displaces the vertices;
//! - clipmap: world-fixed grid tiles chosen per frame on the CPU by distance and frustum
//!   (`render::clipmap`, CDLOD), one index buffer drawn once per tile
//!   (shaders/surface/water_clipmap.vert, which morphs and displaces the vertices); the tile
//!   list is set 2, one host-written buffer per frame slot.
//!
//! The fragment shader shades with the reflection and refraction textures (set 1,
//! [`WaterTextures`], rewritten on resize), the DU/DV map and the sky cube. The same set feeds
//! the texture debug views (`textures_view.rs`).

use std::sync::Arc;

use ash::vk;

use super::{
    bind_scene, lattice_triangles, scene_layout, scene_pipeline, Depth, Mesh, SceneTarget,
};
use crate::gpu::{
    Bind, Bindings, BoundSet, Buffer, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Image,
    MemoryLocation, Order, Pipeline, Recorder, Sampler, FRAMES_IN_FLIGHT,
};
use crate::render::camera::Camera;
use crate::render::clipmap;
use crate::render::targets::Targets;
use crate::render::uniforms::{ViewIndex, WaterFrame, WaterSide, WATER_LEVEL_M};
use crate::render::{Geometry, ViewMode};
use crate::shaders;

/// Patches per side (shared with water.vert).
pub use crate::shared::PATCHES;

/// Samplers the water's textures use.
pub struct WaterSamplers<'a> {
    /// Linear, clamped: reflection (all its layers: colour, distances and sky) and refraction
    /// colour.
    pub clamp: &'a Sampler,
    /// Nearest, clamped: the refraction's depth.
    pub depth: &'a Sampler,
    /// Linear, repeating: the DU/DV map.
    pub repeat: &'a Sampler,
}

/// The water's textures (set 1 of the water and of the textures view): reflection colour,
/// refraction colour and depth, the DU/DV map, the reflection's distances and sky.
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
                (4, sampled, fragment),
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
        // Each tracked: the passes that sample them wait for their writers (the reflection
        // pass in graphics 1, the refraction pass in graphics 2, the DU/DV map's upload).
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
                (4, Bind::Sampled(&targets.reflection_sky, samplers.clamp, t)),
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
    /// The geometry the pipelines draw.
    geometry: Geometry,
    fill: Pipeline,
    /// The surface seen from under the water (the camera's near plane below it): its own
    /// pipeline (specialization constant 2 of water.frag), because lavapipe pays for a branch
    /// it does not take (6 ms a frame at --quality low when one shader held both views).
    from_below: Pipeline,
    /// The surface from either side, pixel by pixel, when it crosses the near plane.
    waterline: Pipeline,
    /// The debug views that show the water's data (`--view displacement`, `normals`, `foam`,
    /// `crests`, `triangles`; `wireframe` where the device draws no lines): water.frag's
    /// DEBUG_VIEWS (constant 3), whose branches the three above leave out.
    debug: Pipeline,
    /// Line rendering (`--view wireframe`), when the device has fillModeNonSolid.
    wireframe: Option<Pipeline>,
    textures: WaterTextures,
    /// The clipmap's mesh and tile lists (`Geometry::Clipmap`).
    clipmap: Option<ClipmapTiles>,
}

/// What the clipmap geometry draws with: the tile meshes and, per frame slot, the tile list.
struct ClipmapTiles {
    /// For each tile size `quarter` = 1, 2, 4, 8, 16 cells (index log2 quarter): two triangles
    /// per cell of the (quarter + 1)² lattice. Each frame picks the size its screen asks for
    /// (`clipmap::Layout::for_screen`), so a resize or another `--tess-edge` needs no new pass.
    meshes: Vec<Mesh>,
    /// Per slot: the tile buffer (`Tiles` in water_clipmap.vert) and its set (set 2).
    slots: Vec<(Buffer, BoundSet)>,
    /// Per slot: the tiles written for its frame and their size (quarter).
    counts: Vec<(u32, u32)>,
    /// The bytes written into a slot's buffer, kept between frames (no allocation per frame).
    scratch: Vec<u8>,
    _layout: DescriptorSetLayout,
}

/// The header of a slot's tile buffer (`Tiles` in water_clipmap.vert): the tile size (a uvec4),
/// the morph table; the tiles, a vec4 each, follow it.
const TILE_HEADER_BYTES: usize = 16 + clipmap::MAX_LEVELS * 16;

/// What one frame's clipmap tiles are chosen from.
pub struct TileView<'a> {
    pub camera: &'a Camera,
    /// Width over height of the output.
    pub aspect: f32,
    /// The main target's focal length (px): cells are sized for it.
    pub focal_px: f32,
    /// The narrowest cell on screen (px): `--tess-edge`.
    pub cell_px: f32,
    /// How far the waves move a point (m): the culling margin.
    pub reach_m: f32,
}

impl ClipmapTiles {
    fn new(ctx: &Arc<Context>, layout: DescriptorSetLayout) -> GpuResult<ClipmapTiles> {
        let sizes = clipmap::MIN_QUARTER.ilog2()..=clipmap::MAX_QUARTER.ilog2();
        let meshes = sizes
            .map(|log2| {
                let quarter = 1 << log2;
                let name = format!("water clipmap tile indices ({quarter}x{quarter})");
                Mesh::new(ctx, &name, &lattice_triangles(quarter, 1))
            })
            .collect::<GpuResult<Vec<_>>>()?;
        let bytes = (TILE_HEADER_BYTES + clipmap::MAX_TILES * 16) as u64;
        let mut slots = Vec::new();
        for slot in 0..FRAMES_IN_FLIGHT {
            let buffer = Buffer::new(
                ctx,
                &format!("water clipmap tiles slot {slot}"),
                bytes,
                vk::BufferUsageFlags::STORAGE_BUFFER,
                MemoryLocation::CpuToGpu,
            )?;
            let set = BoundSet::new(
                ctx,
                &layout,
                &format!("water clipmap tiles set slot {slot}"),
                &[(0, Bind::Storage(&buffer, Order::Host))],
            )?;
            slots.push((buffer, set));
        }
        Ok(ClipmapTiles {
            meshes,
            slots,
            counts: vec![(0, 1); FRAMES_IN_FLIGHT],
            scratch: Vec::new(),
            _layout: layout,
        })
    }

    /// Chooses this frame's tiles and writes them into `slot`'s buffer (its previous frame
    /// has finished: `Frames::begin` waited for it).
    fn write(&mut self, slot: usize, view: &TileView) {
        let layout = clipmap::Layout::for_screen(f64::from(view.cell_px), f64::from(view.focal_px));
        let camera = view.camera;
        let position = camera.position.as_dvec3();
        let centre = WaterFrame::around([position.x, position.z]).centre;
        let tiles = clipmap::select(
            &layout,
            &clipmap::Viewer {
                xz: [position.x, position.z],
                height_m: position.y - f64::from(WATER_LEVEL_M),
                view_proj: Some(camera.view_proj(view.aspect)),
                reach_m: f64::from(view.reach_m),
            },
        );
        let bytes = &mut self.scratch;
        bytes.clear();
        bytes.extend_from_slice(bytemuck::cast_slice(&[layout.quarter, 0, 0, 0]));
        bytes.extend_from_slice(bytemuck::cast_slice(&layout.morph_table()));
        for t in &tiles {
            let corner = [0, 1].map(|i| (t.corner_m[i] - centre[i]) as f32);
            let row = [
                corner[0],
                corner[1],
                layout.cell_m(t.level) as f32,
                t.packed_level(&layout),
            ];
            bytes.extend_from_slice(bytemuck::cast_slice(&row));
        }
        self.slots[slot].0.write(bytes);
        self.counts[slot] = (tiles.len() as u32, layout.quarter);
    }
}

/// What the water's pipelines are made for (and the terrain's, which sample the same images).
#[derive(Clone, Copy, Debug)]
pub struct WaterKind {
    /// How the triangles are made (tessellated needs the device's tessellation shaders).
    pub geometry: Geometry,
    /// Layers of the ocean images (a specialization constant: the loop bound of the vertex and
    /// fragment shaders).
    pub cascades: u32,
    /// The ocean images are bound with a nearest sampler and the shaders filter them
    /// bilinearly by hand (devices without linear filtering of RGBA32F).
    pub manual_filter: bool,
    /// The sun's shadows are cast (`--shadows`): common/shadow.glsl's SHADOWS, constant 4 of
    /// the water's, the terrain's and the light shafts' shaders, so a run without them does
    /// not pay for their untaken branch (lavapipe runs both sides).
    pub shadows: bool,
    /// The refraction view draws the caustics (`--caustics`, `Quality::refraction_caustics`):
    /// without them its terrain is drawn without the caustics' shader
    /// (src/render/passes/terrain.rs).
    pub refraction_caustics: bool,
    /// The run has a boat and its wake (`--boat`): common/water.glsl's WAKE, constant 7 of the
    /// water's shaders (without it `wake_at` is zero, its lookups left out).
    pub wake: bool,
    /// The normal images have mip levels: common/water.glsl's SLOPE_MIPS (constant 6 of the
    /// water's, the terrain's and the light shafts' shaders). water.frag looks each cascade up
    /// at the pixel's footprint along the view and across it, and the caustics low-pass each
    /// cascade with them (src/ocean/simulation/slope_mips.rs).
    pub slope_mips: bool,
}

impl WaterPass {
    /// The pass for `kind`, drawing into the main target (`targets.display_format`).
    // Long: both geometries' shader stages and set layouts, and the three pipelines of each.
    pub fn new(
        ctx: &Arc<Context>,
        frame_layout: &DescriptorSetLayout,
        targets: &Targets,
        dudv: &Image,
        samplers: &WaterSamplers,
        kind: WaterKind,
    ) -> anyhow::Result<WaterPass> {
        let WaterKind {
            geometry,
            cascades,
            manual_filter,
            shadows,
            wake,
            slope_mips,
            ..
        } = kind;
        if geometry == Geometry::Tessellated && !ctx.info.tessellation_shader {
            anyhow::bail!(
                "--geometry tessellated: {} has no tessellation shaders (tessellationShader); \
                 --geometry clipmap draws the same sea without them",
                ctx.info.name
            );
        }
        let target = SceneTarget::Display(targets.display_format());
        let textures = WaterTextures::new(ctx, targets, dudv, samplers)?;
        let (stages, clipmap, layout) = match geometry {
            Geometry::Tessellated => {
                let layout = scene_layout(ctx, "water layout", frame_layout, &[&textures.layout])?;
                let stages = vec![
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
                (stages, None, layout)
            }
            Geometry::Clipmap => {
                let tile_layout = DescriptorSetLayout::new(
                    ctx,
                    "water clipmap tiles layout",
                    &[(
                        0,
                        vk::DescriptorType::STORAGE_BUFFER,
                        vk::ShaderStageFlags::VERTEX,
                    )],
                )?;
                let layout = scene_layout(
                    ctx,
                    "water clipmap layout",
                    frame_layout,
                    &[&textures.layout, &tile_layout],
                )?;
                let stages = vec![
                    (
                        vk::ShaderStageFlags::VERTEX,
                        shaders::SURFACE_WATER_CLIPMAP_VERT,
                    ),
                    (vk::ShaderStageFlags::FRAGMENT, shaders::SURFACE_WATER_FRAG),
                ];
                (stages, Some(ClipmapTiles::new(ctx, tile_layout)?), layout)
            }
        };
        let (topology, patch_control_points) = match geometry {
            Geometry::Tessellated => (vk::PrimitiveTopology::PATCH_LIST, 4),
            Geometry::Clipmap => (vk::PrimitiveTopology::TRIANGLE_LIST, 0),
        };
        // `side`: water.frag's UNDERWATER_VIEW (0 above, 1 below, 2 split at the waterline);
        // `debug`: its DEBUG_VIEWS.
        let pipeline = |name: &str, polygon_mode, side: u32, debug: bool| {
            scene_pipeline(
                ctx,
                &layout,
                GraphicsDesc {
                    name: &format!("{name} ({})", geometry.name()),
                    stages: &stages,
                    topology,
                    patch_control_points,
                    polygon_mode,
                    // common/water.glsl's CASCADES and OCEAN_MANUAL_FILTER, water.frag's
                    // UNDERWATER_VIEW and DEBUG_VIEWS, common/shadow.glsl's SHADOWS, (5
                    // unused), common/water.glsl's SLOPE_MIPS and WAKE.
                    constants: &[
                        cascades,
                        manual_filter as u32,
                        side,
                        debug as u32,
                        shadows as u32,
                        0,
                        slope_mips as u32,
                        wake as u32,
                    ],
                    ..Default::default()
                },
                Depth::TestWrite,
                target,
            )
        };
        let fill = pipeline("water", vk::PolygonMode::FILL, 0, false)?;
        let from_below = pipeline("water from below", vk::PolygonMode::FILL, 1, false)?;
        let waterline = pipeline("water at the waterline", vk::PolygonMode::FILL, 2, false)?;
        let debug = pipeline("water debug views", vk::PolygonMode::FILL, 0, true)?;
        let wireframe = if ctx.info.fill_mode_non_solid {
            Some(pipeline("water wireframe", vk::PolygonMode::LINE, 0, true)?)
        } else {
            None
        };
        Ok(WaterPass {
            geometry,
            fill,
            from_below,
            waterline,
            debug,
            wireframe,
            textures,
            clipmap,
        })
    }

    /// The geometry it draws (another needs a new pass; the clipmap's cell size and the
    /// screen's follow per frame).
    pub fn geometry(&self) -> Geometry {
        self.geometry
    }

    /// The reflection, refraction and DU/DV textures the water samples.
    pub fn textures(&self) -> &WaterTextures {
        &self.textures
    }

    /// The sets a frame in `slot` draws the water with: the frame set, the textures and, for
    /// the clipmap, the slot's tile list.
    pub fn sets<'a>(&'a self, frame: &'a BoundSet, slot: usize) -> Vec<&'a BoundSet> {
        let mut sets = vec![frame, &self.textures.set];
        sets.extend(self.clipmap.as_ref().map(|c| &c.slots[slot].1));
        sets
    }

    /// Chooses the clipmap's tiles for the frame in `slot` (nothing to do when tessellated).
    pub fn prepare(&mut self, slot: usize, view: &TileView) {
        if let Some(tiles) = &mut self.clipmap {
            tiles.write(slot, view);
        }
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
        [&self.fill, &self.from_below, &self.waterline, &self.debug]
            .into_iter()
            .chain(self.wireframe.as_ref())
    }

    /// Whether `view` shows the water's own data (water.frag's DEBUG_VIEWS branches).
    fn debug_view(view: ViewMode) -> bool {
        matches!(
            view,
            ViewMode::Displacement
                | ViewMode::Normals
                | ViewMode::Foam
                | ViewMode::Wireframe
                | ViewMode::Crests
                | ViewMode::Triangles
        )
    }

    /// Whether `--view wireframe` can draw lines on this device.
    pub fn has_wireframe(&self) -> bool {
        self.wireframe.is_some()
    }

    /// What `record` binds: the pipeline for `view` (lines for `ViewMode::Wireframe` where the
    /// device draws lines; the debug views' for the views of the water's data, from either
    /// side, as they return before the side matters (`crests` draws none from below, where
    /// the final picture has none); else filled, as seen from the camera's
    /// `side`) with `sets` ([`WaterPass::sets`]).
    pub fn draw<'a>(
        &'a self,
        sets: &'a [&'a BoundSet],
        view: ViewMode,
        side: WaterSide,
    ) -> Bindings<'a> {
        let pipeline = match (&self.wireframe, view, side) {
            (Some(lines), ViewMode::Wireframe, _) => lines,
            (_, v, _) if WaterPass::debug_view(v) => &self.debug,
            (_, _, WaterSide::Above) => &self.fill,
            (_, _, WaterSide::Below) => &self.from_below,
            (_, _, WaterSide::Split) => &self.waterline,
        };
        Bindings { pipeline, sets }
    }

    /// Draws the ocean inside the main rendering scope, which declared
    /// `draw(sets, view, side)`; `slot`: the frame's (the clipmap's tile list).
    pub fn record(
        &self,
        rec: &Recorder,
        sets: &[&BoundSet],
        view: ViewMode,
        side: WaterSide,
        slot: usize,
    ) {
        bind_scene(rec, &self.draw(sets, view, side), ViewIndex::Main);
        match &self.clipmap {
            // One instance per row of patches (see water.vert).
            None => rec.draw(PATCHES * 4, PATCHES),
            Some(tiles) => {
                let (count, quarter) = tiles.counts[slot];
                let mesh = &tiles.meshes[quarter.ilog2() as usize];
                rec.bind_index_buffer(&mesh.buffer);
                rec.draw_indexed(mesh.count, count);
            }
        }
    }
}
