//! Fault injection for the reliability tests (tests/command_line/faults.rs), compiled
//! only with the `fault-injection` feature, which only the workspace's
//! test build turns on (a dev-dependency of the root package): a released
//! `elcon` has no such code. With it, the environment variable
//! `ELCON_FAULTS` (comma-separated) may ask for
//!
//! - `panic=NAME`: a panic in the solve of the scene (or batch run) named NAME;
//! - `write_delay_ms=T`: a pause of T ms after each file of a scene's
//!   outputs is written (so that a test can kill or race a run mid-write);
//! - `kill_before_record=K`, `kill_after_record=K`, `term_after_record=K`:
//!   SIGKILL just before, SIGKILL or SIGTERM just after, the K-th finished
//!   run of a batch is written to its journal.
//!
//! Without the feature every point compiles to nothing.

/// The variable read.
#[cfg(feature = "fault-injection")]
const VARIABLE: &str = "ELCON_FAULTS";

/// The value of `key=...` in `ELCON_FAULTS`.
#[cfg(feature = "fault-injection")]
fn fault(key: &str) -> Option<String> {
    let all = std::env::var(VARIABLE).ok()?;
    all.split(',').find_map(|f| {
        f.split_once('=')
            .filter(|(k, _)| k.trim() == key)
            .map(|(_, v)| v.trim().to_string())
    })
}

/// Panics if `ELCON_FAULTS` asks for a panic in scene `name`.
#[cfg(feature = "fault-injection")]
pub fn panic_point(name: &str) {
    if fault("panic").is_some_and(|n| n == name) {
        panic!("fault injected by {VARIABLE} in scene `{name}`");
    }
}

/// Pauses as `ELCON_FAULTS` asks after a file is written.
#[cfg(feature = "fault-injection")]
pub fn write_delay() {
    if let Some(ms) = fault("write_delay_ms").and_then(|v| v.parse().ok()) {
        std::thread::sleep(std::time::Duration::from_millis(ms));
    }
}

/// Without the feature: nothing.
#[cfg(not(feature = "fault-injection"))]
pub fn panic_point(_name: &str) {}

/// Without the feature: nothing.
#[cfg(not(feature = "fault-injection"))]
pub fn write_delay() {}

/// Sends `signal` to this process (through kill(1), as a scheduler
/// would) and waits for it to take effect.
#[cfg(feature = "fault-injection")]
fn signal_self(signal: &str) {
    let _ = std::process::Command::new("kill")
        .arg(format!("-{signal}"))
        .arg(std::process::id().to_string())
        .status();
    std::thread::sleep(std::time::Duration::from_millis(200));
}

/// Before the `n`-th run of this process is journaled (its directory in
/// place): `kill_before_record=n` kills the process (SIGKILL).
#[cfg(feature = "fault-injection")]
pub fn before_record(n: usize) {
    if fault("kill_before_record").is_some_and(|v| v == n.to_string()) {
        signal_self("KILL");
    }
}

/// After the `n`-th run of this process is journaled:
/// `kill_after_record=n` kills the process (SIGKILL),
/// `term_after_record=n` sends it SIGTERM.
#[cfg(feature = "fault-injection")]
pub fn after_record(n: usize) {
    if fault("kill_after_record").is_some_and(|v| v == n.to_string()) {
        signal_self("KILL");
    }
    if fault("term_after_record").is_some_and(|v| v == n.to_string()) {
        signal_self("TERM");
    }
}

/// Without the feature: nothing.
#[cfg(not(feature = "fault-injection"))]
pub fn before_record(_n: usize) {}

/// Without the feature: nothing.
#[cfg(not(feature = "fault-injection"))]
pub fn after_record(_n: usize) {}
