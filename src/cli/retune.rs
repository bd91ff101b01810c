//! The command line's side of live changes: the [`Tunables`] a command line resolves to, and
//! the command line a changed set of tunables stands for (`Cli::retuned`), which
//! `Cli::settings` resolves exactly as it does typed flags.

use std::sync::Arc;

use super::presets::{quality_level, sea_preset, DEFAULT_SEA};
use super::tuning::Tunables;
use super::{Cli, Switch, UsageError, WavesArg};
use crate::frontend::Retune;
use crate::render::{default_sun_dir, AntiAliasing};

impl Cli {
    /// The tunables this command line resolves to (a preset's and the quality level's
    /// defaults filled in).
    pub fn tunables(&self) -> Tunables {
        let quality = quality_level(self.quality_in_force());
        let sea = self.preset.map_or(DEFAULT_SEA, sea_preset);
        let sun = self.sun.unwrap_or_else(|| {
            let d = default_sun_dir();
            [d.z.atan2(d.x).to_degrees(), d.y.asin().to_degrees()]
        });
        Tunables {
            quality: self.quality_in_force(),
            preset: self.preset,
            gerstner: self.waves == WavesArg::Gerstner,
            spectrum: self.spectrum,
            wind_speed: self.wind_speed.unwrap_or(sea.wind_speed_m_s),
            wind_dir: self.wind_dir,
            fetch: self.fetch.unwrap_or(sea.fetch_km),
            depth: self.depth,
            choppiness: self.choppiness.unwrap_or(sea.choppiness),
            cascades: self.cascades.unwrap_or(quality.cascades),
            fft_size: self.fft_size.unwrap_or(quality.fft_size),
            patch_size: self.patch_size.unwrap_or(sea.patch_size_m),
            seed: self.seed,
            view: self.view,
            fresnel: self.fresnel,
            aa: self.aa,
            sun,
            clouds: self.clouds.unwrap_or(sea.cloud_cover),
            slicks: self.slicks,
            gusts: self.gusts != Some(Switch::Off),
            time_scale: self.time_scale,
            render_scale: self.render_scale.unwrap_or(quality.render_scale),
            rtt_scale: self.rtt_scale.unwrap_or(quality.rtt_scale),
            tess_edge: self.tess_edge.unwrap_or(quality.tess_edge_px),
            geometry: self.geometry,
            terrain_grid: self.terrain_grid.unwrap_or(quality.terrain_grid),
            camera: self.camera.zip(self.look_at),
        }
    }

    /// This command line with `t`'s values given as flags (the Gerstner table flags kept only
    /// with `--waves gerstner`).
    pub fn retuned(&self, t: &Tunables) -> Cli {
        let mut cli = self.clone();
        cli.quality = Some(t.quality);
        cli.preset = t.preset;
        cli.waves = if t.gerstner {
            WavesArg::Gerstner
        } else {
            cli.gerstner_waves = None;
            cli.gerstner_count = None;
            WavesArg::Fft
        };
        cli.spectrum = t.spectrum;
        cli.wind_speed = Some(t.wind_speed);
        cli.wind_dir = t.wind_dir;
        cli.fetch = Some(t.fetch);
        cli.depth = t.depth;
        cli.choppiness = Some(t.choppiness);
        cli.cascades = Some(t.cascades);
        cli.fft_size = Some(t.fft_size);
        cli.patch_size = Some(t.patch_size);
        cli.seed = t.seed;
        cli.view = t.view;
        cli.fresnel = t.fresnel;
        cli.aa = t.aa;
        // A live `aa = off` takes the sharpening with the pass that does it (given with
        // `--aa off`, --sharpen is refused).
        if t.aa == AntiAliasing::Off {
            cli.sharpen = None;
        }
        cli.sun = Some(t.sun);
        cli.clouds = Some(t.clouds);
        cli.slicks = t.slicks;
        cli.gusts = Some(if t.gusts { Switch::On } else { Switch::Off });
        cli.time_scale = t.time_scale;
        cli.render_scale = Some(t.render_scale);
        cli.rtt_scale = Some(t.rtt_scale);
        cli.tess_edge = Some(t.tess_edge);
        cli.geometry = t.geometry;
        cli.terrain_grid = Some(t.terrain_grid);
        if let Some((eye, at)) = t.camera {
            cli.camera = Some(eye);
            cli.look_at = Some(at);
        }
        cli
    }

    /// The closure the frontends call with changed tunables.
    pub(super) fn retune(&self) -> Retune {
        let base = self.clone();
        Retune(Arc::new(move |t: &Tunables| {
            base.retuned(t).settings().map_err(|e| e.0)
        }))
    }

    /// `--live-set K=V;K=V`, checked against a copy of the tunables (the errors name the key).
    pub(super) fn live_set_pairs(&self) -> Result<Vec<(String, String)>, UsageError> {
        let Some(text) = &self.live_set else {
            return Ok(Vec::new());
        };
        let mut check = self.tunables();
        text.split(';')
            .filter(|p| !p.trim().is_empty())
            .map(|pair| {
                let (k, v) = pair
                    .split_once('=')
                    .ok_or_else(|| UsageError(format!("--live-set {pair}: expected KEY=VALUE")))?;
                check.set(k.trim(), v.trim()).map_err(UsageError)?;
                Ok((k.trim().to_string(), v.trim().to_string()))
            })
            .collect()
    }
}
