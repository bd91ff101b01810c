//! One struct per pass, each owning its pipelines and layouts, with `new` and `record`
//! (and `resize` where the pass holds size-dependent descriptors).
//!
//! The scene passes (sky, terrain, water) share the frame set (set 0: uniforms, ocean images,
//! sky cube) and a push constant picking the view (`ViewIndex`). They draw linear HDR radiance
//! into the reflection and refraction textures and tone-mapped display colour into the main
//! target ([`SceneTarget`], shaders/common/display.glsl), so terrain and sky have a pipeline for
//! each. `textures_view` shows a texture full screen (`--view`); `anti_aliasing` smooths the
//! main target's edges into a target of its own (`--aa fxaa`); `output` puts the main (or the
//! anti-aliased) target into the output image. `spray` draws the spray's particles over the
//! main view (a set of its own: the particles).

pub mod anti_aliasing;
pub mod caustic_means;
pub mod output;
pub mod reflection_distance;
pub mod shafts;
pub mod sky;
pub mod spray;
pub mod terrain;
pub mod textures_view;
pub mod water;

use std::sync::Arc;

use ash::vk;

pub use anti_aliasing::AntiAliasingPass;
pub use caustic_means::CausticMeansPass;
pub use reflection_distance::ReflectionDistancePass;
pub use shafts::{shafts_pass, ShaftsPass};
pub use sky::{SkyCube, SkyPass};
pub use spray::SprayPass;
pub use terrain::TerrainPass;
pub use textures_view::TexturesViewPass;
pub use water::WaterPass;

use crate::gpu::oneshot::{run_once, upload_then};
use crate::gpu::{
    Bindings, BoundSet, Buffer, Context, DescriptorSetLayout, GpuResult, GraphicsDesc, Image,
    ImageDesc, Load, MemoryLocation, Pipeline, PipelineLayout, Recorder, Target, Use,
};
use crate::render::targets::{DEPTH_FORMAT, HDR_FORMAT};
use crate::render::uniforms::ViewIndex;
use crate::shaders;

/// Push constants of the scene shaders (`Pass` in shaders/common/frame.glsl).
#[repr(C)]
#[derive(Clone, Copy, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ViewPush {
    pub view: u32,
}

/// A pipeline layout for scene shaders: the frame set, then `extra` sets, and the view push
/// constant.
pub fn scene_layout(
    ctx: &Arc<Context>,
    name: &str,
    frame_layout: &DescriptorSetLayout,
    extra: &[&DescriptorSetLayout],
) -> GpuResult<PipelineLayout> {
    let mut sets = vec![frame_layout];
    sets.extend_from_slice(extra);
    PipelineLayout::new(
        ctx,
        name,
        &sets,
        Some((
            vk::ShaderStageFlags::ALL_GRAPHICS,
            std::mem::size_of::<ViewPush>() as u32,
        )),
    )
}

/// How a scene pipeline uses the depth buffer (reversed-Z: cleared to 0, the far plane).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Depth {
    /// Geometry: nearer wins, and writes its depth.
    TestWrite,
    /// The background (sky) at the far plane, drawn last: only where nothing was drawn, so
    /// covered pixels are never shaded.
    Background,
    /// Translucent draws (the spray): tested against what was drawn, writing no depth.
    Test,
    /// No depth attachment (full-screen debug views).
    None,
}

/// What a scene pipeline draws into.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SceneTarget {
    /// Linear radiance (`HDR_FORMAT`): the reflection and refraction textures.
    Hdr,
    /// Tone-mapped colour in this 8-bit format: the main target (the output's format; sRGB, or
    /// UNORM with the encoding done by the shaders).
    Display(vk::Format),
}

impl SceneTarget {
    pub fn format(self) -> vk::Format {
        match self {
            SceneTarget::Hdr => HDR_FORMAT,
            SceneTarget::Display(format) => format,
        }
    }

    /// `DISPLAY_TARGET` of shaders/common/display.glsl: 0 HDR, 1 display colour encoded by an
    /// sRGB attachment, 2 display colour the shader encodes (a UNORM target).
    pub fn display_mode(self) -> u32 {
        match self {
            SceneTarget::Hdr => 0,
            SceneTarget::Display(format) if is_srgb(format) => 1,
            SceneTarget::Display(_) => 2,
        }
    }

    /// For object names: "hdr" or "main view".
    pub fn label(self) -> &'static str {
        match self {
            SceneTarget::Hdr => "hdr",
            SceneTarget::Display(_) => "main view",
        }
    }
}

/// One `T` per scene target (pipelines, meshes), picked by the view a draw renders: the main
/// view draws into the display target, the reflection and refraction views into HDR textures.
pub struct PerTarget<T> {
    hdr: T,
    display: T,
}

impl<T> PerTarget<T> {
    /// `make` builds the `T` of a target.
    pub fn new(
        display_format: vk::Format,
        mut make: impl FnMut(SceneTarget) -> GpuResult<T>,
    ) -> GpuResult<PerTarget<T>> {
        Ok(PerTarget {
            hdr: make(SceneTarget::Hdr)?,
            display: make(SceneTarget::Display(display_format))?,
        })
    }

    pub fn for_view(&self, view: ViewIndex) -> &T {
        match view {
            ViewIndex::Main => &self.display,
            ViewIndex::Reflection | ViewIndex::Refraction => &self.hdr,
        }
    }
}

/// An 8-bit sRGB format (the attachment write encodes).
pub fn is_srgb(format: vk::Format) -> bool {
    matches!(
        format,
        vk::Format::R8G8B8A8_SRGB | vk::Format::B8G8R8A8_SRGB | vk::Format::A8B8G8R8_SRGB_PACK32
    )
}

/// `constant_id` of `DISPLAY_TARGET` (shaders/common/display.glsl): scene shaders keep ids
/// below it for their own constants.
const DISPLAY_CONSTANT_ID: usize = 8;

/// A scene pipeline drawing into `target`'s colour + depth; `desc.constants` are the shaders'
/// own specialization constants (ids 0, 1, …), `DISPLAY_TARGET` is added at id 8 and the ids
/// between are specialized to 0 (so a scene shader's own constant must be given a value here,
/// not left to its default). Made on first use (`Pipeline::graphics_on_first_use`): most runs
/// draw with a few of the scene's variants (under the water, at the waterline, wireframe,
/// floating bodies), and the driver's compile of the others was most of a run's start-up.
pub fn scene_pipeline(
    ctx: &Arc<Context>,
    layout: &PipelineLayout,
    desc: GraphicsDesc,
    depth: Depth,
    target: SceneTarget,
) -> GpuResult<Pipeline> {
    let (compare, write) = match depth {
        Depth::TestWrite => (Some(vk::CompareOp::GREATER), true),
        Depth::Background => (Some(vk::CompareOp::GREATER_OR_EQUAL), false),
        Depth::Test => (Some(vk::CompareOp::GREATER), false),
        Depth::None => (None, false),
    };
    assert!(desc.constants.len() <= DISPLAY_CONSTANT_ID);
    let mut constants = desc.constants.to_vec();
    constants.resize(DISPLAY_CONSTANT_ID, 0);
    constants.push(target.display_mode());
    Pipeline::graphics_on_first_use(
        ctx,
        layout,
        &GraphicsDesc {
            colour_formats: &[target.format()],
            constants: &constants,
            depth_format: compare.map(|_| DEPTH_FORMAT),
            depth_compare: compare,
            depth_write: write,
            ..desc
        },
    )
}

/// Binds a scene pipeline with its sets (one of the draws its rendering scope declared) and
/// selects the view.
pub fn bind_scene(rec: &Recorder, draw: &Bindings, view: ViewIndex) {
    rec.bind(draw);
    rec.push_constants(draw.pipeline, &ViewPush { view: view as u32 });
}

/// An index buffer and how many indices it holds.
pub(super) struct Mesh {
    pub buffer: Buffer,
    pub count: u32,
}

impl Mesh {
    pub fn new(ctx: &Arc<Context>, name: &str, indices: &[u32]) -> GpuResult<Mesh> {
        let bytes: &[u8] = bytemuck::cast_slice(indices);
        let buffer = Buffer::new(
            ctx,
            name,
            bytes.len() as u64,
            vk::BufferUsageFlags::INDEX_BUFFER | vk::BufferUsageFlags::TRANSFER_DST,
            MemoryLocation::GpuOnly,
        )?;
        // Then visible to the draws' index reads (no pass declares them).
        upload_then(ctx, &buffer, bytes, Use::IndexRead)?;
        Ok(Mesh {
            buffer,
            count: indices.len() as u32,
        })
    }
}

/// Two triangles per cell of the (quads + 1)² lattice taken `step` points at a time (the last
/// row and column of cells are narrower when `step` does not divide `quads`), row by row.
pub(super) fn lattice_triangles(quads: u32, step: u32) -> Vec<u32> {
    let lattice = |x: u32, z: u32| z * (quads + 1) + x;
    let edges: Vec<(u32, u32)> = (0..quads)
        .step_by(step as usize)
        .map(|a| (a, (a + step).min(quads)))
        .collect();
    let mut list = Vec::with_capacity(edges.len() * edges.len() * 6);
    for &(z0, z1) in &edges {
        for &(x0, x1) in &edges {
            // Corners (0,0) (1,1) (1,0), (0,0) (0,1) (1,1) of the cell.
            list.extend([
                lattice(x0, z0),
                lattice(x1, z1),
                lattice(x1, z0),
                lattice(x0, z0),
                lattice(x0, z1),
                lattice(x1, z1),
            ]);
        }
    }
    list
}

/// A small HDR image of its own that a full-screen draw over the frame set fills (the light
/// shafts, the caustics' means) and the scene's shaders sample through the frame set, and the
/// pipeline that draws it.
pub struct FrameSetImage {
    pub image: Image,
    fill: FullscreenDraw,
}

impl FrameSetImage {
    /// The image, cleared to 1 (a level sea's ratio) when made so what samples it is never
    /// undefined, and its pipeline: common/fullscreen.vert and `fragment`, specialized with
    /// `constants` (the caustics': common/water.glsl's CASCADES, OCEAN_MANUAL_FILTER and
    /// SLOPE_MIPS at ids 0, 1 and 6).
    pub fn new(
        ctx: &Arc<Context>,
        frame_layout: &DescriptorSetLayout,
        name: &str,
        extent: vk::Extent2D,
        fragment: &[u8],
        constants: &[u32],
    ) -> GpuResult<FrameSetImage> {
        let image = Image::new(
            ctx,
            &ImageDesc::new(
                name,
                extent,
                HDR_FORMAT,
                vk::ImageUsageFlags::COLOR_ATTACHMENT | vk::ImageUsageFlags::SAMPLED,
            ),
        )?;
        let layout = scene_layout(ctx, &format!("{name} layout"), frame_layout, &[])?;
        let fill = FullscreenDraw::new(ctx, &layout, name, fragment, constants, SceneTarget::Hdr)?;
        let level = Load::Clear(vk::ClearValue {
            color: vk::ClearColorValue { float32: [1.0; 4] },
        });
        let cleared = format!("{name} cleared");
        run_once(ctx, &cleared, |rec| {
            let target = [Target::new(&image, level)];
            rec.rendering(&cleared, &target, None, &[]).record(|| {});
        })?;
        Ok(FrameSetImage { image, fill })
    }

    /// What `record` binds: the pipeline with `sets` (the frame set).
    pub fn draw<'a>(&'a self, sets: &'a [&'a BoundSet]) -> Bindings<'a> {
        self.fill.draw(sets)
    }

    /// Draws the image, inside a rendering scope into `image` that declared `draw(sets)`.
    pub fn record(&self, rec: &Recorder, sets: &[&BoundSet]) {
        self.fill.record(rec, sets);
    }
}

/// A pipeline that draws one triangle over its whole target (common/fullscreen.vert and a
/// fragment shader: the light shafts, the caustics' means, the textures view).
pub struct FullscreenDraw {
    pipeline: Pipeline,
}

impl FullscreenDraw {
    /// `fragment` specialized with `constants`, drawing into `target` with `layout`'s sets.
    pub fn new(
        ctx: &Arc<Context>,
        layout: &PipelineLayout,
        name: &str,
        fragment: &[u8],
        constants: &[u32],
        target: SceneTarget,
    ) -> GpuResult<FullscreenDraw> {
        let stages = [
            (
                vk::ShaderStageFlags::VERTEX,
                shaders::COMMON_FULLSCREEN_VERT,
            ),
            (vk::ShaderStageFlags::FRAGMENT, fragment),
        ];
        let desc = GraphicsDesc {
            name,
            stages: &stages,
            constants,
            ..Default::default()
        };
        let pipeline = scene_pipeline(ctx, layout, desc, Depth::None, target)?;
        Ok(FullscreenDraw { pipeline })
    }

    /// What `record` binds: the pipeline with `sets`.
    pub fn draw<'a>(&'a self, sets: &'a [&'a BoundSet]) -> Bindings<'a> {
        Bindings {
            pipeline: &self.pipeline,
            sets,
        }
    }

    /// Draws, inside a rendering scope into its target that declared `draw(sets)`.
    pub fn record(&self, rec: &Recorder, sets: &[&BoundSet]) {
        bind_scene(rec, &self.draw(sets), ViewIndex::Main);
        rec.draw(3, 1);
    }
}
