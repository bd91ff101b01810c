//! Stopping a run from outside: Ctrl-C and SIGTERM on Unix, Ctrl-C, Ctrl-Break and closing the
//! console on Windows (the handlers are `platform::install_stop_handlers`). The first one sets a
//! flag that the frame loops and the output commits check ([`check`]), so a run stops after the
//! frame it is in, removes its temporary files, writes no output and exits with 128 + the
//! stop's number (130 for Ctrl-C, 143 for SIGTERM or a closed console). A second one ends the
//! process at once, for a run stuck where no check is reached.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};

use crate::platform::{self, STOP_INTERRUPT};

/// The first stop caught (0: none) and whether one was.
struct Caught {
    stop: Arc<AtomicUsize>,
    any: Arc<AtomicBool>,
}

static CAUGHT: OnceLock<Caught> = OnceLock::new();

/// A run stopped from outside: `main` exits with [`Interrupted::exit_code`].
#[derive(Debug, thiserror::Error)]
#[error("stopped by {name}; no output was written", name = platform::stop_name(*signal))]
pub struct Interrupted {
    /// The signal's number (on Windows `platform::STOP_INTERRUPT` or `STOP_TERMINATE`).
    pub signal: i32,
}

impl Interrupted {
    /// 128 + the signal's number, as a shell reports a process the signal killed.
    pub fn exit_code(&self) -> u8 {
        (128 + self.signal).clamp(0, 255) as u8
    }
}

/// Installs the handlers (once; later calls do nothing).
pub fn install() -> std::io::Result<()> {
    if CAUGHT.get().is_some() {
        return Ok(());
    }
    let caught = Caught {
        stop: Arc::new(AtomicUsize::new(0)),
        any: Arc::new(AtomicBool::new(false)),
    };
    platform::install_stop_handlers(&caught.stop, &caught.any)?;
    let _ = CAUGHT.set(caught);
    Ok(())
}

/// The stop caught so far, if any.
pub fn caught() -> Option<i32> {
    let caught = CAUGHT.get()?;
    if !caught.any.load(Ordering::SeqCst) {
        return None;
    }
    match caught.stop.load(Ordering::SeqCst) {
        0 => Some(STOP_INTERRUPT),
        s => Some(s as i32),
    }
}

/// `Err(Interrupted)` once a stop was caught: call between frames and before committing
/// output files.
pub fn check() -> Result<(), Interrupted> {
    match caught() {
        Some(signal) => Err(Interrupted { signal }),
        None => Ok(()),
    }
}
