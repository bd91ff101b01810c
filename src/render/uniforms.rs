//! The per-frame uniforms: what every scene shader reads of the frame (three views, sun,
//! ocean cascades, the water's camera-relative frame, scene layout), derived from the camera
//! and [`FrameInputs`] on the CPU in f64 where precision needs it.

use glam::{Mat4, Vec3, Vec4};

use super::atmosphere::{reference_light, Sky, SUN_IRRADIANCE};
use super::camera::Camera;
use super::{FresnelModel, ViewMode};
use crate::ocean::buoy::BuoyPose;
use crate::ocean::foam::{FoamLevels, MAX_LEVELS};
use crate::ocean::moments::{SeaMoments, MIP_LEVELS};
use crate::ocean::shore::{reference_group_speed, shoaling, surf_clock};
use crate::shared::{BUOY_FREEBOARD_M, BUOY_RADIUS_M};

/// Per-frame inputs.
#[derive(Clone, Copy, Debug, Default)]
pub struct FrameInputs {
    /// Simulation time in seconds (f64: reduced on the CPU before it reaches a shader).
    pub time_s: f64,
    /// World position of the ocean images' texel (0, 0) (0 for periodic cascades).
    pub ocean_origin_m: [f64; 2],
    /// The images cover one bounded window (Gerstner) rather than repeating tiles.
    pub ocean_window: bool,
    /// The buoy's heave and axis at `time_s` (`ocean::buoy`; the session fills it in).
    pub buoy: BuoyPose,
    /// Height of the surface above the camera's (x, z) at `time_s` (m; the session fills it
    /// in): below it the camera is under water.
    pub camera_surface_m: f64,
    /// The surface's slope there (∂h/∂x, ∂h/∂z; the session fills it in): with
    /// `camera_surface_m`, the tangent plane the near plane is split against at the waterline
    /// (`water_side`).
    pub camera_slope: [f64; 2],
    /// Where the foam's levels lie this frame (`Simulation::foam_levels`; none for Gerstner).
    pub foam_levels: FoamLevels,
    /// `--boat`: where the wake's grid lies this frame, its texel (0, 0) (world x, z; m) and
    /// texel size (m) (`Wake::place_of`).
    pub wake: Option<([f64; 2], f64)>,
}

impl FrameInputs {
    /// How deep a camera at height `eye_y` is under the surface (m; ≤ 0 above it): the water
    /// pass draws the surface from below (`WaterPass::record`) and the uniforms say so where
    /// it is > 0.
    pub fn camera_depth_m(&self, eye_y: f32) -> f64 {
        self.camera_surface_m - eye_y as f64
    }

    /// Which side of the water `camera`'s near plane (at `aspect`) lies on: its four corners
    /// against the surface's tangent plane at the camera (the near plane is 0.1 m away and
    /// about as wide; the waves are metres long).
    pub fn water_side(&self, camera: &Camera, aspect: f32) -> WaterSide {
        let inverse = camera.view_proj(aspect).inverse();
        let over = self.camera_depth_m(camera.position.y);
        let below = [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)]
            .into_iter()
            .filter(|&(x, y)| {
                // Reversed-Z: the near plane is at depth 1 (camera-relative positions).
                let p = inverse * Vec4::new(x, y, 1.0, 1.0);
                let q = p.truncate() / p.w;
                let [sx, sz] = self.camera_slope;
                (q.y as f64) < over + sx * q.x as f64 + sz * q.z as f64
            })
            .count();
        match below {
            0 => WaterSide::Above,
            4 => WaterSide::Below,
            _ => WaterSide::Split,
        }
    }
}

/// Where the camera's near plane lies against the water (`FrameInputs::water_side`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum WaterSide {
    /// All of it above the surface: the view from above.
    Above,
    /// All of it below: the view from under the water.
    Below,
    /// The surface crosses it: each pixel takes the side of its point on the near plane
    /// (`pixel_underwater` in shaders/common/underwater.glsl), so the picture splits at the
    /// waterline.
    Split,
}

/// What the scene passes sample of the ocean simulation.
#[derive(Clone, Debug)]
pub struct OceanBindings {
    /// Per frame slot: displacement and normal+foam images (GENERAL layout, written on the
    /// compute queue).
    pub displacement: Vec<crate::gpu::Image>,
    pub normals: Vec<crate::gpu::Image>,
    /// Per frame slot: the foam near the camera (`Simulation::foam`), one layer per level.
    pub foam: Vec<crate::gpu::Image>,
    /// Per frame slot: the wake (`Simulation::wake`; 1×1 without a boat).
    pub wake: Vec<crate::gpu::Image>,
    /// The spray's particles and draw arguments (`Simulation::spray`), when the run has spray.
    pub spray: Option<crate::ocean::simulation::SprayBuffers>,
    /// The stages at which a graphics submission waits for the compute timeline before
    /// sampling them (`simulation::graphics_wait_stages`): the frame set's `Order::Wait`.
    pub wait_stages: ash::vk::PipelineStageFlags2,
    /// Patch side of each cascade (m), padded to four.
    pub patch_m: [f32; 4],
    pub cascades: u32,
    /// Texels per side of the images (N).
    pub texels: u32,
    /// Bound on the surface's displacement from its rest position (m): patch culling, and how
    /// deep the main view can see under the water (`frame_views`).
    pub max_displacement_m: f32,
    /// The rendered sea's height, mean frequency and slopes: how the waves change over the
    /// shallows (`ocean::shore`, `FrameUniforms::shore`), what the normals resolve of the
    /// roughness (`FrameUniforms::slope_variance`).
    pub sea_moments: SeaMoments,
    /// The whole sea surface's mean-square slope (Cox & Munk 1954 at the wind; at least what the
    /// cascades resolve): the sun's reflection takes what the normals do not resolve.
    pub mean_square_slope: f32,
    /// How the whole sea surface's slopes differ by direction (`Simulation::slope_anisotropy`).
    pub slope_anisotropy: [f32; 2],
    /// The sea's natural slicks (`Slicks::of_sea`).
    pub slicks: super::slicks::Slicks,
    /// The sea's wind gusts (`Gusts::of_sea`).
    pub gusts: super::gusts::Gusts,
}

/// The views a frame renders: the camera, its mirror image below the water plane (reflection)
/// and the camera again clipped to what lies under the water (refraction). Indices into
/// `FrameUniforms::views`, picked per draw with a push constant (`common/frame.glsl`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[repr(u32)]
pub enum ViewIndex {
    Main = 0,
    Reflection = 1,
    Refraction = 2,
}

/// Mean water level (m): the plane the reflection mirrors about and the clip planes cut at.
pub const WATER_LEVEL_M: f32 = 0.0;
/// The clip planes sit this far past the water plane (m), so waves crossing the plane do not
/// open gaps at the shoreline (the textures are distorted by the waves anyway).
pub const CLIP_OFFSET_M: f32 = 0.3;

/// One view (std140, 160 bytes): see `View` in shaders/common/frame.glsl.
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct ViewUniforms {
    /// Position relative to `eye` -> clip space.
    pub view_proj: [[f32; 4]; 4],
    pub inv_view_proj: [[f32; 4]; 4],
    /// xyz: world position positions are made relative to; w: unused.
    pub eye: [f32; 4],
    /// World-space plane (a, b, c, d): geometry with a·x + b·y + c·z + d < 0 is clipped.
    pub clip_plane: [f32; 4],
}

impl ViewUniforms {
    fn new(view_proj: Mat4, eye: Vec3, clip_plane: Vec4) -> Self {
        ViewUniforms {
            view_proj: view_proj.to_cols_array_2d(),
            inv_view_proj: view_proj.inverse().to_cols_array_2d(),
            eye: eye.extend(0.0).to_array(),
            clip_plane: clip_plane.to_array(),
        }
    }
}

/// The three views of a frame (seed 001 §3.2, eq. 1–3).
///
/// The reflection camera is the camera mirrored about the water plane y = d: its position
/// C_y ← C_y − 2(C_y − d) (eq. 3), and its view-projection is the main one times the mirror
/// diag(1, −1, 1). Rendering with that matrix puts the reflection of what the main camera sees
/// at screen point s at the same s, so the water samples both textures at its own screen
/// position (the seed's pitch-inverted camera gives the same picture upside down). Clip
/// distances (eq. 2, p · v_world) keep what lies above the water for the reflection and below
/// it for the refraction.
///
/// `hidden_below_m`: when the water is drawn opaque (every view but the wireframe), the depth
/// below the water plane beyond which the waves never reach. The main view then clips what lies
/// deeper while the camera (and its near plane) is above the waves: from there every ray to such
/// a point crosses the water surface, which shows what is under it from the refraction texture.
/// Without that clip the sea floor around the island, most of the terrain grid, was set up,
/// binned and rasterized every frame only to be drawn over by the water (4 ms a frame at
/// --quality low on lavapipe).
pub fn frame_views(camera: &Camera, aspect: f32, hidden_below_m: Option<f32>) -> [ViewUniforms; 3] {
    let d = WATER_LEVEL_M;
    let vp = camera.view_proj(aspect);
    let mirror = Mat4::from_scale(Vec3::new(1.0, -1.0, 1.0));
    let mut mirrored_eye = camera.position;
    mirrored_eye.y -= 2.0 * (camera.position.y - d);
    let main_clip = match hidden_below_m {
        Some(reach) if camera.position.y > d + reach + camera.near_m => {
            Vec4::new(0.0, 1.0, 0.0, -(d - reach))
        }
        _ => Vec4::new(0.0, 0.0, 0.0, 1.0), // keep everything
    };
    [
        ViewUniforms::new(vp, camera.position, main_clip),
        ViewUniforms::new(
            vp * mirror,
            mirrored_eye,
            Vec4::new(0.0, 1.0, 0.0, -(d - CLIP_OFFSET_M)),
        ),
        ViewUniforms::new(
            vp,
            camera.position,
            Vec4::new(0.0, -1.0, 0.0, d + CLIP_OFFSET_M),
        ),
    ]
}

/// Mirrors `shaders/common/frame.glsl` (std140: matrices, vec4s and uvec4s only, so no padding).
#[repr(C)]
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
pub struct FrameUniforms {
    /// Indexed by `ViewIndex`: the camera, the mirrored camera (reflection), the refraction view.
    pub views: [ViewUniforms; 3],
    /// x: debug view (`ViewMode`, `VIEW_*`); y: Fresnel model (`FresnelModel`, `FRESNEL_*`);
    /// z: 1 for a bounded ocean window (Gerstner), 0 for repeating cascades; w: 1 to paint the
    /// solid test background instead of the sky.
    pub modes: [u32; 4],
    /// xyz: unit vector toward the sun; w: the share of the sun's light the clouds let
    /// through to the sea on average (`clouds::mean_through`; the sun's light is in `light`).
    pub sun_dir: [f32; 4],
    /// xy: main target size (px); zw: reciprocal.
    pub viewport: [f32; 4],
    /// Patch side of each ocean cascade (m).
    pub patch_m: [f32; 4],
    /// x: focal length (px); y: target tessellated edge (px); z: max displacement (m); w: unused.
    pub lod: [f32; 4],
    /// xy: island centre (m); z: sea floor depth (m); w: island radius (m).
    pub terrain: [f32; 4],
    /// Objects standing in the water: (x, z, radius, top height), height 0 = none. Object 0 is
    /// the buoy, whose top is `BUOY_FREEBOARD_M` above its waterline (`buoy`).
    pub objects: [[f32; 4]; 4],
    /// xyz: solid background colour (`--view` tests); w: unused.
    pub background: [f32; 4],
    /// xy: camera xz relative to the water grid's centre (m, `WaterFrame`); z: the water level
    /// (m); w: the near plane (m, `Camera::near_m`: depth = near / view distance).
    pub water: [f32; 4],
    /// Ocean image coordinates of the water grid's centre: cascade c in element c / 2, xy for
    /// even c, zw for odd c; reduced mod 1 for the repeating FFT cascades.
    pub cascade_uv: [[f32; 4]; 2],
    /// DU/DV tile coordinates of the water grid's centre, mod 1: xy for the first sample, zw
    /// for the second.
    pub dudv_origin: [f32; 4],
    /// x: DU/DV tiles per metre; y: the second sample's scale; z: scroll phase (turns, mod 1);
    /// w: unused.
    pub dudv: [f32; 4],
    /// The buoy (object 0, `ocean::buoy`): xyz its unit axis, w its heave (m).
    pub buoy: [f32; 4],
    /// The waves over the shallows (shaders/common/shore.glsl, `ocean::shore`): x the sea's
    /// significant height (m), y its mean angular frequency ω̄ (rad/s), z c_g(ω̄) at the depth
    /// it is simulated for (m/s); w the surf's clock (`ocean::shore::surf_clock`).
    pub shore: [f32; 4],
    /// Past the island's slope: x the open sea's floor depth (m, `SceneLayout::deep_floor_m`),
    /// y the shoaling coefficient there; zw: unused.
    pub open_sea: [f32; 4],
    /// x: radiance of the sun's disc above the atmosphere, drawn by the sky pass
    /// (shaders/sky/sky.frag), or 0 with `--skybox` (its faces hold their own sun); y: the sea's
    /// mean-square slope (`OceanBindings::mean_square_slope`); z: the sun's irradiance above
    /// the atmosphere (`atmosphere::SUN_IRRADIANCE`); w: 1 with the sun's shadows
    /// (`--shadows on`; shaders/common/shadow.glsl), else 0.
    pub light: [f32; 4],
    /// Mean-square slope of each cascade's waves (`SeaMoments::slope_variance`): what the
    /// normal images resolve of the sea's roughness.
    pub slope_variance: [f32; 4],
    /// Mean square of the Laplacian of each cascade's height (`SeaMoments::curvature_variance`):
    /// how deep its waves focus the sun (shaders/common/caustics.glsl).
    pub curvature_variance: [f32; 4],
    /// How each cascade's slopes differ by direction (`SeaMoments::slope_anisotropy`): [0] its
    /// Σ(k_x² − k_z²)E, [1] its Σk_x k_z E.
    pub slope_anisotropy: [[f32; 4]; 2],
    /// xy: the same for the whole sea surface (`OceanBindings::slope_anisotropy`: Cox & Munk's
    /// upwind excess along the wind for the FFT sea, the waves' own for Gerstner's); z: their
    /// growth per unit of a gust's g over them (`Gusts::uniforms`).
    pub sea_slopes: [f32; 4],
    /// rgb: the sun's irradiance at the sea on a surface facing it, through the clear air
    /// (`Sky::sun_light`; the shaders take what the clouds above a point let through,
    /// shaders/common/clouds.glsl); w: the cloud cover the sun's light passes (0–1; 0 with a
    /// `--skybox`, which has no layer: `sky_uniforms`).
    pub sun_light: [f32; 4],
    /// rgb: the sun's and sky's irradiance on the sea over the default day's
    /// (`Sky::global_irradiance`, `reference_light`): deep water's light; w: the display's
    /// exposure (`Sky::exposure`, times `atmosphere::underwater_adaptation` under the water).
    pub sky_light: [f32; 4],
    /// x: 1 when the camera's near plane is all under the water (`WaterSide::Below`), else
    /// 0; y: the camera's depth below the surface (m, ≥ 0); z: 1 with the caustics
    /// (`--caustics on`; shaders/common/caustics.glsl), else 0; w: the share of the sun the
    /// clouds above the camera let through (`clouds::through`; 1 with a `--skybox`).
    pub underwater: [f32; 4],
    /// The surface at the camera (`FrameInputs`): xy its slope, z its height over the eye (m);
    /// w: 1 when it crosses the near plane (`WaterSide::Split`), else 0.
    pub waterline: [f32; 4],
    /// The foam's levels (`foam_levels`): xy the level's image coordinates of the water grid's
    /// centre, z its image coordinates per metre (1 / its side), w the number of levels (0:
    /// the lattice's foam only).
    pub foam_levels: [[f32; 4]; MAX_LEVELS],
    /// The wake (`--boat`, src/ocean/wake.rs): xy its image coordinates of the water grid's
    /// centre (texel centres at (i + ½)/N), z its image coordinates per metre, w 1 with a boat.
    pub wake: [f32; 4],
    /// Natural slicks (`slicks::Slicks::uniforms`): x their mean-square slope, yz its excess
    /// along the wind (as `sea_slopes`), w the noise's threshold (`SLICK_NONE`: none).
    pub slicks: [f32; 4],
    /// x: the slicks' drift along the wind (the noise's cells); y: the amplitude left of the
    /// short waves in one (√`Slicks::short_damping`); zw: the wind's unit vector.
    pub slick_space: [f32; 4],
    /// Each cascade's slopes in a slick over its slopes out of one (`Slicks::cascades`).
    pub slick_cascades: [f32; 4],
    /// Wind gusts (`gusts::Gusts::uniforms`): x their drift, y σ_u/U10 (0: none), z the
    /// mean-square slope's growth per unit of g, w 1 over the mean whitecap ratio.
    pub gusts: [f32; 4],
    /// What mip level l of the normal images leaves of cascade c's slopes, [l][c]
    /// (`SeaMoments::slope_mip_gain`).
    pub slope_mips: [[f32; 4]; MIP_LEVELS],
}

/// Side of a DU/DV tile on the water (m).
pub const DUDV_TILE_M: f64 = 24.0;
/// The second DU/DV sample's scale relative to the first (seed 001 eq. 5 samples twice).
pub const DUDV_SECOND_SCALE: f64 = 0.73;
/// How fast the DU/DV samples scroll (tiles per second; seed 001 eq. 5: t cycles in (0, 1)).
pub const DUDV_SPEED_TILES_S: f64 = 0.03;
/// The water's patch grid is centred on the camera snapped to this step (m), so the patches
/// do not slide over the waves (about the innermost patch's side; shaders/common/water.glsl).
pub const WATER_SNAP_M: f64 = 8.0;

/// Where the water's vertices are measured from: the camera's xz snapped to `WATER_SNAP_M`,
/// computed in f64. The shaders work with positions relative to it (a few km at most), and
/// everything that depends on absolute world position (the ocean images' and DU/DV map's
/// coordinates, the scroll phase) is reduced here, so a camera 10^6 m from the origin or a
/// simulation time of 10^6 s looks as it does at the origin at t = 0.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WaterFrame {
    /// World xz of the grid's centre (m).
    pub centre: [f64; 2],
}

impl WaterFrame {
    pub fn around(camera_xz: [f64; 2]) -> WaterFrame {
        WaterFrame {
            centre: camera_xz.map(|c| (c / WATER_SNAP_M).floor() * WATER_SNAP_M),
        }
    }

    /// Image coordinates of the centre in a cascade of side `patch_m` whose texel (0, 0) is at
    /// `origin`: reduced mod 1 for periodic cascades (`window` false), as they are for a window.
    pub fn ocean_uv(&self, origin: [f64; 2], patch_m: f64, window: bool) -> [f32; 2] {
        [0, 1].map(|i| {
            let uv = (self.centre[i] - origin[i]) / patch_m;
            (if window { uv } else { uv.rem_euclid(1.0) }) as f32
        })
    }

    /// DU/DV tile coordinates of the centre at `scale` (mod 1).
    pub fn dudv_uv(&self, scale: f64) -> [f32; 2] {
        self.centre
            .map(|c| (c * scale / DUDV_TILE_M).rem_euclid(1.0) as f32)
    }
}

/// The scene's fixed features (island, objects), from the run settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SceneLayout {
    pub island_xz: [f32; 2],
    pub island_radius_m: f32,
    /// Depth of the shelf around the island (m, `--sea-floor`).
    pub sea_floor_m: f32,
    /// Depth of the open sea's floor, past the island's slope (m): the simulated depth
    /// (`--depth`), at most `DEEP_FLOOR_M`.
    pub deep_floor_m: f32,
    pub buoy_xz: [f32; 2],
}

/// The open sea's floor depth when the sea is deep (m): below `VISIBLE_DEPTH_M`, where the
/// terrain is not drawn. Deeper floors would look the same.
pub const DEEP_FLOOR_M: f32 = 200.0;

impl Default for SceneLayout {
    fn default() -> Self {
        SceneLayout {
            island_xz: [-420.0, -900.0],
            island_radius_m: 300.0,
            sea_floor_m: 18.0,
            deep_floor_m: DEEP_FLOOR_M,
            buoy_xz: [9.0, -55.0],
        }
    }
}

impl SceneLayout {
    /// The objects of `FrameUniforms::objects`: the buoy, then three stone pillars off the
    /// island's shore.
    pub fn objects(&self) -> [[f32; 4]; 4] {
        let [ix, iz] = self.island_xz;
        let r = self.island_radius_m;
        [
            [
                self.buoy_xz[0],
                self.buoy_xz[1],
                BUOY_RADIUS_M,
                BUOY_FREEBOARD_M,
            ],
            [ix + 0.95 * r, iz + 0.55 * r, 6.0, 28.0],
            [ix + 1.05 * r, iz + 0.15 * r, 4.0, 20.0],
            [ix + 0.70 * r, iz + 0.95 * r, 5.0, 34.0],
        ]
    }
}

/// Everything `FrameUniforms::new` needs besides the camera.
#[derive(Clone, Copy, Debug)]
pub struct FrameParams<'a> {
    pub sky: Sky,
    /// `sky_uniforms(&sky, analytic_sky)`.
    pub sky_light: SkyLight,
    pub sun_scale: f32,
    /// The sky is the analytic one (not `--skybox`): the sky pass draws the sun's disc.
    pub analytic_sky: bool,
    /// `--shadows`: the sun's shadows (`light.w`).
    pub shadows: bool,
    /// `--caustics`: the sun focused on the sea floor, and the light shafts (`underwater.z`).
    pub caustics: bool,
    /// Simulation time (s).
    pub time_s: f64,
    /// Main target size (px).
    pub size: (u32, u32),
    /// Width / height of the output (the main target's rounded size may differ slightly).
    pub aspect: f32,
    pub ocean: &'a OceanBindings,
    pub inputs: &'a FrameInputs,
    pub view_mode: ViewMode,
    pub fresnel: FresnelModel,
    pub tess_edge_px: f32,
    pub scene: &'a SceneLayout,
    pub background: Option<[f32; 3]>,
    /// `--slicks`: the share of the sea in slicks (`None`: by the wind, `Slicks::share`).
    pub slicks: Option<f64>,
    /// `--gusts`: wind gusts (`gusts.y`).
    pub gusts: bool,
}

/// `FrameUniforms::sun_light` and `sky_light` of a sky, and the clouds' mean share of the sun
/// (`sun_dir.w`): `sky_uniforms`' answer.
pub type SkyLight = ([f32; 4], [f32; 4], f32);

/// `SkyLight` of a sky. `layer`: the analytic sky's clouds cast their shadows; a `--skybox` has no
/// layer, so the cover the sun's light passes (`sun_light`'s w) is 0 and all of it passes (the
/// one place that decides it: `clouds::through` and the shaders' `cloud_through` give exactly 1
/// at cover 0). (Some milliseconds of integration: the renderer computes them when the sky
/// changes, `Renderer::write_uniforms`.)
pub fn sky_uniforms(sky: &Sky, layer: bool) -> SkyLight {
    let [r, g, b] = sky.sun_light();
    let (global, reference) = (sky.global_irradiance(), reference_light());
    let light: [f32; 3] = std::array::from_fn(|c| (global[c] / reference[c]) as f32);
    let cover = if layer { sky.cloud_cover } else { 0.0 };
    (
        [r, g, b, cover],
        [light[0], light[1], light[2], sky.exposure()],
        super::clouds::mean_through(sky.sun_dir.normalize(), cover),
    )
}

/// `FrameUniforms::underwater` and `waterline`: where the camera's near plane lies against the
/// water and the surface's tangent plane at the camera.
fn water_side_uniforms(camera: &Camera, p: &FrameParams) -> ([f32; 4], [f32; 4]) {
    let depth = p.inputs.camera_depth_m(camera.position.y);
    let side = p.inputs.water_side(camera, p.aspect);
    let [sx, sz] = p.inputs.camera_slope;
    (
        [
            f32::from(side == WaterSide::Below),
            depth.max(0.0) as f32,
            f32::from(u8::from(p.caustics)),
            // What the clouds above the camera let through of the sun (its light in the
            // water around the eye, common/underwater.glsl); the cover the sun's light passes
            // is `sun_light`'s w (0, all of it, with a --skybox: `sky_uniforms`).
            super::clouds::through(camera.position, p.sky.sun_dir.normalize(), p.sky_light.0[3]),
        ],
        [
            sx as f32,
            sz as f32,
            depth as f32,
            f32::from(side == WaterSide::Split),
        ],
    )
}

impl FrameUniforms {
    pub fn new(camera: &Camera, p: &FrameParams) -> Self {
        let (w, h) = (p.size.0.max(1) as f32, p.size.1.max(1) as f32);
        let water = WaterFrame::around([camera.position.x as f64, camera.position.z as f64]);
        let slick_share = p.slicks.unwrap_or(p.ocean.slicks.share);
        let slicks = p.ocean.slicks.uniforms(slick_share, p.time_s);
        let (gusts, gust_slopes) = p.ocean.gusts.uniforms(p.time_s, p.gusts);
        let focal_px = camera.focal_px(p.aspect, h);
        let (sun_light, sky_light, mean_through) = p.sky_light;
        let depth = p.inputs.camera_depth_m(camera.position.y);
        let (underwater, waterline) = water_side_uniforms(camera, p);
        let exposure = sky_light[3] * super::atmosphere::underwater_adaptation(depth);
        FrameUniforms {
            views: frame_views(
                camera,
                p.aspect,
                // The wireframe view draws the water as lines: what lies under it shows.
                (p.view_mode != ViewMode::Wireframe).then_some(p.ocean.max_displacement_m),
            ),
            modes: [
                p.view_mode as u32,
                p.fresnel as u32,
                p.inputs.ocean_window.into(),
                p.background.is_some().into(),
            ],
            sun_dir: p.sky.sun_dir.normalize().extend(mean_through).to_array(),
            viewport: Vec4::new(w, h, 1.0 / w, 1.0 / h).to_array(),
            patch_m: p.ocean.patch_m,
            lod: [focal_px, p.tess_edge_px, p.ocean.max_displacement_m, 0.0],
            terrain: [
                p.scene.island_xz[0],
                p.scene.island_xz[1],
                p.scene.sea_floor_m,
                p.scene.island_radius_m,
            ],
            objects: p.scene.objects(),
            background: {
                let [r, g, b] = p.background.unwrap_or_default();
                [r, g, b, 0.0]
            },
            water: [
                (camera.position.x as f64 - water.centre[0]) as f32,
                (camera.position.z as f64 - water.centre[1]) as f32,
                WATER_LEVEL_M,
                camera.near_m,
            ],
            cascade_uv: cascade_uv(&water, p),
            dudv_origin: {
                let (a, b) = (water.dudv_uv(1.0), water.dudv_uv(DUDV_SECOND_SCALE));
                [a[0], a[1], b[0], b[1]]
            },
            dudv: [
                (1.0 / DUDV_TILE_M) as f32,
                DUDV_SECOND_SCALE as f32,
                (p.time_s * DUDV_SPEED_TILES_S).rem_euclid(1.0) as f32,
                0.0,
            ],
            buoy: {
                let b = &p.inputs.buoy;
                [b.axis[0], b.axis[1], b.axis[2], b.heave_m].map(|v| v as f32)
            },
            shore: shore_uniform(&p.ocean.sea_moments, p.time_s),
            light: [
                if p.analytic_sky { p.sun_scale } else { 0.0 },
                p.ocean.mean_square_slope,
                SUN_IRRADIANCE,
                f32::from(u8::from(p.shadows)),
            ],
            sun_light,
            underwater,
            waterline,
            sky_light: [sky_light[0], sky_light[1], sky_light[2], exposure],
            foam_levels: foam_levels(&p.inputs.foam_levels, &water),
            wake: wake_uniform(p.inputs.wake, &water),
            slicks: slicks[0],
            slick_space: slicks[1],
            slick_cascades: slicks[2],
            gusts,
            slope_variance: p.ocean.sea_moments.slope_variance.map(|v| v as f32),
            slope_mips: rows_f32(p.ocean.sea_moments.slope_mip_gain),
            curvature_variance: p.ocean.sea_moments.curvature_variance.map(|v| v as f32),
            slope_anisotropy: [0, 1]
                .map(|i| p.ocean.sea_moments.slope_anisotropy.map(|c| c[i] as f32)),
            sea_slopes: [
                p.ocean.slope_anisotropy[0],
                p.ocean.slope_anisotropy[1],
                gust_slopes,
                0.0,
            ],
            open_sea: {
                let floor = p.scene.deep_floor_m;
                [
                    floor,
                    shoaling(&p.ocean.sea_moments, floor as f64) as f32,
                    0.0,
                    0.0,
                ]
            },
        }
    }
}

/// `FrameUniforms::cascade_uv`: each cascade's image coordinates of the water grid's centre,
/// two cascades a vector, reduced in f64.
fn cascade_uv(water: &WaterFrame, p: &FrameParams) -> [[f32; 4]; 2] {
    [0, 1].map(|half| {
        // Plus half a texel: texel i holds the node at i·L/N, and a sampler puts texel
        // i's centre at u = (i + ½)/N. Without it the drawn waves sat half a texel (0.8 m
        // of the 400 m cascade at N = 256) off the simulated ones (the buoy, stats).
        let half_texel = 0.5 / p.ocean.texels.max(1) as f32;
        let uv = |c: usize| {
            water
                .ocean_uv(
                    p.inputs.ocean_origin_m,
                    p.ocean.patch_m[c] as f64,
                    p.inputs.ocean_window,
                )
                .map(|u| u + half_texel)
        };
        let (a, b) = (uv(2 * half), uv(2 * half + 1));
        [a[0], a[1], b[0], b[1]]
    })
}

/// `FrameUniforms::foam_levels`: each level's image coordinates of the water grid's centre,
/// reduced in f64.
fn foam_levels(levels: &FoamLevels, water: &WaterFrame) -> [[f32; 4]; MAX_LEVELS] {
    std::array::from_fn(|l| {
        if l >= levels.count {
            return [0.0, 0.0, 0.0, levels.count as f32];
        }
        let side = levels.texel_m(l) * levels.size as f64;
        let uv = |i: usize| ((water.centre[i] - levels.origin_m[l][i]) / side) as f32;
        [uv(0), uv(1), (1.0 / side) as f32, levels.count as f32]
    })
}

/// `FrameUniforms::wake`: the wake image's coordinates of the water grid's centre (texel i's
/// centre at (i + ½)/N), reduced in f64, and per metre; zero without a boat.
fn wake_uniform(place: Option<([f64; 2], f64)>, water: &WaterFrame) -> [f32; 4] {
    let Some((origin, spacing)) = place else {
        return [0.0; 4];
    };
    let side = spacing * crate::ocean::wake::GRID_N as f64;
    let uv = |i: usize| ((water.centre[i] - origin[i] + 0.5 * spacing) / side) as f32;
    [uv(0), uv(1), (1.0 / side) as f32, 1.0]
}

/// Rows of four f64 as the shaders take them.
fn rows_f32<const N: usize>(rows: [[f64; 4]; N]) -> [[f32; 4]; N] {
    rows.map(|row| row.map(|v| v as f32))
}

/// `FrameUniforms::shore` for the sea `sea` at time `time_s`.
fn shore_uniform(sea: &SeaMoments, time_s: f64) -> [f32; 4] {
    let [hs, omega, c_g] = [sea.hs_m, sea.mean_omega, reference_group_speed(sea)];
    [
        hs as f32,
        omega as f32,
        c_g as f32,
        surf_clock(time_s, omega),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reflection_view_shows_the_mirror_image_where_the_camera_sees_the_point() {
        // A point above the water seen by the reflection view lands where the main view sees
        // its mirror image below the water: the water samples both at its own screen position.
        let cam = Camera::default();
        let reach = 3.0;
        let [main, refl, refr] = frame_views(&cam, 1.5, Some(reach));
        let project = |v: &ViewUniforms, world: Vec3| {
            let clip = Mat4::from_cols_array_2d(&v.view_proj)
                * (world - Vec3::from_slice(&v.eye[..3])).extend(1.0);
            clip.truncate() / clip.w
        };
        let above = Vec3::new(30.0, 25.0, -200.0);
        let mirrored = Vec3::new(above.x, 2.0 * WATER_LEVEL_M - above.y, above.z);
        let a = project(&refl, above);
        let b = project(&main, mirrored);
        assert!((a - b).length() < 1e-5, "{a} vs {b}");
        // Clip planes: the reflection keeps what is above the water, the refraction what is below.
        let plane = |v: &ViewUniforms, p: Vec3| Vec4::from_array(v.clip_plane).dot(p.extend(1.0));
        assert!(plane(&refl, above) > 0.0 && plane(&refl, mirrored) < 0.0);
        assert!(plane(&refr, above) < 0.0 && plane(&refr, mirrored) > 0.0);
        // The main view keeps what the waves can uncover and drops what lies deeper.
        let trough = Vec3::new(30.0, WATER_LEVEL_M - 0.9 * reach, -200.0);
        assert!(plane(&main, above) > 0.0 && plane(&main, trough) > 0.0);
        assert!(plane(&main, mirrored) < 0.0);
        // A camera among the waves, and a view where the water does not hide (wireframe), keep
        // everything.
        let low = Camera {
            position: Vec3::new(0.0, WATER_LEVEL_M + 0.5 * reach, 0.0),
            ..Camera::default()
        };
        let [main, _, _] = frame_views(&low, 1.5, Some(reach));
        assert!(plane(&main, mirrored) > 0.0);
        let [main, _, _] = frame_views(&cam, 1.5, None);
        assert!(plane(&main, mirrored) > 0.0);
    }
}
