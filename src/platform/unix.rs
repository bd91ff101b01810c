//! Unix (Linux with X11): POSIX signals through signal-hook, Xlib's lost-connection handler,
//! and advice that names Debian's packages (tools/setup installs them).

use std::sync::atomic::{AtomicBool, AtomicUsize};
use std::sync::Arc;

use signal_hook::consts::{SIGINT, SIGTERM};

use super::{STOP_INTERRUPT, STOP_TERMINATE};

// The stop numbers are the signals' own (`interrupt::Interrupted::exit_code` is 128 + them).
const _: () = assert!(SIGINT == STOP_INTERRUPT && SIGTERM == STOP_TERMINATE);

/// The Vulkan loader `ash::Entry::load` opens.
pub const VULKAN_LOADER: &str = "libvulkan.so.1";
/// How to get the Vulkan loader.
pub const INSTALL_LOADER: &str = "install libvulkan1 (tools/setup)";
/// What to do when no device exists at all.
pub const INSTALL_DRIVER: &str =
    "without a GPU install Mesa's lavapipe (mesa-vulkan-drivers, tools/setup)";
/// Where the loader reads the installed drivers' manifests.
pub const DRIVER_MANIFESTS: &str =
    "the installed driver manifests (/usr/share/vulkan/icd.d, /etc/vulkan/icd.d)";

/// The line for `--validation` without the layer.
pub fn validation_layer_missing() -> String {
    "the validation layer VK_LAYER_KHRONOS_validation is not installed; install \
     vulkan-validationlayers (tools/setup) or run without --validation"
        .to_string()
}

/// The user-facing name of a stop (`stopped by ...`).
pub fn stop_name(stop: i32) -> &'static str {
    match stop {
        STOP_INTERRUPT => "SIGINT (Ctrl-C)",
        STOP_TERMINATE => "SIGTERM",
        _ => "a signal",
    }
}

/// SIGINT and SIGTERM: the first stores its number in `stop` and then sets `any`; a second one
/// of either takes the signal's default action (the process ends at once), for a run stuck
/// where no check is reached. SIGHUP keeps its default (or, under `nohup`, its ignored)
/// disposition: signal-hook would replace an inherited "ignore".
pub fn install_stop_handlers(
    stop: &Arc<AtomicUsize>,
    any: &Arc<AtomicBool>,
) -> std::io::Result<()> {
    for signal in [SIGINT, SIGTERM] {
        // The default action is registered first, so the first signal finds the flag still
        // clear; the number is stored before the flag is set, so a reader never sees the flag
        // without it.
        signal_hook::flag::register_conditional_default(signal, any.clone())?;
        signal_hook::flag::register_usize(signal, stop.clone(), signal as usize)?;
        signal_hook::flag::register(signal, any.clone())?;
    }
    Ok(())
}

/// Fails when there is no X display to open a window on.
pub fn check_display() -> anyhow::Result<()> {
    if std::env::var_os("DISPLAY").is_none() {
        anyhow::bail!("no X display to open a window on (DISPLAY is not set); run with --headless, or under xvfb-run");
    }
    Ok(())
}

/// After the first window opened: a lost X server becomes vkocean's one line (see `x11`).
pub fn watch_display() {
    super::x11::report_lost_connection();
}

/// The same window as XCB handles, for a Vulkan driver with an XCB surface but no Xlib one
/// (SwiftShader): winit's X11 window is an Xlib display and window id, and the XCB connection
/// comes from the display through libX11-xcb (the window id is the same XID). `None` for other
/// handles, or without libX11-xcb.
///
/// # Safety
/// `display` and `window` are the handles of a live window (winit's), whose display stays
/// open while the returned handles are used (the surface made from them, as for any surface).
pub unsafe fn xcb_handles(
    display: raw_window_handle::RawDisplayHandle,
    window: raw_window_handle::RawWindowHandle,
) -> Option<(
    raw_window_handle::RawDisplayHandle,
    raw_window_handle::RawWindowHandle,
)> {
    use raw_window_handle::{RawDisplayHandle, RawWindowHandle, XcbDisplayHandle, XcbWindowHandle};
    let (RawDisplayHandle::Xlib(d), RawWindowHandle::Xlib(w)) = (display, window) else {
        return None;
    };
    // SAFETY: the display handle is live (this function's contract).
    let connection = unsafe { super::x11::xcb_connection(d.display?.as_ptr()) }?;
    let id = std::num::NonZeroU32::new(u32::try_from(w.window).ok()?)?;
    Some((
        RawDisplayHandle::Xcb(XcbDisplayHandle::new(Some(connection), d.screen)),
        RawWindowHandle::Xcb(XcbWindowHandle::new(id)),
    ))
}
