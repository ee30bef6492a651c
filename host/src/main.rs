//! The `gsph` command: see `gsph --help`.
fn main() {
    // With the feature `mpi`, MPI is initialised when a launcher started the process
    // (`mpirun`, `srun`: see gsph::dist::launched); a plain `gsph run` stays one process
    // and pays nothing. Only the main thread calls MPI; rayon's workers never do.
    #[cfg(feature = "mpi")]
    let universe = gsph::dist::launched()
        .then(|| mpi::initialize_with_threading(mpi::Threading::Funneled))
        .flatten()
        .map(|(u, _)| u);
    let code = gsph::cli::main_with_args(std::env::args_os());
    #[cfg(feature = "mpi")]
    {
        use mpi::traits::Communicator as _;
        if code != 0 && gsph::dist_size() > 1 {
            // other ranks may wait in a collective: end them all (mpirun exits non-zero)
            mpi::topology::SimpleCommunicator::world().abort(code);
        }
        drop(universe);
    }
    std::process::exit(code);
}
