//! Running a scene: [`run`], [`run_particles`] and [`run_checkpointed`]. The stepping loop
//! is in `run_loop.rs`, what it records (series, profile) in `record.rs`, the files of the
//! output directory in `files.rs`, summary.json in `summary.rs`.

use crate::checkpoint::{Checkpoint, CheckpointError, Control, DriverState, Policy, SceneSource};
use crate::monitor::Monitor;
use crate::outdir::OutLock;
use crate::output::{write_atomic, write_csv, Frame, OutputError, SnapshotWriter};
use crate::progress::Progress;
use crate::reference::Reference;
use crate::runlog::{RunLog, SceneInfo};
use crate::scene::{build_particles_reporting, InitialParticles, Scene, SceneError};
use crate::sim::{Sim, SimError};
use crate::window::Window;
use serde_json::{json, Map, Value};
use std::path::{Path, PathBuf};
use std::time::Instant;

mod files;
pub mod record;
mod run_loop;
mod summary;
use run_loop::run_dim;
pub use summary::Summary;

/// Why a run failed. `Display` is one line.
#[derive(Debug)]
pub enum RunError {
    /// Bad scene.
    Scene(SceneError),
    /// The simulation failed.
    Sim(SimError),
    /// Writing output failed.
    Output(String),
    /// A checkpoint cannot be used.
    Checkpoint(String),
    /// The scene needs something this run cannot do (a moving window on several ranks),
    /// or the output folder is held by another run.
    Refused(String),
    /// SIGINT or SIGTERM stopped the run after a step ([`crate::interrupt`]).
    Interrupted {
        /// The signal's number.
        signal: i32,
        /// The last step taken.
        step: u64,
        /// Time reached, s.
        t: f64,
        /// Where the checkpoint was written (`None`: none could be).
        checkpoint: Option<PathBuf>,
    },
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunError::Scene(e) => write!(f, "{e}"),
            RunError::Sim(e) => write!(f, "{e}"),
            RunError::Output(e) => write!(f, "output: {e}"),
            RunError::Checkpoint(e) => write!(f, "checkpoint: {e}"),
            RunError::Refused(e) => write!(f, "{e}"),
            RunError::Interrupted {
                signal,
                step,
                t,
                checkpoint,
            } => {
                write!(
                    f,
                    "interrupted by {} after step {step} (t = {t:.6e} s); ",
                    crate::interrupt::name(*signal)
                )?;
                match checkpoint {
                    Some(dir) => write!(
                        f,
                        "checkpoint written: continue with `gsph run --restart {}`",
                        dir.display()
                    ),
                    None => write!(f, "no checkpoint (none can be written for this run)"),
                }
            }
        }
    }
}

impl std::error::Error for RunError {}

impl From<SceneError> for RunError {
    fn from(e: SceneError) -> Self {
        RunError::Scene(e)
    }
}
impl From<SimError> for RunError {
    fn from(e: SimError) -> Self {
        RunError::Sim(e)
    }
}
impl From<OutputError> for RunError {
    fn from(e: OutputError) -> Self {
        RunError::Output(e.to_string())
    }
}
impl From<std::io::Error> for RunError {
    fn from(e: std::io::Error) -> Self {
        RunError::Output(e.to_string())
    }
}

/// How to run.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// Output directory (`None`: keep results in memory only; used by studies and tests).
    /// Its snapshots need the cargo feature `hdf5`: without it a run with a directory is
    /// refused before it starts ([`SnapshotWriter::supported`]).
    pub out: Option<PathBuf>,
    /// Show a progress bar (only drawn on a terminal, and only with the cargo feature `cli`).
    pub progress: bool,
}

/// What a run produced.
#[derive(Debug, Clone)]
pub struct RunResult {
    /// The summary (also written as summary.json).
    pub summary: Summary,
    /// Final particle state.
    pub table: crate::output::ParticleTable,
}

/// Runs a validated scene.
pub fn run(scene: &Scene, scene_name: &str, opts: &RunOptions) -> Result<RunResult, RunError> {
    let parts = build_particles_reporting(scene, opts.progress)?;
    run_particles(scene, scene_name, parts, opts)
}

/// Runs a validated scene from particles built (and possibly modified) by the caller.
pub fn run_particles(
    scene: &Scene,
    scene_name: &str,
    parts: InitialParticles,
    opts: &RunOptions,
) -> Result<RunResult, RunError> {
    let outcome = match scene.dim {
        1 => run_dim::<1>(scene, scene_name, &parts, opts, None),
        2 => run_dim::<2>(scene, scene_name, &parts, opts, None),
        _ => run_dim::<3>(scene, scene_name, &parts, opts, None),
    }?;
    match outcome {
        Outcome::Finished(r) => Ok(*r),
        // only a checkpoint policy stops a run early
        Outcome::Stopped { .. } => unreachable!("a run without checkpoints stopped"),
    }
}

/// How a checkpointed run ended.
#[derive(Debug, Clone)]
pub enum Outcome {
    /// It reached t_end (or max_steps) and wrote its outputs.
    Finished(Box<RunResult>),
    /// It stopped after a checkpoint at this step (`Policy::stop_after_steps`), as if
    /// interrupted: no outputs but the checkpoint.
    Stopped {
        /// The last step taken.
        step: u64,
    },
}

/// What a checkpointed run is given besides [`RunOptions`].
#[derive(Debug, Clone, Default)]
pub struct CheckpointOptions {
    /// When to write checkpoints.
    pub policy: Policy,
    /// The scene as given (stored in each checkpoint).
    pub source: SceneSource,
    /// The checkpoint to continue from (its directory is the output directory).
    pub resume: Option<Checkpoint>,
}

fn ckpt_err(e: CheckpointError) -> RunError {
    RunError::Checkpoint(e.to_string())
}

/// Runs a validated scene writing checkpoints into `opts.out` on the schedule of
/// `ckpt.policy`, or continues from `ckpt.resume`. Moving-window scenes are refused.
pub fn run_checkpointed(
    scene: &Scene,
    scene_name: &str,
    opts: &RunOptions,
    ckpt: &CheckpointOptions,
) -> Result<Outcome, RunError> {
    if scene.window.is_some() && (ckpt.policy.active() || ckpt.resume.is_some()) {
        return Err(RunError::Checkpoint(
            "checkpoints are not supported for moving-window scenes".into(),
        ));
    }
    if opts.out.is_none() && ckpt.policy.active() {
        return Err(RunError::Checkpoint(
            "checkpoints need an output directory".into(),
        ));
    }
    if let Some(ck) = &ckpt.resume {
        if ck.dim != scene.dim {
            return Err(RunError::Checkpoint(format!(
                "{}: {}D checkpoint of a {}D scene",
                ck.dir.display(),
                ck.dim,
                scene.dim
            )));
        }
    }
    let parts = build_particles_reporting(scene, opts.progress)?;
    match scene.dim {
        1 => run_dim::<1>(scene, scene_name, &parts, opts, Some(ckpt)),
        2 => run_dim::<2>(scene, scene_name, &parts, opts, Some(ckpt)),
        _ => run_dim::<3>(scene, scene_name, &parts, opts, Some(ckpt)),
    }
}

/// The files a run writes into its output directory.
pub const RESULT_FILES: [&str; 6] = [
    "summary.json",
    "final.csv",
    "series.csv",
    "profile.csv",
    "snapshots.h5",
    "snapshots.xdmf",
];

/// Every entry of its output folder a run writes or removes (besides the lock file): the
/// results, run.log, the partial snapshots, the checkpoint, and the fixed temp names of the
/// files HDF5 writes by name. Checked for links before the run touches the folder
/// ([`crate::outdir::OutLock::acquire_for`]).
pub fn run_entries() -> Vec<String> {
    use crate::output::atomic::tmp_path;
    use crate::output::{SNAPSHOTS_PARTIAL_H5, SNAPSHOTS_PARTIAL_XDMF};
    let mut names: Vec<String> = RESULT_FILES
        .iter()
        .chain(&[
            crate::runlog::RUN_LOG,
            SNAPSHOTS_PARTIAL_H5,
            SNAPSHOTS_PARTIAL_XDMF,
            crate::checkpoint::CHECKPOINT_BIN,
            crate::checkpoint::CHECKPOINT_H5,
        ])
        .map(|s| s.to_string())
        .collect();
    let tmp: Vec<String> = names
        .iter()
        .map(|n| tmp_path(Path::new(n)).display().to_string())
        .collect();
    names.extend(tmp);
    names
}

/// Removes the files of an earlier run so that a failed run leaves nothing that looks
/// complete; a `fresh` run (not a restart) removes the earlier run's checkpoint too, so it
/// can never be resumed over the new results. Called only once the new run is validated and
/// holds the folder's lock ([`crate::outdir`]).
pub fn clear_outputs(dir: &Path, fresh: bool) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let checkpoint = [
        crate::checkpoint::CHECKPOINT_BIN,
        crate::checkpoint::CHECKPOINT_H5,
    ];
    let extra: &[&str] = if fresh { &checkpoint } else { &[] };
    for &f in RESULT_FILES.iter().chain(extra) {
        match std::fs::remove_file(dir.join(f)) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                return Err(std::io::Error::new(
                    e.kind(),
                    format!("cannot remove an earlier {f}: {e}"),
                ))
            }
            _ => {}
        }
    }
    Ok(())
}
