//! [`Tunables`]: the settings a running sample can change (the overlay's sliders), each one a
//! command-line flag of the same name, and the [`presets`] (`--quality`, `--preset`) that fill
//! them. `Cli::retuned` turns them back into a run's settings through the same resolution as
//! the flags (`Cli::settings`), so a live change and a restart with the flag make the same sea;
//! [`Tunables::to_toml`] writes them as a `--config` file.
//!
//! A layer of its own under `frontend` (whose overlay edits them) and `cli` (which resolves
//! them): the frontend never imports the command line (tests/layout.rs).

use clap::ValueEnum;

pub mod presets;

use crate::ocean::SpectrumKind;
use crate::render::{AntiAliasing, FresnelModel, Geometry, ViewMode};
use presets::{quality_level, sea_preset, PresetArg, QualityArg};

/// Largest `--time-scale`.
pub const MAX_TIME_SCALE: f64 = 100.0;

/// What the overlay edits: resolved values (a preset's or quality level's defaults filled in),
/// named by their flags in [`Tunables::to_toml`].
#[derive(Clone, Debug, PartialEq)]
pub struct Tunables {
    pub quality: QualityArg,
    pub preset: Option<PresetArg>,
    /// `--waves gerstner` (else fft).
    pub gerstner: bool,
    pub spectrum: SpectrumKind,
    pub wind_speed: f64,
    pub wind_dir: f64,
    pub fetch: f64,
    /// `None`: deep water.
    pub depth: Option<f64>,
    pub choppiness: f64,
    pub cascades: usize,
    pub fft_size: usize,
    pub patch_size: f64,
    pub seed: u64,
    pub view: ViewMode,
    pub fresnel: FresnelModel,
    pub aa: AntiAliasing,
    /// Azimuth and elevation (degrees).
    pub sun: [f32; 2],
    pub clouds: f64,
    /// The share of the sea in natural slicks (`None`: by the wind, `render::slicks`).
    pub slicks: Option<f64>,
    /// `--gusts`: wind gusts (`render::gusts`).
    pub gusts: bool,
    /// Simulation seconds per second (or per `--dt` step).
    pub time_scale: f64,
    pub render_scale: f64,
    pub rtt_scale: f64,
    pub tess_edge: f64,
    /// `None`: the default (clipmap).
    pub geometry: Option<Geometry>,
    pub terrain_grid: u32,
    /// Camera position and a point it looks at (written by the frontend when saving).
    pub camera: Option<([f32; 3], [f32; 3])>,
}

/// A value's name on the command line (`ValueEnum`).
fn name<T: ValueEnum>(v: &T) -> String {
    v.to_possible_value()
        .map_or_else(String::new, |p| p.get_name().to_string())
}

/// A TOML number for `x` (Rust's shortest round-tripping form; integers stay integers).
fn number(x: f64) -> String {
    format!("{x}")
}

impl Tunables {
    /// Picks a quality level and the values it sets (FFT size, cascades, scales, tessellation
    /// edge, terrain grid), as `--quality` alone would.
    pub fn set_quality(&mut self, q: QualityArg) {
        let level = quality_level(q);
        self.quality = q;
        self.fft_size = level.fft_size;
        self.cascades = level.cascades;
        self.render_scale = level.render_scale;
        self.rtt_scale = level.rtt_scale;
        self.tess_edge = level.tess_edge_px;
        self.terrain_grid = level.terrain_grid;
    }

    /// Picks a sea preset and the values it sets (wind, fetch, choppiness, patch, clouds), as
    /// `--preset` alone would.
    pub fn set_preset(&mut self, p: PresetArg) {
        let sea = sea_preset(p);
        self.preset = Some(p);
        self.wind_speed = sea.wind_speed_m_s;
        self.fetch = sea.fetch_km;
        self.choppiness = sea.choppiness;
        self.patch_size = sea.patch_size_m;
        self.clouds = sea.cloud_cover;
    }

    /// `key = value` lines, one per flag, that `--config` reads back to these settings.
    pub fn to_toml(&self) -> String {
        let mut lines = vec![
            "# vkocean settings, saved from the overlay; run with: vkocean --config FILE".into(),
            format!("quality = \"{}\"", self.quality.name()),
        ];
        if let Some(p) = self.preset {
            lines.push(format!("preset = \"{}\"", name(&p)));
        }
        let waves = if self.gerstner { "gerstner" } else { "fft" };
        lines.push(format!("waves = \"{waves}\""));
        lines.push(format!("spectrum = \"{}\"", name(&self.spectrum)));
        lines.push(format!("wind-speed = {}", number(self.wind_speed)));
        lines.push(format!("wind-dir = {}", number(self.wind_dir)));
        lines.push(format!("fetch = {}", number(self.fetch)));
        if let Some(d) = self.depth {
            lines.push(format!("depth = {}", number(d)));
        }
        lines.push(format!("choppiness = {}", number(self.choppiness)));
        lines.push(format!("cascades = {}", self.cascades));
        lines.push(format!("fft-size = {}", self.fft_size));
        lines.push(format!("patch-size = {}", number(self.patch_size)));
        // TOML integers stop at 2^63 - 1; a string holds every seed.
        lines.push(format!("seed = \"{}\"", self.seed));
        lines.push(format!("view = \"{}\"", name(&self.view)));
        lines.push(format!("fresnel = \"{}\"", name(&self.fresnel)));
        lines.push(format!("aa = \"{}\"", name(&self.aa)));
        let [az, el] = self.sun;
        lines.push(format!(
            "sun = [{}, {}]",
            number(az as f64),
            number(el as f64)
        ));
        lines.push(format!("clouds = {}", number(self.clouds)));
        if let Some(share) = self.slicks {
            lines.push(format!("slicks = {}", number(share)));
        }
        let gusts = if self.gusts { "on" } else { "off" };
        lines.push(format!("gusts = \"{gusts}\""));
        lines.push(format!("time-scale = {}", number(self.time_scale)));
        lines.push(format!("render-scale = {}", number(self.render_scale)));
        lines.push(format!("rtt-scale = {}", number(self.rtt_scale)));
        lines.push(format!("tess-edge = {}", number(self.tess_edge)));
        if let Some(g) = self.geometry {
            lines.push(format!("geometry = \"{}\"", g.name()));
        }
        lines.push(format!("terrain-grid = {}", self.terrain_grid));
        if let Some((eye, at)) = self.camera {
            let v = |p: [f32; 3]| p.map(|c| number(c as f64)).join(", ");
            lines.push(format!("camera = [{}]", v(eye)));
            lines.push(format!("look-at = [{}]", v(at)));
        }
        lines.join("\n") + "\n"
    }

    /// Sets one tunable by its flag name from text, as the overlay's control would (the
    /// hidden `--live-set KEY=VALUE` of the tests). Ranges are the flags' own.
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), String> {
        let bad = |what: &str| format!("--live-set {key}={value}: {what}");
        let num = |lo: f64, hi: f64| -> Result<f64, String> {
            value
                .parse::<f64>()
                .ok()
                .filter(|v| (lo..=hi).contains(v))
                .ok_or_else(|| bad(&format!("expected a number from {lo} to {hi}")))
        };
        let choice = |v: &str| -> Result<usize, String> {
            v.parse::<usize>()
                .map_err(|_| bad("expected a whole number"))
        };
        fn pick<T: ValueEnum>(value: &str) -> Result<T, String> {
            T::from_str(value, true)
        }
        match key {
            "quality" => self.set_quality(pick(value).map_err(|e| bad(&e))?),
            "preset" => self.set_preset(pick(value).map_err(|e| bad(&e))?),
            "waves" => {
                self.gerstner = match value {
                    "fft" => false,
                    "gerstner" => true,
                    _ => return Err(bad("expected fft or gerstner")),
                }
            }
            "spectrum" => self.spectrum = pick(value).map_err(|e| bad(&e))?,
            "wind-speed" => self.wind_speed = num(1e-3, 100.0)?,
            "wind-dir" => self.wind_dir = num(-360.0, 360.0)?,
            "fetch" => self.fetch = num(1e-3, 10_000.0)?,
            "depth" => self.depth = Some(num(1e-3, 11_000.0)?),
            "choppiness" => self.choppiness = num(0.0, 10.0)?,
            "cascades" => self.cascades = choice(value)?.clamp(1, 4),
            "fft-size" => {
                let n = choice(value)?;
                if !n.is_power_of_two() || !(64..=1024).contains(&n) {
                    return Err(bad("expected a power of two from 64 to 1024"));
                }
                self.fft_size = n;
            }
            "patch-size" => self.patch_size = num(1e-3, 100_000.0)?,
            "seed" => self.seed = value.parse().map_err(|_| bad("expected a seed"))?,
            "view" => self.view = pick(value).map_err(|e| bad(&e))?,
            "fresnel" => self.fresnel = pick(value).map_err(|e| bad(&e))?,
            "aa" => self.aa = pick(value).map_err(|e| bad(&e))?,
            "sun-azimuth" => self.sun[0] = num(-360.0, 360.0)? as f32,
            "sun-elevation" => self.sun[1] = num(-10.0, 90.0)? as f32,
            "clouds" => self.clouds = num(0.0, 1.0)?,
            "slicks" => self.slicks = Some(num(0.0, 1.0)?),
            "gusts" => {
                self.gusts = match value {
                    "on" => true,
                    "off" => false,
                    _ => return Err(bad("expected on or off")),
                }
            }
            "time-scale" => self.time_scale = num(0.0, MAX_TIME_SCALE)?,
            "render-scale" => self.render_scale = num(0.25, 1.0)?,
            "rtt-scale" => self.rtt_scale = num(0.1, 1.0)?,
            "tess-edge" => self.tess_edge = num(2.0, 256.0)?,
            "geometry" => self.geometry = Some(pick(value).map_err(|e| bad(&e))?),
            _ => return Err(bad("not a setting the overlay changes")),
        }
        Ok(())
    }
}
