//! `gsph hugoniot`: the shock Hugoniot of a moving-window scene ([`crate::window`]).

use crate::scene::{self, scene_name};
use std::path::PathBuf;

/// The fastest particle velocity or shock speed `gsph hugoniot` takes, m/s.
pub const MAX_SPEED: f64 = 1e5;

/// Arguments of `gsph hugoniot`.
#[derive(clap::Args, Debug)]
pub struct HugoniotArgs {
    /// Scene file with a `[window]` section.
    pub scene: PathBuf,
    /// Particle velocities u_p, m/s, comma-separated.
    #[arg(long, default_value = "50,75,100,125,150,200")]
    pub up: String,
    /// Initial bracket of u_s, m/s, `LO,HI` (default from the full-compaction bound B = m u_p/(m-1): 0.85 B and max(2 B, B + 300)); widened if it misses the root.
    #[arg(long)]
    pub bracket: Option<String>,
    /// Bisection stops below this bracket width, m/s.
    #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
    pub tolerance: f64,
    /// Feed lengths entering during each trial (seed: 3).
    #[arg(long, default_value_t = 3.0, allow_negative_numbers = true)]
    pub samples: f64,
    /// Feed lengths over which the production profiles are averaged.
    #[arg(long, default_value_t = 4.5, allow_negative_numbers = true)]
    pub average: f64,
    /// Scene overrides.
    #[command(flatten)]
    pub overrides: super::Overrides,
    /// Output directory (default `out/<scene name>_hugoniot`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Worker threads (default: all cores).
    #[arg(long, allow_negative_numbers = true)]
    pub threads: Option<usize>,
    /// No per-trial progress lines.
    #[arg(long)]
    pub quiet: bool,
}

/// Runs `gsph hugoniot`.
pub fn command(args: HugoniotArgs) -> Result<(), String> {
    let HugoniotArgs {
        scene: path,
        up,
        bracket,
        tolerance,
        samples,
        average,
        overrides,
        out,
        threads,
        quiet,
    } = args;
    let set = overrides.list();
    let sc = scene::load(&path, &set).map_err(|e| e.to_string())?;
    if sc.window.is_none() {
        return Err(format!(
            "{}: no [window] section: `gsph hugoniot` needs a moving-window scene",
            path.display()
        ));
    }
    let name = scene_name(&sc, &path);
    let bracket = match bracket {
        None => None,
        Some(b) => match super::parse_positive("--bracket", &b)?[..] {
            [lo, hi] if lo < hi => Some((lo, hi)),
            _ => return Err(format!("--bracket: `{b}` must be LO,HI with LO < HI")),
        },
    };
    for (flag, v) in [
        ("--tolerance", tolerance),
        ("--samples", samples),
        ("--average", average),
    ] {
        if !(v.is_finite() && v > 0.0) {
            return Err(format!("{flag}: must be positive (got {v})"));
        }
    }
    // speeds of real impacts and shocks: a particle velocity or a shock speed beyond
    // 1e5 m/s (meteoroids reach 7.2e4) is a typo, and 1e300 overflows the first step
    let ups = super::parse_positive("--up", &up)?;
    let fast = |flag: &str, v: &[f64]| match v.iter().find(|&&x| x > MAX_SPEED) {
        Some(x) => Err(format!(
            "{flag}: {x:e} m/s is faster than any impact or shock (at most {MAX_SPEED:e} m/s)"
        )),
        None => Ok(()),
    };
    fast("--up", &ups)?;
    if let Some((lo, hi)) = bracket {
        fast("--bracket", &[lo, hi])?;
    }
    let opts = crate::window::hugoniot::HugoniotOptions {
        ups,
        bracket,
        tolerance,
        samples,
        average,
        verbose: !quiet,
        ..Default::default()
    };
    let out = match out {
        Some(o) => o,
        None => crate::outdir::default_dir(&name, "_hugoniot")?,
    };
    let pool = super::pool(threads)?;
    pool.install(|| crate::window::run_hugoniot(&sc, &opts, &out))
        .map_err(|e| format!("{}: {e}", path.display()))?;
    out!("wrote {}", out.display());
    Ok(())
}
