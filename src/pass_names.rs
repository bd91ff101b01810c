//! The names of the frame's passes, defined once: `--profile` and `bench frames` report GPU
//! times under them, debug labels (RenderDoc, validation messages) carry them, and the tests
//! match on them. `FFT_FRAME` lists an FFT frame's passes in the order `--profile` reports them
//! (compute first, then graphics; `render::record_frame` submits graphics 1 before the compute).

/// The sky cubemap, rendered again when the sun changes (first frames only).
pub const SKY_CUBE: &str = "sky cube";
/// The mirrored scene above the water, into the reflection texture.
pub const REFLECTION: &str = "reflection";
/// The reflection's distances (from its depth) and the sky its objects hide (a debug label
/// only: timed within `REFLECTION`, with the blurs of its layers).
pub const REFLECTION_DISTANCE: &str = "reflection distance";
/// The caustics' area ratio's means over the floor, by depth and pixel footprint (the first
/// frame that draws caustics, and again when the sun, the waves or the focal length change).
pub const CAUSTIC_MEANS: &str = "caustic means";
/// From under the water: the caustics' means along the camera's rays, for the light shafts.
pub const SHAFTS: &str = "light shafts";
/// The scene below the water, into the refraction texture.
pub const REFRACTION: &str = "refraction";
/// The terrain and objects into the main target.
pub const SCENE: &str = "scene";
/// The tessellated ocean into the main target.
pub const WATER: &str = "water";
/// The sky into what the scene and the water left.
pub const SKY: &str = "sky";
/// `--view reflection|refraction|dudv`: a texture over the whole main target.
pub const TEXTURES_VIEW: &str = "textures view";
/// `--aa fxaa`: FXAA from the main target into the anti-aliased target.
pub const ANTI_ALIASING: &str = "anti-aliasing";
/// The main (or anti-aliased) target copied or scaled into the output.
pub const OUTPUT: &str = "output";
/// The overlay (F1, `--overlay`): egui's panel drawn into the output image.
pub const OVERLAY: &str = "overlay";
/// FFT model: the spectrum h0 evolved to this frame's time.
pub const OCEAN_EVOLVE: &str = "ocean evolve";
/// FFT model: the inverse FFTs of every cascade.
pub const OCEAN_FFT: &str = "ocean fft";
/// FFT model: the FFT output written into the displacement and normal images.
pub const OCEAN_ASSEMBLE: &str = "ocean assemble";
/// Above a 64² grid: the normal images' mip levels (after the wave model).
pub const OCEAN_SLOPE_MIPS: &str = "ocean slope mips";
/// FFT model: the foam near the camera (whitecaps, drift, residual foam, windrows).
pub const OCEAN_FOAM: &str = "ocean foam";
/// FFT model with `--spray on`: the spray's particles moved, landed and born (after the foam).
pub const OCEAN_SPRAY: &str = "ocean spray";
/// Height queries (`Simulation::ask`): the surface above up to 4096 points, for the host.
pub const OCEAN_QUERIES: &str = "ocean height queries";
/// The spray's particles drawn over the scene (after the sky).
pub const SPRAY: &str = "spray";
/// Gerstner model: the wave sum written into the displacement and normal images.
pub const OCEAN_GERSTNER: &str = "ocean gerstner";
/// `--boat`: the wake's steps (eWave: spectrum, inverse FFT, the boat's pressure, forward FFT).
pub const OCEAN_WAKE: &str = "ocean wake";
/// The first frame's foam warm-up steps (a debug label only, never timed).
pub const OCEAN_WARMUP: &str = "ocean foam warm-up";

/// The passes of an FFT frame with the final view, the default `--aa fxaa` and `--spray on`
/// (after the first frames, which also render the sky cube), in the order `--profile` reports
/// them, at `--quality low`; at medium and high `OCEAN_FOAM` follows `OCEAN_ASSEMBLE`.
pub const FFT_FRAME: [&str; 12] = [
    OCEAN_EVOLVE,
    OCEAN_FFT,
    OCEAN_ASSEMBLE,
    OCEAN_SPRAY,
    REFLECTION,
    REFRACTION,
    SCENE,
    WATER,
    SKY,
    SPRAY,
    ANTI_ALIASING,
    OUTPUT,
];
