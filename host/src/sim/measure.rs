//! What is read off a [`Sim`]: particles in id order, energies, momentum, the free-surface
//! flags, and the particle table of the output files.

use super::*;

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
        for i in self.by_id() {
            let g = |v: &Vector<D>, a: usize| if a < D { v[a] } else { 0.0 };
            let s = if self.s.is_empty() {
                Sym3::ZERO
            } else {
                self.s[i]
            };
            let opt = |v: &Vec<f64>| if v.is_empty() { 0.0 } else { v[i] };
            t.push(&ParticleRow {
                id: self.ids[i],
                material: self.mat[i] as u32,
                x: g(&self.x[i], 0),
                y: g(&self.x[i], 1),
                z: g(&self.x[i], 2),
                vx: g(&self.v[i], 0),
                vy: g(&self.v[i], 1),
                vz: g(&self.v[i], 2),
                m: self.m[i],
                rho: self.rho[i],
                p: self.p[i],
                e: self.e[i],
                sxx: s.xx,
                syy: s.yy,
                szz: s.zz,
                sxy: s.xy,
                sxz: s.xz,
                syz: s.yz,
                eps_p: opt(&self.eps_p),
                damage: opt(&self.damage),
                temperature: opt(&self.temp),
                h: self.h[i],
            });
        }
        t
    }
}
