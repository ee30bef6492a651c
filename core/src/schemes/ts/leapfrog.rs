//! `options.integrator = "leapfrog"` for the time-split family: instead of the
//! Lie–Trotter split of symplectic-Euler sub-steps (first order in time), the shared
//! leap-frog (`core/src/schemes/leapfrog.rs`) with every rate of the split evaluated at once
//! at the predicted state: the contact velocities of the continuity equation, the
//! deviator's rate, the deviatoric forces `F_ij` and the hydrodynamic forces `G_ij` of the
//! same Riemann states. The energy advanced is the total energy `E = e + v²/2` with rate
//! `sum_j (F_ij . vbar_ij + G_ij . u*_ij n_ij)/m_i`, whose pair terms cancel (`F`, `G`
//! antisymmetric, `vbar`, `u* n` symmetric), so total energy is conserved to round-off as
//! in the split. Density follows `rho' = -rho div` exactly over each half step.

use super::pairs::{deviatoric_pass, hydro_pass};
use super::{kinematics, EXCHANGES};
use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::halo::Halo;
use crate::math::{Real, Vector};
use crate::schemes::av::records::AvRates;
use crate::schemes::common::{
    artificial_stress_tensors, deviator_rate, equivalent_strain_rate, halo_exchange,
};
use crate::schemes::hourglass;
use crate::schemes::leapfrog;
use crate::schemes::workspace::{StepParams, Workspace};
use crate::state::{Hourglass, PairGeom, PairSums, StepError, System};

/// One leap-frog step of `ts1`/`ts2` (see the module).
pub(super) fn step<const D: usize, E: Effects, X: Executor>(
    sys: &mut System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
    halo: &mut dyn Halo<D>,
) -> Result<(), StepError> {
    leapfrog::step::<D, E, X, true, true>(sys, ws, params, exec, |sys, ws| {
        rates::<D, E, X>(sys, ws, params, exec, halo)
    })
}

/// Every rate of the current state into `ws.av`: the split's passes without the updates
/// between them.
fn rates<const D: usize, E: Effects, X: Executor>(
    sys: &mut System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
    halo: &mut dyn Halo<D>,
) {
    let [_, _, deviatoric, _] = &EXCHANGES;
    kinematics::<D, E, X>(sys, ws, params, exec, halo);
    let stiff = hourglass::on::<D, E>(params);
    if stiff {
        let half = ws.primed.then_some(0.5 * params.dt);
        hourglass::rates::<D, X>(sys, ws.geom, ws.aux, ws.hg, ws.av, params, half, exec);
    }
    let (geom, fac): (&[PairGeom<D>], &[Real]) = (ws.geom, ws.fac);
    // the deviatoric forces read S of the neighbours (and the stiffness's records)
    halo_exchange!(params, halo, deviatoric, sys, ws);
    let hg: &[Hourglass<D>] = if stiff { ws.hg } else { &[] };
    let sysr: &System<'_, D> = sys;
    {
        let sums: &[PairSums<D>] = ws.sums;
        exec.run(&mut *ws.av, |off, chunk: &mut [AvRates<D>]| {
            for (k, a) in chunk.iter_mut().enumerate() {
                let i = off + k;
                let ps = &sums[i];
                a.drho = ps.div;
                a.acc = Vector::<D>::zeros();
                a.de = 0.0;
                if E::STRENGTH {
                    let mat = &params.materials[sysr.mat[i] as usize];
                    // with the stiffness, the corrected gradient (see the split)
                    let grad_v = match hg.get(i) {
                        Some(r) => &r.l,
                        None => &ps.grad_v,
                    };
                    a.ds = deviator_rate(&sysr.s[i], mat, grad_v);
                    a.rate = equivalent_strain_rate(grad_v);
                }
            }
        });
    }
    let art_on = params.has::<E>(EffectSet::ARTIFICIAL_STRESS);
    if art_on {
        artificial_stress_tensors::<D, E, X>(sys, ws.art, params, exec);
    }
    if E::STRENGTH || art_on {
        deviatoric_pass::<D, E, X>(sys, geom, ws.aux, ws.art, fac, hg, ws.sums, params, exec);
        if stiff {
            hourglass::add_forces::<D, X, false>(sys, geom, hg, ws.sums, params, exec);
        }
        add_forces(ws.av, ws.sums, exec);
    }
    hydro_pass::<D, E, X>(
        sys, ws.grad, geom, ws.aux, ws.ts_star, ws.rec, ws.sums, params, exec,
    );
    add_forces(ws.av, ws.sums, exec);
}

/// Adds a pass's acceleration and power to the rates.
fn add_forces<const D: usize, X: Executor>(av: &mut [AvRates<D>], sums: &[PairSums<D>], exec: &X) {
    exec.run(av, |off, chunk: &mut [AvRates<D>]| {
        for (k, a) in chunk.iter_mut().enumerate() {
            let ps = &sums[off + k];
            a.acc += ps.acc;
            a.de += ps.power;
        }
    });
}
