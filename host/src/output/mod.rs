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
//! [`mod@hdf5`] (the snapshot writer), [`hdf5_read`] (its reader), [`xdmf`] (the sidecar).

pub mod atomic;
pub mod csv;
pub mod hdf5;
pub mod hdf5_read;
pub mod table;
pub mod xdmf;

pub use self::atomic::{write_atomic, AtomicFile};
pub use self::csv::{read_csv, write_csv};
pub use self::hdf5::{OutputError, SnapshotWriter, SNAPSHOTS_H5, SNAPSHOTS_XDMF};
pub use self::hdf5_read::{read_frame, read_snapshot_times};
pub use self::table::{Frame, ParticleRow, ParticleTable, COLUMNS};
