//! `av`: standard SPH with Monaghan artificial viscosity (seed 000 §4; Monaghan & Gingold
//! 1983), integrated with the leap-frog (kick–drift–kick with a predictor for the rates).
//!
//! Rates of particle i (`sigma = S - P I`, `grad_i W_ij = (x_i - x_j)/r dW/dr`):
//!
//! ```text
//! dv_i/dt   = sum_j m_j [ (sigma_i + sigma_j)/(rho_i rho_j) - Pi_ij I ] . grad_i W_ij
//! de_i/dt   = 1/2 sum_j m_j (v_j - v_i) . [ (sigma_i + sigma_j)/(rho_i rho_j) - Pi_ij I ] . grad_i W_ij
//! drho_i/dt = rho_i sum_j m_j/rho_j (v_i - v_j) . grad_i W_ij               (seed 000 eq 12)
//! Pi_ij     = (-alpha c_ij mu_ij + beta mu_ij²)/rho_ij  if (v_i - v_j).(x_i - x_j) < 0, else 0
//! mu_ij     = h_ij (v_i - v_j).(x_i - x_j) / (r² + 0.01 h_ij²)
//! ```
//!
//! The pair force is antisymmetric, so momentum is conserved to round-off; the energy
//! rate is the exact counterpart of the force, so total energy is conserved up to the
//! time-integration error (leap-frog, second order). With the effect `artificial_stress`
//! the pair force gains `f_ij^n (R_i + R_j) . grad_i W_ij` (see
//! [`super::artificial_stress`]), in the force and so in the energy rate.

use super::artificial_stress::pair_acceleration;
use super::common::{
    artificial_stress_tensors, cauchy, deviator_rate, equivalent_strain_rate, for_each_pair,
    geometry_pass, halo_exchange, outer, refresh_aux, refresh_eos, return_deviator,
};
use super::options::{read_if, why, NotRead, OptionKey};
use super::{Scheme, SchemeFamily};
use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::halo::{Exchange, Fields, Halo};
use crate::math::{Matrix, Real, Sym3, Vector};
use crate::state::{
    Aux, AvRates, Family, Layout, PairGeom, StepError, StepParams, System, Workspace,
};

/// The halo exchanges of an `av` step (see [`crate::halo`]). The step is: kick and drift
/// (local), then the rate evaluation — the pair geometry (x, h), the per-particle aux
/// (local, from rho), the artificial stress tensors (local), the pair forces (v, rho, h,
/// c_l, the Cauchy stress: S, p and damage) — then the second kick (local). So the one
/// exchange comes before each rate evaluation.
pub const EXCHANGES: [Exchange; 1] = [Exchange {
    before: "rates",
    fields: Fields::STRESS_STATE,
    needs: EffectSet::HYDRO,
    needs_any: EffectSet::HYDRO,
}];

/// The artificial-viscosity family.
#[derive(Clone, Copy, Debug, Default)]
pub struct Av;

/// Evaluates the rates of every particle at the current state into `ws.av` (the pair
/// geometry, artificial-stress tensors and per-particle aux of `ws` are its scratch).
fn rates<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let (rates, geom, fac, art, aux) = (
        &mut *ws.av,
        &mut *ws.geom,
        &mut *ws.fac,
        &mut *ws.art,
        &mut *ws.aux,
    );
    geometry_pass::<D, E, X>(sys.x, sys.h, params, geom, fac, exec);
    refresh_aux::<D, false, X>(sys, aux, params, exec);
    let art_on = params.has::<E>(EffectSet::ARTIFICIAL_STRESS);
    if art_on {
        artificial_stress_tensors::<D, E, X>(sys, art, params, exec);
    }
    let (geom, fac, art, aux): (&[PairGeom<D>], &[Real], &[Matrix<D>], &[Aux]) =
        (geom, fac, art, aux);
    let alpha = params.options.av_alpha;
    let beta = params.options.av_beta;
    exec.run(rates, |off, chunk: &mut [AvRates<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let sig_i = cauchy::<D, E>(sys, i);
            let (vi, rhoi, hi, cli) = (sys.v[i], sys.rho[i], sys.h[i], sys.cl[i]);
            let inv_i = aux[i].inv_rho;
            let mut acc = Vector::<D>::zeros();
            let mut de: Real = 0.0;
            let mut div: Real = 0.0;
            let mut grad_v = Matrix::<D>::zeros();
            for_each_pair(params, geom, i, |pr, e| {
                let j = pr.j;
                let aj = aux[j];
                let vij = vi - sys.v[j];
                // (v_i - v_j).(x_i - x_j) = -r (v_ij . n)
                let vr = -pr.r * vij.dot(&pr.n);
                let mut pi_ij = 0.0;
                if vr < 0.0 {
                    let hij = 0.5 * (hi + sys.h[j]);
                    let mu = hij * vr / (pr.r * pr.r + 0.01 * hij * hij);
                    let cij = 0.5 * (cli + sys.cl[j]);
                    pi_ij = (-alpha * cij * mu + beta * mu * mu) / (0.5 * (rhoi + sys.rho[j]));
                }
                let sig = sig_i + cauchy::<D, E>(sys, j);
                let mut t = sig.dot_vec(&pr.grad) * (inv_i * aj.inv_rho) - pr.grad * pi_ij;
                if art_on {
                    t += pair_acceleration(1.0, fac[e.pair], &art[i], &art[j], &pr.grad);
                }
                let mj = sys.m[j];
                acc += t * mj;
                de -= 0.5 * mj * vij.dot(&t);
                div -= aj.vol * vij.dot(&pr.grad);
                if E::STRENGTH {
                    grad_v -= outer(&vij, &pr.grad) * aj.vol;
                }
            });
            out.acc = acc;
            out.de = de;
            out.drho = -rhoi * div;
            out.rate = if E::STRENGTH {
                equivalent_strain_rate(&grad_v)
            } else {
                0.0
            };
            out.ds = if E::STRENGTH {
                deviator_rate(&sys.s[i], &params.materials[sys.mat[i] as usize], &grad_v)
            } else {
                Sym3::ZERO
            };
        }
    });
}

/// Whether scheme `av` reads `key`, or why not ([`crate::schemes::options`]).
pub(crate) fn reads(scheme: Scheme, key: OptionKey) -> Result<(), NotRead> {
    use OptionKey::*;
    match key {
        AvAlpha | AvBeta | ArtificialStress | ArtificialStressExponent => Ok(()),
        Limiter => read_if(false, scheme, why::NO_MUSCL),
        Riemann => read_if(false, scheme, why::NO_RIEMANN),
        MusclTime => read_if(false, scheme, why::NO_MUSCL_TIME),
        SurfaceLambda | DetEpsilon => read_if(false, scheme, why::NO_SURFACE),
        Correction | Muscl => Err(NotRead::OnlyPm { scheme }),
    }
}

impl SchemeFamily for Av {
    const FAMILY: Family = Family::Av;
    const SUPPORTED: EffectSet = EffectSet::STRENGTH
        .union(EffectSet::PLASTICITY)
        .union(EffectSet::DAMAGE)
        .union(EffectSet::HEAT)
        .union(EffectSet::PERIODIC)
        .union(EffectSet::ARTIFICIAL_STRESS);
    const EXCHANGES: &'static [Exchange] = &EXCHANGES;

    fn layout(effects: EffectSet) -> Layout {
        Layout {
            av: true,
            ..Layout::base(effects)
        }
    }

    fn step<const D: usize, E: Effects, X: Executor>(
        sys: &mut System<'_, D>,
        ws: &mut Workspace<'_, D>,
        params: &StepParams<'_, D>,
        exec: &X,
        halo: &mut dyn Halo<D>,
    ) -> Result<(), StepError> {
        let dt = params.dt;
        let hdt = 0.5 * dt;
        if !ws.primed {
            halo_exchange!(params, halo, &EXCHANGES[0], sys, ws);
            rates::<D, E, X>(sys, ws, params, exec);
            ws.primed = true;
        }
        // Kick, drift, and predict the state at the end of the step.
        exec.run(
            (sys.reborrow(), &mut ws.av[..]),
            |_, (mut s, av): (System<'_, D>, &mut [AvRates<D>])| {
                for k in 0..s.len() {
                    let mat = &params.materials[s.mat[k] as usize];
                    let a = &mut av[k];
                    a.v_half = s.v[k] + a.acc * hdt;
                    a.e_half = s.e[k] + a.de * hdt;
                    a.rho_half = s.rho[k] + a.drho * hdt;
                    s.x[k] += a.v_half * dt;
                    s.v[k] = a.v_half + a.acc * hdt;
                    s.e[k] = a.e_half + a.de * hdt;
                    s.rho[k] = a.rho_half + a.drho * hdt;
                    if E::STRENGTH {
                        a.s_half = s.s[k] + a.ds * hdt;
                        let (trial, rate) = (a.s_half + a.ds * hdt, a.rate);
                        return_deviator::<D, E>(&mut s, k, mat, trial, rate, dt, false);
                    }
                    if params.has::<E>(EffectSet::PERIODIC) {
                        s.x[k] = params.periodic.wrap(s.x[k]);
                    }
                    refresh_eos(&mut s, k, mat, params);
                }
            },
        );
        halo_exchange!(params, halo, &EXCHANGES[0], sys, ws);
        rates::<D, E, X>(sys, ws, params, exec);
        // Second kick with the rates of the predicted state.
        exec.run(
            (sys.reborrow(), &ws.av[..]),
            |_, (mut s, av): (System<'_, D>, &[AvRates<D>])| {
                for k in 0..s.len() {
                    let mat = &params.materials[s.mat[k] as usize];
                    let a = &av[k];
                    s.v[k] = a.v_half + a.acc * hdt;
                    s.e[k] = a.e_half + a.de * hdt;
                    s.rho[k] = a.rho_half + a.drho * hdt;
                    if E::STRENGTH {
                        let trial = a.s_half + a.ds * hdt;
                        return_deviator::<D, E>(&mut s, k, mat, trial, a.rate, dt, true);
                    }
                    refresh_eos(&mut s, k, mat, params);
                }
            },
        );
        Ok(())
    }
}
