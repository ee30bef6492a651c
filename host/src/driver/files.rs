//! The files of a run in its output directory (written by rank 0 alone under MPI): the
//! folder's lock, an earlier run's results cleared, run.log, the snapshots as they are
//! taken, and at the end final.csv, series.csv, profile.csv and summary.json.

use super::record::Recorder;
use super::*;

/// A run's output directory while the run goes on.
pub(super) struct Files {
    /// Whether the run has an output directory (on every rank).
    outputs: bool,
    /// The directory this process writes (rank 0 only).
    dir: Option<PathBuf>,
    _lock: Option<OutLock>,
    /// The snapshot file (rank 0 only).
    pub writer: Option<SnapshotWriter>,
    /// Snapshots taken so far (a checkpoint records it).
    pub frames: u64,
}

impl Files {
    /// Opens the output directory of a validated run: locks it (refused if another run
    /// holds it), clears an earlier run's results (and, for a fresh run, its checkpoint),
    /// starts run.log (into `log`), creates the snapshot file and writes `frames` into it
    /// (the restored snapshots of a restart, or the initial state).
    #[allow(clippy::too_many_arguments)]
    pub fn open<const D: usize>(
        scene: &Scene,
        scene_name: &str,
        opts: &RunOptions,
        ckpt: Option<&CheckpointOptions>,
        run_id: &str,
        sim: &Sim<D>,
        frames: Vec<Frame>,
        log: &mut Option<RunLog>,
    ) -> Result<Files, RunError> {
        let resume = ckpt.and_then(|c| c.resume.as_ref());
        let dir = opts.out.clone().filter(|_| crate::dist_rank() == 0);
        let lock = match &dir {
            // no entry it writes or removes may be a link (checked before anything is
            // created)
            Some(d) => Some(OutLock::acquire_for(d, &run_entries()).map_err(RunError::Refused)?),
            None => None,
        };
        let source = ckpt.map(|c| &c.source);
        let mut writer = None;
        if let Some(dir) = &dir {
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
            *log = Some(RunLog::start(dir, run_id, &info, resume.map(|c| c.step))?);
            let info = crate::output::RunInfo {
                name: scene_name.into(),
                scene: source.map_or_else(String::new, |s| s.text.clone()),
                overrides: source.map_or_else(Vec::new, |s| s.overrides.clone()),
                scheme: sim.scheme.name().into(),
                effects: sim.effects.names().map(String::from).collect(),
                materials: scene.materials.iter().map(|m| m.name.clone()).collect(),
                run_id: run_id.into(),
            };
            let mut w = SnapshotWriter::create(dir, D, &info)?;
            for f in &frames {
                w.append(f)?;
            }
            writer = Some(w);
        }
        Ok(Files {
            outputs: opts.out.is_some(),
            dir,
            _lock: lock,
            writer,
            frames: frames.len() as u64,
        })
    }

    /// Takes a snapshot of `sim` (every rank takes part in the gather behind it).
    pub fn snapshot<const D: usize>(&mut self, sim: &Sim<D>) -> Result<(), RunError> {
        if self.outputs {
            let table = sim.table();
            if let Some(w) = self.writer.as_mut() {
                w.append(&Frame {
                    time: sim.t,
                    step: sim.step,
                    dim: D,
                    table,
                })?;
            }
            self.frames += 1;
        }
        Ok(())
    }

    /// Marks the snapshots as those of an interrupted run.
    pub fn interrupt(&mut self, step: u64, t: f64) -> Result<(), RunError> {
        if let Some(w) = self.writer.take() {
            w.interrupt(step, t)?;
        }
        Ok(())
    }

    /// Writes the results of a finished run: final.csv, series.csv, profile.csv (with a
    /// stress-profile reference), the snapshot file closed, summary.json, and the end of
    /// run.log.
    pub fn finish(
        mut self,
        table: &crate::output::ParticleTable,
        rec: &Recorder,
        summary: &super::Summary,
        (step, t, wall): (u64, f64, f64),
        log: &Option<RunLog>,
    ) -> Result<(), RunError> {
        let Some(dir) = &self.dir else {
            return Ok(());
        };
        write_csv(dir.join("final.csv"), table)?;
        write_atomic(dir.join("series.csv"), rec.series.as_bytes())?;
        if let Some(p) = rec.profile_csv(table, t) {
            write_atomic(dir.join("profile.csv"), p.as_bytes())?;
        }
        if let Some(w) = self.writer.take() {
            w.finish()?;
        }
        let text = serde_json::to_string_pretty(summary).expect("json");
        write_atomic(dir.join("summary.json"), text.as_bytes())?;
        if let Some(log) = log {
            log.append(&format!(
                "finished {}: {step} steps, t = {t:e} s, wall {wall:.3} s\nsummary: {}",
                crate::runlog::utc_now(),
                serde_json::to_string(summary).expect("json")
            ));
        }
        Ok(())
    }
}
