//! Fixed-capacity neighbour lists and the geometry of pairs (periodic images).
//!
//! Lists are stored flat in caller-provided slices: particle `i` owns
//! `index[i*capacity .. i*capacity + count[i]]`, sorted by neighbour index so that sums
//! over neighbours are evaluated in one fixed order (bitwise reproducible results). A
//! particle with more candidates than `capacity` is an error ([`NeighborError::Overflow`]),
//! never a silent truncation. The host fills the same structure with a parallel cell list;
//! [`build_naive`] is the O(N²) reference that needs no allocation.

use crate::math::{real, Real, Vector};

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
            if self.axes[a] {
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
        /// The fixed per-particle capacity.
        capacity: usize,
    },
    /// The slices handed in have inconsistent lengths.
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

/// Flat fixed-capacity neighbour lists over caller-provided storage.
#[derive(Debug)]
pub struct NeighborList<'a> {
    /// Per-particle capacity.
    pub capacity: usize,
    /// `n * capacity` neighbour indices.
    pub index: &'a mut [u32],
    /// `n` counts.
    pub count: &'a mut [u32],
}

impl<'a> NeighborList<'a> {
    /// Wraps storage for `count.len()` particles; `index` must hold `count.len() * capacity`.
    pub fn new(
        capacity: usize,
        index: &'a mut [u32],
        count: &'a mut [u32],
    ) -> Result<Self, NeighborError> {
        if index.len() != count.len() * capacity {
            return Err(NeighborError::BadStorage);
        }
        Ok(NeighborList {
            capacity,
            index,
            count,
        })
    }
    /// Number of particles.
    #[inline]
    pub fn len(&self) -> usize {
        self.count.len()
    }
    /// True if there are no particles.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.count.is_empty()
    }
    /// The neighbours of `i` (sorted, excluding `i`).
    #[inline]
    pub fn of(&self, i: usize) -> &[u32] {
        let s = i * self.capacity;
        &self.index[s..s + self.count[i] as usize]
    }
    /// Read-only view.
    pub fn view(&self) -> Neighbors<'_> {
        Neighbors {
            capacity: self.capacity,
            index: self.index,
            count: self.count,
        }
    }
}

/// Read-only view of neighbour lists, as the pair loops consume them.
#[derive(Clone, Copy, Debug)]
pub struct Neighbors<'a> {
    /// Per-particle capacity.
    pub capacity: usize,
    /// `n * capacity` neighbour indices.
    pub index: &'a [u32],
    /// `n` counts.
    pub count: &'a [u32],
}

impl<'a> Neighbors<'a> {
    /// The neighbours of `i` (sorted, excluding `i`).
    #[inline]
    pub fn of(&self, i: usize) -> &'a [u32] {
        let s = i * self.capacity;
        &self.index[s..s + self.count[i] as usize]
    }
    /// Number of particles.
    #[inline]
    pub fn len(&self) -> usize {
        self.count.len()
    }
    /// True if there are no particles.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.count.is_empty()
    }
    /// Total number of (directed) pairs.
    pub fn pairs(&self) -> usize {
        self.count.iter().map(|&c| c as usize).sum()
    }
}

/// O(N²) neighbour search: `j` is a neighbour of `i` when `|x_i - x_j| < radius(i, j)`
/// (minimum image on periodic axes). No allocation; lists come out sorted.
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
    for i in 0..n {
        let mut c = 0usize;
        let mut found = 0usize;
        for j in 0..n {
            if i == j {
                continue;
            }
            let d = periodic.min_image(x[i] - x[j]);
            let r = radius(i, j);
            if d.norm_squared() < r * r {
                if c < cap {
                    list.index[i * cap + c] = j as u32;
                    c += 1;
                }
                found += 1;
            }
        }
        if found > cap {
            return Err(NeighborError::Overflow {
                particle: i,
                found,
                capacity: cap,
            });
        }
        list.count[i] = c as u32;
    }
    Ok(())
}

/// Smallest pair distance divided by `scale(i, j)` over all listed pairs, with the pair;
/// used to reject overlapping particles.
pub fn closest_pair<const D: usize>(
    x: &[Vector<D>],
    periodic: &Periodic<D>,
    nbrs: &Neighbors<'_>,
) -> Option<(usize, usize, Real)> {
    let mut best: Option<(usize, usize, Real)> = None;
    for i in 0..nbrs.len() {
        for &j in nbrs.of(i) {
            let j = j as usize;
            if j <= i {
                continue;
            }
            let r = real::sqrt(periodic.min_image(x[i] - x[j]).norm_squared());
            if best.is_none_or(|b| r < b.2) {
                best = Some((i, j, r));
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn naive_search_finds_pairs_and_reports_overflow() {
        let x: [Vector<1>; 5] = core::array::from_fn(|i| Vector::<1>::new(i as Real));
        let mut idx = [0u32; 10];
        let mut cnt = [0u32; 5];
        let mut list = NeighborList::new(2, &mut idx, &mut cnt).unwrap();
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
