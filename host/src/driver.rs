//! The run loop: time-step control, output schedule, diagnostics, progress, summary.

use crate::checkpoint::{Checkpoint, CheckpointError, Control, DriverState, Policy, SceneSource};
use crate::monitor::Monitor;
use crate::output::{write_atomic, write_csv, Frame, OutputError, SnapshotWriter};
use crate::reference::Reference;
use crate::scene::{build_particles, InitialParticles, Scene, SceneError};
use crate::sim::{Sim, SimError};
use crate::window::Window;
use serde_json::{json, Map, Value};
use std::path::{Path, PathBuf};
use std::time::Instant;

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
    /// The scene needs something this run cannot do (a moving window on several ranks).
    Refused(String),
}

impl std::fmt::Display for RunError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            RunError::Scene(e) => write!(f, "{e}"),
            RunError::Sim(e) => write!(f, "{e}"),
            RunError::Output(e) => write!(f, "output: {e}"),
            RunError::Checkpoint(e) => write!(f, "checkpoint: {e}"),
            RunError::Refused(e) => write!(f, "{e}"),
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

/// Scene name: the `name` key or the file stem of `path`.
pub fn scene_name(scene: &Scene, path: &Path) -> String {
    scene.name.clone().unwrap_or_else(|| {
        path.file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    })
}

/// The progress bar of a run (drawn with the cargo feature `cli` only).
struct Progress {
    #[cfg(feature = "cli")]
    bar: Option<indicatif::ProgressBar>,
}

impl Progress {
    /// A bar if `show` and stderr is a terminal.
    fn new(show: bool) -> Self {
        #[cfg(feature = "cli")]
        {
            use std::io::IsTerminal;
            let bar = (show && std::io::stderr().is_terminal()).then(|| {
                let b = indicatif::ProgressBar::new(1000);
                b.set_style(
                    indicatif::ProgressStyle::with_template(
                        "{spinner} [{elapsed_precise}] {bar:40} {percent:>3}% t={msg} eta {eta}",
                    )
                    .expect("valid template"),
                );
                b
            });
            Progress { bar }
        }
        #[cfg(not(feature = "cli"))]
        {
            let _ = show;
            Progress {}
        }
    }

    /// Shows time `t` of `t_end`.
    fn set(&self, t: f64, t_end: f64) {
        #[cfg(feature = "cli")]
        if let Some(b) = &self.bar {
            b.set_position((1000.0 * t / t_end) as u64);
            b.set_message(format!("{t:.3e}"));
        }
        #[cfg(not(feature = "cli"))]
        let _ = (t, t_end);
    }

    /// Removes the bar.
    fn finish(self) {
        #[cfg(feature = "cli")]
        if let Some(b) = self.bar {
            b.finish_and_clear();
        }
    }
}

/// What a run produced.
#[derive(Debug, Clone)]
pub struct RunResult {
    /// The summary (also written as summary.json).
    pub summary: Map<String, Value>,
    /// Final particle state.
    pub table: crate::output::ParticleTable,
}

/// Runs a validated scene.
pub fn run(scene: &Scene, scene_name: &str, opts: &RunOptions) -> Result<RunResult, RunError> {
    let parts = build_particles(scene)?;
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
    let parts = build_particles(scene)?;
    match scene.dim {
        1 => run_dim::<1>(scene, scene_name, &parts, opts, Some(ckpt)),
        2 => run_dim::<2>(scene, scene_name, &parts, opts, Some(ckpt)),
        _ => run_dim::<3>(scene, scene_name, &parts, opts, Some(ckpt)),
    }
}

/// sigma_xx of every particle against the exact profile at time t, sorted by x
/// (`x,sigma_xx,sigma_xx_exact`; the exact value is empty where it does not hold), or
/// `None` for references that are not stress profiles.
fn profile_csv(r: &Reference, table: &crate::output::ParticleTable, t: f64) -> Option<String> {
    let rows = r.profile(table, t)?;
    let mut s = String::from("x,sigma_xx,sigma_xx_exact\n");
    for (x, sxx, ex) in rows {
        s.push_str(&format!(
            "{x:e},{sxx:e},{}\n",
            ex.map(|v| format!("{v:e}")).unwrap_or_default()
        ));
    }
    Some(s)
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

/// Removes the files of an earlier run so that a failed run leaves nothing that looks complete.
pub fn clear_outputs(dir: &Path) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    for f in RESULT_FILES {
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

/// The series so far and the quantities sampled with it.
struct Recorder<'a> {
    series: String,
    kinetic_max: f64,
    monitor: Monitor,
    reference: &'a Option<Reference>,
    extra: &'a [&'static str],
}

impl Recorder<'_> {
    fn push<const D: usize>(&mut self, sim: &Sim<D>, window: &Option<Window<D>>, dt: f64) {
        let series = &mut self.series;
        let (k, i) = sim.energy();
        self.kinetic_max = self.kinetic_max.max(k);
        let p = sim.momentum();
        series.push_str(&format!(
            "{:e},{},{:e},{:e},{:e},{:e},{:e},{:e},{:e}",
            sim.t,
            sim.step,
            dt,
            k,
            i,
            k + i,
            p[0],
            p[1],
            p[2]
        ));
        if !self.extra.is_empty() || self.monitor.samples() {
            let table = sim.table();
            let mut values = self
                .reference
                .as_ref()
                .map_or_else(Vec::new, |r| r.series_values(&table, sim.t));
            values.extend(self.monitor.sample(&table, sim.t));
            for v in values {
                series.push_str(&format!(",{v:e}"));
            }
        }
        if let Some(w) = window {
            for v in w.series_values(sim) {
                series.push_str(&format!(",{v:e}"));
            }
        }
        series.push('\n');
    }
}

fn run_dim<const D: usize>(
    scene: &Scene,
    scene_name: &str,
    parts: &InitialParticles,
    opts: &RunOptions,
    ckpt: Option<&CheckpointOptions>,
) -> Result<Outcome, RunError> {
    let t_total = Instant::now();
    if opts.out.is_some() {
        // before anything is built or cleared, on every MPI rank
        SnapshotWriter::supported()?;
    }
    let reference = Reference::from_scene(scene, &parts.x, &parts.spacing)?;
    let mut sim = Sim::<D>::new(scene, parts)?;
    let ranks = crate::dist_size();
    if ranks > 1 && scene.window.is_some() {
        return Err(RunError::Refused(format!(
            "the moving window (`window`) runs on one rank; this run has {ranks} MPI ranks"
        )));
    }
    let mut monitor = Monitor::new(scene, parts, &sim.materials)?;
    let mut window = match &scene.window {
        Some(w) => Some(Window::new(scene, w.geometry(scene)?, parts, &mut sim)),
        None => None,
    };
    let resume = ckpt.and_then(|c| c.resume.as_ref());
    let mut resumed = DriverState::default();
    let mut frames = Vec::new();
    if let Some(ck) = resume {
        ck.restore_sim(&mut sim).map_err(ckpt_err)?;
        monitor
            .restore_accumulated(&ck.driver.monitor)
            .map_err(|e| RunError::Checkpoint(format!("{}: {e}", ck.dir.display())))?;
        frames = ck.frames().map_err(ckpt_err)?;
        resumed = ck.driver.clone();
    }
    // MPI: split the particles over the ranks; rank 0 alone writes files, every rank
    // takes part in the gathers behind them
    #[cfg(feature = "mpi")]
    sim.distribute()?;
    let root = crate::dist_rank() == 0;
    let files = if root { opts.out.clone() } else { None };
    if let Some(dir) = &files {
        clear_outputs(dir)?;
    }
    let mut writer = match &files {
        Some(dir) => Some(SnapshotWriter::create(dir, D)?),
        None => None,
    };
    let mut control = match (ckpt, &opts.out) {
        (Some(c), Some(dir)) if c.policy.active() => {
            Some(Control::new(c.policy, c.source.clone(), dir))
        }
        _ => None,
    };
    let (energy0, mom0) = if resume.is_some() {
        (resumed.energy0, resumed.mom0)
    } else {
        let (k0, i0) = sim.energy();
        (k0 + i0, sim.momentum())
    };
    let n_out = scene.output.snapshots;
    let n_series = scene.output.series.unwrap_or(200);
    let mut series =
        String::from("t,step,dt,kinetic,internal,total,momentum_x,momentum_y,momentum_z");
    let extra = reference.as_ref().map_or(&[][..], |r| r.series_names());
    let window_names = if window.is_some() {
        &Window::<D>::series_names()[..]
    } else {
        &[]
    };
    let monitor_names = monitor.series_names();
    for name in extra
        .iter()
        .copied()
        .chain(monitor_names.iter().map(String::as_str))
        .chain(window_names.iter().copied())
    {
        series.push(',');
        series.push_str(name);
    }
    series.push('\n');
    let mut rec = Recorder {
        series,
        kinetic_max: 0.0,
        monitor,
        reference: &reference,
        extra,
    };
    let mut next_out = 1usize;
    let mut next_series = 1usize;
    if resume.is_some() {
        rec.series = resumed.series;
        rec.kinetic_max = resumed.kinetic_max;
        next_out = resumed.next_out as usize;
        next_series = resumed.next_series as usize;
    } else {
        rec.push(&sim, &window, 0.0);
        if opts.out.is_some() {
            frames.push(Frame {
                time: 0.0,
                step: 0,
                dim: D,
                table: sim.table(),
            });
        }
    }
    let mut n_frames = frames.len() as u64;
    if let Some(w) = writer.as_mut() {
        for f in &frames {
            w.append(f)?;
        }
    }
    drop(frames);
    let bar = Progress::new(root && opts.progress);
    let t_end = scene.t_end;
    let max_steps = scene.max_steps.unwrap_or(u64::MAX);
    let t_loop = Instant::now();
    while sim.t < t_end * (1.0 - 1e-12) {
        if sim.step >= max_steps {
            break;
        }
        let t_out = t_end * next_out as f64 / n_out as f64;
        let mut dt = sim.next_dt(scene.cfl(), scene.dt)?;
        if sim.t + dt >= t_out {
            dt = t_out - sim.t;
        }
        match window.as_mut() {
            Some(w) => w.step(&mut sim, dt)?,
            None => sim.step(dt)?,
        }
        if sim.t >= t_end * next_series as f64 / n_series as f64 {
            rec.push(&sim, &window, dt);
            while sim.t >= t_end * next_series as f64 / n_series as f64 {
                next_series += 1;
            }
        }
        if sim.t >= t_out * (1.0 - 1e-12) {
            if opts.out.is_some() {
                let table = sim.table();
                if let Some(w) = writer.as_mut() {
                    w.append(&Frame {
                        time: sim.t,
                        step: sim.step,
                        dim: D,
                        table,
                    })?;
                }
                n_frames += 1;
            }
            next_out += 1;
        }
        bar.set(sim.t, t_end);
        if let Some(c) = control.as_mut() {
            let (write, stop) = c.due(sim.step);
            // a wall-clock schedule differs between ranks: rank 0's decision holds
            #[cfg(feature = "mpi")]
            let (write, stop) = if sim.dist.is_some() {
                let pick = |b: bool| crate::dist::any(root && b);
                (pick(write), pick(stop))
            } else {
                (write, stop)
            };
            if write {
                let state = DriverState {
                    next_out: next_out as u64,
                    next_series: next_series as u64,
                    kinetic_max: rec.kinetic_max,
                    energy0,
                    mom0,
                    frames: n_frames,
                    series: rec.series.clone(),
                    monitor: rec.monitor.accumulated(),
                };
                #[cfg(feature = "mpi")]
                let all = sim.gathered();
                #[cfg(feature = "mpi")]
                let whole = all.as_ref().unwrap_or(&sim);
                #[cfg(not(feature = "mpi"))]
                let whole = &sim;
                if root {
                    c.write(whole, &state, writer.as_ref())
                        .map_err(|e| RunError::Output(format!("checkpoint: {e}")))?;
                }
            }
            if stop {
                bar.finish();
                return Ok(Outcome::Stopped { step: sim.step });
            }
        }
    }
    let wall = t_loop.elapsed().as_secs_f64();
    bar.finish();
    let (k1, i1) = sim.energy();
    let energy1 = k1 + i1;
    let mom1 = sim.momentum();
    let table = sim.table();
    let mut s = Map::new();
    s.insert("scene".into(), json!(scene_name));
    s.insert("dim".into(), json!(D));
    s.insert("scheme".into(), json!(sim.scheme.name()));
    s.insert(
        "effects".into(),
        json!(sim.effects.names().collect::<Vec<_>>()),
    );
    s.insert("particles".into(), json!(sim.global_len()));
    s.insert("steps".into(), json!(sim.step));
    s.insert("t_end".into(), json!(sim.t));
    s.insert("wall_s".into(), json!(wall));
    s.insert(
        "wall_total_s".into(),
        json!(t_total.elapsed().as_secs_f64()),
    );
    s.insert("threads".into(), json!(rayon::current_num_threads()));
    s.insert("ranks".into(), json!(ranks));
    #[cfg(feature = "mpi")]
    let pairs = match &sim.dist {
        Some(d) => {
            s.insert("mpi".into(), crate::dist::report::summary(d, sim.step));
            crate::dist::all_sum_u64(sim.pair_interactions)
        }
        None => sim.pair_interactions,
    };
    #[cfg(not(feature = "mpi"))]
    let pairs = sim.pair_interactions;
    s.insert("pair_interactions".into(), json!(pairs));
    s.insert("neighbor_rebuilds".into(), json!(sim.rebuilds));
    s.insert("bytes_per_particle".into(), json!(sim.bytes_per_particle()));
    s.insert("energy_initial".into(), json!(energy0));
    s.insert("energy_final".into(), json!(energy1));
    // relative to the initial energy, or to the final kinetic plus |internal| energy when
    // the initial energy is zero (a case that starts at rest with e = 0)
    let scale = energy0.abs().max(k1 + i1.abs()).max(f64::MIN_POSITIVE);
    s.insert(
        "energy_rel_error".into(),
        json!((energy1 - energy0) / scale),
    );
    s.insert("kinetic_final".into(), json!(k1));
    s.insert("kinetic_max".into(), json!(rec.kinetic_max.max(k1)));
    s.insert("internal_final".into(), json!(i1));
    s.insert("momentum_initial".into(), json!(mom0[..D].to_vec()));
    s.insert("momentum_final".into(), json!(mom1[..D].to_vec()));
    if let Some(r) = &reference {
        for (k, v) in r.measures(&table, sim.t) {
            s.insert(k.into(), json!(v));
        }
    }
    for (k, v) in rec.monitor.measures(&table) {
        s.insert(k, json!(v));
    }
    if let Some(w) = &window {
        for (k, v) in Window::<D>::series_names()
            .iter()
            .zip(w.series_values(&sim))
        {
            s.insert((*k).into(), json!(v));
        }
        s.insert("window_u_in".into(), json!(w.u_in));
        s.insert("window_u_out".into(), json!(w.u_out()));
    }
    if let Some(dir) = &files {
        write_csv(dir.join("final.csv"), &table)?;
        write_atomic(dir.join("series.csv"), rec.series.as_bytes())?;
        if let Some(p) = reference
            .as_ref()
            .and_then(|r| profile_csv(r, &table, sim.t))
        {
            write_atomic(dir.join("profile.csv"), p.as_bytes())?;
        }
        if let Some(w) = writer.take() {
            w.finish()?;
        }
        let text = serde_json::to_string_pretty(&Value::Object(s.clone())).expect("json");
        write_atomic(dir.join("summary.json"), text.as_bytes())?;
    }
    Ok(Outcome::Finished(Box::new(RunResult { summary: s, table })))
}
