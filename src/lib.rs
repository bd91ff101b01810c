//! vkocean: a real-time FFT ocean on hand-written Vulkan.
//!
//! Layers, bottom up (a module uses only lower layers; tests/layout.rs checks it):
//! [`pass_names`], [`shared`], [`input`], [`platform`] (no crate imports); [`gpu`] (with
//! [`platform`], the only `unsafe`: Vulkan objects, frames, profiler), [`interrupt`];
//! [`ocean`], [`profile`], [`output`]; [`render`] (passes that record the frame); [`tuning`]
//! (what a running sample can change, the presets); [`frontend`] (window or headless output);
//! [`bench`]; the command line in [`cli`] and `main.rs`.

pub mod bench;
pub mod cli;
pub mod frontend;
pub mod gpu;
pub mod input;
pub mod interrupt;
pub mod ocean;
pub mod output;
pub mod pass_names;
pub mod platform;
pub mod profile;
pub mod render;
/// Constants Rust and the shaders share (build.rs writes them as `shared.glsl`).
pub mod shared;
pub mod tuning;

/// SPIR-V of every shader under `shaders/`, compiled by build.rs with glslc.
pub mod shaders {
    include!(concat!(env!("OUT_DIR"), "/shaders.rs"));
}
