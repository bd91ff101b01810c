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
    /// The sun's shadows (`--shadows`): off at low, where the island's ray march cost the
    /// scene pass twice its time on lavapipe (README, Shadows).
    pub shadows: bool,
    /// The caustics in the refraction view, the floor seen from above through the water
    /// (`--caustics` not given): off at low, where they cost 2 ms a frame on lavapipe in a
    /// quarter-size picture the waves then distort. The view from under the water keeps them.
    pub refraction_caustics: bool,
    /// FXAA at Lottes' fastest preset (`--aa fxaa`; shaders/common/fxaa.glsl's FXAA_FAST): at
    /// low, where his default preset's search and edge threshold cost 0.65 ms a frame more on
    /// lavapipe.
    pub fxaa_fast: bool,
}

pub fn quality_level(q: QualityArg) -> Quality {
    let (fft_size, cascades, render_scale, rtt_scale, tess_edge_px, terrain_grid) = match q {
        QualityArg::Low => (64, 3, 0.5, 0.25, 64.0, 64),
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
        shadows: q != QualityArg::Low,
        refraction_caustics: q != QualityArg::Low,
        fxaa_fast: q == QualityArg::Low,
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
    /// The weather's share of the sky under cloud (0–1): the rougher the sea, the more cloud,
    /// up to a storm's overcast.
    pub cloud_cover: f64,
}

/// The sea without `--preset`: a fresh breeze (Beaufort 5, 8.0–10.7 m/s) over 100 km of fetch.
pub const DEFAULT_SEA: SeaPreset = SeaPreset {
    wind_speed_m_s: 10.0,
    fetch_km: 100.0,
    choppiness: 1.0,
    patch_size_m: 400.0,
    cloud_cover: crate::render::atmosphere::DEFAULT_CLOUD_COVER,
};

/// The sea of a `--preset`. Wind speeds are mid-range of their Beaufort force (WMO: force 2
/// light breeze 1.6–3.3 m/s, 4 moderate breeze 5.5–7.9, 6 strong breeze 10.8–13.8, 10 storm
/// 24.5–28.4); fetches grow with the force. All four seas are fetch-limited JONSWAP
/// (X = gF/U² = 1.1–1.6·10⁴, below full development at 1.9·10⁴): Hs from Hasselmann et al.'s
/// (1973) growth law 0.13, 0.77, 2.81 and 13.5 m, T_p 1.8, 4.3, 8.4 and 18.6 s; the storm's
/// 1000 m patch holds its 540 m peak wavelength (2πg/ω_p², ω_p = 22 (g²/(U F))^⅓).
pub fn sea_preset(p: PresetArg) -> SeaPreset {
    let sea = |wind_speed_m_s, fetch_km, choppiness, patch_size_m, cloud_cover| SeaPreset {
        wind_speed_m_s,
        fetch_km,
        choppiness,
        patch_size_m,
        cloud_cover,
    };
    match p {
        PresetArg::Calm => sea(2.5, 10.0, 0.5, 400.0, 0.1),
        PresetArg::Breeze => sea(6.7, 50.0, 0.8, 400.0, 0.3),
        PresetArg::Moderate => sea(12.3, 200.0, 1.0, 400.0, 0.5),
        PresetArg::Storm => sea(26.5, 1000.0, 1.2, 1000.0, 1.0),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ocean::spectrum::{peak_omega, spectrum_shape, G};
    use crate::ocean::SeaState;

    #[test]
    fn presets_have_the_wave_heights_their_comment_quotes() {
        // (preset, Hs m, T_p s) as quoted above: Hs = 1.6·10⁻³ (gF/U²)^½ U²/g (Hasselmann et al.
        // 1973), T_p = 2π/ω_p, ω_p = 22 (g²/(U F))^⅓.
        let quoted = [
            (PresetArg::Calm, 0.13, 1.8),
            (PresetArg::Breeze, 0.77, 4.3),
            (PresetArg::Moderate, 2.81, 8.4),
            (PresetArg::Storm, 13.5, 18.6),
        ];
        for (preset, hs_quoted, tp_quoted) in quoted {
            let SeaPreset {
                wind_speed_m_s: wind,
                fetch_km: fetch,
                patch_size_m: patch,
                ..
            } = sea_preset(preset);
            let sea = SeaState {
                wind_speed_m_s: wind,
                fetch_km: fetch,
                ..SeaState::default()
            };
            let hs = 4.0 * spectrum_shape(&sea).variance().sqrt();
            let hs_growth = 1.6e-3 * (G * fetch * 1000.0 / (wind * wind)).sqrt() * wind * wind / G;
            let wp = peak_omega(&sea);
            let tp = 2.0 * std::f64::consts::PI / wp;
            assert!(
                (hs / hs_quoted - 1.0).abs() < 0.02 && (hs / hs_growth - 1.0).abs() < 0.02,
                "{preset:?}: Hs {hs} m, quoted {hs_quoted} m, Hasselmann et al. growth law {hs_growth} m"
            );
            assert!(
                (tp / tp_quoted - 1.0).abs() < 0.02,
                "{preset:?}: Tp {tp} s, quoted {tp_quoted} s"
            );
            let wavelength = 2.0 * std::f64::consts::PI * G / (wp * wp);
            assert!(
                wavelength < patch,
                "{preset:?}: peak wavelength {wavelength} m, patch {patch} m"
            );
        }
    }
}
