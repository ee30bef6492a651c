//! What is read off a [`Sim`]: particles in id order, energies, momentum, the free-surface
//! flags, and the particle table of the output files.

use super::*;
use crate::output::table::NUM_FLOAT_COLUMNS;

impl<const D: usize> Sim<D> {
    /// The free-surface flags of the last step's kernel-correction pass, one per particle:
    /// 0 interior, 1 near a boundary particle, 2 boundary particle (computed from the state
    /// at the start of that step). Empty without kernel correction; all 0 before a step.
    pub fn boundary_flags(&self) -> Vec<u8> {
        if self.corr.is_empty() {
            return Vec::new();
        }
        self.by_id().map(|i| self.corr[i].boundary).collect()
    }

    /// Owned particle indices in id order.
    pub fn by_id(&self) -> impl Iterator<Item = usize> {
        let mut order: Vec<usize> = (0..self.owned).collect();
        order.sort_unstable_by_key(|&i| self.ids[i]);
        order.into_iter()
    }

    /// The number of particles of the run (on all ranks).
    pub fn global_len(&self) -> usize {
        #[cfg(feature = "mpi")]
        if self.dist.is_some() {
            return crate::dist::all_sum_u64(self.owned as u64) as usize;
        }
        self.owned
    }

    /// `(id, m, e, v)` of every particle of the run in id order: the order of every
    /// diagnostic sum, so that they depend neither on memory order nor on the rank count.
    pub(super) fn motion_by_id(&self) -> Vec<f64> {
        #[cfg(feature = "mpi")]
        if self.dist.is_some() {
            return self.gathered_motion();
        }
        let mut out = Vec::with_capacity(self.owned * (3 + D));
        for i in self.by_id() {
            out.extend_from_slice(&[self.ids[i] as f64, self.m[i], self.e[i]]);
            out.extend_from_slice(self.v[i].as_slice());
        }
        out
    }

    /// Total energy (kinetic, internal), J, summed in id order.
    pub fn energy(&self) -> (f64, f64) {
        let mut kin = 0.0;
        let mut int = 0.0;
        for r in self.motion_by_id().chunks_exact(3 + D) {
            let v = Vector::<D>::from_column_slice(&r[3..]);
            kin += 0.5 * r[1] * v.norm_squared();
            int += r[1] * r[2];
        }
        (kin, int)
    }

    /// Total momentum, padded to 3 components, summed in id order.
    pub fn momentum(&self) -> [f64; 3] {
        let mut p = [0.0; 3];
        for r in self.motion_by_id().chunks_exact(3 + D) {
            for (a, pa) in p.iter_mut().enumerate().take(D) {
                *pa += r[1] * r[3 + a];
            }
        }
        p
    }

    /// The particle table (final.csv columns).
    /// Rows in id order, whatever the order of the particles in memory.
    pub fn table(&self) -> ParticleTable {
        #[cfg(feature = "mpi")]
        if let Some(all) = self.gathered() {
            return all.table();
        }
        let mut t = ParticleTable::with_capacity(self.owned);
        let derived = self.derived_columns();
        for i in self.by_id() {
            let mut floats = [0.0; NUM_FLOAT_COLUMNS];
            let mut k = 0;
            self.state_columns(i, &mut floats, &mut k);
            for d in &derived {
                floats[k] = d[i];
                k += 1;
            }
            debug_assert_eq!(k, NUM_FLOAT_COLUMNS);
            let row = ParticleRow::from_parts(self.ids[i], self.mat[i] as u32, floats);
            t.push(&row);
        }
        t
    }
}
