//! Loading the Vulkan loader and creating the instance: validation layer with synchronization
//! validation (and the extra checks of `--validation-extra`), the debug messenger chained in (so
//! instance creation is covered too), and the window-system extensions.

use std::ffi::{c_char, CStr};
use std::sync::Arc;

use ash::vk;
use raw_window_handle::{RawDisplayHandle, RawWindowHandle};

use super::debug::{self, MessageCounters};
use super::error::{GpuError, GpuResult, VkResultExt};

pub(crate) const VALIDATION_LAYER: &CStr = c"VK_LAYER_KHRONOS_validation";
/// Environment variable naming the Vulkan loader library to load instead of the system's
/// (`libvulkan.so.1`, `vulkan-1.dll`).
pub const LOADER_ENV: &str = "VKOCEAN_VULKAN_LIBRARY";

/// Checks of the validation layer beyond its core checks and synchronization validation
/// (`--validation-extra`). Best Practices and GPU-assisted validation are enabled through
/// `VkValidationFeaturesEXT` (every layer version has them); the vendor checks have no such
/// flag and are layer settings (`VK_EXT_layer_settings`, validation layers 1.3.268 and newer).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct ValidationExtras {
    /// Best Practices: the layer's vendor-neutral advice on API use (`best-practices`).
    pub best_practices: bool,
    /// Best Practices' AMD, Arm, IMG and NVIDIA checks (`vendors`); implies `best_practices`.
    pub vendors: bool,
    /// GPU-assisted validation: instrumented shaders check descriptor and buffer accesses
    /// (`gpu-assisted`).
    pub gpu_assisted: bool,
}

impl ValidationExtras {
    /// The names `--validation-extra` takes, with what each enables.
    pub const NAMES: [(&'static str, &'static str); 3] = [
        ("best-practices", "Best Practices"),
        (
            "vendors",
            "Best Practices with its AMD, Arm, IMG and NVIDIA checks",
        ),
        ("gpu-assisted", "GPU-assisted validation"),
    ];

    /// Parses a comma-separated list of [`Self::NAMES`]; the error names the unknown entry.
    pub fn parse(list: &str) -> Result<Self, String> {
        let mut extras = ValidationExtras::default();
        for name in list.split(',').map(str::trim) {
            match name {
                "best-practices" => extras.best_practices = true,
                "vendors" => extras.vendors = true,
                "gpu-assisted" => extras.gpu_assisted = true,
                _ => {
                    let known: Vec<&str> = Self::NAMES.iter().map(|n| n.0).collect();
                    return Err(format!(
                        "unknown check '{name}' (known: {})",
                        known.join(", ")
                    ));
                }
            }
        }
        Ok(extras)
    }

    /// `VkValidationFeaturesEXT`'s enables: synchronization validation, and what these add.
    fn features(self) -> Vec<vk::ValidationFeatureEnableEXT> {
        let mut enabled = vec![vk::ValidationFeatureEnableEXT::SYNCHRONIZATION_VALIDATION];
        if self.best_practices || self.vendors {
            enabled.push(vk::ValidationFeatureEnableEXT::BEST_PRACTICES);
        }
        if self.gpu_assisted {
            enabled.push(vk::ValidationFeatureEnableEXT::GPU_ASSISTED);
        }
        enabled
    }
}

/// The validation layer's settings (`VK_EXT_layer_settings`) that turn on Best Practices'
/// vendor checks.
const VENDOR_SETTINGS: [&CStr; 4] = [
    c"validate_best_practices_amd",
    c"validate_best_practices_arm",
    c"validate_best_practices_img",
    c"validate_best_practices_nvidia",
];

/// Loads the Vulkan loader (or the library named by `VKOCEAN_VULKAN_LIBRARY`).
pub(super) fn load_entry() -> GpuResult<ash::Entry> {
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

/// The window handles to make the surface from: winit's, or on X11 the same window as XCB
/// handles where the Vulkan implementation offers VK_KHR_xcb_surface but not
/// VK_KHR_xlib_surface (SwiftShader). The instance is created with the extensions these need.
pub(super) fn surface_handles(
    entry: &ash::Entry,
    (display, window): (RawDisplayHandle, RawWindowHandle),
) -> GpuResult<(RawDisplayHandle, RawWindowHandle)> {
    if !matches!(display, RawDisplayHandle::Xlib(_)) {
        return Ok((display, window));
    }
    let has = instance_extensions(entry)?;
    if has(ash::khr::xlib_surface::NAME) || !has(ash::khr::xcb_surface::NAME) {
        return Ok((display, window));
    }
    // SAFETY: the handles are those of the live winit window the context is made for, which
    // outlives the context and its surface (`ContextDesc::window`, the windowed frontend).
    match unsafe { crate::platform::xcb_handles(display, window) } {
        Some(handles) => {
            log::info!("no VK_KHR_xlib_surface: the window's surface is made through XCB");
            Ok(handles)
        }
        None => Ok((display, window)),
    }
}

/// Whether the loader offers an instance extension, by name (the list read once).
fn instance_extensions(entry: &ash::Entry) -> GpuResult<impl Fn(&CStr) -> bool> {
    // SAFETY: enumerating properties only reads loader state.
    let available =
        unsafe { entry.enumerate_instance_extension_properties(None) }.map_err(|result| {
            GpuError::Loader {
                call: "vkEnumerateInstanceExtensionProperties",
                result,
            }
        })?;
    Ok(move |name: &CStr| {
        available
            .iter()
            .any(|e| e.extension_name_as_c_str() == Ok(name))
    })
}

/// Creates an instance; returns it with the debug-utils availability.
pub(super) fn create_instance(
    entry: &ash::Entry,
    validation: bool,
    extras: ValidationExtras,
    display: Option<RawDisplayHandle>,
    counters: &Arc<MessageCounters>,
) -> GpuResult<(ash::Instance, bool)> {
    let has_ext = instance_extensions(entry)?;

    let mut layers: Vec<*const c_char> = Vec::new();
    let mut extensions: Vec<*const c_char> = Vec::new();
    if validation {
        check_validation_layer(entry, extras)?;
        layers.push(VALIDATION_LAYER.as_ptr());
        extensions.push(ash::ext::validation_features::NAME.as_ptr());
        // VK_EXT_layer_settings (vendor checks) is not enabled by name: loaders older than the
        // extension (Debian 12's 1.3.239) refuse a name they do not know, and the layer reads
        // the settings from the pNext chain either way.
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
    let enabled_validation = extras.features();
    let mut validation_features =
        vk::ValidationFeaturesEXT::default().enabled_validation_features(&enabled_validation);
    // One VkBool32 per setting. (ash 0.38's `values(&[u8])` would count bytes, not values, so
    // the count and pointer are set by hand; `on` outlives the instance creation below.)
    let on: vk::Bool32 = vk::TRUE;
    let vendor_settings: Vec<vk::LayerSettingEXT> = VENDOR_SETTINGS
        .iter()
        .map(|&name| {
            let mut setting = vk::LayerSettingEXT::default()
                .layer_name(VALIDATION_LAYER)
                .setting_name(name)
                .ty(vk::LayerSettingTypeEXT::BOOL32);
            setting.value_count = 1;
            setting.p_values = std::ptr::from_ref(&on).cast();
            setting
        })
        .collect();
    let mut layer_settings = vk::LayerSettingsCreateInfoEXT::default().settings(&vendor_settings);
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
        if extras.vendors {
            info = info.push_next(&mut layer_settings);
        }
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

/// Errors unless the validation layer is installed and, for the vendor checks, has
/// VK_EXT_layer_settings.
fn check_validation_layer(entry: &ash::Entry, extras: ValidationExtras) -> GpuResult<()> {
    // SAFETY: enumerating properties only reads loader state.
    let available_layers = unsafe { entry.enumerate_instance_layer_properties() }
        .vk("vkEnumerateInstanceLayerProperties")?;
    let Some(layer) = available_layers
        .iter()
        .find(|l| l.layer_name_as_c_str() == Ok(VALIDATION_LAYER))
    else {
        return Err(GpuError::ValidationLayerMissing);
    };
    if !extras.vendors {
        return Ok(());
    }
    // SAFETY: as above; the layer name is a nul-terminated constant.
    let layer_ext =
        unsafe { entry.enumerate_instance_extension_properties(Some(VALIDATION_LAYER)) }
            .vk("vkEnumerateInstanceExtensionProperties")?;
    if layer_ext
        .iter()
        .any(|e| e.extension_name_as_c_str() == Ok(ash::ext::layer_settings::NAME))
    {
        return Ok(());
    }
    let v = layer.spec_version;
    Err(GpuError::Unsupported(format!(
        "--validation-extra vendors: the validation layer {}.{}.{} has no VK_EXT_layer_settings, which its vendor checks need (layers 1.3.268 and newer; tools/newest-layer fetches one)",
        vk::api_version_major(v),
        vk::api_version_minor(v),
        vk::api_version_patch(v)
    )))
}
