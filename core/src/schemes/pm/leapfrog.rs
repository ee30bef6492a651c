//! `options.integrator = "leapfrog"` for the contact family: the shared leap-frog
//! (`core/src/schemes/leapfrog.rs`) with one pair pass per step. With correction (tkc) the
//! energy advanced is the total energy `E = e + v²/2` with rate `sum f.V*`, whose pair
//! terms cancel, so total energy is conserved to round-off at every step; without (pm) it
//! is the internal energy with rate `sum f.(V* - v_i)`. Density follows
//! `rho' = -rho div v` exactly over each half step.

use super::pairs::pair_pass;
use super::prepare;
use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::halo::Halo;
use crate::schemes::av::records::AvRates;
use crate::schemes::common::{artificial_stress_tensors, deviator_rate, equivalent_strain_rate};
use crate::schemes::leapfrog;
use crate::schemes::workspace::{StepParams, Workspace};
use crate::state::{PairSums, StepError, System};

/// One leap-frog step of `pm`/`tkc` (`core/src/schemes/leapfrog.rs`): density by its
/// exponential, the total energy with correction (tkc) or `options.energy_equation =
/// "total"`, else the internal energy (pm, the seed's).
pub(super) fn step<const D: usize, E: Effects, X: Executor>(
    sys: &mut System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
    halo: &mut dyn Halo<D>,
) -> Result<(), StepError> {
    let eval = |sys: &mut System<'_, D>, ws: &mut Workspace<'_, D>| {
        rates::<D, E, X>(sys, ws, params, exec, halo)
    };
    if super::total_energy::<D, E>(params) {
        leapfrog::step::<D, E, X, true, true>(sys, ws, params, exec, eval)
    } else {
        leapfrog::step::<D, E, X, true, false>(sys, ws, params, exec, eval)
    }
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
    super::stiffness_forces::<D, E, X>(sys, ws, params, exec);
    let sysr: &System<'_, D> = sys;
    let sums: &[PairSums<D>] = ws.sums;
    let hg: &[crate::state::Hourglass<D>] = if super::split_stress::<D, E>(params) {
        ws.hg
    } else {
        &[]
    };
    exec.run(&mut *ws.av, |off, chunk: &mut [AvRates<D>]| {
        for (k, a) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let ps = &sums[i];
            let mat = &params.materials[sysr.mat[i] as usize];
            a.acc = ps.acc;
            a.de = ps.power;
            a.drho = ps.div;
            if E::STRENGTH {
                // with the stiffness, its corrected gradient (`super::split_stress`)
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
