//! Two frontends, one renderer: [`headless`] renders offscreen and reads the last frame back,
//! [`windowed`] presents to a winit window. Both drive a [`session::Session`].

pub mod clock;
pub mod fly;
pub mod headless;
pub mod overlay;
pub mod session;
pub mod windowed;

use std::path::PathBuf;
use std::sync::Arc;

use crate::gpu::{MessageCounters, PresentMode};
use crate::tuning::Tunables;

/// Everything a run needs, validated by the command line.
#[derive(Clone, Debug)]
pub struct RunSettings {
    /// The `--quality` level in force and who chose it ("flag", "device" or "default"), for the window title and reports.
    pub quality: (&'static str, &'static str),
    pub headless: bool,
    /// Stop after this many frames (`None`: until the window closes).
    pub frames: Option<u64>,
    pub size: (u32, u32),
    pub screenshot: Option<PathBuf>,
    /// `--screenshot-every N`: frames 1, N+1, 2N+1, … as numbered PNGs instead of the last.
    pub screenshot_every: Option<u64>,
    pub profile: Option<PathBuf>,
    /// `--frame-graph PATH`: one frame's graph, as JSON or (`.dot`) Graphviz.
    pub frame_graph: Option<PathBuf>,
    pub validation: bool,
    /// `--validation-extra`: the layer's checks beyond the core and synchronization ones.
    pub validation_extras: crate::gpu::ValidationExtras,
    pub gpu: Option<usize>,
    pub present_mode: PresentMode,
    /// Test-only: record a deliberate synchronization hazard in the first frame.
    pub inject_sync_hazard: bool,
    /// Test-only: headless output in R8G8B8A8_UNORM (shader-encoded sRGB) instead of _SRGB.
    pub unorm_output: bool,
    /// Sea state and simulation grid.
    pub ocean: crate::ocean::OceanSettings,
    /// `--stats`: one JSON line of height statistics per frame on stdout.
    pub stats: bool,
    /// `--log-resources N`: every N headless frames, resident memory and live Vulkan objects.
    pub log_resources: Option<u64>,
    /// `--dump DIR`: the last frame's h0, displacement, normals (.npy) and params.json.
    pub dump: Option<PathBuf>,
    /// `--bodies N`: floating bodies (`ocean::bodies`).
    pub bodies: usize,
    /// How the scene looks (views, Fresnel, island, sky, DU/DV).
    pub scene: crate::render::SceneSettings,
    /// `--camera` / `--look-at` (`None`: the default camera).
    pub camera: Option<crate::render::Camera>,
    /// Simulation time of the first frame (s).
    pub start_time_s: f64,
    /// Time step per frame (s); `None`: 1/60 headless, wall-clock time in a window.
    pub dt_s: Option<f64>,
    /// `--time-scale`: simulation seconds per second (or per `--dt` step).
    pub time_scale: f64,
    /// `--overlay`: the overlay is drawn from the first frame (headless screenshots too).
    pub overlay: bool,
    /// What the overlay can change, as resolved from the flags.
    pub tunables: Tunables,
    /// Turns changed tunables into the settings a restart with those flags would have.
    pub retune: Retune,
    /// Test only (`--live-set`): tunables changed after the first headless frame.
    pub live_set: Vec<(String, String)>,
}

/// The settings a run with other tunables would have: the command line's resolution of its
/// flags (`Cli::retuned`), so a live change and a restart with the flag agree.
#[derive(Clone)]
pub struct Retune(pub Arc<RetuneFn>);

/// [`Retune`]'s function: changed tunables to settings, or the flags' error message.
pub type RetuneFn = dyn Fn(&Tunables) -> Result<RunSettings, String> + Send + Sync;

impl std::fmt::Debug for Retune {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("Retune")
    }
}

/// What a finished run reports back to `main`.
pub struct Outcome {
    /// Validation message counts, complete (read after the context was destroyed).
    pub counters: Arc<MessageCounters>,
}

/// Runs the frontend the settings ask for.
pub fn run(settings: &RunSettings) -> anyhow::Result<Outcome> {
    if settings.headless {
        headless::run(settings)
    } else {
        windowed::run(settings)
    }
}
