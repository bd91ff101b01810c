//! What `--quality` and `--preset` set: cost levels (FFT size, cascades, render and RTT scale,
//! tessellation edge, terrain grid) and sea states by the Beaufort scale. Each fills only what the
//! command line and the config file leave unset (`Cli::settings`).

use clap::ValueEnum;

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum QualityArg {
    Low,
    Medium,
    High,
}

impl QualityArg {
    /// The level when `--quality` is not given: `low` on a CPU implementation (lavapipe draws
    /// the default scene at about 2 FPS at `high` on 2 cores), `high` on a GPU.
    pub fn device_default(cpu_device: bool) -> QualityArg {
        if cpu_device {
            QualityArg::Low
        } else {
            QualityArg::High
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            QualityArg::Low => "low",
            QualityArg::Medium => "medium",
            QualityArg::High => "high",
        }
    }
}

/// What a `--quality` level sets (each flag given explicitly wins).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Quality {
    pub fft_size: usize,
    pub cascades: usize,
    pub render_scale: f64,
    pub rtt_scale: f64,
    pub tess_edge_px: f64,
    pub terrain_grid: u32,
}

pub fn quality_level(q: QualityArg) -> Quality {
    let (fft_size, cascades, render_scale, rtt_scale, tess_edge_px, terrain_grid) = match q {
        QualityArg::Low => (64, 3, 0.5, 0.25, 48.0, 64),
        QualityArg::Medium => (128, 3, 0.75, 0.35, 24.0, 96),
        QualityArg::High => (256, 3, 1.0, 0.5, 16.0, 160),
    };
    Quality {
        fft_size,
        cascades,
        render_scale,
        rtt_scale,
        tess_edge_px,
        terrain_grid,
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum PresetArg {
    Calm,
    Breeze,
    Moderate,
    Storm,
}

/// What a `--preset` sets (and the defaults without one).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SeaPreset {
    /// Wind speed 10 m above the sea, U10 (m/s).
    pub wind_speed_m_s: f64,
    /// Fetch (km).
    pub fetch_km: f64,
    /// Choppy displacement factor.
    pub choppiness: f64,
    /// Side of the largest cascade's patch (m).
    pub patch_size_m: f64,
}

/// The sea without `--preset`: a fresh breeze (Beaufort 5, 8.0–10.7 m/s) over 100 km of fetch.
pub const DEFAULT_SEA: SeaPreset = SeaPreset {
    wind_speed_m_s: 10.0,
    fetch_km: 100.0,
    choppiness: 1.0,
    patch_size_m: 400.0,
};

/// The sea of a `--preset`. Wind speeds are mid-range of their Beaufort force (WMO: force 2
/// light breeze 1.6–3.3 m/s, 4 moderate breeze 5.5–7.9, 6 strong breeze 10.8–13.8, 10 storm
/// 24.5–28.4); fetches grow with the force, the storm's patch holds its ~570 m peak wavelength
/// (2πg/ω_p², ω_p = 0.877 g/U).
pub fn sea_preset(p: PresetArg) -> SeaPreset {
    let sea = |wind_speed_m_s, fetch_km, choppiness, patch_size_m| SeaPreset {
        wind_speed_m_s,
        fetch_km,
        choppiness,
        patch_size_m,
    };
    match p {
        PresetArg::Calm => sea(2.5, 10.0, 0.5, 400.0),
        PresetArg::Breeze => sea(6.7, 50.0, 0.8, 400.0),
        PresetArg::Moderate => sea(12.3, 200.0, 1.0, 400.0),
        PresetArg::Storm => sea(26.5, 1000.0, 1.2, 1000.0),
    }
}
