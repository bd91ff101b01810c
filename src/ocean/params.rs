//! Ocean settings: the sea state plus the simulation grid (plain data, SI units).

use super::gerstner::Wave;
use super::spectrum::{cascades, Cascade, SeaState};

/// Which model makes the surface.
#[derive(Clone, Debug, PartialEq, Default)]
pub enum Waves {
    /// The spectrum, evolved and inverse-transformed (FFT), in cascades.
    #[default]
    Fft,
    /// A sum of analytic Gerstner waves over a camera-following window of side `patch_size_m`.
    Gerstner(Vec<Wave>),
}

/// Everything that determines the simulated fields.
#[derive(Clone, Debug, PartialEq)]
pub struct OceanSettings {
    pub sea: SeaState,
    /// FFT size N (a power of two, 64..=1024).
    pub fft_size: usize,
    /// Side of the largest cascade's patch (m).
    pub patch_size_m: f64,
    /// Number of cascades (1..=4).
    pub cascades: usize,
    /// Horizontal displacement scale λ (0 = no choppiness).
    pub choppiness: f64,
    /// Seed of h0.
    pub seed: u64,
    /// FFT cascades or Gerstner waves.
    pub waves: Waves,
    /// Spray from breaking crests (`--spray`; FFT waves only: Gerstner waves have no wind).
    pub spray: bool,
    /// The foam simulation near the camera (`--foam-sim`; FFT waves only): `None` for the
    /// default, on above a 64² grid (`foam::FoamLevels::layout`).
    pub foam_sim: Option<bool>,
    /// `--boat SPEED,HEADING`: a boat driven in a straight line (m/s, degrees from +x toward
    /// +z) and its wake (`ocean::wake`).
    pub boat: Option<[f64; 2]>,
}

impl Default for OceanSettings {
    /// A pleasant sea seen from 12 m: JONSWAP, 10 m/s over 100 km, 3 cascades from a 400 m patch.
    fn default() -> Self {
        OceanSettings {
            sea: SeaState::default(),
            fft_size: 256,
            patch_size_m: 400.0,
            cascades: 3,
            choppiness: 1.0,
            seed: 1,
            waves: Waves::Fft,
            spray: true,
            foam_sim: None,
            boat: None,
        }
    }
}

impl OceanSettings {
    /// Patch sizes and k bands of the cascades (Gerstner: one "cascade", the window).
    pub fn cascade_list(&self) -> Vec<Cascade> {
        match self.waves {
            Waves::Fft => cascades(self.patch_size_m, self.cascades),
            Waves::Gerstner(_) => cascades(self.patch_size_m, 1),
        }
    }
}
