//! Removing and inserting particles during a run (the moving window of seed 004 §3 removes
//! particles past its exit and feeds new ones through its entry). Both keep every
//! per-particle array (state, effect storage, workspace) in step and force a neighbour-list
//! rebuild before the next step.

use super::{vec_of, Sim};
use crate::scene::InitialParticles;
use gsph_core::effects::EffectSet;
use gsph_core::math::Vector;
use gsph_core::state::{smoothing_length, AvRates, Correction, Gradients, Layout, PairSums};

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
        let has = |e: EffectSet| self.effects.contains(e);
        let (strength, plasticity, damage, heat) = (
            has(EffectSet::STRENGTH),
            has(EffectSet::PLASTICITY),
            has(EffectSet::DAMAGE),
            has(EffectSet::HEAT),
        );
        let layout = Layout::of(self.scheme.family(), self.effects);
        for i in 0..parts.len() {
            let mat = self.materials[parts.mat[i] as usize];
            let st = mat.eos(parts.rho[i], parts.e[i]);
            self.ids.push(first + i as u32);
            self.x.push(self.periodic.wrap(vec_of::<D>(&parts.x[i])));
            self.v.push(vec_of::<D>(&parts.v[i]));
            self.m.push(parts.m[i]);
            self.mat.push(parts.mat[i]);
            self.rho.push(parts.rho[i]);
            self.e.push(parts.e[i]);
            self.p.push(st.p);
            self.c.push(st.c2.max(0.0).sqrt());
            self.cl.push(mat.c_long(parts.rho[i], st.c2.max(0.0)));
            self.h.push(smoothing_length::<D>(
                self.h_factor,
                parts.m[i],
                parts.rho[i],
            ));
            if strength {
                self.s.push(parts.s[i]);
            }
            // from the scene's particles where given (a body read from a file), else the
            // initial state
            if plasticity {
                self.eps_p.push(parts.eps_p.get(i).copied().unwrap_or(0.0));
            }
            if damage {
                self.damage
                    .push(parts.damage.get(i).copied().unwrap_or(0.0));
            }
            if heat {
                let t = parts.temperature.get(i).copied();
                self.temp
                    .push(t.unwrap_or_else(|| mat.initial_temperature()));
            }
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
pub struct HeldState {
    rho: f64,
    e: f64,
    p: f64,
    c: f64,
    cl: f64,
    h: f64,
    s: Option<gsph_core::math::Sym3>,
    eps_p: Option<f64>,
    damage: Option<f64>,
    temp: Option<f64>,
}

impl<const D: usize> Sim<D> {
    /// The material state of particle `i`.
    pub fn held_state(&self, i: usize) -> HeldState {
        let opt = |v: &Vec<f64>| v.get(i).copied();
        HeldState {
            rho: self.rho[i],
            e: self.e[i],
            p: self.p[i],
            c: self.c[i],
            cl: self.cl[i],
            h: self.h[i],
            s: self.s.get(i).copied(),
            eps_p: opt(&self.eps_p),
            damage: opt(&self.damage),
            temp: opt(&self.temp),
        }
    }

    /// Puts back a state taken by [`Sim::held_state`].
    pub fn restore_state(&mut self, i: usize, st: &HeldState) {
        self.rho[i] = st.rho;
        self.e[i] = st.e;
        self.p[i] = st.p;
        self.c[i] = st.c;
        self.cl[i] = st.cl;
        self.h[i] = st.h;
        let put = |v: &mut Vec<f64>, x: Option<f64>| {
            if let Some(x) = x {
                v[i] = x;
            }
        };
        if let Some(s) = st.s {
            self.s[i] = s;
        }
        put(&mut self.eps_p, st.eps_p);
        put(&mut self.damage, st.damage);
        put(&mut self.temp, st.temp);
    }
}
