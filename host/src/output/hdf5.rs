//! HDF5 snapshots (`snapshots.h5`) with their XDMF sidecar (`snapshots.xdmf`).
//!
//! Layout (format version 3; docs/output.md). Root attributes: `dim` (u32), `format_version`
//! (u32, [`FORMAT_VERSION`]), `gsph_version`, `scene_name`, `scene` (the scene text as given),
//! `scene_overrides`, `scheme`, `effects`, `material_names` (index = the `material` column) and
//! `conventions`, `run_id` (strings, the lists 1-D string arrays; [`RunInfo`]). One group per snapshot,
//! `/step_000123`, with attributes `time` (f64, s) and `step` (u64); datasets `position` and
//! `velocity` (N x 3 f64), `stress` (the Cauchy stress `-p I + S`, N x 3 x 3 f64), one 1-D
//! dataset per other column of `final.csv` ([`scalar_datasets`]: `id` and `material` as u32, the
//! rest f64) and `von_mises`. Every dataset has string attributes `units` (SI) and
//! `description`, and is chunked (about [`CHUNK_BYTES`] per chunk) and compressed with shuffle +
//! deflate ([`DEFLATE_LEVEL`]). N may differ between snapshots.
//!
//! While the run goes on, the data go to `snapshots.partial.h5`, reopened for every snapshot and
//! closed again (so the file is whole between snapshots, holds no lock a viewer would trip on, and
//! a killed run leaves every finished snapshot readable), and `snapshots.partial.xdmf` is
//! rewritten atomically after every snapshot with `<Information Name="status"
//! Value="partial: ...">`, so ParaView can follow the run. [`SnapshotWriter::finish`] renames the
//! data to `snapshots.h5`, writes `snapshots.xdmf` (status `complete`) and removes the partial
//! XDMF. [`SnapshotWriter::interrupt`] (SIGTERM/SIGINT) and a writer dropped without `finish` (a
//! failed run) leave the partial pair, its status saying why. [`SnapshotWriter::create`] removes
//! the snapshot files of an earlier run, partial ones included.
//! [`read_frame`](super::hdf5_read::read_frame) reads a snapshot back.

use std::io;
use std::path::{Path, PathBuf};
use std::time::Duration;

pub use super::error::OutputError;

use super::atomic::{sync_parent_dir, tmp_path, write_atomic};
use super::meta::{cauchy_stress, quantity, unit, von_mises, RunInfo, GSPH_VERSION};
use super::table::{Frame, ParticleTable};
use super::xdmf::{
    group_name, scalar_datasets, xdmf_document, XdmfGrid, XdmfHeader, STATUS_COMPLETE,
};

pub use super::{SNAPSHOTS_H5, SNAPSHOTS_PARTIAL_H5, SNAPSHOTS_PARTIAL_XDMF, SNAPSHOTS_XDMF};

/// The layout version in the root attribute `format_version` (files without it are version 1:
/// no `stress`, `von_mises`, run attributes, units or compression).
/// Version 3 added `run_id`.
pub const FORMAT_VERSION: u32 = 3;
/// Deflate (gzip) level of every dataset (after the shuffle filter). After the shuffle, level 1
/// compresses a 2D impact's snapshots to 41 % of their raw size, level 4 to 40 % (at two thirds
/// of the speed), level 6 to 40 % (at 40 %): 1 it is.
pub const DEFLATE_LEVEL: u8 = 1;
/// Target size of one chunk, bytes (the chunks span whole rows of particles).
pub const CHUNK_BYTES: usize = 1 << 18;
/// Half the rank of the B-trees that index the chunks. HDF5's default, 32, gives every dataset a
/// 2.5 KiB node, which outweighs the data of a small run's snapshots (the 1D flyer plate, 100
/// particles: a file of 2.7 times its raw data; with 4, 1.2 times); 10^7 particles, a few
/// thousand chunks a dataset, still get a tree of depth 4 or 5.
pub const ISTORE_K: u32 = 4;
/// The root attribute `conventions`.
pub const CONVENTIONS: &str = "SI units (each dataset's `units` attribute; m is per unit area \
     in 1D, per unit length in 2D); stress = -p I + S, tension positive; p positive in \
     compression; s.. (sxx .. syz) the stress deviator S; von_mises = sqrt(3/2 S:S)";

/// Removes `path`, treating "not found" as success.
fn remove_if_exists(path: &Path) -> io::Result<()> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => Err(e),
        _ => Ok(()),
    }
}

/// Writes snapshots to `snapshots.h5` and the sidecar `snapshots.xdmf` in one directory (through
/// `snapshots.partial.h5` / `.xdmf` while the run goes on).
#[derive(Debug)]
pub struct SnapshotWriter {
    dir: PathBuf,
    dim: usize,
    materials: Vec<String>,
    grids: Vec<XdmfGrid>,
    /// Why the run stopped, once [`SnapshotWriter::interrupt`] was called (then `Drop` leaves
    /// the partial XDMF as it is).
    stopped: Option<String>,
    finished: bool,
}

impl SnapshotWriter {
    /// `Ok`: this build writes snapshots (a build without the feature `hdf5` refuses with
    /// [`OutputError::Unsupported`]).
    pub fn supported() -> Result<(), OutputError> {
        Ok(())
    }

    /// Starts `dir/snapshots.partial.h5` (with the run's attributes from `info`) and
    /// `dir/snapshots.partial.xdmf` for a run of dimension `dim`; removes the snapshot files of an
    /// earlier run in `dir` (`snapshots.h5`, `snapshots.xdmf`, partial and temp ones), so a failed
    /// run leaves none that looks complete.
    pub fn create(dir: &Path, dim: usize, info: &RunInfo) -> Result<Self, OutputError> {
        if !(1..=3).contains(&dim) {
            return Err(OutputError::Format(format!(
                "dimension {dim} is not 1, 2 or 3"
            )));
        }
        for name in [
            SNAPSHOTS_XDMF,
            SNAPSHOTS_H5,
            SNAPSHOTS_PARTIAL_XDMF,
            SNAPSHOTS_PARTIAL_H5,
        ] {
            remove_if_exists(&dir.join(name))?;
            remove_if_exists(&tmp_path(&dir.join(name)))?;
        }
        let writer = Self {
            dir: dir.to_path_buf(),
            dim,
            materials: info.materials.clone(),
            grids: Vec::new(),
            stopped: None,
            finished: false,
        };
        // exclusive: the name was just removed, and HDF5 creating by name must not follow a
        // link planted since (O_EXCL fails on one)
        let started = hdf5::File::with_options()
            .with_fcpl(|p| p.istore_k(ISTORE_K))
            .create_excl(writer.tmp_path())
            .map_err(OutputError::from)
            .and_then(|file| {
                write_run_attributes(&file, dim, info)?;
                file.close().map_err(OutputError::from)
            })
            .and_then(|()| writer.write_partial_xdmf());
        if let Err(e) = started {
            let mut w = writer;
            w.finished = true;
            let _ = std::fs::remove_file(w.tmp_path());
            let _ = std::fs::remove_file(w.dir.join(SNAPSHOTS_PARTIAL_XDMF));
            return Err(e);
        }
        Ok(writer)
    }

    /// The HDF5 file written until [`SnapshotWriter::finish`], `snapshots.partial.h5`; it is
    /// closed and whole between [`SnapshotWriter::append`]s (checkpoints copy it).
    pub fn tmp_path(&self) -> PathBuf {
        self.dir.join(SNAPSHOTS_PARTIAL_H5)
    }

    /// Number of snapshots appended so far.
    pub fn len(&self) -> usize {
        self.grids.len()
    }

    /// True before the first [`SnapshotWriter::append`].
    pub fn is_empty(&self) -> bool {
        self.grids.is_empty()
    }

    /// Writes `frame` as group `/step_XXXXXX`, then rewrites `snapshots.partial.xdmf`; steps must
    /// be distinct, the dimension the writer's.
    pub fn append(&mut self, frame: &Frame) -> Result<(), OutputError> {
        self.check_open()?;
        if frame.dim != self.dim {
            return Err(OutputError::Format(format!(
                "frame of dimension {} in snapshots of dimension {}",
                frame.dim, self.dim
            )));
        }
        if self.grids.iter().any(|g| g.step == frame.step) {
            return Err(OutputError::Format(format!(
                "step {} written twice",
                frame.step
            )));
        }
        let t = &frame.table;
        let n = t.len();
        if t.material.len() != n || t.float_columns().iter().any(|c| c.len() != n) {
            return Err(OutputError::Format(format!(
                "step {}: particle table columns differ in length",
                frame.step
            )));
        }
        // HDF5 opens by name: never a link put in the file's place during the run
        super::safe::refuse_link(&self.tmp_path()).map_err(OutputError::Format)?;
        let file = open_rw(&self.tmp_path())?;
        write_group(&file, frame, self.dim)?;
        file.close()?;
        self.grids.push(XdmfGrid {
            step: frame.step,
            time: frame.time,
            n,
        });
        self.write_partial_xdmf()
    }

    /// Ends the writer of an interrupted run (SIGTERM, SIGINT): the snapshots written so far are
    /// on disk already; rewrites `snapshots.partial.xdmf` with status `partial: run interrupted
    /// at step STEP, t = T s; ...` and leaves the partial pair.
    pub fn interrupt(mut self, step: u64, t: f64) -> Result<(), OutputError> {
        self.check_open()?;
        self.stopped = Some(format!(
            "partial: run interrupted at step {step}, t = {t:e} s; {}",
            self.written()
        ));
        self.write_partial_xdmf()
    }

    /// Renames `snapshots.partial.h5` to `snapshots.h5`, writes `snapshots.xdmf` atomically and
    /// removes `snapshots.partial.xdmf`.
    pub fn finish(mut self) -> Result<(), OutputError> {
        self.check_open()?;
        let (from, to) = (self.tmp_path(), self.dir.join(SNAPSHOTS_H5));
        std::fs::File::open(&from)?.sync_all()?;
        std::fs::rename(&from, &to)?;
        sync_parent_dir(&to);
        self.finished = true;
        let doc = xdmf_document(&self.header(SNAPSHOTS_H5, STATUS_COMPLETE), &self.grids);
        write_atomic(self.dir.join(SNAPSHOTS_XDMF), doc.as_bytes())?;
        remove_if_exists(&self.dir.join(SNAPSHOTS_PARTIAL_XDMF))?;
        Ok(())
    }

    fn check_open(&self) -> Result<(), OutputError> {
        if self.finished {
            return Err(OutputError::Format("snapshot writer already closed".into()));
        }
        Ok(())
    }

    /// `K snapshots, the last at step S, t = T s` (or `no snapshot`).
    fn written(&self) -> String {
        match self.grids.last() {
            None => "no snapshot".into(),
            Some(g) => format!(
                "{} snapshot(s), the last at step {}, t = {:e} s",
                self.grids.len(),
                g.step,
                g.time
            ),
        }
    }

    fn header<'a>(&'a self, h5_file: &'a str, status: &'a str) -> XdmfHeader<'a> {
        XdmfHeader {
            h5_file,
            dim: self.dim,
            status,
            materials: &self.materials,
        }
    }

    fn write_partial_xdmf(&self) -> Result<(), OutputError> {
        let status = match &self.stopped {
            Some(s) => s.clone(),
            None => format!("partial: run in progress; {}", self.written()),
        };
        self.write_partial_xdmf_with(&status)
    }

    fn write_partial_xdmf_with(&self, status: &str) -> Result<(), OutputError> {
        let doc = xdmf_document(&self.header(SNAPSHOTS_PARTIAL_H5, status), &self.grids);
        write_atomic(self.dir.join(SNAPSHOTS_PARTIAL_XDMF), doc.as_bytes())?;
        Ok(())
    }
}

impl Drop for SnapshotWriter {
    /// A writer dropped without [`SnapshotWriter::finish`] (a failed or stopped run) leaves the
    /// partial pair, marked as such.
    fn drop(&mut self) {
        if self.finished || self.stopped.is_some() {
            return;
        }
        let status = format!(
            "partial: run ended without finishing (error or stop); {}",
            self.written()
        );
        let _ = self.write_partial_xdmf_with(&status);
    }
}

/// Opens `path` for writing; retries for up to 5 s while another program (a viewer reading the
/// partial file) holds an HDF5 file lock on it.
fn open_rw(path: &Path) -> Result<hdf5::File, OutputError> {
    let mut tries = 0;
    loop {
        match hdf5::File::open_rw(path) {
            Ok(f) => return Ok(f),
            Err(e) if tries < 50 && e.to_string().contains("lock") => {
                tries += 1;
                std::thread::sleep(Duration::from_millis(100));
            }
            Err(e) => return Err(e.into()),
        }
    }
}

fn varlen(s: &str) -> Result<hdf5::types::VarLenUnicode, OutputError> {
    s.parse()
        .map_err(|e| OutputError::Format(format!("string `{s:.40}`: {e}")))
}

fn str_attr(loc: &hdf5::Location, name: &str, value: &str) -> Result<(), OutputError> {
    loc.new_attr::<hdf5::types::VarLenUnicode>()
        .shape(())
        .create(name)?
        .write_scalar(&varlen(value)?)?;
    Ok(())
}

fn str_list_attr(loc: &hdf5::Location, name: &str, values: &[String]) -> Result<(), OutputError> {
    let v = values
        .iter()
        .map(|s| varlen(s))
        .collect::<Result<Vec<_>, _>>()?;
    let a = loc
        .new_attr::<hdf5::types::VarLenUnicode>()
        .shape(v.len())
        .create(name)?;
    if !v.is_empty() {
        a.write_raw(&v)?;
    }
    Ok(())
}

fn write_run_attributes(file: &hdf5::File, dim: usize, info: &RunInfo) -> Result<(), OutputError> {
    for (name, v) in [("dim", dim as u32), ("format_version", FORMAT_VERSION)] {
        file.new_attr::<u32>().create(name)?.write_scalar(&v)?;
    }
    str_attr(file, "gsph_version", GSPH_VERSION)?;
    str_attr(file, "scene_name", &info.name)?;
    str_attr(file, "scene", &info.scene)?;
    str_list_attr(file, "scene_overrides", &info.overrides)?;
    str_attr(file, "scheme", &info.scheme)?;
    str_list_attr(file, "effects", &info.effects)?;
    str_list_attr(file, "material_names", &info.materials)?;
    str_attr(file, "conventions", CONVENTIONS)?;
    str_attr(file, "run_id", &info.run_id)?;
    Ok(())
}

fn write_group(file: &hdf5::File, frame: &Frame, dim: usize) -> Result<(), OutputError> {
    let t = &frame.table;
    let n = t.len();
    let group = file.create_group(&group_name(frame.step))?;
    group
        .new_attr::<f64>()
        .create("time")?
        .write_scalar(&frame.time)?;
    group
        .new_attr::<u64>()
        .create("step")?
        .write_scalar(&frame.step)?;
    for (name, cols) in [
        ("position", [&t.x, &t.y, &t.z]),
        ("velocity", [&t.vx, &t.vy, &t.vz]),
    ] {
        let flat: Vec<f64> = (0..n).flat_map(|i| cols.map(|c| c[i])).collect();
        write_dataset(&group, name, &[n, 3], &flat, dim)?;
    }
    let stress: Vec<f64> = (0..n).flat_map(|i| cauchy_stress(t, i)).collect();
    write_dataset(&group, "stress", &[n, 3, 3], &stress, dim)?;
    for name in scalar_datasets() {
        match name {
            "id" => write_dataset(&group, name, &[n], &t.id, dim)?,
            "material" => write_dataset(&group, name, &[n], &t.material, dim)?,
            "von_mises" => {
                let vm: Vec<f64> = (0..n).map(|i| von_mises(t, i)).collect();
                write_dataset(&group, name, &[n], &vm, dim)?;
            }
            _ => write_dataset(&group, name, &[n], float_column(t, name)?, dim)?,
        }
    }
    Ok(())
}

/// Writes `data` (row-major, `shape`) as dataset `name` of `group`: chunked by whole rows,
/// shuffle + deflate, with attributes `units` and `description`.
fn write_dataset<T: hdf5::H5Type>(
    group: &hdf5::Group,
    name: &str,
    shape: &[usize],
    data: &[T],
    dim: usize,
) -> Result<(), OutputError> {
    let row_bytes = shape[1..].iter().product::<usize>() * std::mem::size_of::<T>();
    let mut chunk = shape.to_vec();
    chunk[0] = (CHUNK_BYTES / row_bytes).clamp(1, shape[0].max(1));
    let mut b = group.new_dataset::<T>().shape(shape).chunk(chunk).shuffle();
    if hdf5::filters::deflate_available() {
        b = b.deflate(DEFLATE_LEVEL);
    }
    let ds = b.create(name)?;
    if !data.is_empty() {
        ds.write_raw(data)?;
    }
    str_attr(&ds, "units", unit(name, dim))?;
    let description = quantity(name).map_or("", |q| q.description);
    str_attr(&ds, "description", description)?;
    Ok(())
}

fn float_column<'t>(t: &'t ParticleTable, name: &str) -> Result<&'t [f64], OutputError> {
    t.float_column(name)
        .ok_or_else(|| OutputError::Format(format!("no column `{name}`")))
}

#[cfg(test)]
#[path = "hdf5_tests.rs"]
mod tests;
