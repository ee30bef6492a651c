//! A [`Sim`] split over MPI ranks (feature `mpi`; see [`crate::dist`]): particle records
//! for migration, ghosts and gathers, the distributed neighbour-list rebuild, and the
//! gathered views (table, diagnostics, checkpoints) in global id order.

use super::Sim;
use crate::dist::{self, rcb::Rcb, Dist, Plan, REBALANCE_THRESHOLD};
use crate::sim::SimError;
use crate::words::Words;
use gsph_core::math::Vector;
use gsph_core::schemes::AvRates;
use std::time::Instant;

impl<const D: usize> Sim<D> {
    /// Splits the particles over the ranks of the world communicator (no-op on one rank):
    /// keeps this rank's block of the ids and rebuilds the neighbour lists, which moves
    /// every particle to the rank whose sub-domain holds it and sets up the ghosts.
    /// Every rank must call it with the same particles (all ranks build the same scene).
    pub fn distribute(&mut self) -> Result<(), SimError> {
        let size = dist::size();
        if size <= 1 || self.dist.is_some() {
            return Ok(());
        }
        let rank = dist::rank();
        let mut order: Vec<usize> = (0..self.len()).collect();
        order.sort_unstable_by_key(|&i| self.ids[i]);
        let n = order.len();
        let (a, b) = (rank * n / size, (rank + 1) * n / size);
        let mut keep = vec![false; n];
        for &i in &order[a..b] {
            keep[i] = true;
        }
        self.retain(&keep);
        // counters of the whole run (a restart restored them on every rank): rank 0's
        if rank != 0 {
            self.mirrors.crossings = 0;
            self.mirrors.friction_work = 0.0;
        }
        self.dist = Some(Box::new(Dist::new()));
        self.rebuild()
    }

    /// Words of one particle record (id, the state fields the run stores in the order of
    /// the core's table, `av` rates, driven velocity), whether or not this rank holds
    /// particles.
    fn record_width(&self) -> usize {
        fn width<T: Words>(_: &[T], stored: bool, w: &mut usize) {
            if stored {
                *w += T::words();
            }
        }
        let mut w = 1;
        gsph_core::particle_fields!(each_state_field { stored self, width, &mut w });
        if self.stores_av() {
            w += AvRates::<D>::words();
        }
        w + 1 + D
    }

    /// Whether the run keeps `av`'s rates (they carry over from step to step).
    fn stores_av(&self) -> bool {
        self.scheme.family().layout(self.effects, &self.options).av
    }

    /// Appends the record of local particle `i` (`driven`: its prescribed velocity).
    fn put_record(&self, i: usize, driven: Option<Vector<D>>, out: &mut Vec<f64>) {
        fn put<T: Words>(v: &[T], stored: bool, (i, out): (usize, &mut Vec<f64>)) {
            if stored {
                v[i].put_words(out);
            }
        }
        out.push(self.ids[i] as f64);
        gsph_core::particle_fields!(each_state_field { stored self, put, (i, &mut *out) });
        if self.stores_av() {
            self.av[i].put_words(out);
        }
        out.push(driven.is_some() as u8 as f64);
        driven.unwrap_or_else(Vector::<D>::zeros).put_words(out);
    }

    /// Appends a particle from its record (with default workspace entries); returns its
    /// driven velocity.
    fn push_record(&mut self, r: &[f64]) -> Option<Vector<D>> {
        let mut at = 0;
        let mut next = |w: usize| {
            let s = &r[at..at + w];
            at += w;
            s
        };
        fn get<'r, T: Words>(
            v: &mut Vec<T>,
            stored: bool,
            next: &mut impl FnMut(usize) -> &'r [f64],
        ) {
            if stored {
                v.push(T::from_words(next(T::words())));
            }
        }
        self.ids.push(next(1)[0] as u32);
        gsph_core::particle_fields!(each_state_field { stored_mut self, get, &mut next });
        let layout = self.scheme.family().layout(self.effects, &self.options);
        if layout.av {
            self.av
                .push(AvRates::<D>::from_words(next(AvRates::<D>::words())));
        }
        let driven = next(1)[0] != 0.0;
        let vd = Vector::<D>::from_words(next(D));
        self.push_scratch(&layout);
        driven.then_some(vd)
    }

    /// The prescribed velocity of each local particle that is driven.
    fn driven_of(&self) -> Vec<Option<Vector<D>>> {
        let mut d = vec![None; self.len()];
        for &(i, v) in &self.driven {
            d[i] = Some(v);
        }
        d
    }

    /// Records of `idx` (local particles), concatenated.
    fn records(&self, idx: impl Iterator<Item = usize>) -> Vec<f64> {
        let driven = self.driven_of();
        let mut out = Vec::new();
        for i in idx {
            self.put_record(i, driven[i], &mut out);
        }
        out
    }

    /// Appends the particles of concatenated records; `owned` ones may be driven.
    fn push_records(&mut self, buf: &[f64], owned: bool) {
        let w = self.record_width();
        for r in buf.chunks_exact(w) {
            let i = self.len();
            if let Some(v) = self.push_record(r) {
                if owned {
                    self.driven.push((i, v));
                }
            }
        }
    }

    /// The distributed rebuild: drop the ghosts, rebalance if needed, migrate, renumber,
    /// exchange ghosts, build the lists over owned and ghost particles (collective).
    pub(super) fn rebuild_distributed(&mut self) -> Result<(), SimError> {
        let t0 = Instant::now();
        let mut d = self.dist.take().expect("a distributed sim");
        let (rank, size) = (d.rank, d.size);
        // 1. owned particles only (no wall mirrors, no ghosts)
        self.drop_mirrors();
        if self.owned < self.len() {
            let keep: Vec<bool> = (0..self.len()).map(|i| i < self.owned).collect();
            self.retain(&keep);
        }
        // 2. sub-domains: recomputed when the owned counts are out of balance
        let counts = dist::all_gather_u64(self.len() as u64);
        let total: u64 = counts.iter().sum();
        let mean = total as f64 / size as f64;
        let max = counts.iter().copied().max().unwrap_or(0) as f64;
        if d.rcb.is_none() || max > mean * (1.0 + REBALANCE_THRESHOLD) {
            d.rcb = Some(Rcb::build(self.list_positions(), size));
            d.rebalances += 1;
        }
        let rcb = d.rcb.as_ref().expect("sub-domains");
        // 3. migration
        // tl's sub-domains and ghosts are those of its reference positions (where its
        // lists are built): its particles migrate only when the reference is updated
        let dest: Vec<usize> = self
            .list_positions()
            .iter()
            .map(|x| rcb.rank_of(x))
            .collect();
        let parts: Vec<Vec<f64>> = (0..size)
            .map(|r| {
                if r == rank {
                    Vec::new()
                } else {
                    self.records((0..self.len()).filter(|&i| dest[i] == r))
                }
            })
            .collect();
        let mut bytes = 8 * parts.iter().map(Vec::len).sum::<usize>() as u64;
        let came = dist::all_to_all(&parts);
        let keep: Vec<bool> = dest.iter().map(|&r| r == rank).collect();
        self.retain(&keep);
        for buf in &came {
            self.push_records(buf, true);
        }
        // 4. memory order (results do not depend on it)
        if self.reorder {
            let hmax = self.h.iter().cloned().fold(0.0, f64::max);
            let order = crate::neighbors::morton_order(
                self.list_positions(),
                &self.ids,
                hmax,
                &self.periodic,
            );
            self.permute(&order);
        }
        self.owned = self.len();
        // 5. ghosts: owned particles within the lists' reach of another sub-domain
        let hmax = dist::all_max(self.h.iter().cloned().fold(0.0, f64::max));
        let reach = self.kernel.support() * (1.0 + self.skin) * hmax;
        let send: Vec<Vec<u32>> = (0..size)
            .map(|r| {
                if r == rank {
                    return Vec::new();
                }
                (0..self.owned)
                    .filter(|&i| rcb.near(r, &self.list_positions()[i], reach, &self.periodic))
                    .map(|i| i as u32)
                    .collect()
            })
            .collect();
        let parts: Vec<Vec<f64>> = send
            .iter()
            .map(|idx| self.records(idx.iter().map(|&i| i as usize)))
            .collect();
        bytes += 8 * parts.iter().map(Vec::len).sum::<usize>() as u64;
        let came = dist::all_to_all(&parts);
        let w = self.record_width();
        let recv: Vec<usize> = came.iter().map(|b| b.len() / w).collect();
        for buf in &came {
            self.push_records(buf, false);
        }
        d.owned = self.owned;
        d.plan = Plan { send, recv };
        d.rebuild.seconds += t0.elapsed().as_secs_f64();
        d.rebuild.bytes += bytes;
        d.rebuild.calls += 1;
        self.dist = Some(d);
        // 6. the walls' mirrors of owned and ghost particles (collective), then lists
        // over all of them; a failure on one rank fails all
        self.build_x = self.list_positions().clone();
        self.build_h.clone_from(&self.h);
        self.add_mirrors()?;
        let built = self.build_lists();
        let msg = built.as_ref().err().map(|e| e.to_string());
        match dist::agree(msg.map_or(Ok(()), Err)) {
            Ok(()) => Ok(()),
            Err(m) => built.and(Err(SimError::Distributed(m))),
        }
    }

    /// All particles, gathered from every rank in global id order, as one serial
    /// simulation (no lists); `None` when this simulation is not distributed.
    pub fn gathered(&self) -> Option<Sim<D>> {
        self.dist.as_ref()?;
        let mine = self.records(0..self.owned);
        let all = dist::all_gather(&mine);
        let w = self.record_width();
        let mut recs: Vec<&[f64]> = all.chunks_exact(w).collect();
        recs.sort_unstable_by_key(|r| r[0] as u32);
        let mut s = self.clone();
        s.dist = None;
        let none = vec![false; s.len()];
        s.retain(&none);
        for r in recs {
            let i = s.len();
            if let Some(v) = s.push_record(r) {
                s.driven.push((i, v));
            }
        }
        s.owned = s.len();
        (s.mirrors.crossings, s.mirrors.friction_work) = self.wall_totals();
        // a checkpoint of it rebuilds its lists at these positions on restore
        s.build_x = s.list_positions().clone();
        s.build_h.clone_from(&s.h);
        s.rebuilds = dist::all_max(self.rebuilds as f64) as u64;
        s.reference_updates = dist::all_max(self.reference_updates as f64) as u64;
        s.pair_interactions = dist::all_sum_u64(self.pair_interactions);
        Some(s)
    }

    /// `(id, m, e, v)` of the owned particles of every rank, in global id order.
    pub(super) fn gathered_motion(&self) -> Vec<f64> {
        let w = 3 + D;
        let mut mine = Vec::with_capacity(self.owned * w);
        for i in 0..self.owned {
            mine.extend_from_slice(&[self.ids[i] as f64, self.m[i], self.e[i]]);
            self.v[i].put_words(&mut mine);
        }
        let all = dist::all_gather(&mine);
        let mut rows: Vec<&[f64]> = all.chunks_exact(w).collect();
        rows.sort_unstable_by_key(|r| r[0] as u32);
        rows.concat()
    }
}
