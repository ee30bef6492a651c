//! Output of a run.
//!
//! `gsph run SCENE --out DIR` writes into `DIR` (every file, dataset and unit: docs/output.md):
//! - `summary.json`: scene, dimension, scheme, effects, counts, timings, conservation diagnostics
//!   and the case's own measures (written with [`write_atomic`]).
//! - `final.csv`: one row per particle; header [`COLUMNS`] then the Cauchy stress and von Mises
//!   stress ([`DERIVED_COLUMNS`]) ([`write_csv`], read back by [`read_csv`]); units and meanings
//!   in [`quantities`].
//! - `snapshots.h5`: one group `/step_XXXXXX` per output time with the particle columns, the
//!   Cauchy stress tensor `stress` and `von_mises`, every dataset compressed and carrying its
//!   `units`; root attributes name the gsph version, the scene text, the effects and the
//!   materials ([`SnapshotWriter`], read back by [`read_snapshot_times`], [`read_frame`] and
//!   [`read_run_info`]).
//! - `snapshots.xdmf`: the sidecar that lets ParaView open the snapshots as a time series (the
//!   stress as a Tensor attribute).
//!
//! Every file is written atomically: data go to `<name>.tmp` in the same directory, are synced and
//! then renamed, so a run that fails or is killed never leaves a file that looks complete. The
//! snapshots are the exception that proves it: while the run goes on they are
//! `snapshots.partial.h5` and `snapshots.partial.xdmf` (rewritten after every snapshot, so
//! ParaView can follow the run, and marked `partial` inside), renamed or rewritten to
//! `snapshots.h5` / `snapshots.xdmf` when the run finishes. An interrupted or failed run leaves
//! the partial pair, its status saying why.
//!
//! Files: [`table`] (the particle table), [`meta`] (units, derived quantities, [`RunInfo`]),
//! [`atomic`] (temp-file-and-rename helpers), [`safe`] (no file written through a link, only
//! regular files read, short excerpts in messages), [`csv`], `hdf5` (the snapshot writer), `hdf5_read`
//! (its reader), [`xdmf`] (the sidecar), [`error`] ([`OutputError`]).
//!
//! The snapshots need the cargo feature `hdf5` (on by default). Without it
//! [`SnapshotWriter`], [`read_snapshot_times`], [`read_frame`] and [`read_run_info`] keep their
//! signatures but refuse with [`OutputError::Unsupported`] ([`error::NO_HDF5`]): `gsph run` with
//! an output directory fails in one line, a run without one (the library's) is unaffected.

pub mod atomic;
pub mod csv;
pub mod error;
#[cfg(feature = "hdf5")]
pub mod hdf5;
#[cfg(feature = "hdf5")]
pub mod hdf5_read;
pub mod meta;
#[cfg(not(feature = "hdf5"))]
mod no_hdf5;
pub mod quantity;
pub mod safe;
pub mod table;
pub mod xdmf;

/// File name of the HDF5 snapshots in the output directory.
pub const SNAPSHOTS_H5: &str = "snapshots.h5";
/// File name of the XDMF sidecar in the output directory.
pub const SNAPSHOTS_XDMF: &str = "snapshots.xdmf";
/// File name of the HDF5 snapshots while the run goes on (and after it was interrupted or failed).
pub const SNAPSHOTS_PARTIAL_H5: &str = "snapshots.partial.h5";
/// File name of the XDMF sidecar while the run goes on (and after it was interrupted or failed).
pub const SNAPSHOTS_PARTIAL_XDMF: &str = "snapshots.partial.xdmf";

pub use self::atomic::{write_atomic, AtomicFile};
pub use self::csv::{read_csv, write_csv};
pub use self::error::OutputError;
#[cfg(feature = "hdf5")]
pub use self::hdf5::SnapshotWriter;
#[cfg(feature = "hdf5")]
pub use self::hdf5_read::{read_frame, read_run_info, read_snapshot_times};
pub use self::meta::{quantities, RunInfo, DERIVED_COLUMNS};
#[cfg(not(feature = "hdf5"))]
pub use self::no_hdf5::{read_frame, read_run_info, read_snapshot_times, SnapshotWriter};
pub use self::table::{Frame, ParticleRow, ParticleTable, COLUMNS};
