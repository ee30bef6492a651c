//! Checkpoints: the state of a run written every K steps or S seconds of wall time, from
//! which `gsph run --restart DIR` continues bitwise identically (see docs/checkpoint.md).
//!
//! `DIR/checkpoint.bin` is little-endian:
//!
//! | offset | size | content |
//! |---|---|---|
//! | 0 | 8 | magic `GSPHCKPT` |
//! | 8 | 4 | format version (u32, [`FORMAT_VERSION`]) |
//! | 12 | 4 | dimension (u32) |
//! | 16 | 8 | payload length in bytes (u64) |
//! | 24 | 8 | FNV-1a 64 of the payload (u64) |
//! | 32 | … | payload |
//!
//! Payload, in order ([`crate::codec`]: integers and floats fixed-width, floats as bit patterns;
//! strings and arrays prefixed by their length as u64): the gsph version; the run id
//! (also in summary.json: a checkpoint resumes only the run that wrote it); the scene
//! origin, text, overrides and name; the checkpoint policy (steps, 0 for none; seconds,
//! 0 for none); the [`DriverState`]; the simulation state (`Sim::save_checkpoint`: counters,
//! ids, the particle table's field names, then each field in table order, then the workspace).
//! Version 4 added the field names and follows the order of the core's table; version 5
//! the spin of the gradients (`Gradients::w`, `options.objective`); version 6 the specific
//! volume's slope (`Gradients::sv`, `options.specific_volume`); version 7 the same bytes,
//! with a `checkpoint.h5` that carries the run id (a restart checks it: the snapshots of a
//! version-6 checkpoint carry none); version 8 tl's reference-update count after the
//! rebuild count (and the particle table's `xr`, `vr`, `phi`).
//!
//! The snapshots written so far are kept in `DIR/checkpoint.h5`, a copy of the snapshot
//! file taken at the checkpoint (only when a snapshot was added since the last one).
//! Both files are written atomically (temp file, fsync, rename, directory fsync), the
//! snapshot copy first: a checkpoint.h5 newer than checkpoint.bin holds every snapshot
//! the older checkpoint needs.

use crate::codec::{fnv1a64, Dec, DecodeError, Enc};
use crate::output::safe::excerpt;
use crate::output::{
    read_frame, read_snapshot_times, write_atomic, AtomicFile, Frame, SnapshotWriter,
};
use crate::sim::Sim;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// File name of the checkpoint in the output directory.
pub const CHECKPOINT_BIN: &str = "checkpoint.bin";
/// File name of the copy of the snapshots written up to the checkpoint.
pub const CHECKPOINT_H5: &str = "checkpoint.h5";
/// Magic bytes at the start of a checkpoint.
pub const MAGIC: &[u8; 8] = b"GSPHCKPT";
/// The format version this build writes and reads.
pub const FORMAT_VERSION: u32 = 8;
const HEADER: usize = 32;

/// A checkpoint problem; `Display` is one line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CheckpointError(pub String);

impl std::fmt::Display for CheckpointError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let words: Vec<&str> = self.0.split_whitespace().collect();
        write!(f, "{}", words.join(" "))
    }
}

impl std::error::Error for CheckpointError {}

/// When to write checkpoints.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Policy {
    /// Every this many steps.
    pub every_steps: Option<u64>,
    /// Every this many seconds of wall time (checked after each step).
    pub every_seconds: Option<f64>,
    /// Write a checkpoint after this step and stop, as if interrupted (for tests).
    pub stop_after_steps: Option<u64>,
}

impl Policy {
    /// True if this policy writes any checkpoint.
    pub fn active(&self) -> bool {
        self.every_steps.is_some()
            || self.every_seconds.is_some()
            || self.stop_after_steps.is_some()
    }
}

/// A scene as given to `gsph run`, so that a restart needs no scene file.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct SceneSource {
    /// Where the text came from (used in messages).
    pub origin: String,
    /// The scene text.
    pub text: String,
    /// `--set` overrides, in order.
    pub overrides: Vec<String>,
    /// Scene name (`name` key or file stem).
    pub name: String,
}

/// The run driver's state between steps.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DriverState {
    /// Index of the next snapshot time.
    pub next_out: u64,
    /// Index of the next series sample.
    pub next_series: u64,
    /// Largest kinetic energy sampled so far.
    pub kinetic_max: f64,
    /// Total energy at t = 0.
    pub energy0: f64,
    /// Momentum at t = 0.
    pub mom0: [f64; 3],
    /// Snapshots written so far.
    pub frames: u64,
    /// series.csv so far.
    pub series: String,
    /// The monitor's accumulated values ([`crate::monitor::Monitor::accumulated`]).
    pub monitor: Vec<f64>,
}

/// A checkpoint read back and checked.
#[derive(Debug, Clone)]
pub struct Checkpoint {
    /// Where it was read from.
    pub dir: PathBuf,
    /// Dimension of the run.
    pub dim: usize,
    /// The scene.
    pub source: SceneSource,
    /// The checkpoint policy of the run (steps, seconds).
    pub policy: Policy,
    /// The driver state.
    pub driver: DriverState,
    /// Time of the checkpoint, s.
    pub t: f64,
    /// Steps taken at the checkpoint.
    pub step: u64,
    /// The id of the run that wrote it ([`crate::outdir::new_run_id`]).
    pub run_id: String,
    payload: Vec<u8>,
    sim_at: usize,
}

fn err(path: &Path, msg: impl std::fmt::Display) -> CheckpointError {
    CheckpointError(format!("{}: {msg}", path.display()))
}

fn decode_err(path: &Path) -> impl Fn(DecodeError) -> CheckpointError + '_ {
    move |e| err(path, format!("bad checkpoint: {}", e.0))
}

impl Checkpoint {
    /// Reads and checks `dir/checkpoint.bin`.
    pub fn read(dir: &Path) -> Result<Checkpoint, CheckpointError> {
        let path = dir.join(CHECKPOINT_BIN);
        crate::output::safe::regular_file(&path).map_err(|e| err(&path, e))?;
        let bytes = std::fs::read(&path).map_err(|e| err(&path, format!("cannot read: {e}")))?;
        if bytes.len() < HEADER {
            return Err(err(&path, format!("truncated ({} bytes)", bytes.len())));
        }
        if &bytes[..8] != MAGIC {
            return Err(err(&path, "not a gsph checkpoint"));
        }
        let word = |at: usize| u32::from_le_bytes(bytes[at..at + 4].try_into().expect("4"));
        let long = |at: usize| u64::from_le_bytes(bytes[at..at + 8].try_into().expect("8"));
        let version = word(8);
        if version != FORMAT_VERSION {
            return Err(err(
                &path,
                format!("format version {version}; this gsph reads version {FORMAT_VERSION}"),
            ));
        }
        let payload = &bytes[HEADER..];
        if long(16) != payload.len() as u64 {
            return Err(err(
                &path,
                format!(
                    "truncated or extended: the header gives {} payload bytes, the file holds {}",
                    long(16),
                    payload.len()
                ),
            ));
        }
        if long(24) != fnv1a64(payload) {
            return Err(err(&path, "checksum mismatch: the file is corrupted"));
        }
        let dim = word(12) as usize;
        if !(1..=3).contains(&dim) {
            return Err(err(&path, format!("dimension {dim}")));
        }
        let mut d = Dec::new(payload);
        let de = decode_err(&path);
        let made_by: String = d.get().map_err(&de)?;
        if made_by != env!("CARGO_PKG_VERSION") {
            return Err(err(
                &path,
                format!(
                    "written by gsph {}; this is gsph {}",
                    excerpt(&made_by),
                    env!("CARGO_PKG_VERSION")
                ),
            ));
        }
        let run_id: String = d.get().map_err(&de)?;
        let source = SceneSource {
            origin: d.get().map_err(&de)?,
            text: d.get().map_err(&de)?,
            overrides: d.get().map_err(&de)?,
            name: d.get().map_err(&de)?,
        };
        // the origin and name start messages of the restarted run: a path and a name,
        // not a file's worth of text (the checksum does not prove who wrote them)
        for (what, v) in [
            ("scene origin", &source.origin),
            ("scene name", &source.name),
        ] {
            if v.len() > 4096 || v.chars().any(char::is_control) {
                return Err(err(
                    &path,
                    format!(
                        "bad checkpoint: the {what} `{}` is not a path or name",
                        excerpt(v)
                    ),
                ));
            }
        }
        let steps: u64 = d.get().map_err(&de)?;
        let seconds: f64 = d.get().map_err(&de)?;
        let policy = Policy {
            every_steps: (steps > 0).then_some(steps),
            every_seconds: (seconds > 0.0).then_some(seconds),
            stop_after_steps: None,
        };
        let driver = DriverState {
            next_out: d.get().map_err(&de)?,
            next_series: d.get().map_err(&de)?,
            kinetic_max: d.get().map_err(&de)?,
            energy0: d.get().map_err(&de)?,
            mom0: d.get().map_err(&de)?,
            frames: d.get().map_err(&de)?,
            series: d.get().map_err(&de)?,
            monitor: d.get().map_err(&de)?,
        };
        let sim_at = payload.len() - d.remaining();
        let t: f64 = d.get().map_err(&de)?;
        let step: u64 = d.get().map_err(&de)?;
        Ok(Checkpoint {
            dir: dir.to_path_buf(),
            dim,
            source,
            policy,
            driver,
            t,
            step,
            run_id,
            payload: payload.to_vec(),
            sim_at,
        })
    }

    /// Checks the decoded driver state against the checkpoint's scene: a checksum proves
    /// the bytes are as written, not that the values are a state a run can reach.
    pub fn check_state(&self, scene: &crate::scene::Scene) -> Result<(), CheckpointError> {
        let path = self.dir.join(CHECKPOINT_BIN);
        let bad = |what: String| Err(err(&path, format!("bad checkpoint: {what}")));
        let (t, t_end, dr) = (self.t, scene.t_end, &self.driver);
        if !(t.is_finite() && t >= 0.0 && t <= t_end * (1.0 + 1e-9)) {
            return bad(format!("time t = {t:e} s outside [0, t_end = {t_end:e} s]"));
        }
        if scene.max_steps.is_some_and(|m| self.step > m) {
            return bad(format!("step {} beyond max_steps", self.step));
        }
        // the next snapshot and series sample: one past the last passed time
        let schedule = |name: &str, next: u64, n: u64| -> Result<(), CheckpointError> {
            let passed = t_end * (next.saturating_sub(1)) as f64 / n as f64;
            if !(1..=n + 1).contains(&next) || passed > t * (1.0 + 1e-9) {
                return Err(err(
                    &path,
                    format!("bad checkpoint: {name} = {next} at t = {t:e} s ({n} per run)"),
                ));
            }
            Ok(())
        };
        schedule("next snapshot", dr.next_out, scene.output.snapshots as u64)?;
        schedule(
            "next series sample",
            dr.next_series,
            scene.output.series.unwrap_or(200) as u64,
        )?;
        if dr.frames > dr.next_out {
            return bad(format!(
                "{} snapshots written before snapshot {}",
                dr.frames, dr.next_out
            ));
        }
        let finite = dr.energy0.is_finite()
            && dr.kinetic_max.is_finite()
            && dr.kinetic_max >= 0.0
            && dr.mom0.iter().all(|v| v.is_finite());
        if !finite {
            return bad("initial energy, momentum or largest kinetic energy not finite".into());
        }
        if !dr.series.starts_with("t,step,") {
            return bad("series.csv so far has no header".into());
        }
        Ok(())
    }

    /// Checks that the files a restart continues belong to the run of `checkpoint.bin`:
    /// `checkpoint.h5` (the snapshots up to the checkpoint), `snapshots.partial.h5` (the
    /// snapshots the restart replaces) and `run.log` (which it appends to) each carry a run
    /// id, and it must be this one. A checkpoint copied into the folder of another run is
    /// refused in one line naming both files, before anything is written.
    pub fn check_same_run(&self) -> Result<(), CheckpointError> {
        let bin = self.dir.join(CHECKPOINT_BIN);
        let mismatch = |other: &Path, id: &str| {
            CheckpointError(format!(
                "{} is run {} but {} is run {}: a restart never continues one run with another's files (restart the run's own folder, or start afresh)",
                bin.display(),
                self.run_id,
                other.display(),
                if id.is_empty() { "of no recorded id" } else { id }
            ))
        };
        for name in [CHECKPOINT_H5, crate::output::SNAPSHOTS_PARTIAL_H5] {
            let h5 = self.dir.join(name);
            if std::fs::symlink_metadata(&h5).is_err() {
                continue;
            }
            let info = crate::output::read_run_info(&h5).map_err(|e| err(&h5, e))?;
            let id = info.map(|i| i.run_id).unwrap_or_default();
            if id != self.run_id {
                return Err(mismatch(&h5, &id));
            }
        }
        let log = self.dir.join(crate::runlog::RUN_LOG);
        match crate::runlog::run_id_of(&self.dir) {
            Ok(Some(id)) if id != self.run_id => Err(mismatch(&log, &id)),
            Ok(_) => Ok(()),
            Err(e) => Err(CheckpointError(e)),
        }
    }

    /// Overwrites the state of `sim` (built from the checkpoint's scene) with the saved one.
    pub fn restore_sim<const D: usize>(&self, sim: &mut Sim<D>) -> Result<(), CheckpointError> {
        let path = self.dir.join(CHECKPOINT_BIN);
        if D != self.dim {
            return Err(err(
                &path,
                format!("{}D checkpoint for a {D}D scene", self.dim),
            ));
        }
        let mut d = Dec::new(&self.payload[self.sim_at..]);
        sim.restore_checkpoint(&mut d).map_err(decode_err(&path))?;
        if d.remaining() != 0 {
            return Err(err(&path, format!("{} bytes left over", d.remaining())));
        }
        Ok(())
    }

    /// The snapshots written up to the checkpoint, from `dir/checkpoint.h5`, each of at
    /// most `limit` particles (the scene's particle limit).
    pub fn frames(&self, limit: usize) -> Result<Vec<Frame>, CheckpointError> {
        let step = self.step;
        let path = self.dir.join(CHECKPOINT_H5);
        let times = read_snapshot_times(&path).map_err(|e| err(&path, e))?;
        let frames: Vec<Frame> = times
            .iter()
            .filter(|&&(s, _)| s <= step)
            .map(|&(s, _)| read_frame(&path, s, limit).map_err(|e| err(&path, e)))
            .collect::<Result<_, _>>()?;
        if frames.len() as u64 != self.driver.frames {
            return Err(err(
                &path,
                format!(
                    "{} snapshots up to step {step}; the checkpoint expects {}",
                    frames.len(),
                    self.driver.frames
                ),
            ));
        }
        Ok(frames)
    }
}

/// Writes checkpoints of a run on its schedule.
#[derive(Debug)]
pub struct Control {
    policy: Policy,
    source: SceneSource,
    dir: PathBuf,
    last: Instant,
    /// Snapshots in the current checkpoint.h5 written by this process.
    frames_saved: Option<u64>,
    run_id: String,
}

impl Control {
    /// Checkpoints of the run `run_id` of `source` into `dir` on the schedule of `policy`.
    pub fn new(policy: Policy, source: SceneSource, dir: &Path, run_id: &str) -> Self {
        Control {
            policy,
            source,
            dir: dir.to_path_buf(),
            last: Instant::now(),
            frames_saved: None,
            run_id: run_id.to_owned(),
        }
    }

    /// After step `step`: (write a checkpoint, then stop).
    pub fn due(&self, step: u64) -> (bool, bool) {
        let stop = self.policy.stop_after_steps == Some(step);
        let by_steps = self
            .policy
            .every_steps
            .is_some_and(|k| step.is_multiple_of(k));
        let by_time = self
            .policy
            .every_seconds
            .is_some_and(|s| self.last.elapsed().as_secs_f64() >= s);
        (stop || by_steps || by_time, stop)
    }

    /// Writes `checkpoint.h5` (when a snapshot was added since the last checkpoint), then
    /// `checkpoint.bin`, both atomically.
    pub fn write<const D: usize>(
        &mut self,
        sim: &Sim<D>,
        driver: &DriverState,
        writer: Option<&SnapshotWriter>,
    ) -> std::io::Result<()> {
        if let Some(w) = writer {
            if self.frames_saved != Some(driver.frames) {
                // copied into a fresh temp file renamed over checkpoint.h5 (a copy onto a
                // fixed name would follow a link planted there)
                let mut src = std::fs::File::open(w.tmp_path())?;
                let mut dst = AtomicFile::create(self.dir.join(CHECKPOINT_H5))?;
                std::io::copy(&mut src, &mut dst)?;
                dst.commit()?;
                self.frames_saved = Some(driver.frames);
            }
        }
        let mut e = Enc::default();
        e.put(&env!("CARGO_PKG_VERSION").to_string());
        e.put(&self.run_id);
        e.put(&self.source.origin);
        e.put(&self.source.text);
        e.put(&self.source.overrides);
        e.put(&self.source.name);
        e.put(&self.policy.every_steps.unwrap_or(0));
        e.put(&self.policy.every_seconds.unwrap_or(0.0));
        e.put(&driver.next_out);
        e.put(&driver.next_series);
        e.put(&driver.kinetic_max);
        e.put(&driver.energy0);
        e.put(&driver.mom0);
        e.put(&driver.frames);
        e.put(&driver.series);
        e.put(&driver.monitor);
        sim.save_checkpoint(&mut e);
        let payload = e.buf;
        let mut bytes = Vec::with_capacity(HEADER + payload.len());
        bytes.extend_from_slice(MAGIC);
        bytes.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        bytes.extend_from_slice(&(D as u32).to_le_bytes());
        bytes.extend_from_slice(&(payload.len() as u64).to_le_bytes());
        bytes.extend_from_slice(&fnv1a64(&payload).to_le_bytes());
        bytes.extend_from_slice(&payload);
        write_atomic(self.dir.join(CHECKPOINT_BIN), &bytes)?;
        self.last = Instant::now();
        Ok(())
    }
}
