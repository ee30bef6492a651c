//! Output of a run.
//!
//! `gsph run SCENE --out DIR` writes into `DIR`:
//! - `summary.json`: scene, dimension, scheme, effects, counts, timings, conservation diagnostics
//!   and the case's own measures (written with [`write_atomic`]).
//! - `final.csv`: one row per particle with header [`COLUMNS`] ([`write_csv`], read back by
//!   [`read_csv`]).
//! - `snapshots.h5`: one group `/step_XXXXXX` per output time ([`SnapshotWriter`], read back by
//!   [`read_snapshot_times`] and [`read_frame`]).
//! - `snapshots.xdmf`: the sidecar that lets ParaView open the snapshots as a time series.
//!
//! Every file is written atomically: data go to `<name>.tmp` in the same directory, are synced and
//! then renamed, so a run that fails or is killed never leaves a file that looks complete. The XDMF
//! sidecar is written only after `snapshots.h5` has been renamed into place.
//!
//! Files: [`table`] (the particle table), [`atomic`] (temp-file-and-rename helpers), [`csv`],
//! `hdf5` (the snapshot writer), `hdf5_read` (its reader), [`xdmf`] (the sidecar),
//! [`error`] ([`OutputError`]).
//!
//! The snapshots need the cargo feature `hdf5` (on by default). Without it
//! [`SnapshotWriter`], [`read_snapshot_times`] and [`read_frame`] keep their signatures but
//! refuse with [`OutputError::Unsupported`] ([`error::NO_HDF5`]): `gsph run` with an output
//! directory fails in one line, a run without one (the library's) is unaffected.

pub mod atomic;
pub mod csv;
pub mod error;
#[cfg(feature = "hdf5")]
pub mod hdf5;
#[cfg(feature = "hdf5")]
pub mod hdf5_read;
#[cfg(not(feature = "hdf5"))]
mod no_hdf5;
pub mod table;
pub mod xdmf;

/// File name of the HDF5 snapshots in the output directory.
pub const SNAPSHOTS_H5: &str = "snapshots.h5";
/// File name of the XDMF sidecar in the output directory.
pub const SNAPSHOTS_XDMF: &str = "snapshots.xdmf";

pub use self::atomic::{write_atomic, AtomicFile};
pub use self::csv::{read_csv, write_csv};
pub use self::error::OutputError;
#[cfg(feature = "hdf5")]
pub use self::hdf5::SnapshotWriter;
#[cfg(feature = "hdf5")]
pub use self::hdf5_read::{read_frame, read_snapshot_times};
#[cfg(not(feature = "hdf5"))]
pub use self::no_hdf5::{read_frame, read_snapshot_times, SnapshotWriter};
pub use self::table::{Frame, ParticleRow, ParticleTable, COLUMNS};
