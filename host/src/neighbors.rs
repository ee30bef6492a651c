//! Parallel cell-list neighbour search filling the core's compressed-row lists, and the
//! Morton order in which particles are renumbered at rebuilds.
//!
//! Pair (i, j) is listed when `|x_i - x_j| < support * (h_i + h_j)/2 * (1 + skin)`
//! (minimum image on periodic axes). Each row is sorted by the particles' keys (their
//! global ids), so the lists, and every sum over them, do not depend on how particles are
//! numbered in memory, on the traversal order or on the number of threads. Tested against
//! the O(N²) search of the core with particles placed at 0.9999, 1 and 1.0001 times the
//! radius.

use crate::exec::Rayon;
use gsph_core::exec::{Executor, Rows, Split};
use gsph_core::kernel::Kernel;
use gsph_core::math::Vector;
use gsph_core::neighbors::{lower_pairs_of, owned_count, NeighborError, Neighbors, Periodic};
use rayon::prelude::*;

/// Neighbour lists in compressed rows with their pair numbering (see
/// [`gsph_core::neighbors`]), in growable storage.
#[derive(Clone, Debug, Default)]
pub struct Lists {
    /// Row offsets (`n + 1`).
    pub start: Vec<u32>,
    /// Neighbour indices, rows sorted by key.
    pub index: Vec<u32>,
    /// Offsets of the pairs each particle owns (`n + 1`).
    pub pair_start: Vec<u32>,
    /// Pair numbers of the lower entries.
    pub lower_pair: Vec<u32>,
}

impl Lists {
    /// The view the core's passes read.
    pub fn view(&self) -> Neighbors<'_> {
        Neighbors {
            start: &self.start,
            index: &self.index,
            pair_start: &self.pair_start,
            lower_pair: &self.lower_pair,
        }
    }
    /// Empty lists for `n` particles (no pairs).
    pub fn empty(n: usize) -> Self {
        Lists {
            start: vec![0; n + 1],
            index: Vec::new(),
            pair_start: vec![0; n + 1],
            lower_pair: Vec::new(),
        }
    }
    /// Bytes held, by array: the row starts, the neighbour indices, the first pair of each
    /// row and the pair numbers of the lower entries.
    pub fn memory(&self) -> [(&'static str, usize); 4] {
        use std::mem::size_of_val;
        [
            ("lists.start", size_of_val(&self.start[..])),
            ("lists.index", size_of_val(&self.index[..])),
            ("lists.pair_start", size_of_val(&self.pair_start[..])),
            ("lists.lower_pair", size_of_val(&self.lower_pair[..])),
        ]
    }
    /// Number of unordered pairs.
    pub fn unordered_pairs(&self) -> usize {
        self.pair_start.last().map_or(0, |&p| p as usize)
    }
}

/// A cell grid over the particles (counting sort by cell).
pub(crate) struct Grid<const D: usize> {
    lo: [f64; D],
    size: [f64; D],
    ncell: [usize; D],
    /// Particles sorted by cell.
    pub(crate) sorted: Vec<u32>,
    /// Their positions, in the same order (a cell's candidates are read in one sweep).
    pub(crate) xs: Vec<Vector<D>>,
    /// Cell offsets into `sorted`.
    start: Vec<u32>,
    /// Neighbour cell offsets (-1, 0, 1 along each axis).
    offsets: Vec<[i64; D]>,
    periodic: Periodic<D>,
}

impl<const D: usize> Grid<D> {
    /// Cells at least `cell` wide; at most about 4 cells per particle in all (sparse or
    /// degenerate layouts get coarser cells instead of a huge grid).
    pub(crate) fn new(x: &[Vector<D>], cell: f64, periodic: &Periodic<D>) -> Self {
        let n = x.len();
        let mut lo = [0.0; D];
        let mut extent = [0.0; D];
        for a in 0..D {
            if periodic.axes[a] {
                lo[a] = periodic.lo[a];
                extent[a] = periodic.len[a];
            } else {
                let (mn, mx) = x
                    .iter()
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(mn, mx), p| {
                        (mn.min(p[a]), mx.max(p[a]))
                    });
                lo[a] = mn;
                extent[a] = mx - mn;
            }
        }
        let max_cells = (4 * n).max(1024) as f64;
        let mut width = cell.max(f64::MIN_POSITIVE);
        let cells_along = |w: f64, a: usize| -> f64 {
            let k = (extent[a] / w).floor();
            if k.is_finite() && k >= 1.0 {
                k
            } else {
                1.0
            }
        };
        while (0..D).map(|a| cells_along(width, a)).product::<f64>() > max_cells {
            width *= 2.0;
        }
        let mut ncell = [1usize; D];
        let mut size = [width; D];
        for a in 0..D {
            ncell[a] = cells_along(width, a) as usize;
            if periodic.axes[a] {
                // periodic axes: cells tile the box exactly
                size[a] = extent[a] / ncell[a] as f64;
            }
        }
        let mut g = Grid {
            lo,
            size,
            ncell,
            sorted: Vec::new(),
            xs: Vec::new(),
            start: Vec::new(),
            offsets: Vec::new(),
            periodic: *periodic,
        };
        let total: usize = ncell.iter().product();
        let cells: Vec<usize> = x.par_iter().map(|p| g.flat(&g.cell_of(p))).collect();
        let mut start = vec![0u32; total + 1];
        for &c in &cells {
            start[c + 1] += 1;
        }
        for k in 0..total {
            start[k + 1] += start[k];
        }
        let mut fill = start.clone();
        let mut sorted = vec![0u32; n];
        for (i, &c) in cells.iter().enumerate() {
            sorted[fill[c] as usize] = i as u32;
            fill[c] += 1;
        }
        let mut offsets = vec![[0i64; D]];
        for a in 0..D {
            let mut next = Vec::new();
            for o in &offsets {
                for d in -1..=1 {
                    let mut q = *o;
                    q[a] = d;
                    next.push(q);
                }
            }
            offsets = next;
        }
        g.xs = sorted.iter().map(|&i| x[i as usize]).collect();
        g.sorted = sorted;
        g.start = start;
        g.offsets = offsets;
        g
    }

    fn cell_of(&self, p: &Vector<D>) -> [usize; D] {
        let mut c = [0usize; D];
        for a in 0..D {
            let k = ((p[a] - self.lo[a]) / self.size[a]).floor();
            c[a] = (k.max(0.0) as usize).min(self.ncell[a] - 1);
        }
        c
    }

    fn flat(&self, c: &[usize; D]) -> usize {
        let mut f = 0;
        for a in (0..D).rev() {
            f = f * self.ncell[a] + c[a];
        }
        f
    }

    /// Calls `f(k)` for every particle `sorted[k]` (at `xs[k]`) in the cells around `xi`
    /// (each cell once, also when a periodic axis has fewer than 3 cells).
    #[inline]
    pub(crate) fn for_candidates(&self, xi: &Vector<D>, mut f: impl FnMut(usize)) {
        let ci = self.cell_of(xi);
        let mut seen: [usize; 27] = [usize::MAX; 27];
        let mut nseen = 0;
        'cells: for o in &self.offsets {
            let mut cc = [0usize; D];
            for a in 0..D {
                let k = ci[a] as i64 + o[a];
                if self.periodic.axes[a] {
                    cc[a] = k.rem_euclid(self.ncell[a] as i64) as usize;
                } else if k < 0 || k >= self.ncell[a] as i64 {
                    continue 'cells;
                } else {
                    cc[a] = k as usize;
                }
            }
            let fl = self.flat(&cc);
            if seen[..nseen].contains(&fl) {
                continue;
            }
            seen[nseen] = fl;
            nseen += 1;
            for k in self.start[fl] as usize..self.start[fl + 1] as usize {
                f(k);
            }
        }
    }
}

/// Builds the neighbour lists of `x` (smoothing lengths `h`, canonical order by `key`,
/// unique per particle) into `lists`. A particle with more than `capacity` neighbours is an
/// error naming the such particle of lowest key.
#[allow(clippy::too_many_arguments)]
pub fn build<const D: usize>(
    x: &[Vector<D>],
    h: &[f64],
    key: &[u32],
    support: f64,
    skin: f64,
    periodic: &Periodic<D>,
    capacity: usize,
    lists: &mut Lists,
) -> Result<(), NeighborError> {
    let n = x.len();
    if h.len() != n || key.len() != n {
        return Err(NeighborError::BadStorage);
    }
    *lists = Lists::empty(n);
    if n == 0 {
        return Ok(());
    }
    let factor = support * (1.0 + skin);
    let hmax = h.iter().cloned().fold(0.0, f64::max);
    let grid = Grid::new(x, factor * hmax, periodic);
    // the smoothing lengths in the grid's order, beside its positions
    let hs: Vec<f64> = grid.sorted.iter().map(|&j| h[j as usize]).collect();
    // one sweep over the candidates: each run of particles collects its rows (sorted by
    // key), keeping at most capacity + 1 entries of a row (an overflow is an error: its
    // count is all the message needs, and the memory stays bounded whatever the input)
    const RUN: usize = 256;
    let runs: Vec<(Vec<u32>, Vec<u32>)> = (0..n.div_ceil(RUN))
        .into_par_iter()
        .map(|run| {
            let (a, b) = (run * RUN, ((run + 1) * RUN).min(n));
            let mut counts = Vec::with_capacity(b - a);
            let mut rows: Vec<u32> = Vec::with_capacity((b - a) * capacity.min(64));
            for i in a..b {
                let (xi, hi) = (x[i], h[i]);
                let first = rows.len();
                let mut c = 0u32;
                grid.for_candidates(&xi, |k| {
                    let d = periodic.min_image(xi - grid.xs[k]);
                    let reach = factor * 0.5 * (hi + hs[k]);
                    let j = grid.sorted[k];
                    if j as usize != i && d.norm_squared() < reach * reach {
                        c += 1;
                        if c as usize <= capacity {
                            rows.push(j);
                        }
                    }
                });
                rows[first..].sort_unstable_by_key(|&j| key[j as usize]);
                counts.push(c);
            }
            (counts, rows)
        })
        .collect();
    let counts: Vec<u32> = runs.iter().flat_map(|(c, _)| c.iter().copied()).collect();
    // the overflowing particle of lowest key (the message does not depend on the order)
    if let Some(i) = (0..n)
        .filter(|&i| counts[i] as usize > capacity)
        .min_by_key(|&i| key[i])
    {
        return Err(NeighborError::Overflow {
            particle: i,
            found: counts[i] as usize,
            capacity,
        });
    }
    let mut total = 0u64;
    for (i, &c) in counts.iter().enumerate() {
        lists.start[i] = total as u32;
        total += c as u64;
    }
    if total > u32::MAX as u64 {
        return Err(NeighborError::BadStorage);
    }
    lists.start[n] = total as u32;
    let mut index = Vec::with_capacity(total as usize);
    for (_, rows) in &runs {
        index.extend_from_slice(rows);
    }
    drop(runs);
    lists.index = index;
    let exec = Rayon::default();
    // pair numbering: the owner of a pair is its particle of lower key
    let k = |i: usize| key[i] as u64;
    let owned: Vec<u32> = (0..n)
        .into_par_iter()
        .map(|i| {
            let row = &lists.index[lists.start[i] as usize..lists.start[i + 1] as usize];
            owned_count(row, k, i) as u32
        })
        .collect();
    for (i, &o) in owned.iter().enumerate() {
        lists.pair_start[i + 1] = lists.pair_start[i] + o;
    }
    let lstart: Vec<u32> = (0..=n)
        .map(|i| lists.start[i] - lists.pair_start[i])
        .collect();
    let mut lower_pair = vec![0u32; lstart[n] as usize];
    let (start, index, pair_start) = (&lists.start, &lists.index, &lists.pair_start);
    let bad = std::sync::atomic::AtomicBool::new(false);
    exec.run(
        Rows {
            start: &lstart,
            data: &mut lower_pair,
        },
        |off, mut rows: Rows<'_, u32>| {
            for k2 in 0..rows.len() {
                let i = off + k2;
                if lower_pairs_of(i, start, index, pair_start, k, rows.of(k2)).is_err() {
                    bad.store(true, std::sync::atomic::Ordering::Relaxed);
                }
            }
        },
    );
    if bad.into_inner() {
        return Err(NeighborError::BadStorage);
    }
    lists.lower_pair = lower_pair;
    Ok(())
}

/// The distance from each particle to its nearest neighbour, or infinity if none lies
/// within `reach` (no periodic images).
pub fn nearest_distances<const D: usize>(x: &[Vector<D>], reach: f64) -> Vec<f64> {
    if x.is_empty() {
        return Vec::new();
    }
    let grid = Grid::new(x, reach, &Periodic::none());
    (0..x.len())
        .into_par_iter()
        .map(|i| {
            let mut best = f64::INFINITY;
            grid.for_candidates(&x[i], |k| {
                if grid.sorted[k] as usize != i {
                    let d = (x[i] - grid.xs[k]).norm();
                    if d < reach {
                        best = best.min(d);
                    }
                }
            });
            best
        })
        .collect()
}

/// A permutation that puts particles in Morton (Z-curve) order of cells `cell` wide, ties
/// broken by key: `order[k]` is the particle that goes to place `k`. Neighbours then sit
/// close together in memory, so the pair passes gather their state from a few cache lines.
pub fn morton_order<const D: usize>(
    x: &[Vector<D>],
    key: &[u32],
    cell: f64,
    periodic: &Periodic<D>,
) -> Vec<u32> {
    let n = x.len();
    if n == 0 {
        return Vec::new();
    }
    let mut lo = [f64::INFINITY; D];
    for p in x {
        for a in 0..D {
            lo[a] = lo[a].min(p[a]);
        }
    }
    for (a, l) in lo.iter_mut().enumerate() {
        if periodic.axes[a] {
            *l = periodic.lo[a];
        }
    }
    let bits = 63 / D as u32;
    let limit = ((1u64 << bits) - 1) as f64;
    let cell = cell.max(f64::MIN_POSITIVE);
    let morton = |p: &Vector<D>| -> u64 {
        let mut code = 0u64;
        let mut c = [0u64; D];
        for a in 0..D {
            let k = ((p[a] - lo[a]) / cell).floor();
            c[a] = if k.is_finite() {
                k.clamp(0.0, limit) as u64
            } else {
                0
            };
        }
        for b in (0..bits).rev() {
            for ca in c.iter() {
                code = (code << 1) | ((ca >> b) & 1);
            }
        }
        code
    };
    let mut order: Vec<(u64, u32, u32)> = x
        .par_iter()
        .enumerate()
        .map(|(i, p)| (morton(p), key[i], i as u32))
        .collect();
    order.par_sort_unstable();
    order.into_iter().map(|(_, _, i)| i).collect()
}

/// Default neighbour capacity for a dimension and kernel.
pub fn default_capacity(dim: usize, kernel: Kernel, h_factor: f64) -> usize {
    let r = kernel.support() * h_factor * 1.5; // room for compression and skin
    match dim {
        1 => (2.0 * r).ceil() as usize + 4,
        2 => (std::f64::consts::PI * r * r).ceil() as usize + 8,
        _ => (4.0 / 3.0 * std::f64::consts::PI * r * r * r).ceil() as usize + 16,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use gsph_core::neighbors::{build_naive, NeighborList};

    #[test]
    fn nearest_distances_on_a_row() {
        let x: Vec<Vector<3>> = [0.0, 1.0, 1.5, 4.0]
            .iter()
            .map(|&a| Vector::<3>::new(a, 0.0, 0.0))
            .collect();
        let d = nearest_distances(&x, 2.0);
        assert_eq!(d, vec![1.0, 0.5, 0.5, f64::INFINITY]);
    }

    #[test]
    fn morton_order_is_a_permutation_that_keeps_cells_together() {
        let x: Vec<Vector<2>> = (0..64)
            .map(|k| Vector::<2>::new((k % 8) as f64, (k / 8) as f64))
            .collect();
        let key: Vec<u32> = (0..64).collect();
        let o = morton_order(&x, &key, 2.0, &Periodic::none());
        let mut s = o.clone();
        s.sort_unstable();
        assert_eq!(s, key);
        // the first four are the 2 x 2 block at the origin (one cell), in key order
        assert_eq!(&o[..4], &[0, 1, 8, 9]);
    }

    /// The cell-list build against the naive search: the same rows in the same order
    /// (with keys equal to indices), the same pair numbering; and with reversed keys,
    /// every row in descending index order and the pairs owned by the other side.
    fn compare<const D: usize>(x: &[Vector<D>], h: &[f64], periodic: &Periodic<D>, cap: usize) {
        let n = x.len();
        let key: Vec<u32> = (0..n as u32).collect();
        let mut lists = Lists::default();
        build(x, h, &key, 2.0, 0.0, periodic, cap, &mut lists).unwrap();
        let mut st = vec![0u32; NeighborList::storage_len(n, cap)];
        let mut l = NeighborList::new(cap, n, &mut st).unwrap();
        build_naive(x, periodic, |i, j| 2.0 * 0.5 * (h[i] + h[j]), &mut l).unwrap();
        let (a, b) = (lists.view(), l.view());
        for i in 0..n {
            assert_eq!(a.of(i), b.of(i), "particle {i}");
        }
        assert_eq!(a.pair_start, b.pair_start);
        assert_eq!(a.lower_pair, b.lower_pair);
        let rev: Vec<u32> = (0..n as u32).rev().collect();
        build(x, h, &rev, 2.0, 0.0, periodic, cap, &mut lists).unwrap();
        let c = lists.view();
        for i in 0..n {
            let mut row = b.of(i).to_vec();
            row.reverse();
            assert_eq!(c.of(i), &row[..], "particle {i}");
            assert!(c.owned(i).iter().all(|&j| (j as usize) < i));
        }
    }

    #[test]
    fn matches_naive_search_at_the_radius_boundary() {
        // pairs at 0.9999, 1 and 1.0001 times the radius 2h = 1
        let h = 0.5;
        let mut x = Vec::new();
        for (k, f) in [0.9999, 1.0, 1.0001].iter().enumerate() {
            let y = k as f64 * 10.0;
            x.push(Vector::<2>::new(0.0, y));
            x.push(Vector::<2>::new(*f, y));
        }
        compare(&x, &vec![h; x.len()], &Periodic::none(), 8);
    }

    #[test]
    fn matches_naive_search_on_random_points_and_periodic_boxes() {
        let mut s = 12345u64;
        let mut rnd = || {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let x3: Vec<Vector<3>> = (0..400)
            .map(|_| Vector::<3>::new(rnd(), rnd(), rnd()))
            .collect();
        let h3: Vec<f64> = (0..400).map(|_| 0.05 + 0.05 * rnd()).collect();
        compare(&x3, &h3, &Periodic::none(), 128);
        let p = Periodic::<2> {
            lo: Vector::<2>::new(0.0, 0.0),
            len: Vector::<2>::new(1.0, 0.3),
            axes: [false, true],
        };
        let x2: Vec<Vector<2>> = (0..300)
            .map(|_| Vector::<2>::new(rnd(), 0.3 * rnd()))
            .collect();
        let h2 = vec![0.06; 300];
        compare(&x2, &h2, &p, 128);
        let x1: Vec<Vector<1>> = (0..200).map(|_| Vector::<1>::new(rnd())).collect();
        compare(&x1, &vec![0.01; 200], &Periodic::none(), 32);
    }

    #[test]
    fn overflow_reports_the_lowest_particle() {
        let x: Vec<Vector<1>> = (0..10).map(|i| Vector::<1>::new(i as f64 * 0.1)).collect();
        let key: Vec<u32> = (0..10).collect();
        let err = build(
            &x,
            &[0.2; 10],
            &key,
            2.0,
            0.0,
            &Periodic::none(),
            2,
            &mut Lists::default(),
        )
        .unwrap_err();
        assert_eq!(
            err,
            NeighborError::Overflow {
                particle: 0,
                found: 3,
                capacity: 2
            }
        );
    }

    #[test]
    fn sparse_layouts_get_a_bounded_grid() {
        // two clusters 1e9 cell widths apart in 3D: the grid must stay small and exact
        let mut x: Vec<Vector<3>> = (0..20)
            .map(|k| Vector::<3>::new(k as f64 * 0.01, 0.0, 0.0))
            .collect();
        x.extend((0..20).map(|k| Vector::<3>::new(1e7 + k as f64 * 0.01, 1e7, -1e7)));
        compare(&x, &vec![0.01; x.len()], &Periodic::none(), 16);
    }
}
