//! The stepping loop of a run: set-up (the simulation, monitor, moving window, a restored
//! checkpoint), the snapshot and series schedule, checkpoints and interruption, and the
//! end. What is recorded is in [`super::record`], the files in [`super::files`].

use super::files::Files;
use super::record::Recorder;
use super::summary::{summary, Summed};
use super::*;

pub(super) fn run_dim<const D: usize>(
    scene: &Scene,
    scene_name: &str,
    parts: &InitialParticles,
    opts: &RunOptions,
    ckpt: Option<&CheckpointOptions>,
) -> Result<Outcome, RunError> {
    let mut log = None;
    let result = run_dim_logged::<D>(scene, scene_name, parts, opts, ckpt, &mut log);
    match (&result, &log) {
        (Err(e), Some(log)) => {
            let what = match e {
                RunError::Interrupted { .. } => "INTERRUPTED",
                _ => "FAILED",
            };
            log.append(&format!("{what} {}: {e}", crate::runlog::utc_now()));
        }
        // `--stop-after-steps`: the run ends here too, with a checkpoint to resume from
        (Ok(Outcome::Stopped { step }), Some(log)) => log.append(&format!(
            "STOPPED {}: after step {step} (--stop-after-steps), checkpoint written; `gsph run --restart` continues",
            crate::runlog::utc_now()
        )),
        _ => {}
    }
    result
}

/// The checkpoint state of the driver between steps (`next`: the next snapshot and
/// series indices).
fn driver_state(
    rec: &Recorder,
    next: [usize; 2],
    energy0: f64,
    mom0: [f64; 3],
    frames: u64,
) -> DriverState {
    DriverState {
        next_out: next[0] as u64,
        next_series: next[1] as u64,
        kinetic_max: rec.kinetic_max,
        energy0,
        mom0,
        frames,
        series: rec.series.clone(),
        monitor: rec.monitor.accumulated(),
    }
}

/// Writes a checkpoint of `sim` (gathered from every MPI rank; rank 0 writes).
fn write_checkpoint<const D: usize>(
    c: &mut Control,
    sim: &Sim<D>,
    state: &DriverState,
    writer: Option<&SnapshotWriter>,
    root: bool,
) -> Result<(), RunError> {
    #[cfg(feature = "mpi")]
    let all = sim.gathered();
    #[cfg(feature = "mpi")]
    let whole = all.as_ref().unwrap_or(sim);
    #[cfg(not(feature = "mpi"))]
    let whole = sim;
    if root {
        c.write(whole, state, writer)
            .map_err(|e| RunError::Output(format!("checkpoint: {e}")))?;
    }
    Ok(())
}

/// A run set up: the simulation (split over the MPI ranks), its moving window, the
/// recorder, and what a restart restored (the driver state and the snapshots so far; else
/// the initial state as the first snapshot).
struct Setup<const D: usize> {
    sim: Sim<D>,
    window: Option<Window<D>>,
    rec: Recorder,
    resumed: Option<DriverState>,
    frames: Vec<Frame>,
}

fn set_up<const D: usize>(
    scene: &Scene,
    parts: &InitialParticles,
    opts: &RunOptions,
    ckpt: Option<&CheckpointOptions>,
) -> Result<Setup<D>, RunError> {
    // the one place a scene is refused for its rank count (the CLI, the library, restarts)
    let ranks = crate::dist_size();
    if ranks > 1 && scene.window.is_some() {
        return Err(RunError::Refused(format!(
            "the moving window (`window`) runs on one rank; this run has {ranks} MPI ranks"
        )));
    }
    let reference = Reference::from_scene(scene, &parts.x, &parts.spacing)?;
    let mut sim = Sim::<D>::new(scene, parts)?;
    let mut monitor = Monitor::new(scene, parts, &sim.materials)?;
    let window = match &scene.window {
        Some(w) => Some(Window::new(scene, w.geometry(scene)?, parts, &mut sim)),
        None => None,
    };
    let mut resumed = None;
    let mut frames = Vec::new();
    if let Some(ck) = ckpt.and_then(|c| c.resume.as_ref()) {
        ck.restore_sim(&mut sim).map_err(ckpt_err)?;
        monitor
            .restore_accumulated(&ck.driver.monitor)
            .map_err(|e| RunError::Checkpoint(format!("{}: {e}", ck.dir.display())))?;
        frames = ck.frames(scene.particle_limit()).map_err(ckpt_err)?;
        resumed = Some(ck.driver.clone());
    }
    // MPI: every rank built the same run (else refused on every rank), then the
    // particles are split over the ranks; rank 0 alone writes files, every rank takes
    // part in the gathers behind them
    #[cfg(feature = "mpi")]
    if ranks > 1 {
        crate::dist::same_everywhere(&fingerprint(scene, &sim)).map_err(RunError::Refused)?;
    }
    #[cfg(feature = "mpi")]
    sim.distribute()?;
    let window_names = match window {
        Some(_) => &Window::<D>::series_names()[..],
        None => &[],
    };
    let mut rec = Recorder::new(reference, monitor, window_names);
    match &resumed {
        Some(r) => {
            rec.series = r.series.clone();
            rec.kinetic_max = r.kinetic_max;
        }
        None => {
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
    }
    Ok(Setup {
        sim,
        window,
        rec,
        resumed,
        frames,
    })
}

/// SHA-256 of what a run is built from: the scene (its every key after overrides, as
/// printed by `Debug`, which round-trips every float) and the initial or restored state
/// of every particle.
#[cfg(feature = "mpi")]
fn fingerprint<const D: usize>(scene: &Scene, sim: &Sim<D>) -> String {
    use sha2::{Digest, Sha256};
    let mut h = Sha256::new();
    h.update(format!("{scene:?}").as_bytes());
    h.update(sim.t.to_le_bytes());
    h.update(sim.step.to_le_bytes());
    for i in 0..sim.len() {
        h.update(sim.ids[i].to_le_bytes());
        for a in 0..D {
            h.update(sim.x[i][a].to_le_bytes());
            h.update(sim.v[i][a].to_le_bytes());
        }
        for f in [sim.m[i], sim.rho[i], sim.e[i]] {
            h.update(f.to_le_bytes());
        }
    }
    h.finalize().iter().map(|b| format!("{b:02x}")).collect()
}

fn run_dim_logged<const D: usize>(
    scene: &Scene,
    scene_name: &str,
    parts: &InitialParticles,
    opts: &RunOptions,
    ckpt: Option<&CheckpointOptions>,
    log: &mut Option<RunLog>,
) -> Result<Outcome, RunError> {
    let t_total = Instant::now();
    if opts.out.is_some() {
        // before anything is built or cleared, on every MPI rank
        SnapshotWriter::supported()?;
    }
    let Setup {
        mut sim,
        mut window,
        mut rec,
        resumed,
        frames,
    } = set_up::<D>(scene, parts, opts, ckpt)?;
    let resume = ckpt.and_then(|c| c.resume.as_ref());
    let run_id = resume.map_or_else(crate::outdir::new_run_id, |c| c.run_id.clone());
    // everything is validated: a signal now stops the run after a step (with a
    // checkpoint); lock the folder, then replace an earlier run's results
    crate::interrupt::set_up_done();
    let mut files = Files::open(scene, scene_name, opts, ckpt, &run_id, &sim, frames, log)?;
    if let (Some(log), None) = (log.as_ref(), resume) {
        // the relaxed layouts (a restart's particles come from its checkpoint)
        for line in &parts.layout {
            log.append(line);
        }
    }
    let mut control = match (ckpt, &opts.out) {
        (Some(c), Some(dir)) if c.policy.active() => {
            Some(Control::new(c.policy, c.source.clone(), dir, &run_id))
        }
        _ => None,
    };
    let (energy0, mom0, mut next) = match &resumed {
        Some(r) => (
            r.energy0,
            r.mom0,
            [r.next_out as usize, r.next_series as usize],
        ),
        None => {
            let (k0, i0) = sim.energy();
            (k0 + i0, sim.momentum(), [1, 1])
        }
    };
    let root = crate::dist_rank() == 0;
    let (t_end, n_out) = (scene.t_end, scene.output.snapshots);
    let n_series = scene.output.series.unwrap_or(200);
    let max_steps = scene.max_steps.unwrap_or(u64::MAX);
    let mut bar = Progress::new(root && opts.progress, scene_name, sim.t);
    let t_loop = Instant::now();
    while sim.t < t_end * (1.0 - 1e-12) && sim.step < max_steps {
        // one step, ending on the next snapshot time
        let t_out = t_end * next[0] as f64 / n_out as f64;
        let mut dt = sim.next_dt(scene.cfl(), scene.dt)?;
        if sim.t + dt >= t_out {
            dt = t_out - sim.t;
        }
        match window.as_mut() {
            Some(w) => w.step(&mut sim, dt)?,
            None => sim.step(dt)?,
        }
        if sim.t >= t_end * next[1] as f64 / n_series as f64 {
            rec.push(&sim, &window, dt);
            while sim.t >= t_end * next[1] as f64 / n_series as f64 {
                next[1] += 1;
            }
        }
        if sim.t >= t_out * (1.0 - 1e-12) {
            files.snapshot(&sim)?;
            next[0] += 1;
        }
        bar.set(sim.t, t_end, sim.step, dt);
        // checkpoints on their schedule, and a stop after a given step
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
                let state = driver_state(&rec, next, energy0, mom0, files.frames);
                write_checkpoint(c, &sim, &state, files.writer.as_ref(), root)?;
            }
            if stop {
                bar.finish();
                return Ok(Outcome::Stopped { step: sim.step });
            }
        }
        let signal = crate::interrupt::pending();
        // every rank stops after the same step
        #[cfg(feature = "mpi")]
        let signal = match sim.dist.is_some() {
            true => crate::dist::any(signal.is_some()).then(|| signal.unwrap_or(15)),
            false => signal,
        };
        if let Some(signal) = signal {
            bar.finish();
            // a checkpoint where one can be written: an output folder, a scene source, no
            // moving window
            let mut checkpoint = None;
            if let (Some(dir), Some(c), None) = (&opts.out, ckpt, &window) {
                let mut fallback;
                let c = match control.as_mut() {
                    Some(c) => c,
                    None => {
                        fallback = Control::new(Policy::default(), c.source.clone(), dir, &run_id);
                        &mut fallback
                    }
                };
                let state = driver_state(&rec, next, energy0, mom0, files.frames);
                write_checkpoint(c, &sim, &state, files.writer.as_ref(), root)?;
                checkpoint = Some(dir.clone());
            }
            files.interrupt(sim.step, sim.t)?;
            return Err(RunError::Interrupted {
                signal,
                step: sim.step,
                t: sim.t,
                checkpoint,
            });
        }
    }
    let wall = t_loop.elapsed().as_secs_f64();
    bar.finish();
    let table = sim.table();
    let s = summary(Summed {
        sim: &sim,
        scene_name,
        run_id: &run_id,
        source: ckpt.map(|c| &c.source),
        wall,
        wall_total: t_total.elapsed().as_secs_f64(),
        ranks: crate::dist_size(),
        energy0,
        mom0,
        kinetic_max: rec.kinetic_max,
        reference: &rec.reference,
        monitor: &mut rec.monitor,
        window: &window,
        table: &table,
        ended: if sim.t < t_end * (1.0 - 1e-12) {
            "max_steps"
        } else {
            "t_end"
        },
    });
    files.finish(&table, &rec, &s, (sim.step, sim.t, wall), log)?;
    Ok(Outcome::Finished(Box::new(RunResult { summary: s, table })))
}
