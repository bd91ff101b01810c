//! Loading the Vulkan loader and creating the instance: validation layer with synchronization
//! validation, the debug messenger chained in (so instance creation is covered too), and the
//! window-system extensions.

use std::ffi::{c_char, CStr};
use std::sync::Arc;

use ash::vk;
use raw_window_handle::RawDisplayHandle;

use super::debug::{self, MessageCounters};
use super::error::{GpuError, GpuResult, VkResultExt};

pub(crate) const VALIDATION_LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";
/// Environment variable naming the Vulkan loader library to load instead of the system's
/// (`libvulkan.so.1`, `vulkan-1.dll`).
pub const LOADER_ENV: &str = "VKOCEAN_VULKAN_LIBRARY";

/// Loads the Vulkan loader (or the library named by `VKOCEAN_VULKAN_LIBRARY`).
pub(crate) fn load_entry() -> GpuResult<ash::Entry> {
    let library =
        std::env::var(LOADER_ENV).unwrap_or_else(|_| crate::platform::VULKAN_LOADER.to_string());
    // SAFETY: loading the Vulkan loader runs its initialisers; it is the library's documented use.
    let entry = unsafe {
        if std::env::var_os(LOADER_ENV).is_some() {
            ash::Entry::load_from(&library)
        } else {
            ash::Entry::load()
        }
    };
    entry.map_err(|e| GpuError::LoaderMissing {
        library,
        reason: e.to_string(),
    })
}

/// Creates an instance; returns it with the debug-utils availability.
pub(crate) fn create_instance(
    entry: &ash::Entry,
    validation: bool,
    display: Option<RawDisplayHandle>,
    counters: &Arc<MessageCounters>,
) -> GpuResult<(ash::Instance, bool)> {
    // SAFETY: enumerating properties only reads loader state.
    let available_ext =
        unsafe { entry.enumerate_instance_extension_properties(None) }.map_err(|result| {
            GpuError::Loader {
                call: "vkEnumerateInstanceExtensionProperties",
                result,
            }
        })?;
    let has_ext = |name: &CStr| {
        available_ext
            .iter()
            .any(|e| e.extension_name_as_c_str() == Ok(name))
    };

    let mut layers: Vec<*const c_char> = Vec::new();
    let mut extensions: Vec<*const c_char> = Vec::new();
    if validation {
        // SAFETY: as above.
        let available_layers = unsafe { entry.enumerate_instance_layer_properties() }
            .vk("vkEnumerateInstanceLayerProperties")?;
        if !available_layers
            .iter()
            .any(|l| l.layer_name_as_c_str() == Ok(VALIDATION_LAYER))
        {
            return Err(GpuError::ValidationLayerMissing);
        }
        layers.push(VALIDATION_LAYER.as_ptr());
        extensions.push(ash::ext::validation_features::NAME.as_ptr());
    }
    let debug_utils = validation || has_ext(ash::ext::debug_utils::NAME);
    if debug_utils {
        extensions.push(ash::ext::debug_utils::NAME.as_ptr());
    }
    if let Some(display) = display {
        let required =
            ash_window::enumerate_required_extensions(display).map_err(|result| GpuError::Vk {
                call: "ash_window::enumerate_required_extensions",
                result,
            })?;
        extensions.extend_from_slice(required);
    }

    let app_name = c"vkocean";
    let app = vk::ApplicationInfo::default()
        .application_name(app_name)
        .application_version(vk::make_api_version(0, 0, 1, 0))
        .engine_name(app_name)
        .api_version(vk::API_VERSION_1_3);
    let enabled_validation = [vk::ValidationFeatureEnableEXT::SYNCHRONIZATION_VALIDATION];
    let mut validation_features =
        vk::ValidationFeaturesEXT::default().enabled_validation_features(&enabled_validation);
    let mut messenger_info = debug::messenger_info(counters);
    let mut info = vk::InstanceCreateInfo::default()
        .application_info(&app)
        .enabled_layer_names(&layers)
        .enabled_extension_names(&extensions);
    if debug_utils {
        info = info.push_next(&mut messenger_info);
    }
    if validation {
        info = info.push_next(&mut validation_features);
    }
    // SAFETY: every pointer in `info` refers to locals that outlive the call.
    let instance =
        unsafe { entry.create_instance(&info, None) }.map_err(|result| match result {
            vk::Result::ERROR_INCOMPATIBLE_DRIVER => GpuError::NoDevice,
            vk::Result::ERROR_LAYER_NOT_PRESENT => GpuError::ValidationLayerMissing,
            result => GpuError::Vk {
                call: "vkCreateInstance",
                result,
            },
        })?;
    Ok((instance, debug_utils))
}
