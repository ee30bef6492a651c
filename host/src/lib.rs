//! # gsph
//!
//! The std host of gsph: scenes, parallel neighbour search, the run driver, output
//! (HDF5 + XDMF, CSV, JSON) and the `gsph` command line. The physics is in `gsph-core`.
//!
//! Cargo features besides the step specialisations, all on by default: `hdf5` (snapshot
//! files; without it a run with an output directory is refused), `plot` (the `plot`
//! module and the plots of studies and Hugoniots; without it they write tables only) and
//! `cli` (the `cli` module and the `gsph` binary, with its progress bar).

pub mod api;
pub mod checkpoint;
#[cfg(feature = "cli")]
pub mod cli;
pub mod codec;
#[cfg(feature = "cli")]
pub mod commands;
#[cfg(feature = "mpi")]
pub mod dist;
pub mod driver;
pub mod exec;
pub mod interrupt;

pub mod memory;
pub mod monitor;
pub mod neighbors;
pub mod outdir;
pub mod output;
#[cfg(feature = "plot")]
pub mod plot;
pub mod progress;
pub mod reference;
pub mod runlog;
pub mod scene;
pub mod sim;
pub mod sim_error;
pub mod specs;
pub mod stability;
pub mod study;
pub mod window;

/// Why a plot was refused or left out by a build without the cargo feature `plot`.
pub const NO_PLOT: &str = "this gsph was built without plotting (cargo feature `plot`)";

/// The number of MPI ranks of this run (1 without the feature `mpi` or outside `mpirun`).
pub fn dist_size() -> usize {
    #[cfg(feature = "mpi")]
    return dist::size();
    #[cfg(not(feature = "mpi"))]
    1
}

/// This process's MPI rank (0 without the feature `mpi` or outside `mpirun`).
pub fn dist_rank() -> usize {
    #[cfg(feature = "mpi")]
    return dist::rank();
    #[cfg(not(feature = "mpi"))]
    0
}
