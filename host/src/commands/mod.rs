//! The subcommands of `gsph` (DESIGN §6), one module each: their arguments (clap) and
//! what they print. They use the library ([`crate::driver`], [`crate::study`],
//! [`crate::stability`], [`crate::window`], [`crate::plot`], [`crate::scene`]) and nothing in
//! the library uses them; [`crate::cli`] parses the command line and calls one of them.

/// `println!` that ignores a closed stdout (`gsph check scene | head -1` must not panic);
/// under MPI only rank 0 prints.
macro_rules! out {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        if crate::dist_rank() == 0 {
            let _ = writeln!(std::io::stdout(), $($arg)*);
        }
    }};
}

pub mod check;
pub mod hugoniot;
pub mod materials;
pub mod plot;
pub mod run;
pub mod stability;
pub mod study;

/// The exit code of a failed command when not 1: 128 + the signal's number after
/// SIGINT/SIGTERM stopped a run.
pub(crate) static EXIT_CODE: std::sync::atomic::AtomicI32 = std::sync::atomic::AtomicI32::new(0);

/// Most worker threads per core `--threads` may ask for.
pub const MAX_THREADS_PER_CORE: usize = 8;

/// The worker threads of a command: `--threads` (at least 1, at most
/// [`MAX_THREADS_PER_CORE`] per core) or all cores.
pub fn pool(threads: Option<usize>) -> Result<rayon::ThreadPool, String> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(t) = threads {
        if t == 0 {
            return Err("--threads must be at least 1".into());
        }
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        if t > MAX_THREADS_PER_CORE * cores {
            return Err(format!(
                "--threads {t}: this machine has {cores} cores; more than {MAX_THREADS_PER_CORE} threads per core ({}) only slows a run down",
                MAX_THREADS_PER_CORE * cores
            ));
        }
        b = b.num_threads(t);
    }
    b.build().map_err(|e| format!("cannot start threads: {e}"))
}

/// Parses the comma-separated list of finite numbers given to `flag`.
pub fn parse_finite(flag: &str, s: &str) -> Result<Vec<f64>, String> {
    s.split(',')
        .map(|n| match n.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(format!("{flag}: `{n}` is not a finite number")),
        })
        .collect()
}

/// A comma-separated list of labels (none when not given).
pub fn labels(l: Option<String>) -> Vec<String> {
    l.map(|l| l.split(',').map(|x| x.trim().to_string()).collect())
        .unwrap_or_default()
}
