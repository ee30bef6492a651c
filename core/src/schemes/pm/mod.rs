//! The contact (Parshikov–Medin) family: `pm` (first order) and `tkc` (TKC-MUSCL-SPH: with
//! kernel gradient correction and minmod MUSCL). Seed 000 §3.2, seed 004 §1–2.
//!
//! For each pair the full elastic Riemann problem is solved along the axis `n` from i to j
//! (longitudinal wave with `Z = rho c_l`, transverse waves with `Z = rho c_t`), giving the
//! contact velocity `V*` and traction `T*` ([`crate::riemann::acoustic_star_vector`]).
//! With `W' = dW/dr`:
//!
//! ```text
//! dv_i/dt = -2 sum_j m_j T*_ij W'_ij / (rho_i rho_j)                        (004 eq 10)
//! de_i/dt = -2 sum_j m_j T*_ij . (V*_ij - v_i) W'_ij / (rho_i rho_j)        (004 eq 11 minus kinetic part)
//! div v_i =  2 sum_j m_j/rho_j (V*_ij - v_i) . (L_i^-1 grad_i W_ij)         (004 eq 9, 19)
//! L_ab    =  2 sum_j m_j/rho_j (V*_ij - v_i)_a (L_i^-1 grad_i W_ij)_b        (004 eq 20)
//! rho    <-  rho exp(-dt div v)                                             (004 eq 16)
//! ```
//!
//! `T*` is antisymmetric and `V*` symmetric under i <-> j, so momentum is conserved to
//! round-off and the energy fluxes cancel pairwise; time integration is explicit Euler
//! (seed 004), so total energy drifts at first order in dt.
//!
//! With correction, the traction of each side is `sigma . (L_i^-1 + L_j^-1)/2 . n`
//! (symmetric in i, j, so momentum stays conserved). With MUSCL, every reconstructed
//! quantity Phi (rho, c_l, c_t, and the components of the velocity and of the traction
//! in the pair's frame) is extrapolated to the contact with
//! `Phi_l = Phi_i + minmod(Phi_j - Phi_i, grad Phi_i . r_ji)/2` and
//! `Phi_r = Phi_j - minmod(grad Phi_j . r_ji, Phi_j - Phi_i)/2` (004 eqs 13–15).
//! Seed 004 reconstructs the Cartesian stress and velocity components; limiting them in
//! the scene's axes makes the result depend on how the scene is oriented, so in 2D the
//! vectors are limited in the frame `(n, t)` of the pair instead (the traction from the
//! reconstructed stress slopes, two reconstructions instead of six); in 3D in the scene's
//! axes (see `pairs::pair_basis`).
//!
//! `options.objective` (the default; 2D/3D with strength): the velocities enter the
//! Riemann problem less the pair's mean rigid rotation, `v_i + W r_ji/2` and
//! `v_j - W r_ji/2` with `W` the mean of the two particles' spins (the antisymmetric part
//! of the velocity gradient corrected with the full `L^-1`, `gradients.rs`); the MUSCL
//! slopes are taken less `W` too. A rigid rotation then has no jump, so the transverse
//! problems do not dissipate it; `W r_ji` is normal to `n`, so the longitudinal problem
//! is unchanged.

pub(crate) mod gradients;
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
pub(crate) mod lanes;
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
mod lanes_frame;
mod leapfrog;
mod options;
pub(crate) mod pairs;
mod particles;
pub(crate) mod records;
mod volume;

pub(crate) use gradients::{correction_pass, gradient_pass};
use gradients::{objective, spin_pass};
pub(crate) use options::{defaults, reads};
use pairs::pair_pass;
use particles::{dynamic_update, kinematic_update};

use crate::effects::{EffectSet, Effects};
use crate::exec::{Executor, Optional};
use crate::halo::{Exchange, Fields, Halo};
use crate::schemes::common::{
    artificial_stress_tensors, halo_exchange, refresh_aux, refresh_eos, refresh_pressure,
};
use crate::schemes::family::SchemeFamily;
use crate::schemes::hourglass;
use crate::schemes::options::{EnergyEquation, Integrator, SchemeOptions, SpecificVolume};
use crate::schemes::pairs::geometry_pass;
use crate::schemes::scheme::Family;
use crate::schemes::workspace::{Layout, StepParams, Workspace};
use crate::state::{Hourglass, PairGeom, PairSums, StepError, System};
pub use records::{record_len, PmStar};

/// The halo exchanges of a `pm`/`tkc` step, in order (see [`crate::halo`]).
///
/// 1. At the start: x, h (pair geometry); v, rho, p, c_l, S, damage (the kernel
///    correction, the gradients, the Riemann problems; aux and c_t are recomputed locally
///    from rho).
/// 2. Before the pair pass, with correction, MUSCL or strength: the corrections and
///    gradients of both sides of every pair (with strength the spin of
///    `options.objective`), and the records of the hourglass stiffness (effect
///    `hourglass`).
/// 3. With MUSCL, after the kinematic update (rho, S, p, c_l, damage changed) and before
///    the dynamic pair pass.
pub const EXCHANGES: [Exchange; 3] = [
    Exchange {
        before: "correction+gradients",
        fields: Fields::STRESS_STATE,
        needs: EffectSet::HYDRO,
        needs_any: EffectSet::HYDRO,
    },
    Exchange {
        before: "pair",
        fields: Fields::CORR
            .with(Fields::GRAD)
            .with(Fields::GRAD_STRESS)
            .with(Fields::HOURGLASS),
        needs: EffectSet::HYDRO,
        needs_any: EffectSet::CORRECTION
            .union(EffectSet::MUSCL)
            .union(EffectSet::STRENGTH),
    },
    Exchange {
        before: "dynamic pair",
        fields: Fields::RHO
            .with(Fields::S)
            .with(Fields::P)
            .with(Fields::CL)
            .with(Fields::DAMAGE),
        needs: EffectSet::MUSCL,
        needs_any: EffectSet::HYDRO,
    },
];

/// The contact family (`pm`, `tkc`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Pm;

impl SchemeFamily for Pm {
    const FAMILY: Family = Family::Pm;
    const SUPPORTED: EffectSet = EffectSet::STRENGTH
        .union(EffectSet::PLASTICITY)
        .union(EffectSet::DAMAGE)
        .union(EffectSet::HEAT)
        .union(EffectSet::PERIODIC)
        .union(EffectSet::CORRECTION)
        .union(EffectSet::MUSCL)
        .union(EffectSet::ARTIFICIAL_STRESS)
        .union(EffectSet::HOURGLASS);
    const EXCHANGES: &'static [Exchange] = &EXCHANGES;

    fn layout(effects: EffectSet, options: &SchemeOptions) -> Layout {
        Layout {
            grad_stress: effects.contains(EffectSet::MUSCL)
                && effects.contains(EffectSet::STRENGTH),
            // the spin of `options.objective` lives in the gradients
            // and the specific volume's slopes of `options.specific_volume`
            grad: effects.contains(EffectSet::MUSCL)
                || effects.contains(EffectSet::STRENGTH)
                || options.specific_volume == SpecificVolume::Interpolated,
            pm_star: true,
            // the leap-frog's rates and half-step state
            av: options.integrator == Integrator::Leapfrog,
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
        if params.options.integrator == Integrator::Leapfrog {
            return leapfrog::step::<D, E, X>(sys, ws, params, exec, halo);
        }
        let dt = params.dt;
        let [_, _, dynamic] = &EXCHANGES;
        prepare::<D, E, X>(sys, ws, params, exec, halo);
        if E::MUSCL {
            // With MUSCL the Riemann dissipation nearly vanishes in smooth flow, and the
            // explicit Euler of the seed (forces and strain rates from the same old state)
            // amplifies waves: a sound pulse gained 6 % kinetic energy in 1 us. So, as in
            // `ts`, density and deviator are advanced first from the contact velocities of
            // the old state, and the forces then use the new stresses (symplectic Euler);
            // the reconstruction slopes of the second pass are those of the first.
            pair_pass::<D, E, X, true, false>(sys, ws, params, exec);
            let hg: &mut [Hourglass<D>] = if split_stress::<D, E>(params) {
                ws.hg
            } else {
                &mut []
            };
            exec.run(
                (sys.reborrow(), (&ws.sums[..], Optional(hg))),
                |_, (mut s, (sums, hg)): (System<'_, D>, (&[PairSums<D>], Optional<Hourglass<D>>))| {
                    for k in 0..s.len() {
                        let mat = &params.materials[s.mat[k] as usize];
                        kinematic_update::<D, E>(&mut s, k, mat, &sums[k], hg.0.get_mut(k).map(|r| (r, params.options.hourglass)), dt);
                        refresh_pressure(&mut s, k, mat);
                    }
                },
            );
            halo_exchange!(params, halo, dynamic, sys, ws);
            refresh_aux::<D, true, X>(sys, ws.aux, params, exec);
            if params.has::<E>(EffectSet::ARTIFICIAL_STRESS) {
                artificial_stress_tensors::<D, E, X>(sys, ws.art, params, exec);
            }
            pair_pass::<D, E, X, false, true>(sys, ws, params, exec);
            stiffness_forces::<D, E, X>(sys, ws, params, exec);
            exec.run(
                (sys.reborrow(), &ws.sums[..]),
                |_, (mut s, sums): (System<'_, D>, &[PairSums<D>])| {
                    for k in 0..s.len() {
                        let mat = &params.materials[s.mat[k] as usize];
                        dynamic_update::<D, E>(&mut s, k, &sums[k], params);
                        refresh_eos(&mut s, k, mat, params);
                    }
                },
            );
        } else {
            if params.has::<E>(EffectSet::ARTIFICIAL_STRESS) {
                artificial_stress_tensors::<D, E, X>(sys, ws.art, params, exec);
            }
            pair_pass::<D, E, X, true, true>(sys, ws, params, exec);
            stiffness_forces::<D, E, X>(sys, ws, params, exec);
            let hg: &mut [Hourglass<D>] = if split_stress::<D, E>(params) {
                ws.hg
            } else {
                &mut []
            };
            exec.run(
                (sys.reborrow(), (&ws.sums[..], Optional(hg))),
                |_, (mut s, (sums, hg)): (System<'_, D>, (&[PairSums<D>], Optional<Hourglass<D>>))| {
                    for k in 0..s.len() {
                        let mat = &params.materials[s.mat[k] as usize];
                        // explicit Euler (seed 000): every rate from the same old state
                        dynamic_update::<D, E>(&mut s, k, &sums[k], params);
                        kinematic_update::<D, E>(&mut s, k, mat, &sums[k], hg.0.get_mut(k).map(|r| (r, params.options.hourglass)), dt);
                        refresh_eos(&mut s, k, mat, params);
                    }
                },
            );
        }
        Ok(())
    }
}

/// Whether the deviator acts through a central force instead of the Riemann problem:
/// with the hourglass stiffness (effect `hourglass`), the deviator is advanced with the
/// stiffness's kernel-corrected gradient of the pair velocities and acts through that
/// gradient's adjoint, `f_i = sum_j V_i V_j (S_i C_i + S_j C_j) grad_i W_ij`, whose power is
/// exactly minus the stress power that stores the strain energy and whose torque
/// vanishes; the Riemann problems carry the pressure (the longitudinal and transverse
/// velocity jumps with pressure tractions). Without it the deviator's rate from the
/// contact velocities and its force from the Riemann tractions are not each other's
/// adjoint, and with `dissipation = "compression"` the stresses store strain energy no
/// force gave them: the breathing ring's (KE + SE)/E0 reached 5.0 (tkc) with the
/// stiffness alone (issue 46).
#[inline(always)]
pub(super) fn split_stress<const D: usize, E: Effects>(params: &StepParams<'_, D>) -> bool {
    E::STRENGTH && hourglass::on::<D, E>(params)
}

/// Whether the step books the total energy (`sum f t*.v*`, exact): always with kernel
/// correction (`tkc`, Rublev & Murzov eq 11), for `pm` with `options.energy_equation =
/// "total"`; else the seed's internal-energy rate at the start-of-step velocity.
#[inline(always)]
pub(super) fn total_energy<const D: usize, E: Effects>(params: &StepParams<'_, D>) -> bool {
    E::CORRECTION || params.options.energy_equation == EnergyEquation::Total
}

/// What every pair pass of a step reads besides the particles: the start exchange, the
/// pair geometry, the per-particle aux, the kernel correction, the spin and the MUSCL
/// gradients, and their exchange.
fn prepare<const D: usize, E: Effects, X: Executor>(
    sys: &mut System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
    halo: &mut dyn Halo<D>,
) {
    let [start, pair, _] = &EXCHANGES;
    halo_exchange!(params, halo, start, sys, ws);
    geometry_pass::<D, E, X>(sys.x, sys.h, params, ws.geom, ws.fac, exec);
    refresh_aux::<D, true, X>(sys, ws.aux, params, exec);
    {
        let sysr: &System<'_, D> = sys;
        let geom: &[PairGeom<D>] = ws.geom;
        if E::MUSCL {
            // the kernel correction and the spin come with the gradients
            gradient_pass::<D, E, X>(
                sysr,
                geom,
                ws.aux,
                ws.corr,
                ws.sums,
                ws.grad,
                ws.grad_stress,
                params,
                exec,
            );
        } else {
            if E::CORRECTION {
                correction_pass::<D, X>(sysr, geom, ws.aux, ws.corr, ws.sums, params, exec);
            }
            if objective::<D, E>(params) {
                spin_pass::<D, X>(sysr, geom, ws.aux, ws.grad, params, exec);
            }
        }
        if params.options.specific_volume == SpecificVolume::Interpolated {
            volume::specific_volume_pass::<D, X>(sysr, geom, ws.grad, params, exec);
        }
    }
    if hourglass::on::<D, E>(params) {
        if params.options.integrator == Integrator::Leapfrog {
            // the rate, which the leap-frog integrates with the others
            let half = ws.primed.then_some(0.5 * params.dt);
            hourglass::rates::<D, X>(sys, ws.geom, ws.aux, ws.hg, ws.av, params, half, exec);
        } else {
            // from the start-of-step velocities and positions, as the deviator
            hourglass::update::<D, X>(sys, ws.geom, ws.aux, ws.hg, params, exec);
        }
    }
    halo_exchange!(params, halo, pair, sys, ws);
}

/// The hourglass stiffness's force added to the dynamic pair pass's sums (effect
/// `hourglass`), its power booked as the step's energy equation books the pairs'.
pub(super) fn stiffness_forces<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
) {
    if !hourglass::on::<D, E>(params) {
        return;
    }
    if total_energy::<D, E>(params) {
        hourglass::add_forces::<D, X, false>(sys, ws.geom, ws.hg, ws.sums, params, exec);
    } else {
        hourglass::add_forces::<D, X, true>(sys, ws.geom, ws.hg, ws.sums, params, exec);
    }
}
