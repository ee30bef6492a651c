//! The per-particle updates of the contact family: kinematic (positions, density, deviator)
//! and dynamic (velocity, energy).

use crate::effects::{EffectSet, Effects};
use crate::math::Real;
use crate::schemes::common::advance_deviator;
use crate::schemes::workspace::StepParams;
use crate::state::{PairSums, System};

/// Density (eq 16) and deviator (Hooke + Jaumann + return) of local particle `k`.
#[inline(always)]
pub(super) fn kinematic_update<const D: usize, E: Effects>(
    s: &mut System<'_, D>,
    k: usize,
    mat: &crate::material::Material,
    ps: &PairSums<D>,
    hg: Option<(&mut crate::state::Hourglass<D>, Real)>,
    dt: Real,
) {
    s.rho[k] *= crate::math::real::exp(-dt * ps.div);
    if E::STRENGTH {
        match hg {
            // with the hourglass stiffness, its corrected gradient (`super::split_stress`),
            // and the stiffness yields with the material
            Some((r, xi)) => {
                crate::schemes::hourglass::advance_deviator::<D, E>(s, k, mat, r, xi, dt)
            }
            None => advance_deviator::<D, E>(s, k, mat, &ps.grad_v, dt),
        }
    }
}

/// Velocity, energy and position of local particle `k`. With correction (or pm's
/// `options.energy_equation = "total"`) the energy equation is seed 004's total energy,
/// `E += dt sum f.V*`, which with
/// `e = E - v²/2` is `de = dt (power - acc . (v + dv/2))`: exactly conservative.
#[inline(always)]
pub(super) fn dynamic_update<const D: usize, E: Effects>(
    s: &mut System<'_, D>,
    k: usize,
    ps: &PairSums<D>,
    params: &StepParams<'_, D>,
) {
    let dt = params.dt;
    let dv = ps.acc * dt;
    if super::total_energy::<D, E>(params) {
        let xdot = s.v[k] + dv * 0.5;
        s.e[k] += dt * (ps.power - ps.acc.dot(&xdot));
    } else {
        s.e[k] += dt * ps.power;
    }
    s.v[k] += dv;
    s.x[k] += s.v[k] * dt;
    if params.has::<E>(EffectSet::PERIODIC) {
        s.x[k] = params.periodic.wrap(s.x[k]);
    }
}
