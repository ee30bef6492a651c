//! What a [`Simulation`] gives back besides its fields: the summary, the stress profile,
//! the series (`series.csv` of `gsph run`, recorded by the same
//! [`Recorder`](crate::driver::record::Recorder)), snapshots as CSV or as the HDF5/XDMF pair
//! of `gsph run` (the same [`SnapshotWriter`]), and checkpoints.

use super::{with_sim, ApiError, ApiResult, Simulation};
use crate::outdir::OutLock;
use crate::output::{write_atomic, Frame, RunInfo, SnapshotWriter};
use serde_json::{json, Map, Value};
use std::path::Path;

/// The series recorded so far: the columns of `gsph run`'s `series.csv` (t, step, dt,
/// energies, momentum, then the reference's and the monitor's quantities), one row per
/// sample (`output.series` samples per run, 200 by default, and the initial state).
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Column names, as in the header of `series.csv`.
    pub names: Vec<String>,
    /// The samples, `names.len()` values each.
    pub rows: Vec<Vec<f64>>,
}

impl Series {
    /// The values of column `name` over the samples, if there is such a column.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let k = self.names.iter().position(|n| n == name)?;
        Some(self.rows.iter().map(|r| r[k]).collect())
    }
}

/// HDF5/XDMF snapshots being written by a simulation, and the lock on their folder.
pub(super) struct Snapshots {
    // dropped before the lock: a writer dropped unfinished marks its pair partial
    writer: SnapshotWriter,
    /// The step of the last snapshot written.
    last_step: u64,
    _lock: OutLock,
}

fn io(dir: &Path, e: impl std::fmt::Display) -> ApiError {
    ApiError::Io(format!("{}: {e}", dir.display()))
}

impl Simulation {
    /// The name of the scene (its `name`, else the file stem; "" for one built in code).
    fn name(&self) -> String {
        self.source
            .as_ref()
            .map(|s| s.name.clone())
            .or_else(|| self.scene.name.clone())
            .unwrap_or_default()
    }

    /// The summary of the state now: the keys of `gsph run`'s summary.json that do not
    /// need the run's timing (scene, scheme, effects, particles, steps, t, energies and
    /// momenta, the largest kinetic energy sampled, the reference's and the monitor's
    /// measures), plus the external impulse and work.
    pub fn summary(&self) -> Map<String, Value> {
        let mut s = Map::new();
        let (k, i) = self.energy();
        let e1 = k + i;
        let scale = self.energy0.abs().max(k + i.abs()).max(f64::MIN_POSITIVE);
        let d = self.dim();
        s.insert("scene".into(), json!(self.name()));
        s.insert("dim".into(), json!(d));
        s.insert("scheme".into(), json!(self.scheme().name()));
        s.insert(
            "effects".into(),
            json!(self.effects().names().collect::<Vec<_>>()),
        );
        s.insert("particles".into(), json!(self.len()));
        s.insert("steps".into(), json!(self.steps()));
        s.insert("t".into(), json!(self.time()));
        s.insert("energy_initial".into(), json!(self.energy0));
        s.insert("energy_final".into(), json!(e1));
        s.insert(
            "energy_rel_error".into(),
            json!((e1 - self.energy0 - self.external_work) / scale),
        );
        s.insert("kinetic_final".into(), json!(k));
        s.insert("kinetic_max".into(), json!(self.rec.kinetic_max.max(k)));
        s.insert("internal_final".into(), json!(i));
        s.insert(
            "momentum_initial".into(),
            json!(self.momentum0[..d].to_vec()),
        );
        s.insert(
            "momentum_final".into(),
            json!(self.momentum()[..d].to_vec()),
        );
        s.insert("external_impulse".into(), json!(self.impulse[..d].to_vec()));
        s.insert("external_work".into(), json!(self.external_work));
        let table = self.table();
        if let Some(r) = &self.rec.reference {
            for (key, v) in r.measures(&table, self.time()) {
                s.insert(key.into(), json!(v));
            }
        }
        // the measures of a monitor update its running values: ask a copy
        for (key, v) in self.rec.monitor.clone().measures(&table) {
            s.insert(key, json!(v));
        }
        s
    }

    /// `[x, sigma_xx, exact sigma_xx]` of every particle sorted by x (the exact value NaN
    /// where it does not hold), for scenes whose reference is a stress profile (the flyer
    /// plate, the elastic-plastic Riemann problem): `gsph run`'s profile.csv.
    pub fn profile(&self) -> ApiResult<Vec<[f64; 3]>> {
        let r = match &self.rec.reference {
            Some(r) if r.is_profile() => r,
            _ => {
                return Err(ApiError::Argument(
                    "profile: the scene's [reference] is not a stress profile (flyer_plate or elastic_plastic_riemann)".into(),
                ))
            }
        };
        let rows = r.profile(&self.table(), self.time()).unwrap_or_default();
        Ok(rows
            .into_iter()
            .map(|(x, s, ex)| [x, s, ex.unwrap_or(f64::NAN)])
            .collect())
    }

    /// The particle table (the columns of `final.csv`), rows in id order.
    pub fn table(&self) -> crate::output::ParticleTable {
        with_sim!(&self.sim, s => s.table())
    }

    /// The series so far as the text of `gsph run`'s `series.csv`: a run of the same
    /// scene through [`Self::run`] records the same file, byte for byte.
    pub fn series_csv(&self) -> &str {
        &self.rec.series
    }

    /// The series so far as numbers.
    pub fn series(&self) -> Series {
        let mut lines = self.rec.series.lines();
        let names = lines
            .next()
            .unwrap_or_default()
            .split(',')
            .map(str::to_string)
            .collect();
        // every value was written with `{:e}`, which reads back exactly
        let rows = lines
            .map(|l| {
                l.split(',')
                    .map(|v| v.parse().unwrap_or(f64::NAN))
                    .collect()
            })
            .collect();
        Series { names, rows }
    }

    /// Writes the series so far to `path` as `series.csv` (atomically).
    pub fn write_series(&self, path: &Path) -> ApiResult<()> {
        write_atomic(path, self.rec.series.as_bytes()).map_err(|e| io(path, e))
    }

    /// Writes the state as `final.csv` does (a CSV file at `path`, written atomically).
    /// HDF5/XDMF snapshots are written into a folder by [`Self::write_snapshots`] and
    /// [`Self::open_snapshots`]: a path ending in `.h5` or `.xdmf` is refused here.
    pub fn write_snapshot(&self, path: &Path) -> ApiResult<()> {
        let ext = path.extension().and_then(|e| e.to_str()).unwrap_or("");
        if ["h5", "hdf5", "xdmf"].contains(&ext.to_ascii_lowercase().as_str()) {
            return Err(ApiError::Argument(format!(
                "{}: write_snapshot writes CSV; snapshots.h5 + snapshots.xdmf are written into a folder by write_snapshots (or open_snapshots, append_snapshot, close_snapshots)",
                path.display()
            )));
        }
        crate::output::write_csv(path, &self.table()).map_err(|e| io(path, e))
    }

    /// Starts `dir/snapshots.h5` + `dir/snapshots.xdmf` (what `gsph run` writes and ParaView,
    /// `gsph plot particles` and [`crate::output::read_frame`] read) with the state now as
    /// its first snapshot. [`Self::run`] then adds one at each of the scene's snapshot
    /// times, [`Self::append_snapshot`] one at any time; [`Self::close_snapshots`] finishes
    /// the pair. Until then it is `snapshots.partial.h5`/`.xdmf`, marked partial (also if
    /// the simulation is dropped first). The folder is created if missing and locked
    /// against other gsph processes while the file is open; earlier snapshot files in it
    /// are replaced.
    pub fn open_snapshots(&mut self, dir: &Path) -> ApiResult<()> {
        if self.snapshots.is_some() {
            return Err(ApiError::Argument(format!(
                "{}: a snapshot file is open already; close_snapshots first",
                dir.display()
            )));
        }
        self.snapshots = Some(self.start_snapshots(dir)?);
        Ok(())
    }

    fn start_snapshots(&self, dir: &Path) -> ApiResult<Snapshots> {
        // refused before the folder is touched in a build without HDF5
        SnapshotWriter::supported().map_err(|e| io(dir, e))?;
        let lock = OutLock::acquire(dir).map_err(ApiError::Io)?;
        let info = RunInfo {
            name: self.name(),
            scene: self
                .source
                .as_ref()
                .map_or_else(String::new, |s| s.text.clone()),
            overrides: self
                .source
                .as_ref()
                .map_or_else(Vec::new, |s| s.overrides.clone()),
            scheme: self.scheme().name().into(),
            effects: self.effects().names().map(String::from).collect(),
            materials: self
                .scene
                .materials
                .iter()
                .map(|m| m.name.clone())
                .collect(),
            run_id: crate::outdir::new_run_id(),
        };
        let mut writer = SnapshotWriter::create(dir, self.dim(), &info).map_err(|e| io(dir, e))?;
        writer.append(&self.frame()).map_err(|e| io(dir, e))?;
        Ok(Snapshots {
            writer,
            last_step: self.steps(),
            _lock: lock,
        })
    }

    fn frame(&self) -> Frame {
        Frame {
            time: self.time(),
            step: self.steps(),
            dim: self.dim(),
            table: self.table(),
        }
    }

    /// Adds the state now to the open snapshot file ([`Self::open_snapshots`]); refused
    /// without one, or when it holds this step already.
    pub fn append_snapshot(&mut self) -> ApiResult<()> {
        let frame = self.frame();
        let Some(s) = self.snapshots.as_mut() else {
            return Err(ApiError::Argument(
                "append_snapshot: no snapshot file is open (open_snapshots first)".into(),
            ));
        };
        if s.last_step == frame.step {
            return Err(ApiError::Argument(format!(
                "append_snapshot: step {} is in the snapshot file already",
                frame.step
            )));
        }
        s.writer
            .append(&frame)
            .map_err(|e| ApiError::Io(format!("snapshots: {e}")))?;
        s.last_step = frame.step;
        Ok(())
    }

    /// A snapshot at a snapshot time reached by [`Self::run`], when a file is open and
    /// does not hold this step yet.
    pub(super) fn snapshot_at_output_time(&mut self) -> ApiResult<()> {
        match &self.snapshots {
            Some(s) if s.last_step != self.steps() => self.append_snapshot(),
            _ => Ok(()),
        }
    }

    /// Finishes the open snapshot file: `snapshots.h5` + `snapshots.xdmf` (status
    /// complete) replace the partial pair, and the folder's lock is released.
    pub fn close_snapshots(&mut self) -> ApiResult<()> {
        let Some(s) = self.snapshots.take() else {
            return Err(ApiError::Argument(
                "close_snapshots: no snapshot file is open".into(),
            ));
        };
        s.writer
            .finish()
            .map_err(|e| ApiError::Io(format!("snapshots: {e}")))
    }

    /// Writes `dir/snapshots.h5` + `dir/snapshots.xdmf` holding the state now (one
    /// snapshot): [`Self::open_snapshots`] and [`Self::close_snapshots`] at once.
    pub fn write_snapshots(&self, dir: &Path) -> ApiResult<()> {
        let s = self.start_snapshots(dir)?;
        s.writer.finish().map_err(|e| io(dir, e))
    }

    /// Writes a checkpoint into `dir` (`dir/checkpoint.bin`) from which the library
    /// ([`Self::from_checkpoint`]) continues bitwise identically, its series and monitor
    /// included. Only for simulations built from a scene file or text.
    pub fn write_checkpoint(&self, dir: &Path) -> ApiResult<()> {
        self.check_usable()?;
        if !self.external.is_empty() || self.external_work != 0.0 {
            return Err(ApiError::Argument(
                "checkpoint: external accelerations have acted on this simulation, and a checkpoint does not hold them nor the impulse and work they added".into(),
            ));
        }
        let Some(source) = &self.source else {
            return Err(ApiError::Argument(
                "checkpoint: only a simulation built from scene text or a file can be checkpointed"
                    .into(),
            ));
        };
        std::fs::create_dir_all(dir).map_err(|e| io(dir, e))?;
        // the next snapshot time of `gsph run`: one past those passed
        let (t, t_end) = (self.time(), self.scene.t_end);
        let n_out = self.scene.output.snapshots.max(1);
        let passed = (1..=n_out)
            .take_while(|&k| t_end * k as f64 / n_out as f64 <= t * (1.0 + 1e-12))
            .count();
        let state = crate::checkpoint::DriverState {
            next_out: passed as u64 + 1,
            next_series: self.next_series as u64,
            kinetic_max: self.rec.kinetic_max,
            energy0: self.energy0,
            mom0: self.momentum0,
            frames: 0,
            series: self.rec.series.clone(),
            monitor: self.rec.monitor.accumulated(),
        };
        let run_id = crate::outdir::new_run_id();
        let mut control =
            crate::checkpoint::Control::new(Default::default(), source.clone(), dir, &run_id);
        with_sim!(&self.sim, s => control.write(s.as_ref(), &state, None))
            .map_err(|e| ApiError::Io(format!("{}: checkpoint: {e}", dir.display())))
    }

    /// Continues from a checkpoint written by [`Self::write_checkpoint`] (or by `gsph run
    /// --checkpoint-every` for a scene the library runs: no `[window]`, no checkpoint
    /// keys), with its series and monitor.
    pub fn from_checkpoint(dir: &Path) -> ApiResult<Self> {
        let ck =
            crate::checkpoint::Checkpoint::read(dir).map_err(|e| ApiError::Io(e.to_string()))?;
        let src = ck.source.clone();
        let mut sim = Self::from_source(&src.text, &src.origin, &src.name, &src.overrides)?;
        ck.check_state(&sim.scene)
            .map_err(|e| ApiError::Io(e.to_string()))?;
        with_sim!(&mut sim.sim, s => ck.restore_sim(s.as_mut()))
            .map_err(|e| ApiError::Io(e.to_string()))?;
        sim.rec
            .monitor
            .restore_accumulated(&ck.driver.monitor)
            .map_err(|e| ApiError::Io(format!("{}: {e}", dir.display())))?;
        sim.rec.series = ck.driver.series.clone();
        sim.rec.kinetic_max = ck.driver.kinetic_max;
        sim.next_series = ck.driver.next_series as usize;
        sim.energy0 = ck.driver.energy0;
        sim.momentum0 = ck.driver.mom0;
        sim.order = (u64::MAX, Vec::new());
        Ok(sim)
    }
}
