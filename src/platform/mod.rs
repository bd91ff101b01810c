//! Everything that differs between operating systems, behind one `cfg` here at the edge: how a
//! run is asked to stop (POSIX signals on Unix, console control events on Windows), what a lost
//! display looks like (Xlib's fatal I/O error on X11; nothing to catch on Windows, where winit
//! reports a closed window as an event), and what the error messages tell a user to install (the
//! Vulkan loader `libvulkan.so.1` from apt, or `vulkan-1.dll` from the GPU driver or the Vulkan
//! SDK). Each platform file offers the same items; the rest of the crate names only `platform::`.
//!
//! With `gpu`, this is the only place with `unsafe`: the OS calls (Xlib's handler,
//! `SetConsoleCtrlHandler`), each with a `// SAFETY:` line.

#[cfg(unix)]
mod unix;
#[cfg(unix)]
pub use unix::*;

#[cfg(unix)]
mod x11;

#[cfg(windows)]
mod windows;
#[cfg(windows)]
pub use windows::*;

/// The number of the stop that asks a run to end at once (Ctrl-C): SIGINT on Unix; the
/// Windows CRT's `SIGINT` has the same number. `main` exits with 128 + it (130), as a shell
/// reports a process that Ctrl-C ended.
pub const STOP_INTERRUPT: i32 = 2;
/// The number of the stop that asks a run to terminate (SIGTERM on Unix; closing the console on
/// Windows): exit 143.
pub const STOP_TERMINATE: i32 = 15;
