//! What the device decides when a flag is not given: what a run uses of it
//! (`device_needs`), and the defaults that follow its type (`--quality`, `--upscale`; main.rs
//! sets `cpu_device` before `Cli::settings` resolves them).

use super::presets::QualityArg;
use super::Cli;
use crate::render::{Geometry, Upscale};

impl Cli {
    /// What a run with these flags (a drawing one) uses of the device: tessellation only for
    /// `--geometry tessellated` (`SceneSettings::needs`).
    pub fn device_needs(&self) -> crate::gpu::Needs {
        crate::gpu::Needs {
            rendering: true,
            tessellation: self.geometry == Some(Geometry::Tessellated),
        }
    }

    /// The quality level: `--quality`, else the device's default (`cpu_device`), else high.
    pub fn quality_in_force(&self) -> QualityArg {
        self.quality
            .unwrap_or(QualityArg::device_default(self.cpu_device == Some(true)))
    }

    /// Who chose the quality level, for the window title and reports: "flag" (`--quality` or
    /// the config file), "device" (the device's default) or "default" (device not known).
    pub fn quality_chosen_by(&self) -> &'static str {
        match (self.quality, self.cpu_device) {
            (Some(_), _) => "flag",
            (None, Some(_)) => "device",
            (None, None) => "default",
        }
    }

    /// `--upscale`, else the device's default (`cpu_device`: bilinear on a CPU device), else
    /// edge-directed.
    pub fn upscale_in_force(&self) -> Upscale {
        self.upscale
            .unwrap_or(Upscale::device_default(self.cpu_device == Some(true)))
    }
}
