//! Neighbour lists in compressed rows, the pair numbering of the pair-once passes, and the
//! geometry of pairs (periodic images).
//!
//! The neighbours of particle `i` are `index[start[i] .. start[i+1]]`, in one canonical
//! order: ascending *key* (the host's key is the global particle id, so the order, and every
//! sum over neighbours, is independent of how particles are numbered in memory, of the
//! thread count and of when lists are rebuilt). Each unordered pair is *owned* by the
//! particle of lower key: row `i` first lists the `lower` neighbours (keys below `i`'s,
//! pairs owned by them), then the `upper` ones (pairs owned by `i`). The pairs owned by `i`
//! are numbered `pair_start[i] ..` in row order, and `lower_pair` gives the number of the
//! pair behind each lower entry, so a pass can solve every pair once, into a buffer indexed
//! by pair number, and each particle can then gather its pairs in the canonical order
//! ([`Neighbors::for_each`]).
//!
//! Storage is caller-provided (`no_std`, no allocator). A particle with more neighbours
//! than the per-particle limit, or lists longer than the storage, are errors
//! ([`NeighborError::Overflow`]), never a silent truncation. The host fills the same
//! structure with a parallel cell list; [`build_naive`] is the O(N²) reference that needs
//! no allocation.

use crate::math::{Real, Vector};

/// Periodic boundaries: along each axis flagged in `axes`, positions live in
/// `[lo, lo + len)` and pair displacements use the minimum image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Periodic<const D: usize> {
    /// Lower corner of the periodic box.
    pub lo: Vector<D>,
    /// Box lengths (only read on periodic axes).
    pub len: Vector<D>,
    /// Which axes are periodic.
    pub axes: [bool; D],
}

impl<const D: usize> Periodic<D> {
    /// No periodic axis.
    pub fn none() -> Self {
        Periodic {
            lo: Vector::<D>::zeros(),
            len: Vector::<D>::zeros(),
            axes: [false; D],
        }
    }
    /// True if some axis is periodic.
    pub fn any(&self) -> bool {
        self.axes.iter().any(|&a| a)
    }
    /// Minimum-image displacement.
    #[inline]
    pub fn min_image(&self, mut d: Vector<D>) -> Vector<D> {
        for a in 0..D {
            if self.axes[a] {
                let l = self.len[a];
                if d[a] > 0.5 * l {
                    d[a] -= l;
                } else if d[a] < -0.5 * l {
                    d[a] += l;
                }
            }
        }
        d
    }
    /// Wraps a position back into the box along periodic axes.
    #[inline]
    pub fn wrap(&self, mut x: Vector<D>) -> Vector<D> {
        for a in 0..D {
            // a non-finite coordinate is left as it is (the step's check reports it)
            if self.axes[a] && x[a].is_finite() {
                let l = self.len[a];
                let lo = self.lo[a];
                while x[a] < lo {
                    x[a] += l;
                }
                while x[a] >= lo + l {
                    x[a] -= l;
                }
            }
        }
        x
    }
}

/// Errors of the neighbour search.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum NeighborError {
    /// Particle `particle` has `found` neighbours but the lists hold `capacity`.
    Overflow {
        /// The particle whose list overflowed.
        particle: usize,
        /// How many neighbours it has.
        found: usize,
        /// The per-particle capacity.
        capacity: usize,
    },
    /// The slices handed in have inconsistent lengths, or the lists are not symmetric
    /// (`j` listed by `i` but not `i` by `j`).
    BadStorage,
}

impl core::fmt::Display for NeighborError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            NeighborError::Overflow { particle, found, capacity } => write!(
                f,
                "neighbour-capacity overflow: particle {particle} has {found} neighbours, capacity is {capacity} (raise `neighbor_capacity`)"
            ),
            NeighborError::BadStorage => f.write_str("neighbour list storage has inconsistent lengths"),
        }
    }
}

/// Read-only view of the neighbour lists, as the passes consume them (module docs).
#[derive(Clone, Copy, Debug)]
pub struct Neighbors<'a> {
    /// Row offsets, `n + 1` entries.
    pub start: &'a [u32],
    /// Neighbour indices, rows in canonical order.
    pub index: &'a [u32],
    /// Offsets of the pairs each particle owns, `n + 1` entries.
    pub pair_start: &'a [u32],
    /// The pair number behind each lower entry: row `i`'s lower entries are
    /// `lower_pair[start[i] - pair_start[i] ..]`.
    pub lower_pair: &'a [u32],
}

/// One neighbour as [`Neighbors::for_each`] hands it over.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Entry {
    /// Neighbour index.
    pub j: usize,
    /// Number of the pair (i, j).
    pub pair: usize,
    /// True when `i` owns the pair (the pair was solved with `i` on the left).
    pub owner: bool,
}

impl<'a> Neighbors<'a> {
    /// Number of particles.
    #[inline]
    pub fn len(&self) -> usize {
        self.start.len().saturating_sub(1)
    }
    /// True if there are no particles.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The neighbours of `i` in canonical order (excluding `i`).
    #[inline]
    pub fn of(&self, i: usize) -> &'a [u32] {
        &self.index[self.start[i] as usize..self.start[i + 1] as usize]
    }
    /// The neighbours of `i` whose pair `i` owns, in order; their pair numbers are
    /// `pair_start[i] + k`.
    #[inline]
    pub fn owned(&self, i: usize) -> &'a [u32] {
        let e = self.start[i + 1] as usize;
        let owned = (self.pair_start[i + 1] - self.pair_start[i]) as usize;
        &self.index[e - owned..e]
    }
    /// Calls `f` for every neighbour of `i` in canonical order, with the pair number and
    /// whether `i` owns the pair.
    #[inline(always)]
    pub fn for_each(&self, i: usize, mut f: impl FnMut(Entry)) {
        let (s, e) = (self.start[i] as usize, self.start[i + 1] as usize);
        let (ps, pe) = (self.pair_start[i] as usize, self.pair_start[i + 1] as usize);
        let lower = (e - s) - (pe - ps);
        let lp = &self.lower_pair[s - ps..s - ps + lower];
        // one loop (one call site of `f`, so it inlines)
        for (k, &j) in self.index[s..e].iter().enumerate() {
            let owner = k >= lower;
            let pair = if owner {
                ps + (k - lower)
            } else {
                lp[k] as usize
            };
            f(Entry {
                j: j as usize,
                pair,
                owner,
            });
        }
    }
    /// Total number of directed pairs (entries of all rows).
    pub fn pairs(&self) -> usize {
        self.start.last().map_or(0, |&s| s as usize)
    }
    /// Number of unordered pairs (the length of a pair buffer).
    pub fn unordered_pairs(&self) -> usize {
        self.pair_start.last().map_or(0, |&s| s as usize)
    }
}

/// Counts the upper entries of row `i` (keys above `key[i]`) of lists whose rows are sorted
/// by key: the number of pairs particle `i` owns.
#[inline]
pub fn owned_count(row: &[u32], key: impl Fn(usize) -> u64, i: usize) -> usize {
    let ki = key(i);
    row.len() - row.partition_point(|&j| key(j as usize) < ki)
}

/// Fills `lower_pair` for row `i` (its lower entries), given `start` and `pair_start` of
/// lists sorted by key. Each lower neighbour `j` owns the pair; its number is found by a
/// binary search for `i` in `j`'s row. Rows are independent, so a host can run this in
/// parallel. Errors with [`NeighborError::BadStorage`] if `i` is not in `j`'s row.
pub fn lower_pairs_of(
    i: usize,
    start: &[u32],
    index: &[u32],
    pair_start: &[u32],
    key: impl Fn(usize) -> u64,
    out: &mut [u32],
) -> Result<(), NeighborError> {
    let (s, e) = (start[i] as usize, start[i + 1] as usize);
    let owned = (pair_start[i + 1] - pair_start[i]) as usize;
    let lower = (e - s) - owned;
    if out.len() != lower {
        return Err(NeighborError::BadStorage);
    }
    let ki = key(i);
    for (slot, &j) in out.iter_mut().zip(&index[s..s + lower]) {
        let j = j as usize;
        let (sj, ej) = (start[j] as usize, start[j + 1] as usize);
        let row = &index[sj..ej];
        let at = row.partition_point(|&k| key(k as usize) < ki);
        if at >= row.len() || row[at] as usize != i {
            return Err(NeighborError::BadStorage);
        }
        let owned_j = (pair_start[j + 1] - pair_start[j]) as usize;
        let lower_j = row.len() - owned_j;
        if at < lower_j {
            return Err(NeighborError::BadStorage);
        }
        *slot = pair_start[j] + (at - lower_j) as u32;
    }
    Ok(())
}

/// Neighbour lists over caller-provided storage, filled by [`build_naive`].
#[derive(Debug)]
pub struct NeighborList<'a> {
    /// Per-particle capacity (a larger row is an error).
    pub capacity: usize,
    /// Row offsets (`n + 1`).
    pub start: &'a mut [u32],
    /// Neighbour indices (total capacity).
    pub index: &'a mut [u32],
    /// Pair offsets (`n + 1`).
    pub pair_start: &'a mut [u32],
    /// Pair numbers of the lower entries (total capacity).
    pub lower_pair: &'a mut [u32],
}

impl<'a> NeighborList<'a> {
    /// Words of storage [`NeighborList::new`] needs for `n` particles with at most
    /// `capacity` neighbours each.
    pub const fn storage_len(n: usize, capacity: usize) -> usize {
        2 * (n + 1) + 2 * n * capacity
    }
    /// Carves the lists for `n` particles out of `storage` (at least
    /// [`NeighborList::storage_len`] words).
    pub fn new(capacity: usize, n: usize, storage: &'a mut [u32]) -> Result<Self, NeighborError> {
        if storage.len() < Self::storage_len(n, capacity) {
            return Err(NeighborError::BadStorage);
        }
        let (start, rest) = storage.split_at_mut(n + 1);
        let (pair_start, rest) = rest.split_at_mut(n + 1);
        let (index, rest) = rest.split_at_mut(n * capacity);
        let lower_pair = &mut rest[..n * capacity];
        Ok(NeighborList {
            capacity,
            start,
            index,
            pair_start,
            lower_pair,
        })
    }
    /// Number of particles.
    #[inline]
    pub fn len(&self) -> usize {
        self.start.len() - 1
    }
    /// True if there are no particles.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }
    /// The neighbours of `i`.
    pub fn of(&self, i: usize) -> &[u32] {
        &self.index[self.start[i] as usize..self.start[i + 1] as usize]
    }
    /// Read-only view.
    pub fn view(&self) -> Neighbors<'_> {
        let n = self.len();
        let total = self.start[n] as usize;
        let pairs = self.pair_start[n] as usize;
        Neighbors {
            start: self.start,
            index: &self.index[..total],
            pair_start: self.pair_start,
            lower_pair: &self.lower_pair[..total - pairs],
        }
    }
}

/// O(N²) neighbour search: `j` is a neighbour of `i` when `|x_i - x_j| < radius(i, j)`
/// (minimum image on periodic axes; `radius` must be symmetric). No allocation; the key
/// of the canonical order is the particle index.
pub fn build_naive<const D: usize>(
    x: &[Vector<D>],
    periodic: &Periodic<D>,
    radius: impl Fn(usize, usize) -> Real,
    list: &mut NeighborList<'_>,
) -> Result<(), NeighborError> {
    let n = x.len();
    if list.len() != n {
        return Err(NeighborError::BadStorage);
    }
    let cap = list.capacity;
    let mut cursor = 0usize;
    list.start[0] = 0;
    for i in 0..n {
        let mut found = 0usize;
        for j in 0..n {
            if i == j {
                continue;
            }
            let d = periodic.min_image(x[i] - x[j]);
            let r = radius(i, j);
            if d.norm_squared() < r * r {
                if found < cap && cursor < list.index.len() {
                    list.index[cursor] = j as u32;
                    cursor += 1;
                }
                found += 1;
            }
        }
        if found > cap || cursor - list.start[i] as usize != found {
            return Err(NeighborError::Overflow {
                particle: i,
                found,
                capacity: cap,
            });
        }
        list.start[i + 1] = cursor as u32;
    }
    number_pairs(
        list.start,
        list.index,
        list.pair_start,
        list.lower_pair,
        |i| i as u64,
    )
}

/// Numbers the pairs of lists whose rows are sorted by `key`: fills `pair_start` and the
/// lower entries' pair numbers (serially; the host does the same per row in parallel with
/// [`owned_count`] and [`lower_pairs_of`]).
pub fn number_pairs(
    start: &[u32],
    index: &[u32],
    pair_start: &mut [u32],
    lower_pair: &mut [u32],
    key: impl Fn(usize) -> u64 + Copy,
) -> Result<(), NeighborError> {
    let n = start.len() - 1;
    if pair_start.len() != n + 1 {
        return Err(NeighborError::BadStorage);
    }
    pair_start[0] = 0;
    for i in 0..n {
        let row = &index[start[i] as usize..start[i + 1] as usize];
        pair_start[i + 1] = pair_start[i] + owned_count(row, key, i) as u32;
    }
    let total = start[n] as usize;
    if total < pair_start[n] as usize || lower_pair.len() < total - pair_start[n] as usize {
        return Err(NeighborError::BadStorage);
    }
    for i in 0..n {
        let lo = (start[i] - pair_start[i]) as usize;
        let hi = (start[i + 1] - pair_start[i + 1]) as usize;
        lower_pairs_of(i, start, index, pair_start, key, &mut lower_pair[lo..hi])?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn naive_search_finds_pairs_and_reports_overflow() {
        let x: [Vector<1>; 5] = core::array::from_fn(|i| Vector::<1>::new(i as Real));
        let mut st = [0u32; NeighborList::storage_len(5, 2)];
        let mut list = NeighborList::new(2, 5, &mut st).unwrap();
        build_naive(&x, &Periodic::none(), |_, _| 1.5, &mut list).unwrap();
        assert_eq!(list.of(0), &[1]);
        assert_eq!(list.of(2), &[1, 3]);
        let err = build_naive(&x, &Periodic::none(), |_, _| 2.5, &mut list).unwrap_err();
        assert_eq!(
            err,
            NeighborError::Overflow {
                particle: 1,
                found: 3,
                capacity: 2
            }
        );
    }

    #[test]
    #[allow(clippy::needless_range_loop)]
    fn every_pair_is_numbered_once_and_both_sides_find_it() {
        // a 1D row with 2 neighbours on each side: 4 + 3 + 2 + 1 ... pairs
        let x: [Vector<1>; 6] = core::array::from_fn(|i| Vector::<1>::new(i as Real));
        let mut st = [0u32; NeighborList::storage_len(6, 4)];
        let mut list = NeighborList::new(4, 6, &mut st).unwrap();
        build_naive(&x, &Periodic::none(), |_, _| 2.5, &mut list).unwrap();
        let v = list.view();
        assert_eq!(v.pairs(), 2 * v.unordered_pairs());
        assert_eq!(v.unordered_pairs(), 9);
        let mut seen = [[None::<usize>; 6]; 6];
        for i in 0..6 {
            let mut order = [0usize; 4];
            let mut k = 0;
            v.for_each(i, |e| {
                order[k] = e.j;
                k += 1;
                assert_eq!(e.owner, e.j > i);
                seen[i][e.j] = Some(e.pair);
            });
            // canonical order: ascending key (index)
            assert!(order[..k].windows(2).all(|w| w[0] < w[1]));
            assert_eq!(
                v.owned(i).len(),
                order[..k].iter().filter(|&&j| j > i).count()
            );
        }
        let mut count = [0; 9];
        for i in 0..6 {
            for j in 0..6 {
                assert_eq!(seen[i][j], seen[j][i]);
                if let (Some(p), true) = (seen[i][j], i < j) {
                    count[p] += 1;
                }
            }
        }
        assert!(count.iter().all(|&c| c == 1), "{count:?}");
    }

    #[test]
    fn asymmetric_lists_are_refused() {
        // j lists i but i does not list j
        let start = [0u32, 0, 1];
        let index = [0u32];
        let mut ps = [0u32; 3];
        let mut lp = [0u32; 1];
        assert_eq!(
            number_pairs(&start, &index, &mut ps, &mut lp, |i| i as u64),
            Err(NeighborError::BadStorage)
        );
    }

    #[test]
    fn periodic_minimum_image_and_wrap() {
        let p = Periodic::<2> {
            lo: Vector::<2>::new(0.0, 0.0),
            len: Vector::<2>::new(1.0, 10.0),
            axes: [true, false],
        };
        let d = p.min_image(Vector::<2>::new(0.9, 6.0));
        assert!((d[0] + 0.1).abs() < 1e-15 && d[1] == 6.0);
        let w = p.wrap(Vector::<2>::new(-0.25, 3.0));
        assert!((w[0] - 0.75).abs() < 1e-15);
    }
}
