//! The neighbour lists of a [`Sim`]: Morton renumbering, building, the staleness test
//! that decides a rebuild, and the overlap check of the initial particles.

use super::*;

impl<const D: usize> Sim<D> {
    /// Renumbers the particles in Morton order (see [`morton_order`]), then builds the
    /// neighbour lists at the current positions.
    pub(super) fn rebuild(&mut self) -> Result<(), SimError> {
        #[cfg(feature = "mpi")]
        if self.dist.is_some() {
            self.rebuild_distributed()?;
            self.rebuilds += 1;
            return Ok(());
        }
        self.drop_mirrors();
        self.owned = self.len();
        if self.reorder {
            let hmax = self.h.iter().cloned().fold(0.0, f64::max);
            let order = morton_order(&self.x, &self.ids, hmax, &self.periodic);
            self.permute(&order);
        }
        // tl's neighbours are those of its reference configuration
        self.build_x = self.list_positions().clone();
        self.build_h.clone_from(&self.h);
        self.add_mirrors()?;
        self.build_lists()?;
        self.rebuilds += 1;
        Ok(())
    }

    /// Builds the neighbour lists at the positions and smoothing lengths of the last
    /// rebuild (`build_x`, `build_h`) and sizes the pair buffers.
    pub(super) fn build_lists(&mut self) -> Result<(), SimError> {
        crate::neighbors::build(
            &self.build_x,
            &self.build_h,
            &self.ids,
            self.kernel.support(),
            self.skin,
            &self.periodic,
            self.capacity,
            &mut self.lists,
        )
        .map_err(|e| SimError::Neighbors(overflow_by_id(e, &self.ids)))?;
        let pairs = self.lists.unordered_pairs();
        let layout = self.scheme.family().layout(self.effects, &self.options);
        if layout.geom {
            self.geom.resize(pairs, PairGeom::default());
            if layout.art {
                self.fac.resize(pairs, 0.0);
            }
        }
        if layout.ts_star {
            self.ts_star.resize(pairs, TsStar::default());
        }
        if layout.pm_star {
            self.pm_star.resize(pairs, PmStar::default());
        }
        Ok(())
    }

    /// Moves particle `order[k]` to place `k` in every per-particle array.
    pub(super) fn permute(&mut self, order: &[u32]) {
        self.renumbered += 1;
        fn apply<T: Copy>(v: &mut Vec<T>, order: &[u32]) {
            if v.len() == order.len() {
                *v = order.iter().map(|&i| v[i as usize]).collect();
            }
        }
        let mut place = vec![0usize; order.len()];
        for (k, &i) in order.iter().enumerate() {
            place[i as usize] = k;
        }
        for d in self.driven.iter_mut() {
            d.0 = place[d.0];
        }
        apply(&mut self.ids, order);
        gsph_core::particle_fields!(each_state_field { self, apply, order });
        apply(&mut self.sums, order);
        apply(&mut self.grad, order);
        apply(&mut self.grad_stress, order);
        apply(&mut self.corr, order);
        apply(&mut self.hg_rec, order);
        apply(&mut self.av, order);
        apply(&mut self.art, order);
        apply(&mut self.aux, order);
        apply(&mut self.build_x, order);
        apply(&mut self.build_h, order);
    }

    /// Rebuilds the neighbour lists (renumbering the particles, see [`Sim::reorder`]) when
    /// some pair may have entered the kernel support since the last build. [`Sim::step`]
    /// calls it first; a caller that holds particle indices across a step (the moving
    /// window) calls it before taking them.
    pub fn maintain(&mut self) -> Result<(), SimError> {
        if self.lists_stale() {
            let (step, t) = (self.step + 1, self.t);
            self.rebuild().map_err(|e| match e {
                SimError::Neighbors(n) => SimError::Rebuild { step, t, cause: n },
                other => other,
            })?;
        }
        Ok(())
    }

    /// The positions the neighbour lists are built at: the reference positions of the
    /// total-Lagrangian scheme (fixed during a run, so its lists never go stale), the
    /// positions now otherwise.
    pub(super) fn list_positions(&self) -> &Vec<Vector<D>> {
        if self.effects.contains(EffectSet::REFERENCE) {
            &self.xr
        } else {
            &self.x
        }
    }

    /// True when some pair may have entered the kernel support since the last build.
    pub(super) fn lists_stale(&self) -> bool {
        if self.build_x.len() != self.x.len() {
            #[cfg(feature = "mpi")]
            if self.dist.is_some() {
                return crate::dist::any(true);
            }
            return true;
        }
        // max and min are exact, so the parallel (and the distributed) reduction is the
        // serial one
        let (dmax2, growth, hmin) = (0..self.owned)
            .into_par_iter()
            .with_min_len(1024)
            .map(|i| {
                let d = self
                    .periodic
                    .min_image(self.list_positions()[i] - self.build_x[i]);
                (
                    d.norm_squared(),
                    self.h[i] / self.build_h[i] - 1.0,
                    self.build_h[i],
                )
            })
            .reduce(
                || (0.0f64, 0.0f64, f64::INFINITY),
                |a, b| (a.0.max(b.0), a.1.max(b.1), a.2.min(b.2)),
            );
        #[cfg(feature = "mpi")]
        let (dmax2, growth, hmin) = if self.dist.is_some() {
            if crate::dist::any(false) {
                return true;
            }
            (
                crate::dist::all_max(dmax2),
                crate::dist::all_max(growth),
                crate::dist::all_min(hmin),
            )
        } else {
            (dmax2, growth, hmin)
        };
        2.0 * dmax2.sqrt() >= self.kernel.support() * hmin * (self.skin - growth)
    }

    /// The first rebuild of a new simulation, then the overlap check of its particles
    /// (`spacing` indexed by id); a neighbour overflow caused by particles on top of each
    /// other is reported as that overlap ([`Sim::overlap_near`]).
    pub(super) fn first_rebuild(&mut self, spacing: &[f64]) -> Result<(), SimError> {
        self.check_same_points()?;
        if let Err(e) = self.rebuild() {
            if let SimError::Neighbors(NeighborError::Overflow { particle, .. }) = e {
                if let Some(overlap) = self.overlap_near(particle, spacing) {
                    return Err(overlap);
                }
            }
            return Err(e);
        }
        self.check_overlap(spacing)
    }

    /// The neighbour lists could not be built because particle `id` has more neighbours
    /// than their capacity: when that is because particles sit on top of each other there
    /// (points given twice in a particle file, overlapping bodies), the overlap naming two
    /// of them, nearest first, as [`Sim::check_overlap`] would have named it.
    pub(super) fn overlap_near(&self, id: usize, spacing: &[f64]) -> Option<SimError> {
        // an owned particle (a wall's mirror may be the one that overflowed)
        let i = self.ids[..self.owned]
            .iter()
            .position(|&k| k as usize == id)?;
        let close = |a: usize, b: usize| {
            let d = self.periodic.min_image(self.x[a] - self.x[b]).norm();
            let sa = spacing.get(self.ids[a] as usize)?;
            let sb = spacing.get(self.ids[b] as usize)?;
            (d < 0.5 * sa.min(*sb)).then_some(d)
        };
        // its own nearest overlapping particle, else the closest overlapping pair among
        // the particles within its reach (a bounded number of them)
        let reach = self.kernel.support() * (1.0 + self.skin) * self.h[i];
        let near: Vec<usize> = (0..self.owned)
            .filter(|&j| self.periodic.min_image(self.x[j] - self.x[i]).norm() < reach)
            .take(2000)
            .collect();
        let pair = near
            .iter()
            .filter(|&&j| j != i)
            .filter_map(|&j| close(i, j).map(|d| (d, i, j)))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .or_else(|| {
                near.iter()
                    .enumerate()
                    .flat_map(|(k, &a)| near[k + 1..].iter().map(move |&b| (a, b)))
                    .filter_map(|(a, b)| close(a, b).map(|d| (d, a, b)))
                    .min_by(|a, b| a.0.total_cmp(&b.0))
            })?;
        let (distance, a, b) = pair;
        Some(self.overlap(a, b, distance))
    }

    /// The overlap of local particles `a` and `b`, `distance` apart, named lower id first
    /// and located at that particle.
    fn overlap(&self, a: usize, b: usize, distance: f64) -> SimError {
        let (a, b) = if self.ids[a] < self.ids[b] {
            (a, b)
        } else {
            (b, a)
        };
        let mut at = [0.0; 3];
        at[..D].copy_from_slice(self.x[a].as_slice());
        SimError::Overlap {
            i: self.ids[a],
            j: self.ids[b],
            distance,
            at,
        }
    }

    /// Refuses particles at exactly the same point before any list is built: a crowd of
    /// them fills every list to its capacity (20,000 particles at one point with
    /// `neighbor_capacity = 20000` asked for gigabytes before the overlap check ran). A
    /// sort of the positions: n log n, an index per particle.
    fn check_same_points(&self) -> Result<(), SimError> {
        let n = self.owned.min(self.len());
        // the bits of each coordinate (+ 0.0 makes -0 and 0 one point)
        let key = |i: u32| -> [u64; D] {
            let x = &self.x[i as usize];
            core::array::from_fn(|a| (x[a] + 0.0).to_bits())
        };
        let mut order: Vec<u32> = (0..n as u32).collect();
        order.sort_unstable_by_key(|&i| key(i));
        match order.windows(2).find(|w| key(w[0]) == key(w[1])) {
            Some(w) => Err(self.overlap(w[0] as usize, w[1] as usize, 0.0)),
            None => Ok(()),
        }
    }

    /// Refuses particles nearer than half their spacing (`spacing` indexed by id).
    pub(super) fn check_overlap(&self, spacing: &[f64]) -> Result<(), SimError> {
        let nb = self.lists.view();
        // owned pairs (a particle's mirror is its own image through a wall)
        for i in 0..self.owned {
            for &j in nb.of(i) {
                let j = j as usize;
                if j >= self.owned {
                    continue;
                }
                let d = self.periodic.min_image(self.x[i] - self.x[j]).norm();
                let (si, sj) = (spacing[self.ids[i] as usize], spacing[self.ids[j] as usize]);
                if d < 0.5 * si.min(sj) {
                    let mut at = [0.0; 3];
                    at[..D].copy_from_slice(self.x[i].as_slice());
                    return Err(SimError::Overlap {
                        i: self.ids[i],
                        j: self.ids[j],
                        distance: d,
                        at,
                    });
                }
            }
        }
        Ok(())
    }
}
