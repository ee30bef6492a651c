//! The `gsph` command line (DESIGN §6): [`run`] parses the arguments and calls one
//! subcommand of [`crate::commands`]; `main` calls only [`run`].

use crate::commands::{self, Failure};
use clap::{Parser, Subcommand};

/// `gsph --version`: the version, the cargo features and the step specialisations this
/// build was compiled with.
fn long_version() -> &'static str {
    static TEXT: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    TEXT.get_or_init(|| {
        let (have, all) = crate::specs::compiled();
        format!(
            "{}\nfeatures: {}\nspecialisations: {have} of {all}",
            env!("CARGO_PKG_VERSION"),
            crate::build_features().join(", ")
        )
    })
}

/// Why a build without the feature `mpi` refuses to run as one of several copies an MPI
/// launcher started (`launcher`: [`crate::launcher`]): each copy would run the whole scene
/// alone and write the same folder. `None`: no launcher, or a launcher of one process.
#[cfg_attr(feature = "mpi", allow(dead_code))]
fn copies_refusal(launcher: Option<(Option<usize>, Option<usize>)>) -> Option<String> {
    let (rank, size) = launcher?;
    if rank.unwrap_or(0) == 0 && size.unwrap_or(1) <= 1 {
        return None;
    }
    let of = size.map_or(String::new(), |n| format!(" of {n}"));
    Some(format!(
        "this gsph was built without MPI, and an MPI launcher started it as rank {}{of}: each copy would run the whole scene alone; build with `--features mpi` (cargo build --release -p gsph --features mpi) or start it without mpirun",
        rank.unwrap_or(0)
    ))
}

/// Godunov SPH for solids under shock and impact.
#[derive(Parser, Debug)]
#[command(name = "gsph", version, long_version = long_version(), about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// Subcommands.
#[derive(Subcommand, Debug)]
pub enum Command {
    /// Run a scene for a grid of schemes and resolutions: error against the reference,
    /// wall time, steps, particles, pair interactions (study.csv, study.md, plots).
    Study(commands::study::StudyArgs),
    /// Shock Hugoniot of a moving-window scene (Rublev & Murzov §3.1): u_s for each u_p by
    /// bisection, stress behind the wave and in the precursor, averaged profiles
    /// (hugoniot.csv, hugoniot.png, profile_up*.csv/png).
    Hugoniot(commands::hugoniot::HugoniotArgs),
    /// Every hard case (cases/hard/) with every scheme: reached t_end, NaN, density,
    /// energy and momentum errors, PASS/FAIL (stability.csv, stability.md); exits non-zero
    /// if any run fails.
    Stability(commands::stability::StabilityArgs),
    /// Pictures of a run's output directory.
    #[command(subcommand)]
    Plot(commands::plot::PlotCommand),
    /// The material library (cases/materials/, compiled in): one line per material; with
    /// NAME, its TOML (source and units in comments); with --scene, the scene's materials
    /// as a run resolves them and where each came from.
    Materials(commands::materials::MaterialsArgs),
    /// Validate a scene, print particle counts and the resolved effects.
    Check(commands::check::CheckArgs),
    /// Run a scene.
    Run(commands::run::RunArgs),
}

/// The `gsph` program: with the feature `mpi`, MPI is initialised when a launcher started
/// the process (`mpirun`, `srun`: see `dist::launched`; a plain `gsph run` stays
/// one process and pays nothing; only the main thread calls MPI), then [`main_with_args`].
/// Returns the exit code; under MPI a failure on any rank aborts them all.
pub fn run(args: impl IntoIterator<Item = std::ffi::OsString>) -> i32 {
    #[cfg(feature = "mpi")]
    let universe = crate::dist::launched()
        .then(|| mpi::initialize_with_threading(mpi::Threading::Funneled))
        .flatten()
        .map(|(u, _)| u);
    let code = main_with_args(args);
    #[cfg(feature = "mpi")]
    {
        use mpi::traits::Communicator as _;
        if code != 0 && crate::dist_size() > 1 {
            // other ranks may wait in a collective: end them all (mpirun exits non-zero)
            mpi::topology::SimpleCommunicator::world().abort(code);
        }
        drop(universe);
    }
    code
}

/// Runs the CLI on `args` (MPI, where used, already initialised); returns the process exit
/// code. Errors are printed as one line.
pub fn main_with_args(args: impl IntoIterator<Item = std::ffi::OsString>) -> i32 {
    let cli = match Cli::try_parse_from(args) {
        Ok(c) => c,
        Err(e) if e.use_stderr() => {
            // clap's message is a paragraph, then usage: keep the paragraph, on one line
            let text = e.render().to_string();
            let first: Vec<&str> = text
                .lines()
                .take_while(|l| !l.trim().is_empty())
                .map(str::trim)
                .collect();
            eprintln!("{}", first.join(" "));
            return 2;
        }
        Err(e) => {
            let _ = e.print();
            return 0;
        }
    };
    #[cfg(not(feature = "mpi"))]
    if let Some(msg) = copies_refusal(crate::launcher()) {
        // one line, from the first copy (the others exit with the same code)
        if crate::launcher().is_some_and(|(rank, _)| rank.unwrap_or(0) == 0) {
            eprintln!("error: {msg}");
        }
        return 2;
    }
    let ranks = crate::dist_size();
    if ranks > 1 && !matches!(cli.command, Command::Run(_)) {
        if crate::dist_rank() == 0 {
            eprintln!(
                "error: only `gsph run` runs on several MPI ranks (this is rank 0 of {ranks}); run the others in one process"
            );
        }
        return 2;
    }
    let result: Result<(), Failure> = match cli.command {
        Command::Study(a) => commands::study::command(a).map_err(Failure::from),
        Command::Hugoniot(a) => commands::hugoniot::command(a).map_err(Failure::from),
        Command::Stability(a) => commands::stability::command(a).map_err(Failure::from),
        Command::Plot(a) => commands::plot::command(a).map_err(Failure::from),
        Command::Materials(a) => commands::materials::command(a).map_err(Failure::from),
        Command::Check(a) => commands::check::command(a).map_err(Failure::from),
        Command::Run(a) => commands::run::command(a),
    };
    match result {
        Ok(()) => 0,
        Err(Failure { message: msg, code }) => {
            let who = match crate::dist_rank() {
                0 => String::new(),
                r => format!("rank {r}: "),
            };
            eprintln!("{who}error: {}", msg.replace('\n', " "));
            code
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn several_copies_started_by_a_launcher_are_refused() {
        assert_eq!(copies_refusal(None), None);
        assert_eq!(copies_refusal(Some((Some(0), Some(1)))), None);
        assert_eq!(copies_refusal(Some((Some(0), None))), None);
        let e = copies_refusal(Some((Some(0), Some(4)))).unwrap();
        assert!(
            e.contains("built without MPI") && e.contains("rank 0 of 4"),
            "{e}"
        );
        assert!(e.contains("--features mpi"), "{e}");
        let e = copies_refusal(Some((Some(3), None))).unwrap();
        assert!(e.contains("rank 3:"), "{e}");
    }

    #[test]
    fn the_long_version_lists_features_and_specialisations() {
        let v = long_version();
        assert!(v.starts_with(env!("CARGO_PKG_VERSION")), "{v}");
        let features = crate::build_features().join(", ");
        assert!(v.contains(&format!("\nfeatures: {features}\n")), "{v}");
        assert_eq!(cfg!(feature = "mpi"), features.contains("mpi"), "{v}");
        let (have, all) = crate::specs::compiled();
        assert!(
            v.ends_with(&format!("specialisations: {have} of {all}")),
            "{v}"
        );
    }
}
