//! SIGINT and SIGTERM during `gsph run`: the first one asks the run to stop after the step
//! in progress (it then writes a checkpoint, leaves its snapshots marked partial, records
//! the interruption in run.log and exits with 128 + the signal's number); a second SIGINT
//! ends the process at once. Handlers are installed by the command line only
//! ([`install`]); a library user's process keeps its own signal handling.
//!
//! While the run is still being set up (the scene built, particles placed, walls mirrored,
//! neighbour lists made, a checkpoint restored: nothing in the output folder touched yet)
//! either signal ends the process at once with 128 + its number, however long the set-up
//! takes; [`set_up_done`] marks the end of that phase, just before the run locks its
//! folder.

use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;

static PENDING: std::sync::OnceLock<Arc<AtomicUsize>> = std::sync::OnceLock::new();

fn flag() -> &'static Arc<AtomicUsize> {
    PENDING.get_or_init(|| Arc::new(AtomicUsize::new(0)))
}

static SETTING_UP: std::sync::OnceLock<Arc<AtomicBool>> = std::sync::OnceLock::new();

/// True until [`set_up_done`]: a signal then ends the process at once.
fn setting_up() -> &'static Arc<AtomicBool> {
    SETTING_UP.get_or_init(|| Arc::new(AtomicBool::new(true)))
}

/// The run is set up and about to touch its output folder: from now on a signal stops it
/// after the step in progress (module docs).
pub fn set_up_done() {
    setting_up().store(false, Ordering::SeqCst);
}

/// Installs the handlers (idempotent). Needs the cargo feature `cli`.
#[cfg(feature = "cli")]
pub fn install() -> Result<(), String> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    static DONE: std::sync::Once = std::sync::Once::new();
    let mut result = Ok(());
    DONE.call_once(|| {
        let f = flag();
        let run = || -> std::io::Result<()> {
            // during the set-up: at once (nothing is written yet)
            let early = setting_up();
            signal_hook::flag::register_conditional_shutdown(SIGINT, 130, Arc::clone(early))?;
            signal_hook::flag::register_conditional_shutdown(SIGTERM, 143, Arc::clone(early))?;
            // a second SIGINT (flag already set) exits at once with 130
            let second = Arc::new(std::sync::atomic::AtomicBool::new(false));
            signal_hook::flag::register_conditional_shutdown(SIGINT, 130, Arc::clone(&second))?;
            signal_hook::flag::register(SIGINT, second)?;
            signal_hook::flag::register_usize(SIGINT, Arc::clone(f), SIGINT as usize)?;
            signal_hook::flag::register_usize(SIGTERM, Arc::clone(f), SIGTERM as usize)?;
            Ok(())
        };
        result = run().map_err(|e| format!("cannot install signal handlers: {e}"));
    });
    result
}

/// The signal received since the run started, if any (its number).
pub fn pending() -> Option<i32> {
    match flag().load(Ordering::Relaxed) {
        0 => None,
        s => Some(s as i32),
    }
}

/// Forgets a received signal (tests).
pub fn clear() {
    flag().store(0, Ordering::Relaxed);
}

/// Name of a signal number.
pub fn name(signal: i32) -> &'static str {
    match signal {
        2 => "SIGINT",
        15 => "SIGTERM",
        _ => "a signal",
    }
}
