//! Typed errors of the GPU layer. Callers can match on them (the CLI maps [`GpuError::is_usage`] to
//! exit code 2); the `Display` text is the one line a user sees.

use ash::vk;

/// Everything that can go wrong below the renderer.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error(
        "cannot load the Vulkan loader ({library}): {reason}; install libvulkan1 (tools/setup)"
    )]
    LoaderMissing { library: String, reason: String },
    #[error(
        "the validation layer VK_LAYER_KHRONOS_validation is not installed; install \
         vulkan-validationlayers (tools/setup) or run without --validation"
    )]
    ValidationLayerMissing,
    #[error(
        "no Vulkan device found; without a GPU install Mesa's lavapipe (mesa-vulkan-drivers, tools/setup)"
    )]
    NoDevice,
    #[error("no usable Vulkan device: {0}")]
    NoSuitableDevice(String),
    #[error("--gpu {index}: there {} only {count} Vulkan device{} (indices 0..{}); see --list-gpus",
        if *count == 1 { "is" } else { "are" }, if *count == 1 { "" } else { "s" }, count.saturating_sub(1))]
    BadGpuIndex { index: usize, count: usize },
    #[error("{call} failed: {result}")]
    Vk {
        call: &'static str,
        result: vk::Result,
    },
    #[error("GPU memory for {name}: {source}")]
    Alloc {
        name: String,
        source: gpu_allocator::AllocationError,
    },
    #[error("the GPU did not finish frame work within {seconds} s (device hung or lost)")]
    Timeout { seconds: u64 },
    #[error("{0}")]
    Unsupported(String),
}

impl GpuError {
    /// True when the error stems from a command-line value the user can correct (exit code 2).
    pub fn is_usage(&self) -> bool {
        matches!(self, GpuError::BadGpuIndex { .. })
    }
}

/// Result of the GPU layer.
pub type GpuResult<T> = Result<T, GpuError>;

/// Attaches the name of the failing Vulkan call to a raw `vk::Result`.
pub(crate) trait VkResultExt<T> {
    fn vk(self, call: &'static str) -> GpuResult<T>;
}

impl<T> VkResultExt<T> for Result<T, vk::Result> {
    fn vk(self, call: &'static str) -> GpuResult<T> {
        self.map_err(|result| GpuError::Vk { call, result })
    }
}
