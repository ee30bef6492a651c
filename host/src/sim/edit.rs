//! Removing and inserting particles during a run (the moving window of seed 004 §3 removes
//! particles past its exit and feeds new ones through its entry). Both keep every
//! per-particle array (state, effect storage, workspace) in step and force a neighbour-list
//! rebuild before the next step.

use super::{vec_of, Particle, Sim};
use crate::scene::InitialParticles;
use gsph_core::math::{Sym3, Vector};
use gsph_core::schemes::{AvRates, Layout};
use gsph_core::state::{smoothing_length, Correction, Gradients, Hourglass, PairSums};

/// Keeps the elements of `v` whose mask entry is true (an empty `v`, storage of an absent
/// effect, stays empty).
fn filter<T>(v: &mut Vec<T>, keep: &[bool]) {
    if v.is_empty() {
        return;
    }
    let mut k = 0;
    v.retain(|_| {
        k += 1;
        keep[k - 1]
    });
}

impl<const D: usize> Sim<D> {
    /// Removes the particles whose `keep` entry is false. Ids of the others are unchanged;
    /// driven particles stay driven. Panics if `keep.len() != self.len()`.
    pub fn retain(&mut self, keep: &[bool]) {
        // wall mirrors are rebuilt with the lists (a mask may cover them or not)
        self.drop_mirrors();
        let keep = &keep[..keep.len().min(self.len())];
        assert_eq!(keep.len(), self.len(), "one mask entry per particle");
        let mut new_index = vec![usize::MAX; keep.len()];
        let mut n = 0;
        for (i, &k) in keep.iter().enumerate() {
            if k {
                new_index[i] = n;
                n += 1;
            }
        }
        self.driven = self
            .driven
            .iter()
            .filter(|(i, _)| keep[*i])
            .map(|&(i, v)| (new_index[i], v))
            .collect();
        filter(&mut self.ids, keep);
        gsph_core::particle_fields!(each_state_field { self, filter, keep });
        filter(&mut self.sums, keep);
        filter(&mut self.grad, keep);
        filter(&mut self.grad_stress, keep);
        filter(&mut self.corr, keep);
        filter(&mut self.hg_rec, keep);
        filter(&mut self.av, keep);
        filter(&mut self.art, keep);
        filter(&mut self.aux, keep);
        self.resize_lists();
    }

    /// Appends the particles of `parts` (state as built: density, energy, deviator,
    /// velocity; plastic strain, damage and temperature where `parts` has them, else zero
    /// plastic strain and damage and the initial temperature), with new ids after the
    /// largest one in use. Returns the first new id.
    pub fn append(&mut self, parts: &InitialParticles) -> u32 {
        self.drop_mirrors();
        let first = self.ids.iter().max().map_or(0, |&m| m + 1);
        let layout = self.scheme.family().layout(self.effects, &self.options);
        for i in 0..parts.len() {
            let mat = self.materials[parts.mat[i] as usize];
            let st = mat.eos(parts.rho[i], parts.e[i]);
            let x = self.periodic.wrap(vec_of::<D>(&parts.x[i]));
            self.ids.push(first + i as u32);
            // every field's initial value (a field the run does not store is dropped);
            // plastic strain, damage and temperature from the scene's particles where
            // given (a body read from a file), else the initial state
            self.push_particle(&Particle {
                x,
                v: vec_of::<D>(&parts.v[i]),
                m: parts.m[i],
                mat: parts.mat[i],
                rho: parts.rho[i],
                p: st.p,
                e: parts.e[i],
                c: st.c2.max(0.0).sqrt(),
                cl: mat.c_long(parts.rho[i], st.c2.max(0.0)),
                s: parts.s.get(i).copied().unwrap_or(Sym3::ZERO),
                eps_p: parts.eps_p.get(i).copied().unwrap_or(0.0),
                damage: parts.damage.get(i).copied().unwrap_or(0.0),
                temp: parts
                    .temp
                    .get(i)
                    .copied()
                    .unwrap_or_else(|| mat.initial_temperature()),
                h: smoothing_length::<D>(self.h_factor, parts.m[i], parts.rho[i]),
                // a new particle sits where its neighbours' affine motion puts it
                hg: Vector::<D>::zeros(),
                // where it was created, or the reference a particle file gives
                x0: parts.x0.get(i).map_or(x, vec_of::<D>),
                // tl's reference configuration: the particle as it enters the run
                xr: x,
                vr: parts.m[i] / parts.rho[i],
                phi: 0.0,
            });
            if layout.av {
                self.av.push(AvRates::default());
            }
            self.push_scratch(&layout);
        }
        self.resize_lists();
        first
    }

    /// Appends one particle's entries of the per-step workspace (recomputed before they
    /// are read in every step; `av`'s rates, which carry over, are the caller's).
    pub(super) fn push_scratch(&mut self, layout: &Layout) {
        self.sums.push(PairSums::default());
        if layout.grad {
            self.grad.push(Gradients::default());
        }
        if layout.grad_stress {
            self.grad_stress.push([Vector::<D>::zeros(); 6]);
        }
        if layout.corr {
            self.corr.push(Correction::default());
        }
        if layout.hg {
            self.hg_rec.push(Hourglass::default());
        }
        if layout.art {
            self.art.push(gsph_core::math::Matrix::<D>::zeros());
        }
        self.aux.push(gsph_core::state::Aux::default());
    }

    /// Empties the neighbour lists (for the current particle count) and marks them stale.
    fn resize_lists(&mut self) {
        self.owned = self.len();
        self.lists = crate::neighbors::Lists::empty(self.len());
        self.geom.clear();
        self.fac.clear();
        self.ts_star.clear();
        self.pm_star.clear();
        self.build_x.clear();
        self.build_h.clear();
    }
}

/// A particle's material state: everything but position, velocity and mass (exit region 2
/// of a moving window holds it fixed).
#[derive(Debug, Clone, Copy)]
pub struct HeldState<const D: usize>(Particle<D>);

impl<const D: usize> Sim<D> {
    /// The material state of particle `i`.
    pub fn held_state(&self, i: usize) -> HeldState<D> {
        HeldState(self.particle(i))
    }

    /// Puts back a state taken by [`Sim::held_state`], keeping the particle's position,
    /// velocity and mass.
    pub fn restore_state(&mut self, i: usize, st: &HeldState<D>) {
        let now = self.particle(i);
        self.set_particle(
            i,
            &Particle {
                x: now.x,
                v: now.v,
                m: now.m,
                ..st.0
            },
        );
    }
}
