//! `options.integrator = "leapfrog"` for the contact family: the predictor–corrector
//! leap-frog of `av` (kick, drift, predict; one evaluation of every rate at the predicted
//! end state; kick), second order in time with one pair pass per step.
//!
//! ```text
//! v_h  = v_n + a_n dt/2            x_n+1 = x_n + v_h dt
//! q_h  = q_n + q'_n dt/2           (q: energy, deviator; rho by its exponential)
//! predicted end state: v_h + a_n dt/2, q_h + q'_n dt/2  ->  a_n+1, q'_n+1
//! v_n+1 = v_h + a_n+1 dt/2,        q_n+1 = q_h + q'_n+1 dt/2
//! ```
//!
//! With correction (tkc) the energy advanced is the total energy `E = e + v²/2` with rate
//! `sum f.V*`, whose pair terms cancel, so total energy is conserved to round-off at
//! every step; without (pm) it is the internal energy with rate `sum f.(V* - v_i)`.
//! Density follows `rho' = -rho div v` exactly over each half step,
//! `rho_h = rho_n exp(-div_n dt/2)`. The deviator's trial states are returned to the yield
//! surface at the prediction without committing the plastic strain, temperature and
//! damage, and with committing them at the end (as `av`). The rates carry from one step to
//! the next in `Workspace::av` (`primed`).

use super::pairs::pair_pass;
use super::prepare;
use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::halo::Halo;
use crate::math::real;
use crate::schemes::common::{
    artificial_stress_tensors, deviator_rate, equivalent_strain_rate, refresh_eos, return_deviator,
};
use crate::state::{AvRates, PairSums, StepError, StepParams, System, Workspace};

/// One leap-frog step of `pm`/`tkc` (see the module).
pub(super) fn step<const D: usize, E: Effects, X: Executor>(
    sys: &mut System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
    halo: &mut dyn Halo<D>,
) -> Result<(), StepError> {
    let dt = params.dt;
    let hdt = 0.5 * dt;
    if !ws.primed {
        rates::<D, E, X>(sys, ws, params, exec, halo);
        ws.primed = true;
    }
    // kick, drift, and predict the state at the end of the step
    exec.run(
        (sys.reborrow(), &mut ws.av[..]),
        |_, (mut s, av): (System<'_, D>, &mut [AvRates<D>])| {
            for k in 0..s.len() {
                let mat = &params.materials[s.mat[k] as usize];
                let a = &mut av[k];
                a.v_half = s.v[k] + a.acc * hdt;
                a.e_half = energy::<D, E>(&s, k) + a.de * hdt;
                a.rho_half = s.rho[k] * real::exp(-hdt * a.drho);
                s.x[k] += a.v_half * dt;
                if params.has::<E>(EffectSet::PERIODIC) {
                    s.x[k] = params.periodic.wrap(s.x[k]);
                }
                s.v[k] = a.v_half + a.acc * hdt;
                set_energy::<D, E>(&mut s, k, a.e_half + a.de * hdt);
                s.rho[k] = a.rho_half * real::exp(-hdt * a.drho);
                if E::STRENGTH {
                    a.s_half = s.s[k] + a.ds * hdt;
                    let trial = a.s_half + a.ds * hdt;
                    return_deviator::<D, E>(&mut s, k, mat, trial, a.rate, dt, false);
                }
                refresh_eos(&mut s, k, mat, params);
            }
        },
    );
    rates::<D, E, X>(sys, ws, params, exec, halo);
    // second kick with the rates of the predicted state
    exec.run(
        (sys.reborrow(), &ws.av[..]),
        |_, (mut s, av): (System<'_, D>, &[AvRates<D>])| {
            for k in 0..s.len() {
                let mat = &params.materials[s.mat[k] as usize];
                let a = &av[k];
                s.v[k] = a.v_half + a.acc * hdt;
                set_energy::<D, E>(&mut s, k, a.e_half + a.de * hdt);
                s.rho[k] = a.rho_half * real::exp(-hdt * a.drho);
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

/// The energy the leap-frog advances: total with correction (tkc), internal otherwise.
#[inline(always)]
fn energy<const D: usize, E: Effects>(s: &System<'_, D>, k: usize) -> crate::math::Real {
    if E::CORRECTION {
        s.e[k] + 0.5 * s.v[k].norm_squared()
    } else {
        s.e[k]
    }
}

/// Sets the internal energy from the advanced energy (after the velocity).
#[inline(always)]
fn set_energy<const D: usize, E: Effects>(s: &mut System<'_, D>, k: usize, en: crate::math::Real) {
    s.e[k] = if E::CORRECTION {
        en - 0.5 * s.v[k].norm_squared()
    } else {
        en
    };
}

/// Every rate of the current state into `ws.av`: one pair pass with both the kinematic
/// and the dynamic sums.
fn rates<const D: usize, E: Effects, X: Executor>(
    sys: &mut System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
    halo: &mut dyn Halo<D>,
) {
    prepare::<D, E, X>(sys, ws, params, exec, halo);
    if params.has::<E>(EffectSet::ARTIFICIAL_STRESS) {
        artificial_stress_tensors::<D, E, X>(sys, ws.art, params, exec);
    }
    pair_pass::<D, E, X, true, true>(sys, ws, params, exec);
    let sysr: &System<'_, D> = sys;
    let sums: &[PairSums<D>] = ws.sums;
    exec.run(&mut *ws.av, |off, chunk: &mut [AvRates<D>]| {
        for (k, a) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let ps = &sums[i];
            let mat = &params.materials[sysr.mat[i] as usize];
            a.acc = ps.acc;
            a.de = ps.power;
            a.drho = ps.div;
            if E::STRENGTH {
                a.ds = deviator_rate(&sysr.s[i], mat, &ps.grad_v);
                a.rate = equivalent_strain_rate(&ps.grad_v);
            }
        }
    });
}
