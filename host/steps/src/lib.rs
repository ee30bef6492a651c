//! The core's step specialisations instantiated for the rayon executor.
//!
//! The steps are generic over the executor, so they are compiled (monomorphised) in the
//! crate that names the executor. Naming it here, in non-generic functions, compiles the
//! up to 48 specialisations once in this crate: the `gsph` host crate calls
//! [`select_1d`], [`select_2d`] and [`select_3d`] and changes to it do not recompile
//! them.

use gsph_core::effects::EffectSet;
use gsph_core::exec::{Executor, Split};

use gsph_core::schemes::Family;
use gsph_core::schemes::StepFn;

/// The 1D step of a scheme family and effect set, if this build contains it.
pub fn select_1d(family: Family, effects: EffectSet) -> Option<StepFn<1, Rayon>> {
    gsph_core::dispatch::select_1d::<Rayon>(family, effects)
}

/// The 2D step of a scheme family and effect set, if this build contains it.
pub fn select_2d(family: Family, effects: EffectSet) -> Option<StepFn<2, Rayon>> {
    gsph_core::dispatch::select_2d::<Rayon>(family, effects)
}

/// The 3D step of a scheme family and effect set, if this build contains it.
pub fn select_3d(family: Family, effects: EffectSet) -> Option<StepFn<3, Rayon>> {
    gsph_core::dispatch::select_3d::<Rayon>(family, effects)
}

/// Splits every loop recursively with `rayon::join` down to chunks of `min_chunk`
/// particles. Chunk boundaries depend only on the particle count, and each particle's
/// result only on its own (sorted) neighbour list, so results are bitwise identical for
/// any number of threads.
#[derive(Clone, Copy, Debug)]
pub struct Rayon {
    /// Smallest chunk handed to one task.
    pub min_chunk: usize,
}

impl Default for Rayon {
    fn default() -> Self {
        Rayon { min_chunk: 256 }
    }
}

impl Executor for Rayon {
    fn run<S: Split, F: Fn(usize, S) + Sync>(&self, data: S, f: F) {
        fn rec<S: Split, F: Fn(usize, S) + Sync>(off: usize, data: S, f: &F, min: usize) {
            let n = data.len();
            if n <= min {
                f(off, data);
                return;
            }
            let mid = n / 2;
            let (a, b) = data.split_at(mid);
            rayon::join(|| rec(off, a, f, min), || rec(off + mid, b, f, min));
        }
        rec(0, data, &f, self.min_chunk.max(1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_index_visited_once_with_its_offset() {
        let mut v = vec![0usize; 10_000];
        Rayon { min_chunk: 7 }.run(&mut v[..], |off, chunk: &mut [usize]| {
            for (k, x) in chunk.iter_mut().enumerate() {
                *x += off + k + 1;
            }
        });
        assert!(v.iter().enumerate().all(|(i, &x)| x == i + 1));
    }
}
