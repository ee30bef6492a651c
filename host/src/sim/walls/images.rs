//! Making and removing the mirror ghosts at a neighbour-list rebuild, with the bound on
//! them: images of images only through perpendicular planes.
//!
//! Planes are taken in scene order; each mirrors every particle so far within the lists'
//! reach, ghosts of the earlier planes included, so a particle near two perpendicular
//! planes also gets the mirror of its mirror (the corner image a whole model would hold;
//! the reflections of perpendicular planes commute, so the set is complete with at most
//! `2^D - 1` images of a particle). Planes that are not perpendicular have no finite set
//! of images near their junction (parallel walls closer than the reach reflect each
//! other's mirrors without end: 50 such walls once took 24 GB for 100 particles), so a
//! mirror of one that falls within the reach of the other is refused, naming both walls.
//!
//! Ghost ids: every ghost is keyed by its chain of planes and the id of the particle it
//! images (its root), and numbered after the largest id present in the order of those
//! keys. The neighbour lists sort each row by id, so the order of an owned particle's
//! neighbours, and every sum over them, is the same in one process and on any number of
//! MPI ranks, whichever particles a rank holds.

use super::super::{Sim, SimError};
use super::Plane;

/// The planes a ghost was reflected through, in order (at most three: mutually
/// perpendicular normals), as plane index + 1 (0: unused).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord)]
struct Chain([u32; 3]);

impl Chain {
    fn planes(self) -> impl Iterator<Item = usize> {
        self.0
            .into_iter()
            .take_while(|&p| p > 0)
            .map(|p| p as usize - 1)
    }

    fn then(self, w: usize) -> Chain {
        let mut c = self;
        let k = self.planes().count();
        c.0[k] = w as u32 + 1;
        c
    }
}

/// Appends a copy of element `i` when `v` holds one element per particle so far (`n`).
fn dup<T: Copy>(v: &mut Vec<T>, i: usize, n: usize) {
    if v.len() == n && i < n {
        v.push(v[i]);
    }
}

/// The mirror image of particle `i` appended to a state field, by the field's kind in the
/// core's table (`gsph_core::particle_fields!`); a field not stored (empty) stays empty.
mod mirror {
    use super::super::Plane;
    use gsph_core::math::{Sym3, Vector};

    /// The mirror of particle `i` through `pl`, appended to `v` as `f` maps it.
    fn push<T: Copy>(v: &mut Vec<T>, i: usize, f: impl Fn(&T) -> T) {
        if let Some(y) = v.get(i).map(f) {
            v.push(y);
        }
    }
    /// A position: reflected through the plane.
    pub(super) fn point<const D: usize>(v: &mut Vec<Vector<D>>, (i, pl): (usize, &Plane<D>)) {
        push(v, i, |x| pl.reflect_point(x));
    }
    /// A vector: its normal component flipped.
    pub(super) fn vector<const D: usize>(v: &mut Vec<Vector<D>>, (i, pl): (usize, &Plane<D>)) {
        push(v, i, |x| pl.reflect(x));
    }
    /// A symmetric tensor: `R S R`.
    pub(super) fn tensor<const D: usize>(v: &mut Vec<Sym3>, (i, pl): (usize, &Plane<D>)) {
        push(v, i, |s| pl.reflect_sym(s));
    }
    /// A scalar (or an index): copied.
    pub(super) fn scalar<T: Copy, const D: usize>(v: &mut Vec<T>, (i, _): (usize, &Plane<D>)) {
        push(v, i, |&y| y);
    }
}

/// Cuts `v` to `n` elements when it holds more.
fn cut<T>(v: &mut Vec<T>, n: usize) {
    v.truncate(n);
}

/// `|n_a . n_b|` below this: perpendicular planes.
const PERPENDICULAR: f64 = 1e-9;

/// Why a mirror of plane `u` may not be mirrored again through plane `w` (the particle
/// it images is `id`).
fn interaction<const D: usize>(
    planes: &[Plane<D>],
    u: usize,
    w: usize,
    reach: f64,
    id: u32,
) -> String {
    let (a, b) = (&planes[u], &planes[w]);
    let cos = a.normal.dot(&b.normal).abs().min(1.0);
    if cos > 1.0 - PERPENDICULAR {
        let gap = (b.point - a.point).dot(&a.normal).abs();
        format!(
            "walls[{u}] and walls[{w}] are parallel and {gap:.3e} m apart, less than the kernel's reach {reach:.3e} m: the mirror of particle {id} in walls[{u}] lies within reach of walls[{w}], and mirrors of mirrors would never end; move them at least the reach apart or remove one"
        )
    } else {
        let angle = cos.acos().to_degrees();
        format!(
            "walls[{u}] and walls[{w}] meet at {angle:.1}°, not at a right angle, within the kernel's reach ({reach:.3e} m) of particle {id}: its mirror images would need more than one reflection; only perpendicular walls may meet within the reach of the particles"
        )
    }
}

impl<const D: usize> Sim<D> {
    /// Removes the mirror ghosts (every per-particle array back to the particles before
    /// them: the owned ones, and under MPI the other ranks' ghosts).
    pub(crate) fn drop_mirrors(&mut self) {
        if self.mirrors.is_empty() || self.mirrors.map.is_empty() {
            return;
        }
        let n = self.mirrors.first;
        cut(&mut self.ids, n);
        gsph_core::particle_fields!(each_state_field { self, cut, n });
        cut(&mut self.sums, n);
        cut(&mut self.grad, n);
        cut(&mut self.grad_stress, n);
        cut(&mut self.corr, n);
        cut(&mut self.hg_rec, n);
        cut(&mut self.av, n);
        cut(&mut self.art, n);
        cut(&mut self.aux, n);
        cut(&mut self.build_x, n);
        cut(&mut self.build_h, n);
        self.mirrors.map.clear();
        self.owned = self.owned.min(n);
    }

    /// Appends the mirror of every particle (owned, and under MPI the other ranks'
    /// ghosts) within the neighbour-list reach of a plane at the positions of the rebuild
    /// (`build_x`, `build_h`, set for every particle); refuses mirrors of mirrors through
    /// planes that are not perpendicular (module docs), before they are made.
    pub(crate) fn add_mirrors(&mut self) -> Result<(), SimError> {
        if self.mirrors.is_empty() {
            return Ok(());
        }
        let first = self.len();
        self.mirrors.first = first;
        let hmax = self.build_h[..self.owned]
            .iter()
            .cloned()
            .fold(0.0, f64::max);
        #[cfg(feature = "mpi")]
        let hmax = if self.dist.is_some() {
            crate::dist::all_max(hmax)
        } else {
            hmax
        };
        let reach = self.kernel.support() * (1.0 + self.skin) * hmax;
        self.mirrors.reach = reach;
        let base = self.ids.iter().max().map_or(0, |&m| m + 1);
        let mut chains: Vec<Chain> = Vec::new();
        let mut roots: Vec<u32> = Vec::new();
        let mut refused: Option<(usize, usize, u32)> = None;
        'planes: for w in 0..self.mirrors.planes.len() {
            // the particles so far: this plane's own mirrors are not mirrored again
            // a copy: the particle arrays grow while it is read
            let pl = self.mirrors.planes[w].clone();
            for i in 0..self.len() {
                if pl.distance(&self.build_x[i]) >= reach {
                    continue;
                }
                let (chain, root) = match i.checked_sub(first) {
                    Some(k) => (chains[k], roots[k]),
                    None => (Chain::default(), self.ids[i]),
                };
                let planes = &self.mirrors.planes;
                if let Some(u) = chain
                    .planes()
                    .find(|&u| planes[u].normal.dot(&pl.normal).abs() > PERPENDICULAR)
                {
                    refused = Some((u, w, root));
                    break 'planes;
                }
                let (bx, bh) = (pl.reflect_point(&self.build_x[i]), self.build_h[i]);
                let n = self.len();
                self.ids.push(0); // numbered below
                gsph_core::particle_fields!(each_state_field { kind self, mirror, (i, &pl) });
                dup(&mut self.sums, i, n);
                dup(&mut self.grad, i, n);
                dup(&mut self.grad_stress, i, n);
                dup(&mut self.corr, i, n);
                dup(&mut self.hg_rec, i, n);
                dup(&mut self.av, i, n);
                dup(&mut self.art, i, n);
                dup(&mut self.aux, i, n);
                self.build_x.push(bx);
                self.build_h.push(bh);
                self.mirrors.map.push((i, w));
                chains.push(chain.then(w));
                roots.push(root);
            }
        }
        let refused = refused.map(|(u, w, id)| {
            let why = interaction(&self.mirrors.planes, u, w, reach, id);
            if self.step > 0 {
                format!("step {} (t = {:e} s): {why}", self.step + 1, self.t)
            } else {
                why
            }
        });
        #[cfg(feature = "mpi")]
        let refused = if self.dist.is_some() {
            crate::dist::agree(refused.map_or(Ok(()), Err)).err()
        } else {
            refused
        };
        if let Some(why) = refused {
            self.drop_mirrors();
            return Err(SimError::Walls(why));
        }
        let mut order: Vec<usize> = (0..chains.len()).collect();
        order.sort_unstable_by_key(|&k| (chains[k], roots[k]));
        for (rank, &k) in order.iter().enumerate() {
            self.ids[first + k] = base + rank as u32;
        }
        Ok(())
    }
}
