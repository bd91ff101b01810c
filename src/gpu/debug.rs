//! VK_EXT_debug_utils: the messenger that counts validation WARNING and ERROR messages, object
//! names and command-buffer labels. INFO and VERBOSE messages are not requested (the loader sends
//! ~90 INFO lines at start-up that say nothing about our use of the API).

use std::borrow::Cow;
use std::ffi::{c_char, c_void, CStr, CString};
use std::sync::atomic::{AtomicU32, Ordering};
use std::sync::Arc;

use ash::vk;

/// Counts of messages the debug messenger received. Shared with the messenger callback through
/// its user-data pointer, so it outlives the instance (the `Context` drops it last).
#[derive(Debug, Default)]
pub struct MessageCounters {
    warnings: AtomicU32,
    errors: AtomicU32,
    /// Log messages at warn/error level (with --validation). Otherwise only loader and driver
    /// chatter arrives (e.g. "Found no drivers!" before our own one-line error), logged at debug.
    loud: bool,
}

impl MessageCounters {
    /// Counters whose messages are logged loudly when `validation` is on.
    pub fn new(validation: bool) -> Self {
        MessageCounters {
            loud: validation,
            ..Default::default()
        }
    }

    /// WARNING-severity messages so far.
    pub fn warnings(&self) -> u32 {
        self.warnings.load(Ordering::Relaxed)
    }
    /// ERROR-severity messages so far.
    pub fn errors(&self) -> u32 {
        self.errors.load(Ordering::Relaxed)
    }
    /// The line printed at exit: `validation: N warnings, M errors`.
    pub fn summary(&self) -> String {
        format!(
            "validation: {} warnings, {} errors",
            self.warnings(),
            self.errors()
        )
    }
}

/// Warnings in which the validation layer describes its own set-up, not our use of the API:
/// logged at info and not counted. With GPU-assisted validation (`--validation-extra
/// gpu-assisted`) layers 1.4 say that core checks slow it down (`VALIDATION-SETTINGS`), that
/// they forced the device features their instrumentation needs on
/// (`WARNING-Setting-Limit-Adjusted`), and that a shader with many buffer reads will be slow to
/// instrument and run under GPU-AV (`GPUAV-Compile-time-general-buffer`, said by 1.4.364 of one
/// pipeline a run since the water's reflection lookup reads more of the reflection's images:
/// the layer's own cost, and the remedy it names is a GPU-AV setting).
const LAYER_NOTICES: [&str; 3] = [
    "VALIDATION-SETTINGS",
    "WARNING-Setting-Limit-Adjusted",
    "GPUAV-Compile-time-general-buffer",
];

/// Severities we subscribe to: the ones that mean our API use is wrong or questionable.
pub(super) fn severities() -> vk::DebugUtilsMessageSeverityFlagsEXT {
    vk::DebugUtilsMessageSeverityFlagsEXT::WARNING | vk::DebugUtilsMessageSeverityFlagsEXT::ERROR
}

pub(super) fn message_types() -> vk::DebugUtilsMessageTypeFlagsEXT {
    vk::DebugUtilsMessageTypeFlagsEXT::GENERAL
        | vk::DebugUtilsMessageTypeFlagsEXT::VALIDATION
        | vk::DebugUtilsMessageTypeFlagsEXT::PERFORMANCE
}

/// Create info for a messenger reporting into `counters`; also chained into `VkInstanceCreateInfo`
/// so that instance creation and destruction are covered.
pub(super) fn messenger_info(
    counters: &Arc<MessageCounters>,
) -> vk::DebugUtilsMessengerCreateInfoEXT<'static> {
    vk::DebugUtilsMessengerCreateInfoEXT::default()
        .message_severity(severities())
        .message_type(message_types())
        .pfn_user_callback(Some(on_message))
        .user_data(Arc::as_ptr(counters) as *mut c_void)
}

/// The messenger callback: counts the message and logs it as `vulkan: [id] message`, where `id`
/// is `pMessageIdName` (a VUID, or e.g. `SYNC-HAZARD-READ-AFTER-WRITE`) when the layer gives one.
/// Validation layers 1.4 put the id only there, 1.3.239 also inside `pMessage`: printing it
/// ourselves gives every layer version the same searchable `[id]`.
unsafe extern "system" fn on_message(
    severity: vk::DebugUtilsMessageSeverityFlagsEXT,
    _types: vk::DebugUtilsMessageTypeFlagsEXT,
    data: *const vk::DebugUtilsMessengerCallbackDataEXT<'_>,
    user: *mut c_void,
) -> vk::Bool32 {
    // SAFETY: `user` is the pointer of an `Arc<MessageCounters>` the Context keeps alive until
    // after the instance (and with it this messenger) is destroyed; `data` and its strings are
    // valid for the duration of the callback per the Vulkan spec (each string may be null).
    let (counters, id, message) = unsafe {
        let counters = &*(user as *const MessageCounters);
        let (id, message) = if data.is_null() {
            (None, None)
        } else {
            (c_str((*data).p_message_id_name), c_str((*data).p_message))
        };
        (counters, id, message)
    };
    let id = id.as_deref().map(str::trim).unwrap_or_default().to_string();
    let (counter, level) = if severity.contains(vk::DebugUtilsMessageSeverityFlagsEXT::ERROR) {
        (Some(&counters.errors), log::Level::Error)
    } else if LAYER_NOTICES.contains(&id.as_str()) {
        (None, log::Level::Info)
    } else {
        (Some(&counters.warnings), log::Level::Warn)
    };
    if let Some(counter) = counter {
        counter.fetch_add(1, Ordering::Relaxed);
    }
    let message = message.unwrap_or_else(|| "(no message)".into());
    let id = if id.is_empty() {
        id
    } else {
        format!("[{id}] ")
    };
    log::log!(
        if counters.loud {
            level
        } else {
            log::Level::Debug
        },
        "vulkan: {id}{message}"
    );
    vk::FALSE
}

/// The text of a nul-terminated string from the layer, or `None` for a null pointer.
///
/// # Safety
/// `ptr` is null or points to a nul-terminated string valid for the returned lifetime.
unsafe fn c_str<'a>(ptr: *const c_char) -> Option<Cow<'a, str>> {
    // SAFETY: the caller guarantees a non-null `ptr` is a valid nul-terminated string.
    (!ptr.is_null()).then(|| unsafe { CStr::from_ptr(ptr) }.to_string_lossy())
}

/// Object names and command-buffer labels (no-ops when VK_EXT_debug_utils is absent).
pub struct DebugNames {
    pub(crate) device_fns: Option<ash::ext::debug_utils::Device>,
}

impl DebugNames {
    /// Names any Vulkan object, so validation messages and captures say which one.
    pub(super) fn name<H: vk::Handle>(&self, handle: H, name: &str) {
        let Some(fns) = &self.device_fns else { return };
        let name = CString::new(name.replace('\0', " ")).expect("NULs were replaced");
        let info = vk::DebugUtilsObjectNameInfoEXT::default()
            .object_handle(handle)
            .object_name(&name);
        // SAFETY: `handle` is a live object of this device and `info` points to valid strings.
        // Naming is best-effort: a failure only loses a debug name.
        let _ = unsafe { fns.set_debug_utils_object_name(&info) };
    }

    /// Opens a labelled region in a command buffer in the recording state.
    pub(super) fn begin_label(&self, cmd: vk::CommandBuffer, name: &str) {
        let Some(fns) = &self.device_fns else { return };
        let name = CString::new(name.replace('\0', " ")).expect("NULs were replaced");
        let label = vk::DebugUtilsLabelEXT::default().label_name(&name);
        // SAFETY: `cmd` is in the recording state (the caller's `Recorder` invariant).
        unsafe { fns.cmd_begin_debug_utils_label(cmd, &label) };
    }

    /// Closes the innermost labelled region.
    pub(super) fn end_label(&self, cmd: vk::CommandBuffer) {
        let Some(fns) = &self.device_fns else { return };
        // SAFETY: `cmd` is recording and has an open label (paired with `begin_label`).
        unsafe { fns.cmd_end_debug_utils_label(cmd) };
    }
}
