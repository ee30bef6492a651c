//! How the per-particle loops of a step are executed.
//!
//! Every loop in a step is a *gather*: particle `i` reads its neighbours and writes only
//! its own outputs. The loop body is handed a chunk of the outputs (anything that
//! implements [`Split`]) together with the index of the chunk's first particle, so the
//! same physics runs serially here ([`Serial`]) and in parallel in the host (rayon splits
//! the outputs recursively). Because each particle's result depends only on its own
//! neighbour list (kept sorted), results are bitwise identical for any number of threads.

/// Something that can be cut at a particle index into two disjoint halves.
pub trait Split: Sized + Send {
    /// Number of particles covered.
    fn len(&self) -> usize;
    /// True when no particle is covered.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// Splits into `[0, mid)` and `[mid, len)`.
    fn split_at(self, mid: usize) -> (Self, Self);
}

impl<T: Send> Split for &mut [T] {
    #[inline]
    fn len(&self) -> usize {
        <[T]>::len(self)
    }
    #[inline]
    fn split_at(self, mid: usize) -> (Self, Self) {
        self.split_at_mut(mid)
    }
}

impl<T: Sync> Split for &[T] {
    #[inline]
    fn len(&self) -> usize {
        <[T]>::len(self)
    }
    #[inline]
    fn split_at(self, mid: usize) -> (Self, Self) {
        <[T]>::split_at(self, mid)
    }
}

impl<A: Split, B: Split> Split for (A, B) {
    #[inline]
    fn len(&self) -> usize {
        self.0.len()
    }
    #[inline]
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (a0, a1) = self.0.split_at(mid);
        let (b0, b1) = self.1.split_at(mid);
        ((a0, b0), (a1, b1))
    }
}

/// Splits an optional per-particle slice: an empty slice (absent effect) stays empty on
/// both sides.
#[inline]
pub fn split_opt<T>(s: &mut [T], mid: usize) -> (&mut [T], &mut [T]) {
    if s.is_empty() {
        (&mut [], &mut [])
    } else {
        s.split_at_mut(mid)
    }
}

/// [`split_opt`] of a shared slice: an empty (optional) slice splits into two empty halves.
#[inline]
pub fn split_opt_ref<T>(s: &[T], mid: usize) -> (&[T], &[T]) {
    if s.is_empty() {
        (&[], &[])
    } else {
        s.split_at(mid)
    }
}

/// Runs a loop body over chunks of particles.
pub trait Executor: Sync {
    /// Calls `f(first_index, chunk)` on disjoint chunks that together cover `data`.
    fn run<S: Split, F: Fn(usize, S) + Sync>(&self, data: S, f: F);
}

/// Runs everything on the calling thread, as one chunk.
#[derive(Clone, Copy, Debug, Default)]
pub struct Serial;

impl Executor for Serial {
    #[inline]
    fn run<S: Split, F: Fn(usize, S) + Sync>(&self, data: S, f: F) {
        f(0, data)
    }
}

/// A per-particle slice that may be empty (an absent effect): splitting an empty
/// `Optional` gives two empty halves instead of panicking.
#[derive(Debug)]
pub struct Optional<'a, T>(pub &'a mut [T]);

impl<T: Send> Split for Optional<'_, T> {
    #[inline]
    fn len(&self) -> usize {
        self.0.len()
    }
    #[inline]
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (a, b) = split_opt(self.0, mid);
        (Optional(a), Optional(b))
    }
}

/// A per-particle array of fixed-width records (`width` elements each, `data.len()` a
/// multiple of it): splitting at particle `mid` splits at its first element.
#[derive(Debug)]
pub struct Fixed<'a, T> {
    /// Elements per particle.
    pub width: usize,
    /// The records, one after the other.
    pub data: &'a mut [T],
}

impl<T: Send> Split for Fixed<'_, T> {
    #[inline]
    fn len(&self) -> usize {
        self.data.len() / self.width
    }
    #[inline]
    fn split_at(self, mid: usize) -> (Self, Self) {
        let (a, b) = self.data.split_at_mut(mid * self.width);
        let width = self.width;
        (Fixed { width, data: a }, Fixed { width, data: b })
    }
}

/// Calls `f(i, record)` for every particle `i`'s record of `data` (`width` elements each),
/// the particles split among the executor's threads: the one loop of the record writers.
#[inline]
pub fn for_each_record<T: Send, X: Executor>(
    exec: &X,
    data: &mut [T],
    width: usize,
    f: impl Fn(usize, &mut [T]) + Sync,
) {
    exec.run(Fixed { width, data }, |off, chunk: Fixed<'_, T>| {
        for (k, r) in chunk.data.chunks_exact_mut(width).enumerate() {
            f(off + k, r);
        }
    });
}

/// The rows of a compressed-row array over a run of particles: the records of the pairs
/// each particle owns (see [`crate::neighbors`]), or its neighbours. `start` holds the
/// run's row offsets (absolute, one more entry than particles) and `data` exactly the run's
/// rows, so splitting at particle `mid` splits the records at that particle's first row
/// entry. Each row is written by the chunk of its particle only. Empty `data` (the rows of
/// an absent effect) splits into empty halves.
#[derive(Debug)]
pub struct Rows<'a, T> {
    /// Row offsets of the run's particles (absolute), `len + 1` entries.
    pub start: &'a [u32],
    /// The entries of the run's rows.
    pub data: &'a mut [T],
}

impl<'a, T> Rows<'a, T> {
    /// The row of local particle `k` of the run.
    #[inline]
    pub fn of(&mut self, k: usize) -> &mut [T] {
        let base = self.start[0];
        let (s, e) = (
            (self.start[k] - base) as usize,
            (self.start[k + 1] - base) as usize,
        );
        &mut self.data[s..e]
    }
}

impl<T: Send> Split for Rows<'_, T> {
    #[inline]
    fn len(&self) -> usize {
        self.start.len() - 1
    }
    #[inline]
    fn split_at(self, mid: usize) -> (Self, Self) {
        // empty data: rows of an absent effect (or no entries at all) stay empty
        let cut = if self.data.is_empty() {
            0
        } else {
            (self.start[mid] - self.start[0]) as usize
        };
        let (a, b) = self.data.split_at_mut(cut);
        (
            Rows {
                start: &self.start[..=mid],
                data: a,
            },
            Rows {
                start: &self.start[mid..],
                data: b,
            },
        )
    }
}
