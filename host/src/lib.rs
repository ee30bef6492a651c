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
pub mod specs;
pub mod stability;
pub mod study;
pub mod window;
pub mod words;

/// Why a plot was refused or left out by a build without the cargo feature `plot`.
pub const NO_PLOT: &str = "this gsph was built without plotting (cargo feature `plot`)";

/// The cargo features this build was compiled with, as `gsph --version` lists them.
pub fn build_features() -> Vec<&'static str> {
    let mut f = Vec::new();
    for (on, name) in [
        (cfg!(feature = "cli"), "cli"),
        (cfg!(feature = "hdf5"), "hdf5"),
        (cfg!(feature = "mpi"), "mpi"),
        (cfg!(feature = "plot"), "plot"),
    ] {
        if on {
            f.push(name);
        }
    }
    f
}

/// What an MPI launcher (Open MPI's `mpirun`, MPICH's Hydra, Slurm's `srun`, PMIx) says of
/// this process, read from the environment it sets: `(rank, size)`, each where known;
/// `None` when no launcher started it. A build without the feature `mpi` uses it to refuse
/// to run as one of several copies.
pub fn launcher() -> Option<(Option<usize>, Option<usize>)> {
    let num = |vars: &[&str]| {
        vars.iter()
            .find_map(|v| std::env::var(v).ok()?.trim().parse::<usize>().ok())
    };
    let rank = num(&[
        "OMPI_COMM_WORLD_RANK",
        "PMIX_RANK",
        "PMI_RANK",
        "SLURM_PROCID",
    ]);
    let size = num(&["OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "SLURM_STEP_NUM_TASKS"]);
    (rank.is_some() || size.is_some()).then_some((rank, size))
}

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
