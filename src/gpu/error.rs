//! Typed errors of the GPU layer. Callers can match on them (the CLI maps [`GpuError::is_usage`] to
//! exit code 2); the `Display` text is the one line a user sees.

use ash::vk;

use crate::platform;

/// Everything that can go wrong below the renderer.
#[derive(Debug, thiserror::Error)]
pub enum GpuError {
    #[error(
        "cannot load the Vulkan loader ({library}): {reason}; {}",
        platform::INSTALL_LOADER
    )]
    LoaderMissing { library: String, reason: String },
    #[error("{}", platform::validation_layer_missing())]
    ValidationLayerMissing,
    #[error("no Vulkan device found; {}", no_device_hint())]
    NoDevice,
    /// Memory for a named object that the driver failed to bind (Mesa 25's lavapipe fails
    /// here, not at allocation, when the address space runs out).
    #[error("GPU memory for {name}: {call} failed: {result}")]
    Bind {
        name: String,
        call: &'static str,
        result: vk::Result,
    },
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
    /// What a pass or pipeline declares disagrees with what its shaders read (`reflect`):
    /// a programming error, found at creation, named by pass, binding and stage.
    #[error("{0}")]
    Interface(String),
    /// The loader failed before any driver ran (in practice: a driver manifest it could not
    /// parse, which it reports as out of host memory).
    #[error("{call} failed: {result}: {}", loader_hint())]
    Loader {
        call: &'static str,
        result: vk::Result,
    },
}

/// [`GpuError::NoDevice`]'s advice: the driver manifests the environment names, if any, else
/// how to install lavapipe.
fn no_device_hint() -> String {
    let set = driver_variables();
    if set.is_empty() {
        platform::INSTALL_DRIVER.to_string()
    } else {
        format!(
            "the Vulkan loader found no usable driver in {}; check that each manifest is valid JSON naming an installed driver",
            set.join(", ")
        )
    }
}

/// The loader's driver-manifest variables that are set, as `NAME=value`.
fn driver_variables() -> Vec<String> {
    ["VK_DRIVER_FILES", "VK_ICD_FILENAMES", "VK_ADD_DRIVER_FILES"]
        .iter()
        .filter_map(|v| std::env::var(v).ok().map(|value| format!("{v}={value}")))
        .collect()
}

/// Where the Vulkan loader found its driver manifests, for [`GpuError::Loader`].
fn loader_hint() -> String {
    let set = driver_variables();
    if set.is_empty() {
        format!(
            "the Vulkan loader could not read {}; check that they are valid JSON",
            platform::DRIVER_MANIFESTS
        )
    } else {
        format!(
            "the Vulkan loader could not use the driver manifests of {}; check that each is valid JSON naming an installed driver",
            set.join(", ")
        )
    }
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
