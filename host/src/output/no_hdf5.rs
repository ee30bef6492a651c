//! What stands in for [`SnapshotWriter`] and its readers in a build without the cargo
//! feature `hdf5`: each refuses with [`OutputError::Unsupported`] ([`NO_HDF5`]), so a run
//! that asks for `snapshots.h5` fails in one line instead of leaving it out.

use std::path::{Path, PathBuf};

use super::error::{OutputError, NO_HDF5};
use super::meta::RunInfo;
use super::table::Frame;
use super::SNAPSHOTS_H5;

fn refused(what: &str) -> OutputError {
    OutputError::Unsupported(format!("{what}: {NO_HDF5}"))
}

/// The snapshot writer of a build without HDF5: [`SnapshotWriter::create`] refuses, so no
/// value of this type exists and its other methods are never called.
#[derive(Debug)]
pub struct SnapshotWriter {
    never: core::convert::Infallible,
}

impl SnapshotWriter {
    /// Refuses: `snapshots.h5: this gsph was built without HDF5 (cargo feature `hdf5`)`.
    pub fn supported() -> Result<(), OutputError> {
        Err(refused(SNAPSHOTS_H5))
    }

    /// Refuses as [`SnapshotWriter::supported`] does.
    pub fn create(_dir: &Path, _dim: usize, _info: &RunInfo) -> Result<Self, OutputError> {
        Err(refused(SNAPSHOTS_H5))
    }

    /// Never called (no writer exists).
    pub fn tmp_path(&self) -> PathBuf {
        match self.never {}
    }

    /// Never called (no writer exists).
    pub fn len(&self) -> usize {
        match self.never {}
    }

    /// Never called (no writer exists).
    pub fn is_empty(&self) -> bool {
        match self.never {}
    }

    /// Never called (no writer exists).
    pub fn append(&mut self, _frame: &Frame) -> Result<(), OutputError> {
        match self.never {}
    }

    /// Never called (no writer exists).
    pub fn interrupt(self, _step: u64, _t: f64) -> Result<(), OutputError> {
        match self.never {}
    }

    /// Never called (no writer exists).
    pub fn finish(self) -> Result<(), OutputError> {
        match self.never {}
    }
}

/// Refuses (the caller names the file): `this gsph was built without HDF5 (cargo feature
/// `hdf5`)`.
pub fn read_snapshot_times(_path: impl AsRef<Path>) -> Result<Vec<(u64, f64)>, OutputError> {
    Err(OutputError::Unsupported(NO_HDF5.into()))
}

/// Refuses as [`read_snapshot_times`] does.
pub fn read_run_info(_path: impl AsRef<Path>) -> Result<Option<RunInfo>, OutputError> {
    Err(OutputError::Unsupported(NO_HDF5.into()))
}

/// Refuses as [`read_snapshot_times`] does.
pub fn read_frame(
    _path: impl AsRef<Path>,
    _step: u64,
    _limit: usize,
) -> Result<Frame, OutputError> {
    Err(OutputError::Unsupported(NO_HDF5.into()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_entry_point_refuses_in_one_line_naming_the_feature() {
        let dir = Path::new("unused");
        let msg = "snapshots.h5: this gsph was built without HDF5 (cargo feature `hdf5`)";
        assert_eq!(SnapshotWriter::supported().unwrap_err().to_string(), msg);
        let info = RunInfo::default();
        let created = SnapshotWriter::create(dir, 1, &info).unwrap_err();
        assert_eq!(created.to_string(), msg);
        assert_eq!(read_run_info(dir).unwrap_err().to_string(), NO_HDF5);
        let read = read_snapshot_times(dir).unwrap_err().to_string();
        assert_eq!(read, NO_HDF5);
        assert_eq!(read_frame(dir, 0, 1).unwrap_err().to_string(), NO_HDF5);
        assert!(!dir.exists());
    }
}
