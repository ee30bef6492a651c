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

/// A failed command: its one-line message and its exit code (1, or 128 + the signal's
/// number when SIGINT/SIGTERM stopped a run).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Failure {
    /// The message, printed after `error: `.
    pub message: String,
    /// The process's exit code.
    pub code: i32,
}

impl From<String> for Failure {
    /// A failure with exit code 1.
    fn from(message: String) -> Self {
        Failure { message, code: 1 }
    }
}

impl From<&str> for Failure {
    /// A failure with exit code 1.
    fn from(message: &str) -> Self {
        message.to_string().into()
    }
}

/// The worker threads of a command: `--threads` (at least 1, at most
/// [`crate::exec::MAX_THREADS_PER_CORE`] per core: [`crate::exec::check_threads`]) or all
/// cores.
pub fn pool(threads: Option<usize>) -> Result<rayon::ThreadPool, String> {
    let mut b = rayon::ThreadPoolBuilder::new();
    if let Some(t) = threads {
        if t == 0 {
            return Err("--threads must be at least 1".into());
        }
        crate::exec::check_threads(t).map_err(|e| format!("--threads {t}: {e}"))?;
        b = b.num_threads(t);
    }
    b.build().map_err(|e| format!("cannot start threads: {e}"))
}

/// Parses the comma-separated list given to `flag`: each item a number for which `ok`
/// holds, else an error naming the flag, the item and `what` it must be.
fn parse_numbers(flag: &str, s: &str, ok: fn(f64) -> bool, what: &str) -> Result<Vec<f64>, String> {
    s.split(',')
        .map(|n| match n.trim().parse::<f64>() {
            Ok(v) if ok(v) => Ok(v),
            _ => Err(format!("{flag}: `{n}` is not {what}")),
        })
        .collect()
}

/// Parses the comma-separated list of finite numbers given to `flag`.
pub fn parse_finite(flag: &str, s: &str) -> Result<Vec<f64>, String> {
    parse_numbers(flag, s, f64::is_finite, "a finite number")
}

/// Parses the comma-separated list of positive numbers given to `flag`.
pub fn parse_positive(flag: &str, s: &str) -> Result<Vec<f64>, String> {
    parse_numbers(flag, s, |v| v > 0.0 && v.is_finite(), "a positive number")
}

/// Scene overrides of a command: `--set KEY=VALUE` and `--unset KEY`, applied in order.
#[derive(clap::Args, Debug)]
pub struct Overrides {
    /// Override a scene key (dotted path), e.g. --set bodies.0.spacing=5e-4.
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub set: Vec<String>,
    /// Remove a scene key (dotted path), e.g. --unset options.riemann.
    #[arg(long = "unset", value_name = "KEY")]
    pub unset: Vec<String>,
}

impl Overrides {
    /// The overrides as the scene loader takes them (`KEY=VALUE`, and each unset).
    pub fn list(self) -> Vec<String> {
        crate::scene::with_unsets(self.set, &self.unset)
    }
}

/// A comma-separated list of labels (none when not given).
pub fn labels(l: Option<String>) -> Vec<String> {
    l.map(|l| l.split(',').map(|x| x.trim().to_string()).collect())
        .unwrap_or_default()
}
