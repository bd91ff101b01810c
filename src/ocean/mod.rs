//! The ocean: sea state and spectra ([`spectrum`]), the CPU reference simulation with rustfft
//! ([`cpu`]), analytic Gerstner waves ([`gerstner`]), per-frame height queries of the drawn
//! surface ([`surface`]), the floating buoy ([`buoy`]), whitecaps ([`foam`]), waves over the
//! island's shallows ([`shore`]) and the rendered waves' moments ([`moments`]).

pub mod accuracy;
pub mod bodies;
pub mod buoy;
pub mod cpu;
pub mod dump;
pub mod fft;
pub mod foam;
pub mod gerstner;
pub mod moments;
pub mod params;
pub mod shore;
pub mod simulation;
pub mod spectrum;
pub mod spray;
pub mod stats;
pub mod surface;
pub mod wake;

pub use params::{OceanSettings, Waves};
pub use spectrum::{SeaState, SpectrumKind};
