//! SIGINT and SIGTERM during `gsph run`: the first one asks the run to stop after the step
//! in progress (it then writes a checkpoint, leaves its snapshots marked partial, records
//! the interruption in run.log and exits with 128 + the signal's number); a second SIGINT
//! ends the process at once. Handlers are installed by the command line only
//! ([`install`]); a library user's process keeps its own signal handling.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::Arc;

static PENDING: std::sync::OnceLock<Arc<AtomicUsize>> = std::sync::OnceLock::new();

fn flag() -> &'static Arc<AtomicUsize> {
    PENDING.get_or_init(|| Arc::new(AtomicUsize::new(0)))
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
