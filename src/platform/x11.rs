//! A lost X server (the window killed with `xdotool windowkill`, Xvfb closed) as vkocean's one
//! line. Xlib learns of it first, in whatever call meets the closed socket (winit's event loop,
//! the swapchain's present), and its default I/O error handler prints two lines of its own
//! before `exit(1)`. The handler here prints ours instead. (The surface and the device go with
//! the display, so there is nothing to tear down; output files are only written at the end of a
//! run, so none is left half-written.)

use std::io::Write;
use std::os::raw::c_int;
use std::sync::OnceLock;

use x11_dl::xlib::{Display, Xlib};

/// libX11, loaded once (the same library winit loaded: the handler is process-wide).
static XLIB: OnceLock<Option<Xlib>> = OnceLock::new();

/// Xlib's fatal I/O error handler: Xlib requires that it does not return.
unsafe extern "C" fn lost_connection(_display: *mut Display) -> c_int {
    let _ = writeln!(
        std::io::stderr(),
        "vkocean: lost the connection to the X server (the window was killed or the display closed)"
    );
    std::process::exit(1)
}

/// Installs the handler (after the first window opened: winit has loaded libX11 then).
pub fn report_lost_connection() {
    if let Some(xlib) = XLIB.get_or_init(|| Xlib::open().ok()) {
        // SAFETY: XSetIOErrorHandler only stores the pointer; the handler is a plain function
        // that never returns and touches no Xlib state.
        unsafe { (xlib.XSetIOErrorHandler)(Some(lost_connection)) };
    }
}

/// libX11-xcb, loaded once: XGetXCBConnection for the XCB surface fallback.
static XLIB_XCB: OnceLock<Option<x11_dl::xlib_xcb::Xlib_xcb>> = OnceLock::new();

/// The XCB connection under an Xlib display (one socket, two client libraries), or `None` when
/// libX11-xcb cannot be loaded or `display` is null.
///
/// # Safety
/// `display` is null or a live Xlib `Display*`; the connection returned is valid only while
/// that display stays open.
pub unsafe fn xcb_connection(
    display: *mut std::ffi::c_void,
) -> Option<std::ptr::NonNull<std::ffi::c_void>> {
    let xcb = XLIB_XCB
        .get_or_init(|| x11_dl::xlib_xcb::Xlib_xcb::open().ok())
        .as_ref()?;
    if display.is_null() {
        return None;
    }
    // SAFETY: `display` is a live, non-null Xlib display (this function's contract);
    // XGetXCBConnection only reads the connection it wraps.
    let connection = unsafe { (xcb.XGetXCBConnection)(display.cast()) };
    std::ptr::NonNull::new(connection.cast())
}
