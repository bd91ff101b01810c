//! The command line (clap derive) and its validation into [`RunSettings`]. Bad values are usage
//! errors (exit code 2) with a one-line message. Value parsers live in `values.rs`, the
//! `--config FILE.toml` expansion in `config.rs`.

use std::path::PathBuf;

use clap::{Parser, ValueEnum};

mod bench;
mod config;
mod device;
mod retune;
mod values;
mod waves;

pub use crate::tuning::{self, presets};
pub use bench::{
    check_bench_fft_flags, command, BenchCommand, BenchFftArgs, BenchFramesArgs, BenchGerstnerArgs,
    Command,
};
pub use config::with_config;
pub use presets::{
    quality_level, sea_preset, PresetArg, Quality, QualityArg, SeaPreset, DEFAULT_SEA,
};
pub use values::parse_fft_size;
pub use values::Switch;
use values::*;

use crate::frontend::RunSettings;
use crate::gpu::PresentMode;
use crate::ocean::{OceanSettings, SeaState, SpectrumKind};
use crate::profile::WARMUP_FRAMES;
use crate::render::camera::LOWEST_M;
use crate::render::uniforms::DEEP_FLOOR_M;
use crate::render::{
    default_sun_dir, AntiAliasing, Camera, FresnelModel, Geometry, SceneLayout, SceneSettings,
    Upscale, ViewMode,
};
use crate::shared::MAX_BODIES;
use glam::Vec3;

/// Largest accepted `--size` side; the device limit is checked again at run time.
pub const MAX_SIDE: u32 = 16384;
/// `--size` when not given.
pub const DEFAULT_SIZE: (u32, u32) = (1280, 720);

/// `--sharpen` when the scene target is scaled up and the flag is not given (README,
/// Anti-aliasing: what it measured against the bilinear scaling alone).
pub const DEFAULT_SHARPEN: f64 = 0.75;

#[derive(Parser, Debug, Clone)]
#[command(
    name = "vkocean",
    version,
    // A flag given twice keeps the last value: --config's settings come first, the command line wins.
    args_override_self = true,
    about = "A real-time FFT ocean on hand-written Vulkan.",
    after_help = "Window controls: W/S forward/back, A/D sideways, Q/E down/up, Shift faster, left mouse drag to look, F1 overlay (settings and GPU timings), F12 screenshot, Esc quit.\n\
                  Exit codes: 0 ok, 1 runtime error, 2 bad usage, 3 validation reported warnings or errors.\n\
                  Without a GPU, Mesa's lavapipe (CPU) driver is used; install it with tools/setup."
)]
pub struct Cli {
    /// Render offscreen without a window (default 1 frame; 60 with --profile).
    #[arg(long)]
    pub headless: bool,

    /// Stop after N frames (a window otherwise runs until Esc or close).
    #[arg(long, value_name = "N", value_parser = parse_frames, allow_hyphen_values = true)]
    pub frames: Option<u64>,

    /// Render size in pixels (window inner size, or the headless image); default 1280x720.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub size: Option<(u32, u32)>,

    /// Save the last frame as PNG (in a window F12 also saves one).
    #[arg(long, value_name = "PATH")]
    pub screenshot: Option<PathBuf>,

    /// With --headless and --screenshot PATH: save frames 1, N+1, 2N+1, … instead, each as
    /// PATH with its frame number before .png (ocean-01.png … ocean-25.png for --frames 25).
    #[arg(long, value_name = "N", value_parser = parse_frames)]
    pub screenshot_every: Option<u64>,

    /// Enable the Khronos validation layer with synchronization validation; prints
    /// "validation: N warnings, M errors" at exit and exits with 3 if there were any.
    #[arg(long, global = true)]
    pub validation: bool,

    /// With --validation (implied): the layer's extra checks, a comma list of best-practices
    /// (Best Practices), vendors (with its AMD, Arm, IMG and NVIDIA checks; needs a layer with
    /// VK_EXT_layer_settings, 1.3.268 or newer) and gpu-assisted (GPU-assisted validation).
    /// What they report on lavapipe is listed in README.
    #[arg(long, global = true, value_name = "LIST", value_parser = parse_validation_extras)]
    pub validation_extra: Option<crate::gpu::ValidationExtras>,

    /// Write GPU timestamps per pass and frame times as JSON (first 5 frames are warm-up).
    #[arg(long, value_name = "PATH")]
    pub profile: Option<PathBuf>,

    /// Write one frame's graph: its submissions (queue, semaphore waits and signals) and each
    /// pass's reads and writes with their stages, accesses and layouts, as recorded. JSON, or a
    /// Graphviz picture if PATH ends in .dot. Headless: the last frame; in a window: the
    /// second.
    #[arg(long, value_name = "PATH")]
    pub frame_graph: Option<PathBuf>,

    /// Use Vulkan device N, 0 to 255 (see --list-gpus); default: the best one (discrete >
    /// integrated > virtual > cpu).
    #[arg(long, value_name = "N", global = true, allow_hyphen_values = true,
          value_parser = |s: &str| parse_whole(s, 0, 255).map(|n| n as usize))]
    pub gpu: Option<usize>,

    /// List the Vulkan devices and exit.
    #[arg(long)]
    pub list_gpus: bool,

    /// Window presentation mode (falls back to fifo when the surface lacks it).
    #[arg(long, value_enum, value_name = "MODE", default_value_t = PresentMode::Fifo)]
    pub present_mode: PresentMode,

    /// Read settings from a TOML file (a regular file, at most 1 MiB; one per run):
    /// `flag-name = value` for any option above, e.g. `wind-speed = 14`, `camera = [0, 12, 0]`,
    /// `validation = true`. Flags given on the command line win; unknown or repeated keys and
    /// bad values are errors naming the key.
    #[arg(long, global = true, value_name = "FILE.toml")]
    pub config: Option<PathBuf>,

    /// Cost level: low, medium or high: FFT size, cascades, render scale, RTT scale,
    /// tessellation edge and terrain grid (table in README); flags given explicitly win.
    /// [default: by device: low on a CPU implementation such as lavapipe, high on a GPU]
    #[arg(long, global = true, value_enum, value_name = "LEVEL")]
    pub quality: Option<QualityArg>,

    /// Whether the device the run will use is a CPU implementation (`None`: not known), set by
    /// `main` before `settings` when `--quality` or `--upscale` is not given: it picks their
    /// defaults.
    #[arg(skip)]
    pub cpu_device: Option<bool>,

    /// Sea state by the Beaufort scale: calm (force 2), breeze (4), moderate (6), storm (10):
    /// wind speed, fetch, choppiness and patch size (table in README); flags given explicitly win.
    #[arg(
        long,
        global = true,
        value_enum,
        value_name = "SEA",
        help_heading = "Ocean"
    )]
    pub preset: Option<PresetArg>,

    /// Wave model: fft (spectrum, cascades) or gerstner (analytic waves, seed 000's table by default).
    #[arg(long, global = true, value_enum, value_name = "MODEL", default_value_t = WavesArg::Fft, help_heading = "Ocean")]
    pub waves: WavesArg,

    /// Gerstner wave table: CSV (kx,kz,amplitude,phase[,steepness]) or TOML ([[wave]] tables),
    /// at most 4 MiB. |k| from 0.001 to 1000 rad/m, amplitude 0 to 100 m, steepness Q 0 to 10
    /// (default 1), |phase| at most 1000 rad; a table with Σ Q·k·a > 1 has every Q scaled down
    /// to Σ = 1 (it would fold over).
    #[arg(long, global = true, value_name = "FILE", help_heading = "Ocean")]
    pub gerstner_waves: Option<PathBuf>,

    /// Use only the first M waves of the Gerstner table.
    #[arg(long, global = true, value_name = "M", allow_hyphen_values = true,
          value_parser = |s: &str| parse_whole(s, 1, 10_000).map(|n| n as usize), help_heading = "Ocean")]
    pub gerstner_count: Option<usize>,

    /// Ocean spectrum.
    #[arg(long, global = true, value_enum, value_name = "KIND", default_value_t = SpectrumKind::Jonswap, help_heading = "Ocean")]
    pub spectrum: SpectrumKind,

    /// Wind speed 10 m above the sea, U10 (m/s, 0 < U <= 100). [default: 10; --preset sets it]
    #[arg(long, global = true, value_name = "M_S", allow_hyphen_values = true,
          value_parser = |s: &str| parse_above(s, 0.0, 100.0), help_heading = "Ocean")]
    pub wind_speed: Option<f64>,

    /// Direction the wind blows toward, degrees from +x toward +z (-360 to 360).
    #[arg(long, global = true, value_name = "DEG", default_value = "0", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, -360.0, 360.0), help_heading = "Ocean")]
    pub wind_dir: f64,

    /// Fetch: distance the wind has blown over water (km, JONSWAP; 0 < F <= 10000). [default: 100; --preset sets it]
    #[arg(long, global = true, value_name = "KM", allow_hyphen_values = true,
          value_parser = |s: &str| parse_above(s, 0.0, 10_000.0), help_heading = "Ocean")]
    pub fetch: Option<f64>,

    /// Water depth (m, 0 < h <= 11000); default deep water. Finite depth changes the dispersion
    /// and applies the TMA attenuation; the open sea's floor lies there (at most 200 m down).
    #[arg(long, global = true, value_name = "M", allow_hyphen_values = true,
          value_parser = |s: &str| parse_above(s, 0.0, 11_000.0), help_heading = "Ocean")]
    pub depth: Option<f64>,

    /// FFT size N: a power of two from 64 to 1024. [default: the quality level's: 64 low, 128 medium, 256 high]
    #[arg(long, global = true, value_name = "N", value_parser = parse_fft_size, help_heading = "Ocean")]
    pub fft_size: Option<usize>,

    /// Side of the largest cascade's patch (m, 0 < L <= 100000); each further cascade is 4.353x smaller. [default: 400; --preset sets it]
    #[arg(long, global = true, value_name = "M", allow_hyphen_values = true,
          value_parser = |s: &str| parse_above(s, 0.0, 100_000.0), help_heading = "Ocean")]
    pub patch_size: Option<f64>,

    /// Horizontal (choppy) displacement scale λ (0 <= λ <= 10). [default: 1; --preset sets it]
    #[arg(long, global = true, value_name = "X", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 0.0, 10.0), help_heading = "Ocean")]
    pub choppiness: Option<f64>,

    /// Spray: puffs of spume torn off breaking crests from Beaufort 6 (10.8 m/s) up, drawn over
    /// the scene (FFT waves only; their count is in --stats).
    #[arg(long, global = true, value_enum, value_name = "ON|OFF", default_value_t = Switch::On,
          help_heading = "Ocean")]
    pub spray: Switch,

    /// The foam simulation near the camera: three world-space levels of 0.25, 1 and 4 m a texel
    /// (drift, residual foam, windrows, the surf's and the objects' foam). Off leaves the FFT
    /// lattice's whitecaps alone, as at --quality low; its cost on lavapipe is in README
    /// (The ocean, foam). FFT waves only. [default: on above a 64² FFT grid (medium, high)]
    #[arg(
        long,
        global = true,
        value_enum,
        value_name = "ON|OFF",
        help_heading = "Ocean"
    )]
    pub foam_sim: Option<Switch>,

    /// Number of cascades, 1 to 4 (disjoint wave-number bands, non-commensurate patches). [default: 3 at every quality level]
    #[arg(long, global = true, value_name = "K", allow_hyphen_values = true,
          value_parser = |s: &str| parse_whole(s, 1, 4).map(|n| n as usize), help_heading = "Ocean")]
    pub cascades: Option<usize>,

    /// Seed of the initial spectrum, 0 to 18446744073709551615 (same seed, same sea on every
    /// machine; in a --config file a seed above 2^63 - 1 is written as a string).
    #[arg(long, global = true, value_name = "S", default_value = "1", allow_hyphen_values = true,
          value_parser = |s: &str| parse_whole(s, 0, u64::MAX), help_heading = "Ocean")]
    pub seed: u64,

    /// Print one JSON line of height statistics per frame on stdout (mean, std, hs = 4·std, min,
    /// max per cascade and for the summed surface); waits for every frame.
    #[arg(long)]
    pub stats: bool,

    /// With --headless: every N frames, print resident memory and the number of live Vulkan
    /// objects on stderr (for leak hunting over long runs).
    #[arg(long, value_name = "N", value_parser = |s: &str| parse_whole(s, 1, u64::MAX))]
    pub log_resources: Option<u64>,

    /// With --headless: write the last frame's h0.npy, displacement.npy, normals.npy and
    /// params.json into DIR (created if missing; its parent must exist). Layout in README.
    #[arg(long, value_name = "DIR")]
    pub dump: Option<PathBuf>,

    /// Simulation time of the first frame (s, 0 to 1e6); with --dt, pictures are reproducible.
    #[arg(long, global = true, value_name = "T", default_value = "0", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 0.0, 1.0e6), help_heading = "Scene")]
    pub time: f64,

    /// Simulation time step per frame (s, 0 < DT <= 10); default 1/60 headless, wall-clock time
    /// in a window.
    #[arg(long, global = true, value_name = "DT", allow_hyphen_values = true,
          value_parser = |s: &str| parse_above(s, 0.0, 10.0), help_heading = "Scene")]
    pub dt: Option<f64>,

    /// Simulation seconds per second of the run (per --dt step headless); 0 stops the waves
    /// (0 to 100).
    #[arg(long, global = true, value_name = "X", default_value = "1", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 0.0, tuning::MAX_TIME_SCALE), help_heading = "Scene")]
    pub time_scale: f64,

    /// Draw the overlay (frame timings and the settings; F1 in a window) into the picture:
    /// shown from the start in a window, drawn into --headless screenshots.
    #[arg(long)]
    pub overlay: bool,

    /// Camera position in metres (y up, water at y = 0; y >= -60, each value at most 1e6 in
    /// size); default 0,12,0.
    #[arg(long, global = true, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true, help_heading = "Scene")]
    pub camera: Option<[f32; 3]>,

    /// Point the camera looks at; default: toward -z, slightly down.
    #[arg(long, global = true, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true, help_heading = "Scene")]
    pub look_at: Option<[f32; 3]>,

    /// Show the final picture or one intermediate full screen.
    #[arg(long, global = true, value_enum, value_name = "VIEW", default_value_t = ViewMode::Final, help_heading = "Scene")]
    pub view: ViewMode,

    /// How the water weighs reflection against refraction.
    #[arg(long, global = true, value_enum, value_name = "MODEL", default_value_t = FresnelModel::Schlick, help_heading = "Scene")]
    pub fresnel: FresnelModel,

    /// Anti-aliasing of the final picture (the debug views are shown as drawn); at --quality low FXAA runs Lottes' fastest preset (3 search steps, edge threshold 0.25).
    #[arg(long, global = true, value_enum, value_name = "MODE", default_value_t = AntiAliasing::Fxaa, help_heading = "Scene")]
    pub aa: AntiAliasing,

    /// How the scene target is scaled up to the output when --render-scale is below 1 (the debug views are always scaled bilinearly). [default: edge; bilinear on a CPU device (lavapipe, SwiftShader), where the edge-directed draw's four lookups a pixel cost more than twice the bilinear one]
    #[arg(
        long,
        global = true,
        value_enum,
        value_name = "MODE",
        help_heading = "Scene"
    )]
    pub upscale: Option<Upscale>,

    /// Size of the reflection and refraction textures relative to the output (window or image; 0.1 to 1). [default: 0.25 low, 0.35 medium, 0.5 high]
    #[arg(long, global = true, value_name = "S", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 0.1, 1.0), help_heading = "Scene")]
    pub rtt_scale: Option<f64>,

    /// Size of the scene (and water) target relative to the output (window or image; 0.25 to 1); the output pass scales it up (--upscale). [default: 0.5 low, 0.75 medium, 1 high]
    #[arg(long, global = true, value_name = "S", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 0.25, 1.0), help_heading = "Scene")]
    pub render_scale: Option<f64>,

    /// Sharpening of the scene target before it is scaled up to the output (0 to 1; 0: none): a contrast-adaptive sharpening of the pixels off the edges, in the anti-aliasing pass (so only with --aa fxaa). [default: 0.75 when the scene target is scaled up (--render-scale below 1) with --aa fxaa, else 0]
    #[arg(long, global = true, value_name = "S", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 0.0, 1.0), help_heading = "Scene")]
    pub sharpen: Option<f64>,

    /// Quads per side of the island's terrain lattice (16 to 512). [default: 64 low, 96 medium, 160 high]
    #[arg(long, global = true, value_name = "N", allow_hyphen_values = true,
          value_parser = |s: &str| parse_whole(s, 16, 512).map(|n| n as u32), help_heading = "Scene")]
    pub terrain_grid: Option<u32>,

    /// Target length of a tessellated ocean edge in scene-target pixels (2 to 256); smaller is finer. [default: 64 low, 24 medium, 16 high]
    #[arg(long, global = true, value_name = "PX", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 2.0, 256.0), help_heading = "Scene")]
    pub tess_edge: Option<f64>,

    /// How the water's triangles are made. [default: clipmap (the faster on lavapipe, and the
    /// only one without tessellation shaders; see --list-gpus)]
    #[arg(
        long,
        global = true,
        value_enum,
        value_name = "KIND",
        help_heading = "Scene"
    )]
    pub geometry: Option<Geometry>,

    /// Sun direction: azimuth (degrees from +x toward +z) and elevation (degrees above the
    /// horizon, -10 to 90: below 0 the dusk); default -70.7,11.7. The sky and the sun's colour
    /// follow it (sunlight scattered by the air).
    #[arg(long, global = true, value_name = "AZ,EL", value_parser = parse_sun, allow_hyphen_values = true, help_heading = "Scene")]
    pub sun: Option<[f32; 2]>,

    /// Share of the sky under cloud, 0 (clear) to 1 (overcast: grey, no sun). [default: 0.3;
    /// --preset sets it: calm 0.1, breeze 0.3, moderate 0.5, storm 1]
    #[arg(long, global = true, value_name = "FRACTION", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 0.0, 1.0), help_heading = "Scene")]
    pub clouds: Option<f64>,

    /// Share of the sea in natural slicks, 0 to 1: smooth bands along the wind that mirror the
    /// sky (FFT waves). [default: by the wind, 0.35 at 2–4 m/s, fading below 2 and to none at 7 m/s (Romano 1996)]
    #[arg(long, global = true, value_name = "FRACTION", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 0.0, 1.0), help_heading = "Ocean")]
    pub slicks: Option<f64>,

    /// Wind gusts: patches of sea under a stronger or weaker wind racing downwind, rougher and
    /// with more whitecaps in a gust (FFT waves; README, Rendering, Wind gusts). [default: on]
    #[arg(
        long,
        global = true,
        value_enum,
        value_name = "ON|OFF",
        help_heading = "Ocean"
    )]
    pub gusts: Option<Switch>,

    /// The sun's shadows: the island, the pillars and the buoy shade the ground, each other and
    /// the water's sun terms (a ray cast toward the sun per pixel; README, Rendering).
    /// [default: off at --quality low, on at medium and high]
    #[arg(
        long,
        global = true,
        value_enum,
        value_name = "ON|OFF",
        help_heading = "Scene"
    )]
    pub shadows: Option<Switch>,

    /// Caustics: the sun focused on the sea floor by the waves, in the shallows seen from above
    /// and from under the water, and the light shafts under the water (README, Rendering,
    /// Caustics; Under the water). [default: on; at --quality low not in the shallows seen
    /// from above, unless given]
    #[arg(
        long,
        global = true,
        value_enum,
        value_name = "ON|OFF",
        help_heading = "Scene"
    )]
    pub caustics: Option<Switch>,

    /// DU/DV map PNG (red = du, green = dv, 128 = no offset), tiled over the water, at most the
    /// device's largest 2D image (16384 on lavapipe); default: generated at start-up.
    #[arg(long, global = true, value_name = "FILE.png", help_heading = "Scene")]
    pub dudv: Option<PathBuf>,

    /// Skybox: a directory of six PNG faces px nx py ny pz nz (square, same size, at most the
    /// device's largest cube face); default: the analytic sky.
    #[arg(long, global = true, value_name = "DIR", help_heading = "Scene")]
    pub skybox: Option<PathBuf>,

    /// Floating bodies (0 to 256): crates, small boats and buoys on a grid 8 m apart in front
    /// of the buoy, moved by buoyancy, drag and gravity on the GPU's height queries
    /// (src/ocean/bodies.rs); `--dump` writes their states to bodies.json.
    #[arg(long, global = true, value_name = "N", default_value = "0", help_heading = "Scene",
          value_parser = |s: &str| parse_whole(s, 0, MAX_BODIES as u64).map(|n| n as usize))]
    pub bodies: usize,

    /// A boat driven in a straight line at SPEED m/s (0.5 to 10) along HEADING (degrees from +x
    /// toward +z), passing in front of the camera at the first frame and leaving a Kelvin wake
    /// (src/ocean/wake.rs); `--dump` writes the wake to wake.npy.
    #[arg(long, global = true, value_name = "SPEED,HEADING", value_parser = parse_boat,
          allow_hyphen_values = true, help_heading = "Scene")]
    pub boat: Option<[f64; 2]>,

    /// Where the buoy floats (m).
    #[arg(long, global = true, value_name = "X,Z", value_parser = parse_vec2, allow_hyphen_values = true,
          default_value = "9,-55", help_heading = "Scene")]
    pub buoy: [f32; 2],

    /// Depth of the shelf around the island (m, 1 to 500); beyond it the floor slopes down to
    /// the open sea's (--depth, or 200 m).
    #[arg(long, global = true, value_name = "M", default_value = "18", allow_hyphen_values = true,
          value_parser = |s: &str| parse_in(s, 1.0, 500.0), help_heading = "Scene")]
    pub sea_floor: f64,

    /// Test only: paint the main view's sky in this solid linear colour (0..1 each).
    #[arg(long, hide = true, value_name = "R,G,B", value_parser = parse_vec3)]
    pub background: Option<[f32; 3]>,

    /// Test only: after the first headless frame, change each KEY (a flag's name) to VALUE
    /// through the overlay's settings API.
    #[arg(long, hide = true, value_name = "KEY=VALUE;...")]
    pub live_set: Option<String>,

    /// Test only: record a deliberate synchronization hazard (validation must catch it).
    #[arg(long, hide = true)]
    pub inject_sync_hazard: bool,

    /// Test only: render headless into an 8-bit UNORM output, as on a window surface without
    /// an sRGB format (the shaders then encode sRGB themselves).
    #[arg(long, hide = true)]
    pub unorm_output: bool,

    #[command(subcommand)]
    pub command: Option<Command>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum WavesArg {
    Fft,
    Gerstner,
}

/// A command-line value that is wrong (exit code 2).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct UsageError(pub String);

/// An input file's problem as a usage error.
fn input(e: crate::input::InputError) -> UsageError {
    UsageError(e.0)
}

impl Cli {
    /// The camera of `--camera` / `--look-at` (`None`: the default camera).
    fn camera_setting(&self) -> Result<Option<Camera>, UsageError> {
        if self.camera.is_none() && self.look_at.is_none() {
            return Ok(None);
        }
        let default = Camera::default();
        let position = self.camera.map(Vec3::from).unwrap_or(default.position);
        if position.y < LOWEST_M {
            return Err(UsageError(format!(
                "--camera {},{},{}: the camera must be at most {} m under the water (y >= {})",
                position.x, position.y, position.z, -LOWEST_M, LOWEST_M
            )));
        }
        let target = self
            .look_at
            .map(Vec3::from)
            .unwrap_or(position + default.forward * 100.0);
        Camera::looking_at(position, target).map(Some).ok_or_else(|| {
            UsageError(format!(
                "--look-at {},{},{}: must differ from the camera position and not be straight above or below it",
                target.x, target.y, target.z
            ))
        })
    }

    fn scene_settings(&self) -> Result<SceneSettings, UsageError> {
        let quality = quality_level(self.quality_in_force());
        require_extension("--dudv", self.dudv.as_deref(), "png")?;
        // The headers now (a bad file is bad usage, before any GPU work); the sizes against
        // this device's limits when the textures are made.
        if let Some(path) = &self.dudv {
            crate::render::scene::dudv_size(path, MAX_SIDE).map_err(input)?;
        }
        if let Some(dir) = &self.skybox {
            crate::render::passes::sky::skybox_side(dir, MAX_SIDE).map_err(input)?;
        }
        if let Some(c) = self.background {
            if c.iter().any(|v| !(0.0..=1.0).contains(v)) {
                return Err(UsageError(
                    "--background: each component must be from 0 to 1".to_string(),
                ));
            }
        }
        if self.sharpen.is_some_and(|s| s > 0.0) && self.aa == AntiAliasing::Off {
            return Err(UsageError(
                "--sharpen: the anti-aliasing pass sharpens, so it needs --aa fxaa".to_string(),
            ));
        }
        let render_scale = self.render_scale.unwrap_or(quality.render_scale);
        let sun_dir = match self.sun {
            None => default_sun_dir(),
            Some([az, el]) => {
                let (az, el) = (az.to_radians(), el.to_radians());
                Vec3::new(el.cos() * az.cos(), el.sin(), el.cos() * az.sin())
            }
        };
        Ok(SceneSettings {
            view: self.view,
            fresnel: self.fresnel,
            aa: self.aa,
            fxaa_fast: quality.fxaa_fast,
            upscale: self.upscale_in_force(),
            rtt_scale: self.rtt_scale.unwrap_or(quality.rtt_scale) as f32,
            render_scale: render_scale as f32,
            // Nothing sharpens without the anti-aliasing pass (given, that is refused above).
            sharpen: self.sharpen.unwrap_or(
                if render_scale < 1.0 && self.aa == AntiAliasing::Fxaa {
                    DEFAULT_SHARPEN
                } else {
                    0.0
                },
            ) as f32,
            terrain_grid: self.terrain_grid.unwrap_or(quality.terrain_grid),
            tess_edge_px: self.tess_edge.unwrap_or(quality.tess_edge_px) as f32,
            geometry: self.geometry,
            layout: SceneLayout {
                buoy_xz: self.buoy,
                sea_floor_m: self.sea_floor as f32,
                // The floor the simulated sea has under it (deep water: one too deep to see).
                deep_floor_m: self
                    .depth
                    .map_or(DEEP_FLOOR_M, |d| (d as f32).min(DEEP_FLOOR_M)),
                ..SceneLayout::default()
            },
            sun_dir,
            cloud_cover: self
                .clouds
                .unwrap_or(self.preset.map_or(DEFAULT_SEA, sea_preset).cloud_cover)
                as f32,
            slicks: self.slicks,
            gusts: self.gusts != Some(Switch::Off),
            shadows: self.shadows.map_or(quality.shadows, |s| s == Switch::On),
            caustics: self.caustics != Some(Switch::Off),
            refraction_caustics: self
                .caustics
                .map_or(quality.refraction_caustics, |s| s == Switch::On),
            dudv: self.dudv.clone(),
            skybox: self.skybox.clone(),
            background: self.background,
        })
    }

    /// The sample's settings for a headless benchmark of `size`. Flags of a single run
    /// (--headless, --frames, --size, --screenshot, --profile, --stats, --dump) do not apply.
    fn bench_run(&self, name: &str, size: (u32, u32)) -> Result<RunSettings, UsageError> {
        let given = [
            ("--headless", self.headless),
            ("--frames", self.frames.is_some()),
            ("--size", self.size.is_some()),
            ("--screenshot", self.screenshot.is_some()),
            ("--profile", self.profile.is_some()),
            ("--stats", self.stats),
            ("--dump", self.dump.is_some()),
        ];
        if let Some((flag, _)) = given.iter().find(|g| g.1) {
            return Err(UsageError(format!(
                "{flag} does not apply to bench {name} (its own --frames, --size and --json go after `bench {name}`)"
            )));
        }
        let mut run = self.settings()?;
        run.headless = true;
        run.size = size;
        Ok(run)
    }

    /// Whether the validation layer is on: `--validation`, or `--validation-extra`, which
    /// implies it.
    pub fn validation_on(&self) -> bool {
        self.validation || self.validation_extra.is_some()
    }

    /// Cross-checks the options and resolves defaults.
    pub fn settings(&self) -> Result<RunSettings, UsageError> {
        require_extension("--screenshot", self.screenshot.as_deref(), "png")?;
        require_extension("--profile", self.profile.as_deref(), "json")?;
        if let Some(path) = &self.frame_graph {
            let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
            if !["json", "dot"].iter().any(|w| ext.eq_ignore_ascii_case(w)) {
                return Err(UsageError(format!(
                    "--frame-graph {}: the file name must end in .json or .dot",
                    path.display()
                )));
            }
        }
        let waves = self.waves_setting()?;
        if self.boat.is_some() && self.bodies >= MAX_BODIES as usize {
            return Err(UsageError(format!(
                "--bodies {} with --boat: at most {} (the boat is a body too)",
                self.bodies,
                MAX_BODIES - 1
            )));
        }
        if self.dump.is_some() && !self.headless {
            return Err(UsageError("--dump needs --headless".to_string()));
        }
        if self.screenshot_every.is_some() && !(self.headless && self.screenshot.is_some()) {
            return Err(UsageError(
                "--screenshot-every needs --headless and --screenshot".into(),
            ));
        }
        if self.log_resources.is_some() && !self.headless {
            return Err(UsageError("--log-resources needs --headless".to_string()));
        }
        let frames = match (self.frames, self.headless, self.profile.is_some()) {
            (Some(n), _, true) if n <= WARMUP_FRAMES => {
                return Err(UsageError(format!(
                    "--profile needs more than {WARMUP_FRAMES} frames (the first {WARMUP_FRAMES} are warm-up); got --frames {n}"
                )))
            }
            (Some(n), _, _) => Some(n),
            (None, true, true) => Some(60),
            (None, true, false) => Some(1),
            (None, false, _) => None,
        };
        let scene = self.scene_settings()?;
        let camera = self.camera_setting()?;
        let quality = quality_level(self.quality_in_force());
        let sea = self.preset.map_or(DEFAULT_SEA, sea_preset);
        let live_set = self.live_set_pairs()?;
        Ok(RunSettings {
            tunables: self.tunables(),
            retune: self.retune(),
            overlay: self.overlay,
            live_set,
            time_scale: self.time_scale,
            quality: (self.quality_in_force().name(), self.quality_chosen_by()),
            scene,
            camera,
            start_time_s: self.time,
            dt_s: self.dt,
            headless: self.headless,
            frames,
            size: self.size.unwrap_or(DEFAULT_SIZE),
            screenshot: self.screenshot.clone(),
            screenshot_every: self.screenshot_every,
            profile: self.profile.clone(),
            frame_graph: self.frame_graph.clone(),
            validation: self.validation_on(),
            validation_extras: self.validation_extra.unwrap_or_default(),
            gpu: self.gpu,
            present_mode: self.present_mode,
            inject_sync_hazard: self.inject_sync_hazard,
            unorm_output: self.unorm_output,
            stats: self.stats,
            log_resources: self.log_resources,
            dump: self.dump.clone(),
            bodies: self.bodies,
            ocean: OceanSettings {
                sea: SeaState {
                    spectrum: self.spectrum,
                    wind_speed_m_s: self.wind_speed.unwrap_or(sea.wind_speed_m_s),
                    wind_dir_deg: self.wind_dir,
                    fetch_km: self.fetch.unwrap_or(sea.fetch_km),
                    depth_m: self.depth,
                },
                fft_size: self.fft_size.unwrap_or(quality.fft_size),
                patch_size_m: self.patch_size.unwrap_or(sea.patch_size_m),
                cascades: self.cascades.unwrap_or(quality.cascades),
                choppiness: self.choppiness.unwrap_or(sea.choppiness),
                seed: self.seed,
                waves,
                spray: self.spray == Switch::On,
                foam_sim: self.foam_sim.map(|s| s == Switch::On),
                boat: self.boat,
            },
        })
    }
}

#[cfg(test)]
mod tests;
