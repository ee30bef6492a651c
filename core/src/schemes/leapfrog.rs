//! The predictor–corrector leap-frog every family can step with: `av` always, `pm`/`tkc`
//! and `ts1`/`ts2` with `options.integrator = "leapfrog"` (kick, drift, predict; one
//! evaluation of every rate at the predicted end state; kick), second order in time with
//! one rate evaluation per step.
//!
//! ```text
//! v_h  = v_n + a_n dt/2            x_n+1 = x_n + v_h dt
//! q_h  = q_n + q'_n dt/2           (q: energy, deviator; density, see `EXP`)
//! predicted end state: v_h + a_n dt/2, q_h + q'_n dt/2  ->  a_n+1, q'_n+1
//! v_n+1 = v_h + a_n+1 dt/2,        q_n+1 = q_h + q'_n+1 dt/2
//! ```
//!
//! Each family says how it advances two fields (const parameters of [`step`]):
//! - `EXP`: density by `rho' = -rho div v` exactly over each half step,
//!   `rho_h = rho_n exp(-div_n dt/2)` (the rate in [`AvRates::drho`] is then the
//!   divergence), or by `rho_h = rho_n + rho'_n dt/2` (`av`).
//! - `TOTAL`: the energy advanced is the total energy `E = e + v²/2`, whose rate is a sum
//!   of pair terms that cancel (tkc, ts), so total energy is conserved to round-off at
//!   every step; otherwise the internal energy (`av`, `pm`).
//!
//! The deviator's trial states are returned to the yield surface at the prediction without
//! committing the plastic strain, temperature and damage, and with committing them at the
//! end. The rates carry from one step to the next in `Workspace::av` (`primed`); `rates`
//! fills them from the current state (halo exchanges included).

use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::math::{real, Real};
use crate::schemes::av::records::AvRates;
use crate::schemes::common::{refresh_eos, return_deviator};
use crate::schemes::workspace::{StepParams, Workspace};
use crate::state::{StepError, System};

/// One leap-frog step (see the module); `rates(sys, ws)` evaluates every rate of the
/// state in `sys` into `ws.av`.
pub(crate) fn step<const D: usize, E: Effects, X: Executor, const EXP: bool, const TOTAL: bool>(
    sys: &mut System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
    mut rates: impl FnMut(&mut System<'_, D>, &mut Workspace<'_, D>),
) -> Result<(), StepError> {
    let dt = params.dt;
    let hdt = 0.5 * dt;
    // the hourglass displacement (effect `hourglass`) is advanced as the deviator
    let stiff = params.has::<E>(EffectSet::HOURGLASS);
    if !ws.primed {
        rates(sys, ws);
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
                a.e_half = energy::<D, TOTAL>(&s, k) + a.de * hdt;
                a.rho_half = density::<EXP>(s.rho[k], a.drho, hdt);
                s.x[k] += a.v_half * dt;
                if params.has::<E>(EffectSet::PERIODIC) {
                    s.x[k] = params.periodic.wrap(s.x[k]);
                }
                s.v[k] = a.v_half + a.acc * hdt;
                set_energy::<D, TOTAL>(&mut s, k, a.e_half + a.de * hdt);
                s.rho[k] = density::<EXP>(a.rho_half, a.drho, hdt);
                if E::STRENGTH {
                    a.s_half = s.s[k] + a.ds * hdt;
                    let trial = a.s_half + a.ds * hdt;
                    return_deviator::<D, E>(&mut s, k, mat, trial, a.rate, dt, false);
                }
                if stiff {
                    a.hg_half = s.hg[k] + a.dhg * hdt;
                    s.hg[k] = a.hg_half + a.dhg * hdt;
                }
                refresh_eos(&mut s, k, mat, params);
            }
        },
    );
    rates(sys, ws);
    // second kick with the rates of the predicted state
    exec.run(
        (sys.reborrow(), &ws.av[..]),
        |_, (mut s, av): (System<'_, D>, &[AvRates<D>])| {
            for k in 0..s.len() {
                let mat = &params.materials[s.mat[k] as usize];
                let a = &av[k];
                s.v[k] = a.v_half + a.acc * hdt;
                set_energy::<D, TOTAL>(&mut s, k, a.e_half + a.de * hdt);
                s.rho[k] = density::<EXP>(a.rho_half, a.drho, hdt);
                if E::STRENGTH {
                    let trial = a.s_half + a.ds * hdt;
                    return_deviator::<D, E>(&mut s, k, mat, trial, a.rate, dt, true);
                }
                // the hourglass displacement was completed by `rates`
                // (`crate::schemes::hourglass::rates`)
                refresh_eos(&mut s, k, mat, params);
            }
        },
    );
    Ok(())
}

/// Density `rho` advanced by half a step `hdt` with rate `drho` (a divergence if `EXP`).
#[inline(always)]
fn density<const EXP: bool>(rho: Real, drho: Real, hdt: Real) -> Real {
    if EXP {
        rho * real::exp(-hdt * drho)
    } else {
        rho + drho * hdt
    }
}

/// The energy the leap-frog advances: total if `TOTAL`, internal otherwise.
#[inline(always)]
fn energy<const D: usize, const TOTAL: bool>(s: &System<'_, D>, k: usize) -> Real {
    if TOTAL {
        s.e[k] + 0.5 * s.v[k].norm_squared()
    } else {
        s.e[k]
    }
}

/// Sets the internal energy from the advanced energy (after the velocity).
#[inline(always)]
fn set_energy<const D: usize, const TOTAL: bool>(s: &mut System<'_, D>, k: usize, en: Real) {
    s.e[k] = if TOTAL {
        en - 0.5 * s.v[k].norm_squared()
    } else {
        en
    };
}
