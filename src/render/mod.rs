//! The renderer: records one frame, pass by pass (see `renderer.rs`). No `unsafe` here: passes
//! record through `gpu::Recorder`.

pub mod camera;
pub mod passes;
pub mod renderer;
pub mod targets;

pub use camera::{Camera, FrameUniforms, OceanBindings};
pub use renderer::{FrameInputs, OutputTarget, Renderer};
