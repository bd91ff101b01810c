//! The ocean: sea state and spectra ([`spectrum`]), the CPU reference simulation with rustfft
//! ([`cpu`]), and analytic Gerstner waves ([`gerstner`]).

pub mod cpu;
pub mod dump;
pub mod fft;
pub mod gerstner;
pub mod params;
pub mod simulation;
pub mod spectrum;
pub mod stats;

pub use params::{OceanSettings, Waves};
pub use spectrum::{SeaState, SpectrumKind};
