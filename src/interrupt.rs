//! SIGINT and SIGTERM: the first one sets a flag that the frame loops and the output
//! commits check ([`check`]), so a run stops after the frame it is in, removes its temporary
//! files, writes no output and exits with 128 + the signal's number (130 for Ctrl-C, 143 for
//! SIGTERM). A second signal of either kills the process at once (the signal's default action),
//! for a run stuck where no check is reached. SIGHUP keeps its default (or, under `nohup`, its
//! ignored) disposition: signal-hook would replace an inherited "ignore".

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, OnceLock};

use signal_hook::consts::{SIGINT, SIGTERM};

/// The first signal caught (0: none) and whether one was.
struct Caught {
    signal: Arc<AtomicUsize>,
    any: Arc<AtomicBool>,
}

static CAUGHT: OnceLock<Caught> = OnceLock::new();

/// A run stopped by a signal: `main` exits with [`Interrupted::exit_code`].
#[derive(Debug, thiserror::Error)]
#[error("stopped by {name}; no output was written", name = signal_name(*signal))]
pub struct Interrupted {
    pub signal: i32,
}

impl Interrupted {
    /// 128 + the signal's number, as a shell reports a process the signal killed.
    pub fn exit_code(&self) -> u8 {
        (128 + self.signal).clamp(0, 255) as u8
    }
}

fn signal_name(signal: i32) -> &'static str {
    match signal {
        SIGINT => "SIGINT (Ctrl-C)",
        SIGTERM => "SIGTERM",
        _ => "a signal",
    }
}

/// Installs the handlers (once; later calls do nothing).
pub fn install() -> std::io::Result<()> {
    if CAUGHT.get().is_some() {
        return Ok(());
    }
    let caught = Caught {
        signal: Arc::new(AtomicUsize::new(0)),
        any: Arc::new(AtomicBool::new(false)),
    };
    for signal in [SIGINT, SIGTERM] {
        // The second signal: the default action (terminate). Registered first, so the first
        // signal finds the flag still clear; the signal's number is stored before the flag is
        // set, so `caught` never sees the flag without it.
        signal_hook::flag::register_conditional_default(signal, caught.any.clone())?;
        signal_hook::flag::register_usize(signal, caught.signal.clone(), signal as usize)?;
        signal_hook::flag::register(signal, caught.any.clone())?;
    }
    let _ = CAUGHT.set(caught);
    Ok(())
}

/// The signal caught so far, if any.
pub fn caught() -> Option<i32> {
    let caught = CAUGHT.get()?;
    if !caught.any.load(Ordering::SeqCst) {
        return None;
    }
    match caught.signal.load(Ordering::SeqCst) {
        0 => Some(SIGINT),
        s => Some(s as i32),
    }
}

/// `Err(Interrupted)` once a signal was caught: call between frames and before committing
/// output files.
pub fn check() -> Result<(), Interrupted> {
    match caught() {
        Some(signal) => Err(Interrupted { signal }),
        None => Ok(()),
    }
}
