//! HDF5 snapshots (`snapshots.h5`) with their XDMF sidecar (`snapshots.xdmf`).
//!
//! Layout: root attribute `dim` (u32); one group per snapshot, `/step_000123`, with attributes
//! `time` (f64) and `step` (u64), datasets `position` and `velocity` (N x 3 f64) and one 1-D
//! dataset per other column of `final.csv` ([`SCALAR_DATASETS`]: `id` and `material` as u32, the
//! rest f64). N may differ between snapshots.
//!
//! The file is written as `snapshots.h5.tmp` and renamed by [`SnapshotWriter::finish`], which then
//! writes the XDMF sidecar atomically; a writer dropped without `finish` removes its temp file.
//! [`read_frame`](super::hdf5_read::read_frame) reads a snapshot back.

use std::io;
use std::path::{Path, PathBuf};

pub use super::error::OutputError;

use super::atomic::{commit_tmp, tmp_path, write_atomic};
use super::table::{Frame, ParticleTable};
use super::xdmf::{group_name, xdmf_document, XdmfGrid, SCALAR_DATASETS};

pub use super::{SNAPSHOTS_H5, SNAPSHOTS_XDMF};

/// Removes `path`, treating "not found" as success.
fn remove_if_exists(path: &Path) -> io::Result<()> {
    match std::fs::remove_file(path) {
        Err(e) if e.kind() != io::ErrorKind::NotFound => Err(e),
        _ => Ok(()),
    }
}

/// Writes snapshots to `snapshots.h5` and the sidecar `snapshots.xdmf` in one directory.
#[derive(Debug)]
pub struct SnapshotWriter {
    dir: PathBuf,
    dim: usize,
    file: Option<hdf5::File>,
    grids: Vec<XdmfGrid>,
}

impl SnapshotWriter {
    /// `Ok`: this build writes snapshots (a build without the feature `hdf5` refuses with
    /// [`OutputError::Unsupported`]).
    pub fn supported() -> Result<(), OutputError> {
        Ok(())
    }

    /// Starts `dir/snapshots.h5.tmp` for a run of dimension `dim`; removes stale `snapshots.h5` and
    /// `snapshots.xdmf` of an earlier run in `dir`, so a failed run leaves neither.
    pub fn create(dir: &Path, dim: usize) -> Result<Self, OutputError> {
        if !(1..=3).contains(&dim) {
            return Err(OutputError::Format(format!(
                "dimension {dim} is not 1, 2 or 3"
            )));
        }
        let h5 = dir.join(SNAPSHOTS_H5);
        remove_if_exists(&dir.join(SNAPSHOTS_XDMF))?;
        remove_if_exists(&h5)?;
        let tmp = tmp_path(&h5);
        let file = hdf5::File::create(&tmp)?;
        let writer = Self {
            dir: dir.to_path_buf(),
            dim,
            file: Some(file),
            grids: Vec::new(),
        };
        let file = writer.file.as_ref().expect("just set");
        file.new_attr::<u32>()
            .create("dim")?
            .write_scalar(&(dim as u32))?;
        Ok(writer)
    }

    /// The temp path written until [`SnapshotWriter::finish`].
    pub fn tmp_path(&self) -> PathBuf {
        tmp_path(&self.dir.join(SNAPSHOTS_H5))
    }

    /// Number of snapshots appended so far.
    pub fn len(&self) -> usize {
        self.grids.len()
    }

    /// True before the first [`SnapshotWriter::append`].
    pub fn is_empty(&self) -> bool {
        self.grids.is_empty()
    }

    /// Writes `frame` as group `/step_XXXXXX`; steps must be distinct, the dimension the writer's.
    pub fn append(&mut self, frame: &Frame) -> Result<(), OutputError> {
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
        let file = self
            .file
            .as_ref()
            .ok_or_else(|| OutputError::Format("snapshot writer already closed".into()))?;
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
            let ds = group.new_dataset::<f64>().shape((n, 3)).create(name)?;
            if n > 0 {
                ds.write_raw(&flat)?;
            }
        }
        for name in SCALAR_DATASETS {
            match name {
                "id" => write_1d(&group, name, &t.id)?,
                "material" => write_1d(&group, name, &t.material)?,
                _ => write_1d(&group, name, float_column(t, name)?)?,
            }
        }
        file.flush()?;
        self.grids.push(XdmfGrid {
            step: frame.step,
            time: frame.time,
            n,
        });
        Ok(())
    }

    /// Closes the HDF5 file, renames it to `snapshots.h5` and writes `snapshots.xdmf` atomically.
    pub fn finish(mut self) -> Result<(), OutputError> {
        let tmp = self.tmp_path();
        let file = self
            .file
            .take()
            .ok_or_else(|| OutputError::Format("snapshot writer already closed".into()))?;
        if let Err(e) = file.close() {
            let _ = std::fs::remove_file(&tmp);
            return Err(e.into());
        }
        commit_tmp(&tmp, &self.dir.join(SNAPSHOTS_H5))?;
        let doc = xdmf_document(SNAPSHOTS_H5, &self.grids);
        write_atomic(self.dir.join(SNAPSHOTS_XDMF), doc.as_bytes())?;
        Ok(())
    }
}

impl Drop for SnapshotWriter {
    fn drop(&mut self) {
        if let Some(file) = self.file.take() {
            drop(file);
            let _ = std::fs::remove_file(self.tmp_path());
        }
    }
}

fn write_1d<T: hdf5::H5Type>(group: &hdf5::Group, name: &str, data: &[T]) -> hdf5::Result<()> {
    let ds = group.new_dataset::<T>().shape(data.len()).create(name)?;
    if !data.is_empty() {
        ds.write_raw(data)?;
    }
    Ok(())
}

fn float_column<'t>(t: &'t ParticleTable, name: &str) -> Result<&'t [f64], OutputError> {
    t.float_column(name)
        .ok_or_else(|| OutputError::Format(format!("no column `{name}`")))
}

#[cfg(test)]
mod tests {
    use super::super::hdf5_read::{read_frame, read_snapshot_times};
    use super::super::table::tests::sample_table;
    use super::super::xdmf::check_balanced_tags;
    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    fn frame(step: u64, time: f64, n: usize) -> Frame {
        Frame {
            time,
            step,
            dim: 2,
            table: sample_table(n, step as f64),
        }
    }

    #[test]
    fn round_trip_two_frames_of_different_sizes() {
        let dir = tempfile::tempdir().unwrap();
        let frames = [frame(0, 0.0, 17), frame(123, 1.25e-6, 9)];
        let mut w = SnapshotWriter::create(dir.path(), 2).unwrap();
        for f in &frames {
            w.append(f).unwrap();
        }
        assert_eq!(w.len(), 2);
        assert!(w.tmp_path().exists());
        assert!(
            !dir.path().join(SNAPSHOTS_H5).exists(),
            "not complete before finish"
        );
        w.finish().unwrap();
        assert_eq!(names(dir.path()), vec![SNAPSHOTS_H5, SNAPSHOTS_XDMF]);

        let h5 = dir.path().join(SNAPSHOTS_H5);
        assert_eq!(
            read_snapshot_times(&h5).unwrap(),
            vec![(0, 0.0), (123, 1.25e-6)]
        );
        for f in &frames {
            assert_eq!(&read_frame(&h5, f.step).unwrap(), f);
        }
        let e = read_frame(&h5, 7).unwrap_err();
        assert!(matches!(e, OutputError::Format(_)) && e.to_string().contains("step 7"));

        let x = std::fs::read_to_string(dir.path().join(SNAPSHOTS_XDMF)).unwrap();
        check_balanced_tags(&x).unwrap();
        assert!(x.contains("NumberOfElements=\"17\"") && x.contains("NumberOfElements=\"9\""));
        assert!(x.contains("Dimensions=\"17 3\""));
        assert!(x.contains(">snapshots.h5:/step_000000/position<"));
        assert!(x.contains(">snapshots.h5:/step_000123/position<"));
        assert!(x.contains(">snapshots.h5:/step_000123/velocity<"));
        assert!(x.contains("<Time Value=\"0e0\"/>") && x.contains("<Time Value=\"1.25e-6\"/>"));
        // Every dataset the XDMF references exists in its group.
        let file = hdf5::File::open(&h5).unwrap();
        for f in &frames {
            let g = file.group(&group_name(f.step)).unwrap();
            for ds in SCALAR_DATASETS.iter().chain(&["position", "velocity"]) {
                assert!(g.link_exists(ds), "{ds}");
                assert!(x.contains(&format!("/{}/{ds}<", group_name(f.step))));
            }
            assert_eq!(
                g.dataset("position").unwrap().shape(),
                vec![f.table.len(), 3]
            );
        }
    }

    #[test]
    fn empty_frame_round_trips() {
        let dir = tempfile::tempdir().unwrap();
        let mut w = SnapshotWriter::create(dir.path(), 2).unwrap();
        w.append(&frame(5, 1.0, 0)).unwrap();
        w.finish().unwrap();
        let f = read_frame(dir.path().join(SNAPSHOTS_H5), 5).unwrap();
        assert_eq!(f, frame(5, 1.0, 0));
    }

    #[test]
    fn drop_without_finish_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        std::fs::write(dir.path().join(SNAPSHOTS_H5), b"stale").unwrap();
        std::fs::write(dir.path().join(SNAPSHOTS_XDMF), b"stale").unwrap();
        let mut w = SnapshotWriter::create(dir.path(), 2).unwrap();
        w.append(&frame(1, 0.5, 4)).unwrap();
        assert!(w.tmp_path().exists());
        drop(w);
        assert!(names(dir.path()).is_empty(), "{:?}", names(dir.path()));
    }

    #[test]
    fn bad_frames_are_rejected() {
        let dir = tempfile::tempdir().unwrap();
        assert!(SnapshotWriter::create(dir.path(), 4).is_err());
        let mut w = SnapshotWriter::create(dir.path(), 2).unwrap();
        w.append(&frame(1, 0.5, 4)).unwrap();
        let e = w.append(&frame(1, 0.6, 4)).unwrap_err();
        assert!(e.to_string().contains("twice"), "{e}");
        let mut f3 = frame(2, 0.7, 4);
        f3.dim = 3;
        assert!(w.append(&f3).is_err());
        let mut ragged = frame(3, 0.8, 4);
        ragged.table.rho.pop();
        assert!(w.append(&ragged).is_err());
        w.finish().unwrap();
        let times = read_snapshot_times(dir.path().join(SNAPSHOTS_H5)).unwrap();
        assert_eq!(times, vec![(1, 0.5)]);
    }

    #[test]
    fn errors_display_on_one_line() {
        let e = read_frame("/nonexistent/snapshots.h5", 0).unwrap_err();
        let s = e.to_string();
        assert!(s.starts_with("HDF5 error") && !s.contains('\n'), "{s}");
        let io = OutputError::from(io::Error::other("a\nb"));
        assert_eq!(io.to_string(), "I/O error: a b");
    }
}
