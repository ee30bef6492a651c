//! The rayon executor of the core's per-particle loops.

use gsph_core::exec::{Executor, Split};

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
