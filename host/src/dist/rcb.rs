//! Recursive coordinate bisection by particle count (Berger & Bokhari 1987), computed in
//! parallel: a group of `k` ranks is cut along the longest side of its particles'
//! bounding box at the coordinate that leaves `floor(k/2)/k` of its particles on the low
//! side, found by bisection on the coordinate with one all-reduce of the counts of every
//! group per iteration. On a lattice whole rows share a coordinate, so a cut balances to
//! within one row. The cuts tile space: every position belongs to exactly one rank.

use gsph_core::math::Vector;
use gsph_core::neighbors::Periodic;

/// Bisection iterations per cut (the coordinate interval shrinks by 2^-60).
const ITERATIONS: usize = 60;

#[derive(Clone, Copy, Debug)]
enum Node {
    Leaf(usize),
    Cut {
        axis: usize,
        at: f64,
        low: usize,
        high: usize,
    },
}

/// The sub-domains: a tree of axis-aligned cuts, one leaf per rank.
#[derive(Clone, Debug)]
pub struct Rcb<const D: usize> {
    nodes: Vec<Node>,
    /// The box of each rank (infinite towards the outside).
    pub boxes: Vec<([f64; D], [f64; D])>,
}

struct Group {
    r0: usize,
    r1: usize,
    node: usize,
}

impl<const D: usize> Rcb<D> {
    /// Bisects the owned particles `x` of every rank into `size` sub-domains (collective).
    pub fn build(x: &[Vector<D>], size: usize) -> Rcb<D> {
        let mut nodes = vec![Node::Leaf(0)];
        let mut groups = vec![Group {
            r0: 0,
            r1: size,
            node: 0,
        }];
        let mut member = vec![0usize; x.len()];
        while groups.iter().any(|g| g.r1 - g.r0 > 1) {
            let ng = groups.len();
            // bounding boxes and counts of every group: min of (x, -x) and sum of counts
            let mut ext = vec![f64::INFINITY; ng * 2 * D];
            let mut count = vec![0u64; ng];
            for (i, xi) in x.iter().enumerate() {
                let g = member[i];
                count[g] += 1;
                for a in 0..D {
                    ext[g * 2 * D + a] = ext[g * 2 * D + a].min(xi[a]);
                    ext[g * 2 * D + D + a] = ext[g * 2 * D + D + a].min(-xi[a]);
                }
            }
            let ext = super::all_min_vec(&ext);
            let count = super::all_sum_vec(&count);
            let mut axis = vec![0usize; ng];
            let mut lo = vec![0.0f64; ng];
            let mut hi = vec![0.0f64; ng];
            let mut target = vec![0u64; ng];
            for (g, grp) in groups.iter().enumerate() {
                let k = (grp.r1 - grp.r0) as u64;
                let span = |a: usize| -ext[g * 2 * D + D + a] - ext[g * 2 * D + a];
                let best = (0..D)
                    .max_by(|&a, &b| span(a).total_cmp(&span(b)))
                    .unwrap_or(0);
                axis[g] = best;
                lo[g] = ext[g * 2 * D + best];
                hi[g] = -ext[g * 2 * D + D + best];
                if !(lo[g].is_finite() && hi[g].is_finite()) {
                    (lo[g], hi[g]) = (0.0, 0.0);
                }
                target[g] = count[g] * (k / 2) / k.max(1);
            }
            let mut best_at: Vec<f64> = hi.clone();
            let mut best_err: Vec<u64> = vec![u64::MAX; ng];
            for _ in 0..ITERATIONS {
                let mid: Vec<f64> = (0..ng).map(|g| 0.5 * (lo[g] + hi[g])).collect();
                let mut below = vec![0u64; ng];
                for (i, xi) in x.iter().enumerate() {
                    let g = member[i];
                    below[g] += (xi[axis[g]] < mid[g]) as u64;
                }
                let below = super::all_sum_vec(&below);
                for g in 0..ng {
                    let err = below[g].abs_diff(target[g]);
                    if err < best_err[g] {
                        (best_err[g], best_at[g]) = (err, mid[g]);
                    }
                    if below[g] < target[g] {
                        lo[g] = mid[g];
                    } else {
                        hi[g] = mid[g];
                    }
                }
            }
            let mut next = Vec::new();
            let mut remap = vec![0usize; ng];
            for (g, grp) in groups.iter().enumerate() {
                if grp.r1 - grp.r0 <= 1 {
                    remap[g] = next.len();
                    next.push(Group { ..*grp });
                    continue;
                }
                let mid = grp.r0 + (grp.r1 - grp.r0) / 2;
                let (low, high) = (nodes.len(), nodes.len() + 1);
                nodes.push(Node::Leaf(grp.r0));
                nodes.push(Node::Leaf(mid));
                nodes[grp.node] = Node::Cut {
                    axis: axis[g],
                    at: best_at[g],
                    low,
                    high,
                };
                remap[g] = next.len();
                next.push(Group {
                    r0: grp.r0,
                    r1: mid,
                    node: low,
                });
                next.push(Group {
                    r0: mid,
                    r1: grp.r1,
                    node: high,
                });
            }
            for (i, xi) in x.iter().enumerate() {
                let g = member[i];
                member[i] = remap[g];
                if let Node::Cut { axis, at, .. } = nodes[groups[g].node] {
                    if xi[axis] >= at {
                        member[i] += 1;
                    }
                }
            }
            groups = next;
        }
        let mut rcb = Rcb {
            nodes,
            boxes: vec![([f64::NEG_INFINITY; D], [f64::INFINITY; D]); size],
        };
        rcb.fill_boxes(0, [f64::NEG_INFINITY; D], [f64::INFINITY; D]);
        rcb
    }

    fn fill_boxes(&mut self, node: usize, lo: [f64; D], hi: [f64; D]) {
        match self.nodes[node] {
            Node::Leaf(r) => self.boxes[r] = (lo, hi),
            Node::Cut {
                axis,
                at,
                low,
                high,
            } => {
                let (mut h, mut l) = (hi, lo);
                h[axis] = at;
                l[axis] = at;
                self.fill_boxes(low, lo, h);
                self.fill_boxes(high, l, hi);
            }
        }
    }

    /// The rank whose sub-domain holds `x`.
    pub fn rank_of(&self, x: &Vector<D>) -> usize {
        let mut n = 0;
        loop {
            match self.nodes[n] {
                Node::Leaf(r) => return r,
                Node::Cut {
                    axis,
                    at,
                    low,
                    high,
                } => n = if x[axis] < at { low } else { high },
            }
        }
    }

    /// True if `x` (or, along periodic axes, one of its images) lies within `reach` of the
    /// sub-domain of rank `r`.
    pub fn near(&self, r: usize, x: &Vector<D>, reach: f64, periodic: &Periodic<D>) -> bool {
        let (lo, hi) = &self.boxes[r];
        let gap = |c: f64, a: usize| {
            if c < lo[a] {
                lo[a] - c
            } else if c > hi[a] {
                c - hi[a]
            } else {
                0.0
            }
        };
        let mut d2 = 0.0;
        for a in 0..D {
            let mut d = gap(x[a], a);
            if periodic.axes[a] {
                let l = periodic.len[a];
                d = d.min(gap(x[a] - l, a)).min(gap(x[a] + l, a));
            }
            d2 += d * d;
        }
        d2 < reach * reach
    }
}
