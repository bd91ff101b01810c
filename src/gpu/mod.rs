//! The GPU layer: the only place with `unsafe`. Small RAII wrappers over Vulkan objects (ash);
//! their `Drop` hands the handles to the context's deletion queue, which destroys them once the
//! frame timeline says the GPU finished every frame that could use them.

pub mod buffer;
pub mod command;
pub mod compute;
pub mod context;
pub mod debug;
pub mod descriptors;
pub mod egui;
pub mod error;
pub mod formats;
pub mod frame;
mod garbage;
pub mod graph;
pub mod image;
pub mod instance;
pub mod oneshot;
pub mod pass;
pub mod physical;
pub mod pipeline;
pub mod queues;
pub mod reflect;
pub mod selftest;
pub mod submit;
pub mod swapchain;
pub mod timestamps;
pub mod track;
mod transfer;

pub use ash::vk;
pub use buffer::{Buffer, BufferView};
pub use command::{Access, Load, Recorder};
pub use context::{Context, ContextDesc, DeviceInfo, DeviceSummary, Needs};
pub use debug::MessageCounters;
pub use descriptors::{Bind, BoundSet, DescriptorSetLayout, Order};
pub use error::{GpuError, GpuResult};
pub use formats::FormatUse;
pub use frame::{Frame, Frames, Submission, FRAMES_IN_FLIGHT};
pub use gpu_allocator::MemoryLocation;
pub use image::{Image, ImageDesc, Output, Sampler};
pub use instance::ValidationExtras;
pub use pass::{check_bindings, Bindings, Rendering, Target};
pub use pipeline::{GraphicsDesc, Pipeline, PipelineLayout};
pub use queues::{QueuePlan, QueueUsers};
pub use submit::SemaphoreOp;
pub use swapchain::{AcquiredImage, PresentMode, Swapchain};
pub use timestamps::{
    DrawStatistics, FrameTimes, GpuTimings, Profiler, Profilers, COMPUTE, GRAPHICS_OCEAN,
    GRAPHICS_SCENE,
};
pub use track::{ExternalImage, State, Tracked, Use};
