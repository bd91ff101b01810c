//! Windows: console control events (`SetConsoleCtrlHandler`) in place of POSIX signals, and
//! advice that names `vulkan-1.dll`, the GPU driver and the Vulkan SDK. A window needs no
//! display check, and a window closed by the system arrives as winit's `CloseRequested`, so
//! there is no lost connection to report.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};
use std::time::Duration;

use windows_sys::core::BOOL;
use windows_sys::Win32::System::Console::{SetConsoleCtrlHandler, CTRL_BREAK_EVENT, CTRL_C_EVENT};
use windows_sys::Win32::System::LibraryLoader::{GetModuleHandleA, GetProcAddress};

use super::{STOP_INTERRUPT, STOP_TERMINATE};

/// The Vulkan loader `ash::Entry::load` opens (installed with every GPU driver that has Vulkan).
pub const VULKAN_LOADER: &str = "vulkan-1.dll";
/// How to get the Vulkan loader.
pub const INSTALL_LOADER: &str =
    "install the GPU's driver (it brings the Vulkan loader), or the Vulkan Runtime from the Vulkan SDK";
/// What to do when no device exists at all.
pub const INSTALL_DRIVER: &str = "install or update the GPU's driver (vkocean needs Vulkan 1.3)";
/// Where the loader reads the installed drivers' manifests.
pub const DRIVER_MANIFESTS: &str =
    "the drivers registered under HKEY_LOCAL_MACHINE\\SOFTWARE\\Khronos\\Vulkan\\Drivers";

/// The line for `--validation` without the layer. Under Wine the loader lists no layers at
/// all, but the host's layer can run below it (README, Windows: what tools/windows does).
pub fn validation_layer_missing() -> String {
    if under_wine() {
        "Wine's vulkan-1.dll lists no layers, so --validation cannot enable \
         VK_LAYER_KHRONOS_validation; run without it and enable the host's layer where wine \
         runs (VK_INSTANCE_LAYERS=VK_LAYER_KHRONOS_validation \
         VK_LAYER_ENABLES=VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT \
         VK_KHRONOS_VALIDATION_DEBUG_ACTION=VK_DBG_LAYER_ACTION_LOG_MSG)"
            .to_string()
    } else {
        "the validation layer VK_LAYER_KHRONOS_validation is not installed; install the Vulkan \
         SDK (it carries the layer) or run without --validation"
            .to_string()
    }
}

/// The user-facing name of a stop (`stopped by ...`).
pub fn stop_name(stop: i32) -> &'static str {
    match stop {
        STOP_INTERRUPT => "Ctrl-C",
        STOP_TERMINATE => "closing the console",
        _ => "a console event",
    }
}

/// The flags the handler sets: the stop's number, then whether one came.
static FLAGS: OnceLock<(Arc<AtomicUsize>, Arc<AtomicBool>)> = OnceLock::new();

/// How long the handler holds a closing console open for the run to stop cleanly: Windows ends
/// the process when the handler returns, and by itself about 5 s after the close (then with
/// exit code 0xC000013A, not 143, if the run did not reach its next check in time); the run's
/// own exit ends the process, this thread with it, before either.
const CLOSE_GRACE: Duration = Duration::from_secs(10);

/// The console control handler. It runs on a thread the system starts for each event.
/// Ctrl-C and Ctrl-Break (both reported as Ctrl-C): the first sets the flags and is handled
/// (`TRUE`); any later one is left to the default handler, which ends the process at once (as a
/// second signal does on Unix). Closing the console: the flags, then wait for the run to exit.
/// (Log-off and shutdown reach services only, not a program in a console window.)
unsafe extern "system" fn on_console_event(event: u32) -> BOOL {
    let Some((stop, any)) = FLAGS.get() else {
        return 0;
    };
    let number = match event {
        CTRL_C_EVENT | CTRL_BREAK_EVENT => STOP_INTERRUPT,
        _ => STOP_TERMINATE,
    };
    // The first event claims the number in one step (two quick Ctrl-C's run on two threads;
    // the second must end the process), then sets the flag: a reader never sees the flag
    // without the number.
    if stop
        .compare_exchange(0, number as usize, Ordering::SeqCst, Ordering::SeqCst)
        .is_err()
    {
        return 0;
    }
    any.store(true, Ordering::SeqCst);
    if number == STOP_TERMINATE {
        std::thread::sleep(CLOSE_GRACE);
    }
    1
}

/// Ctrl-C, Ctrl-Break and closing the console: the first stores its stop number in `stop` and
/// then sets `any`.
pub fn install_stop_handlers(
    stop: &Arc<AtomicUsize>,
    any: &Arc<AtomicBool>,
) -> std::io::Result<()> {
    if FLAGS.set((stop.clone(), any.clone())).is_err() {
        return Ok(()); // installed before
    }
    // SAFETY: the handler is a plain function that lives as long as the process; it only
    // touches atomics in a static that is set before the handler is registered.
    if unsafe { SetConsoleCtrlHandler(Some(on_console_event), 1) } == 0 {
        return Err(std::io::Error::last_os_error());
    }
    Ok(())
}

/// A window can always be tried on Windows (no display variable to check).
pub fn check_display() -> anyhow::Result<()> {
    Ok(())
}

/// Nothing to watch: a window the system closes arrives as winit's `CloseRequested`.
pub fn watch_display() {}

/// No X11 on Windows: a Win32 window has one kind of surface.
///
/// # Safety
/// None here (Unix's takes live window handles); `unsafe` to match it.
pub unsafe fn xcb_handles(
    _display: raw_window_handle::RawDisplayHandle,
    _window: raw_window_handle::RawWindowHandle,
) -> Option<(
    raw_window_handle::RawDisplayHandle,
    raw_window_handle::RawWindowHandle,
)> {
    None
}

/// Whether this process runs under Wine: Wine's ntdll exports `wine_get_version`.
fn under_wine() -> bool {
    // SAFETY: ntdll.dll is loaded in every Windows process; both calls take NUL-terminated
    // names and only look the module and the symbol up (the result is not called).
    unsafe {
        let ntdll = GetModuleHandleA(c"ntdll.dll".as_ptr().cast());
        !ntdll.is_null() && GetProcAddress(ntdll, c"wine_get_version".as_ptr().cast()).is_some()
    }
}
