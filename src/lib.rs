//! vkocean: a real-time FFT ocean on hand-written Vulkan.
//!
//! Layers, bottom up: [`gpu`] (with [`platform`], the only `unsafe`: Vulkan objects, frames,
//! profiler; the OS calls that differ between Unix and Windows),
//! [`render`] (passes that record the frame), [`frontend`] (window or headless output) and the
//! command line in `main.rs` / [`cli`].

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

/// SPIR-V of every shader under `shaders/`, compiled by build.rs with glslc.
pub mod shaders {
    include!(concat!(env!("OUT_DIR"), "/shaders.rs"));
}
