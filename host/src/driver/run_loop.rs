//! The stepping loop of a run: output schedule, checkpoints, interruption, results.

use super::summary::{summary, Summed};
use super::*;

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

pub(super) fn run_dim<const D: usize>(
    scene: &Scene,
    scene_name: &str,
    parts: &InitialParticles,
    opts: &RunOptions,
    ckpt: Option<&CheckpointOptions>,
) -> Result<Outcome, RunError> {
    let mut log = None;
    let result = run_dim_logged::<D>(scene, scene_name, parts, opts, ckpt, &mut log);
    if let (Err(e), Some(log)) = (&result, &log) {
        let what = match e {
            RunError::Interrupted { .. } => "INTERRUPTED",
            _ => "FAILED",
        };
        log.append(&format!("{what} {}: {e}", crate::runlog::utc_now()));
    }
    result
}

/// The checkpoint state of the driver between steps (`next`: the next snapshot and
/// series indices).
fn driver_state(
    rec: &Recorder<'_>,
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
    let reference = Reference::from_scene(scene, &parts.x, &parts.spacing)?;
    let mut sim = Sim::<D>::new(scene, parts)?;
    let ranks = crate::dist_size();
    if ranks > 1 && !scene.walls.is_empty() {
        return Err(RunError::Refused(format!(
            "walls: rigid walls and symmetry planes run on one rank; this run has {ranks} MPI ranks"
        )));
    }
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
    // everything is validated: lock the folder (refused if another run holds it), then
    // replace an earlier run's results
    let _lock = match &files {
        Some(dir) => Some(OutLock::acquire(dir).map_err(RunError::Refused)?),
        None => None,
    };
    let run_id = resume.map_or_else(crate::outdir::new_run_id, |c| c.run_id.clone());
    let source = ckpt.map(|c| &c.source);
    if let Some(dir) = &files {
        clear_outputs(dir, resume.is_none())?;
        let info = source.map_or_else(
            || SceneInfo {
                origin: scene_name,
                ..Default::default()
            },
            |s| SceneInfo {
                origin: &s.origin,
                text: &s.text,
                overrides: &s.overrides,
            },
        );
        *log = Some(RunLog::start(dir, &run_id, &info, resume.map(|c| c.step))?);
    }
    let mut writer = match &files {
        Some(dir) => {
            let info = crate::output::RunInfo {
                name: scene_name.into(),
                scene: source.map_or_else(String::new, |s| s.text.clone()),
                overrides: source.map_or_else(Vec::new, |s| s.overrides.clone()),
                scheme: sim.scheme.name().into(),
                effects: sim.effects.names().map(String::from).collect(),
                materials: scene.materials.iter().map(|m| m.name.clone()).collect(),
            };
            Some(SnapshotWriter::create(dir, D, &info)?)
        }
        None => None,
    };
    let mut control = match (ckpt, &opts.out) {
        (Some(c), Some(dir)) if c.policy.active() => {
            Some(Control::new(c.policy, c.source.clone(), dir, &run_id))
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
    let mut bar = Progress::new(root && opts.progress, scene_name, sim.t);
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
        bar.set(sim.t, t_end, sim.step, dt);
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
                let state = driver_state(&rec, [next_out, next_series], energy0, mom0, n_frames);
                write_checkpoint(c, &sim, &state, writer.as_ref(), root)?;
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
                let state = driver_state(&rec, [next_out, next_series], energy0, mom0, n_frames);
                write_checkpoint(c, &sim, &state, writer.as_ref(), root)?;
                checkpoint = Some(dir.clone());
            }
            if let Some(w) = writer.take() {
                w.interrupt(sim.step, sim.t)?;
            }
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
        source,
        wall,
        wall_total: t_total.elapsed().as_secs_f64(),
        ranks,
        energy0,
        mom0,
        kinetic_max: rec.kinetic_max,
        reference: &reference,
        monitor: &mut rec.monitor,
        window: &window,
        table: &table,
    });
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
        if let Some(log) = log {
            log.append(&format!(
                "finished {}: {} steps, t = {:e} s, wall {:.3} s\nsummary: {}",
                crate::runlog::utc_now(),
                sim.step,
                sim.t,
                wall,
                serde_json::to_string(&Value::Object(s.clone())).expect("json")
            ));
        }
    }
    Ok(Outcome::Finished(Box::new(RunResult { summary: s, table })))
}
