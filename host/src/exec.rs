//! The rayon executor of the core's per-particle loops (in `gsph-steps`, which compiles
//! the step specialisations for it), and the bound on the worker threads a caller may ask
//! for (`gsph --threads`, the C ABI's `gsph_set_threads`).

pub use gsph_steps::Rayon;

/// Most worker threads per core a caller may ask for.
pub const MAX_THREADS_PER_CORE: usize = 8;

/// `Ok` if `threads` worker threads are at most [`MAX_THREADS_PER_CORE`] per core of this
/// machine; else why not (`this machine has 2 cores; more than 8 threads per core (16)
/// only slows a run down`), for the caller to prefix with what it names (`--threads N`).
pub fn check_threads(threads: usize) -> Result<(), String> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    if threads > MAX_THREADS_PER_CORE * cores {
        return Err(format!(
            "this machine has {cores} cores; more than {MAX_THREADS_PER_CORE} threads per core ({}) only slows a run down",
            MAX_THREADS_PER_CORE * cores
        ));
    }
    Ok(())
}
