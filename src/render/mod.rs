//! The renderer: records one frame, pass by pass (`frame.rs`), with what `renderer.rs` holds. No `unsafe` here: passes
//! record through `gpu::Recorder`.

pub mod atmosphere;
pub mod camera;
pub mod clipmap;
pub mod clouds;
pub mod frame;
pub mod gusts;
pub mod multiple_scattering;
pub mod passes;
pub mod renderer;
pub mod scene;
pub mod slicks;
pub mod targets;
pub mod uniforms;

use std::path::PathBuf;

use glam::Vec3;

use crate::shared;

pub use camera::Camera;
pub use frame::{record_frame, Delivery, FrameParts, OverlayDraw, ACQUIRE_WAIT_STAGE};
pub use renderer::{OutputTarget, Renderer};
pub use uniforms::{FrameInputs, FrameUniforms, OceanBindings, SceneLayout};

/// `--view`: the final picture, or one intermediate full screen. (The variants' doc comments are
/// `--help`'s descriptions of the values.)
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
#[repr(u32)]
pub enum ViewMode {
    /// The final picture.
    #[default]
    Final = shared::VIEW_FINAL,
    /// The reflection texture.
    Reflection = shared::VIEW_REFLECTION,
    /// The refraction texture.
    Refraction = shared::VIEW_REFRACTION,
    /// The ocean coloured by its displacement (x, y, z → r, b, g around grey).
    Displacement = shared::VIEW_DISPLACEMENT,
    /// The ocean coloured by its normal.
    Normals = shared::VIEW_NORMALS,
    /// The foam as drawn: its layer's reflectance, 0 (none) to 1 (opaque), in grey.
    Foam = shared::VIEW_FOAM,
    /// The DU/DV map, tiled.
    Dudv = shared::VIEW_DUDV,
    /// The water's triangles as lines over the scene.
    Wireframe = shared::VIEW_WIREFRAME,
    /// The light through the crests alone, as it reaches the picture (after the surface's
    /// Fresnel, the foam and the haze).
    Crests = shared::VIEW_CRESTS,
    /// The water's triangles, each in a colour of its own (tessellated: its patches), as the
    /// rasterizer shades them.
    Triangles = shared::VIEW_TRIANGLES,
}

/// `--fresnel`: how the water weighs reflection against refraction.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
#[repr(u32)]
pub enum FresnelModel {
    /// Schlick's approximation, F0 = 0.02.
    #[default]
    Schlick = shared::FRESNEL_SCHLICK,
    /// The Fresnel equations for unpolarised light (seed 004 §2.5), n = 1.333.
    Exact = shared::FRESNEL_EXACT,
    /// Seed 001 eq. 6: refraction weight cos θ^0.5.
    Power = shared::FRESNEL_POWER,
}

/// `--aa`: how the final picture is anti-aliased. (The variants' doc comments are `--help`'s
/// descriptions of the values.)
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum AntiAliasing {
    /// FXAA (Lottes 2009) on the scene target, before it is scaled to the output.
    #[default]
    Fxaa,
    /// None: the scene target goes to the output as drawn.
    Off,
}

/// `--upscale`: how the output pass scales the scene target up to the output (with
/// `--render-scale` below 1). (The variants' doc comments are `--help`'s descriptions.)
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Upscale {
    /// Edge-directed: the bilinear sample sharpened across the local edge, clamped to the
    /// samples either side of it so it cannot ring (shaders/post/output.frag).
    #[default]
    Edge,
    /// Bilinear, as a blit scales.
    Bilinear,
}

impl Upscale {
    /// `--upscale` when not given: bilinear on a CPU device, whose texture lookups `low`'s frame
    /// cannot spare (README, Anti-aliasing), edge-directed elsewhere.
    pub fn device_default(cpu_device: bool) -> Upscale {
        if cpu_device {
            Upscale::Bilinear
        } else {
            Upscale::Edge
        }
    }
}

/// `--geometry`: how the water's triangles are made. (The variants' doc comments are `--help`'s
/// descriptions of the values.)
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum Geometry {
    /// Patches the GPU tessellates by their edges' size on screen (needs tessellation shaders).
    Tessellated,
    /// Camera-centred grid tiles, coarser by distance, morphed between levels (CDLOD).
    Clipmap,
}

impl Geometry {
    pub fn name(self) -> &'static str {
        match self {
            Geometry::Tessellated => "tessellated",
            Geometry::Clipmap => "clipmap",
        }
    }

    /// The geometry `requested` resolves to: the clipmap when none is asked for, on every
    /// device (the only one without tessellation shaders, and the faster one where both run:
    /// README, Water geometry).
    pub fn resolve(requested: Option<Geometry>) -> Geometry {
        requested.unwrap_or(Geometry::Clipmap)
    }
}

/// How the scene looks: everything the renderer takes from the command line.
#[derive(Clone, Debug)]
pub struct SceneSettings {
    pub view: ViewMode,
    pub fresnel: FresnelModel,
    /// Applies to `--view final` only (`anti_aliased`).
    pub aa: AntiAliasing,
    /// FXAA at Lottes' fastest preset, 3 search steps and the edge threshold 0.25 of his "low
    /// quality", instead of his default, 5 steps and 0.166 (`--quality low`:
    /// `Quality::fxaa_fast`; shaders/common/fxaa.glsl).
    pub fxaa_fast: bool,
    /// `--sharpen`: how much the anti-aliasing pass sharpens the pixels off the edges (0 to 1;
    /// shaders/post/fxaa_edges.frag), before the output pass scales the picture up.
    pub sharpen: f32,
    /// `--upscale`: how the output pass scales the main target up (final view only).
    pub upscale: Upscale,
    /// Reflection and refraction target size relative to the output (0 < s <= 1).
    pub rtt_scale: f32,
    /// Main (scene and water) target size relative to the output (0 < s <= 1); the output pass
    /// scales it up (`upscale`).
    pub render_scale: f32,
    /// Island lattice quads per side.
    pub terrain_grid: u32,
    /// Target length of a tessellated ocean edge in pixels of the main (scene) target; for the
    /// clipmap, the width of its smallest cells on screen.
    pub tess_edge_px: f32,
    /// `--geometry` (`None`: the default, [`Geometry::resolve`]).
    pub geometry: Option<Geometry>,
    pub layout: SceneLayout,
    /// Unit vector toward the sun.
    pub sun_dir: Vec3,
    /// `--clouds`: share of the sky under cloud, 0 (clear) to 1 (overcast).
    pub cloud_cover: f32,
    /// `--slicks`: the share of the sea in natural slicks, 0–1 (`None`: by the wind,
    /// `slicks::slick_share`).
    pub slicks: Option<f64>,
    /// `--gusts`: wind gusts (shaders/common/gusts.glsl).
    pub gusts: bool,
    /// `--shadows`: the sun's shadows (shaders/common/shadow.glsl).
    pub shadows: bool,
    /// `--caustics`: the sun focused on the sea floor, and the light shafts
    /// (shaders/common/caustics.glsl).
    pub caustics: bool,
    /// The caustics in the refraction view too (the floor seen from above through the water):
    /// `--caustics on`, or not given at medium and high (`Quality::refraction_caustics`);
    /// never without `caustics`.
    pub refraction_caustics: bool,
    /// `--dudv FILE.png` instead of the generated map.
    pub dudv: Option<PathBuf>,
    /// `--skybox DIR` (six PNG faces) instead of the analytic sky.
    pub skybox: Option<PathBuf>,
    /// Test only: the main view's sky is this solid linear colour.
    pub background: Option<[f32; 3]>,
}

impl SceneSettings {
    /// The sky these settings draw.
    pub fn sky(&self) -> atmosphere::Sky {
        atmosphere::Sky {
            sun_dir: self.sun_dir,
            cloud_cover: self.cloud_cover,
        }
    }

    /// What these settings use of the device (tessellation only for `--geometry tessellated`).
    pub fn needs(&self) -> crate::gpu::Needs {
        crate::gpu::Needs {
            rendering: true,
            tessellation: self.geometry == Some(Geometry::Tessellated),
        }
    }

    /// Whether the frame runs the anti-aliasing pass: `--aa fxaa` with the final view (the
    /// debug views show their data as drawn).
    pub fn anti_aliased(&self) -> bool {
        self.aa == AntiAliasing::Fxaa && self.view == ViewMode::Final
    }
}

/// Default sun: low, ahead and to the right of the default camera, so its glitter path lies on
/// the water.
pub fn default_sun_dir() -> Vec3 {
    Vec3::new(0.35, 0.22, -1.0).normalize()
}

impl Default for SceneSettings {
    fn default() -> Self {
        SceneSettings {
            view: ViewMode::Final,
            fresnel: FresnelModel::Schlick,
            aa: AntiAliasing::default(),
            fxaa_fast: false,
            sharpen: 0.0,
            upscale: Upscale::default(),
            rtt_scale: 0.5,
            render_scale: 1.0,
            terrain_grid: 160,
            tess_edge_px: 16.0,
            geometry: None,
            layout: SceneLayout::default(),
            sun_dir: default_sun_dir(),
            cloud_cover: 0.0,
            slicks: None,
            gusts: true,
            shadows: true,
            caustics: true,
            refraction_caustics: true,
            dudv: None,
            skybox: None,
            background: None,
        }
    }
}
