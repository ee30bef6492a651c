//! tl's updated reference (issue 47 item 2; `options.reference_update`): after a step in
//! which some pair's stretch `|r_ij/R_ij - 1|` (current against reference separation,
//! over the pairs within the kernel's support in the reference configuration) exceeds
//! the threshold, every particle's reference position becomes its position and its
//! reference volume `m/rho`, and the neighbour lists are rebuilt there — LAMMPS SMD's
//! `UPDATE_PAIRWISE_RATIO`, the updated reference Lagrangian of Refachinho de Campos et
//! al. (CMAME 2022).
//!
//! What carries over: the stress (the deviator is a Cauchy one, advanced in rate form;
//! the pressure comes from the density and the internal energy), the density (the new
//! reference density `m/V0` is the density now, and `F` restarts from the identity), the
//! velocities and the acceleration of velocity Verlet. What does not: the energy the
//! hourglass stiffness stored (`phi`, which each step books into the internal energy) is
//! zero in the new reference; `phi` is reset and the internal energy kept, so the stored
//! energy becomes heat and total energy is unchanged by the update.
//!
//! The largest stretch is a maximum (exact in any order, reduced over the MPI ranks), so
//! the decision, and the run, are the same on any thread and rank count.

use super::*;

impl<const D: usize> Sim<D> {
    /// The neighbours `j` of particle `i` within the kernel's support in the reference
    /// configuration, with their reference distance `R > 0` (the pairs tl's passes weigh).
    fn reference_pairs(&self, i: usize) -> impl Iterator<Item = (usize, Real)> + '_ {
        let support = self.kernel.support();
        let nbrs = self.lists.view();
        let row = &nbrs.index[nbrs.start[i] as usize..nbrs.start[i + 1] as usize];
        row.iter().filter_map(move |&j| {
            let j = j as usize;
            let big_r = (self.xr[j] - self.xr[i]).norm();
            (big_r > 0.0 && big_r < support * 0.5 * (self.h[i] + self.h[j])).then_some((j, big_r))
        })
    }

    /// The largest `|r/R - 1|` over the owned particles' pairs within the kernel's
    /// support in the reference configuration (0 without pairs).
    pub fn largest_pair_stretch(&self) -> Real {
        (0..self.owned)
            .into_par_iter()
            .with_min_len(1024)
            .map(|i| {
                self.reference_pairs(i)
                    .map(|(j, big_r)| ((self.x[j] - self.x[i]).norm() / big_r - 1.0).abs())
                    .fold(0.0, Real::max)
            })
            .reduce(|| 0.0, Real::max)
    }

    /// tl's pairs are those of the reference configuration, so bodies that share no pair
    /// at the start would pass through each other: refused, naming the first such body
    /// (`body` by particle id; bodies that touch at the start stay bonded).
    pub(super) fn check_bodies_bonded(&self, body: &[u16]) -> Result<(), SimError> {
        let bodies = body.iter().copied().max().map_or(0, |b| b as usize + 1);
        if !self.effects.contains(EffectSet::REFERENCE) || bodies < 2 {
            return Ok(());
        }
        let mut bonded = vec![false; bodies];
        for i in 0..self.owned {
            let bi = body[self.ids[i] as usize];
            for (j, _) in self.reference_pairs(i) {
                if j < self.owned && body[self.ids[j] as usize] != bi {
                    bonded[bi as usize] = true;
                }
            }
        }
        match bonded.iter().position(|&b| !b) {
            Some(k) => Err(SimError::Reference(format!(
                "bodies[{k}]: shares no pair with another body at the start, and scheme tl's pairs are those of the start (it would pass through the others); bodies that touch at the start stay bonded"
            ))),
            None => Ok(()),
        }
    }

    /// After a step of a `tl` run with `options.reference_update` set: re-bases the
    /// reference configuration when the largest pair stretch exceeds it (module docs).
    pub(super) fn update_reference(&mut self) -> Result<(), SimError> {
        let threshold = self.options.reference_update;
        if !self.effects.contains(EffectSet::REFERENCE) || threshold <= 0.0 {
            return Ok(());
        }
        let most = self.largest_pair_stretch();
        // every rank decides as one process would (a maximum: exact)
        #[cfg(feature = "mpi")]
        let most = if self.dist.is_some() {
            crate::dist::all_max(most)
        } else {
            most
        };
        if most <= threshold {
            return Ok(());
        }
        for i in 0..self.owned {
            self.xr[i] = self.x[i];
            self.vr[i] = self.m[i] / self.rho[i];
            // the stiffness stores nothing in the new reference: what it stored stays in
            // the internal energy (where each step booked it) as heat
            self.phi[i] = 0.0;
        }
        self.reference_updates += 1;
        let (step, t) = (self.step, self.t);
        self.rebuild().map_err(|e| match e {
            SimError::Neighbors(n) => SimError::Rebuild { step, t, cause: n },
            other => other,
        })
    }
}
