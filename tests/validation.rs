//! Validation is really on: a deliberate synchronization hazard (a test-only path) is reported
//! by synchronization validation, counted, and turns the exit code into 3.

mod common;

use common::{clean_run, run, stderr, validation_counts};

#[test]
fn deliberate_sync_hazard_is_detected() {
    let out = run(&[
        "--headless",
        "--validation",
        "--inject-sync-hazard",
        "--size",
        "320x180",
    ]);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(3), "{err}");
    // The id as the messenger prints it (`vulkan: [id] message`): validation layers 1.4 give it
    // only in pMessageIdName, 1.3.239 also inside the message as `[ id ]`.
    assert!(err.contains("[SYNC-HAZARD-READ-AFTER-WRITE]"), "{err}");
    let (warnings, errors) = validation_counts(&err).expect("summary line");
    assert!(warnings + errors >= 1, "{err}");
}

#[test]
fn clean_run_counts_zero() {
    // The same path without the hazard: the counters stay at zero and the exit code is 0.
    let out = run(&[
        "--headless",
        "--validation",
        "--frames",
        "3",
        "--size",
        "320x180",
    ]);
    clean_run(&out, "vkocean");
}
