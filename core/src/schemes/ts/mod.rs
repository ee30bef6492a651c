//! The time-split family: `ts1` and `ts2` (seed 000 §3.3–3.4).
//!
//! Each step is a Lie–Trotter split: a deviatoric step without dissipation, then a
//! hydrodynamic step with a longitudinal Riemann problem per pair. With
//! `F_ij = m_i m_j (S_i + S_j)/(rho_i rho_j) . grad_i W_ij` (antisymmetric) and
//! `G_ij = -2 m_i m_j P*_ij/(rho_i rho_j) grad_i W_ij` (antisymmetric):
//!
//! ```text
//! kinematics:  rho_i <- rho_i exp(-dt div_i),  div_i = 2 sum_j m_j/rho_j (u*_ij n_ij - v_i) . grad_i W_ij   (eq 22)
//!              S_i   <- S_i + dt (2G dev(sym L_i) + W.S - S.W), plastic return,  L_i = sum_j V_j (v_j - v_i) ⊗ grad_i W_ij
//! deviatoric:  m_i dv_i = dt sum_j F_ij,            xdot_i = v_i + dv_i/2
//!              m_i de_i = dt sum_j F_ij . (vbar_ij - xdot_i),  vbar_ij = (v_i + v_j)/2                         (eq 32)
//! hydro:       m_i dv_i = dt sum_j G_ij,            xdot_i = v~_i + dv_i/2
//!              m_i de_i = dt sum_j G_ij . (u*_ij n_ij - xdot_i)                                                 (eq 34)
//! ```
//!
//! Energy is conserved to round-off: in each sub-step the kinetic energy change is
//! `sum_i m_i dv_i . xdot_i` exactly (because `xdot_i = v_i + dv_i/2`), which cancels the
//! `-xdot_i` term of the energy equation, and what is left, `sum_ij F_ij . vbar_ij` or
//! `sum_ij G_ij . u*_ij n_ij`, vanishes because `F`, `G` are antisymmetric and `vbar`,
//! `u* n` symmetric under i <-> j (seed 000 eqs 30–35).
//!
//! **Order of the updates.** Density and deviator are advanced first, from the state at
//! the start of the step, and the forces then use the new pressure and deviator: each
//! sub-step is symplectic Euler. Done the other way round (forces from the old state,
//! then density and deviator, as a literal reading of the seed suggests) it is forward
//! Euler, whose amplification factor `|1 + i w dt| > 1` makes waves grow wherever the
//! Riemann dissipation vanishes: always in the deviatoric step and in smooth flow with
//! MUSCL (measurements in docs/ts2_reconstruction.md, "History of the ts code").
//! `tests/tests/standing_wave.rs` guards this.
//!
//! **Riemann problem.** It uses the bulk sound speed (it carries pressure only) and is
//! acoustic or two-shock. `ts2` reconstructs P, rho and the normal velocity at the
//! contact (eq 23), `Q_l = Q_i + (r/2) phi(r_i) (grad Q_i . n) f_i` with
//! `r_i = (grad Q_j . n)/(grad Q_i . n)` (eq 25), each side's extrapolation bounded by
//! half the pair difference (see `reconstruct`). One reconstruction serves every use of
//! the pair's star state: the contact velocity of the continuity equation (eq 22) and the
//! contact pressure and velocity of the momentum and energy equations (eq 34) come from
//! the same left/right states, as in the seed. Eq 23 prints the factor `[1 - c_i dt]`,
//! which has units of length; divided by the pair distance it becomes the MUSCL–Hancock
//! factor `f_i = max(0, 1 - c_i dt / r_ij)` ([`MusclTime::CourantFactor`](crate::schemes::options::MusclTime::CourantFactor)); a genuine
//! half-step predictor is [`MusclTime::Predictor`](crate::schemes::options::MusclTime::Predictor); the default is the spatial
//! reconstruction alone (`f = 1`, [`MusclTime::None`](crate::schemes::options::MusclTime::None)): the most accurate of the three,
//! and with the bounded extrapolation and the symplectic-Euler ordering it keeps an
//! elastic standing wave bounded (measurements in docs/ts2_reconstruction.md).
//!
//! Failed particles (damage = 1; seed 000 Algorithm 1) are handled in
//! `riemann_states`: the place where first order is forced and tension is cut.

mod gradients;
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
pub(crate) mod lanes;
mod leapfrog;
mod options;
pub(crate) mod pairs;
pub(crate) mod records;

use gradients::front_gradient_pass;
pub(crate) use options::reads;
use pairs::{continuity_pass, deviatoric_pass, hydro_pass};

use crate::effects::{EffectSet, Effects};
use crate::exec::{Executor, Optional};
use crate::halo::{Exchange, Fields, Halo};
use crate::math::{real, Real};
use crate::schemes::common::{
    advance_deviator, artificial_stress_tensors, halo_exchange, refresh_aux, refresh_eos,
    refresh_pressure,
};
use crate::schemes::family::SchemeFamily;
use crate::schemes::hourglass;
use crate::schemes::options::{Integrator, SchemeOptions};
use crate::schemes::pairs::geometry_pass;
use crate::schemes::scheme::Family;
use crate::schemes::workspace::{Layout, StepParams, Workspace};
use crate::state::{Hourglass, PairGeom, PairSums, StepError, System};
pub use records::{record_len, TsStar};

/// The halo exchanges of a `ts` step, in order (see [`crate::halo`]).
///
/// 1. Before the front gradients (and the pair geometry): x, h; v, rho, p, damage (the
///    gradients and the free-surface test; aux is recomputed locally from rho) and c (the
///    continuity pass's Riemann problems).
/// 2. Before the continuity pass, with MUSCL: the gradients (its reconstruction reads the
///    slopes of both sides of every pair).
/// 3. After the continuity update (rho, S, p, c, damage changed): the deviatoric pass reads
///    S, p, damage and aux (from rho), and the hourglass force the records of the
///    stiffness's update (effect `hourglass`); without it the hydro pass is next and
///    reads rho, p, c, damage.
/// 4. Before the hydro pass, after the deviatoric update (v, e and so p, c changed).
pub const EXCHANGES: [Exchange; 4] = [
    Exchange {
        before: "front gradients",
        fields: Fields::X
            .with(Fields::H)
            .with(Fields::V)
            .with(Fields::RHO)
            .with(Fields::P)
            .with(Fields::C)
            .with(Fields::DAMAGE),
        needs: EffectSet::HYDRO,
        needs_any: EffectSet::HYDRO,
    },
    Exchange {
        before: "continuity",
        fields: Fields::GRAD,
        needs: EffectSet::MUSCL,
        needs_any: EffectSet::HYDRO,
    },
    Exchange {
        before: "deviatoric",
        fields: Fields::RHO
            .with(Fields::S)
            .with(Fields::P)
            .with(Fields::C)
            .with(Fields::DAMAGE)
            .with(Fields::HOURGLASS),
        needs: EffectSet::HYDRO,
        needs_any: EffectSet::HYDRO,
    },
    Exchange {
        before: "hydro",
        fields: Fields::V.with(Fields::P).with(Fields::C),
        needs: EffectSet::HYDRO,
        needs_any: EffectSet::STRENGTH.union(EffectSet::ARTIFICIAL_STRESS),
    },
];

/// The time-split family (`ts1`, `ts2`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Ts;

impl SchemeFamily for Ts {
    const FAMILY: Family = Family::Ts;
    const SUPPORTED: EffectSet = EffectSet::STRENGTH
        .union(EffectSet::PLASTICITY)
        .union(EffectSet::DAMAGE)
        .union(EffectSet::HEAT)
        .union(EffectSet::PERIODIC)
        .union(EffectSet::MUSCL)
        .union(EffectSet::ARTIFICIAL_STRESS)
        .union(EffectSet::HOURGLASS);
    const EXCHANGES: &'static [Exchange] = &EXCHANGES;

    fn layout(effects: EffectSet, options: &SchemeOptions) -> Layout {
        Layout {
            ts_star: true,
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
        // 1. Kinematics at the start of the step: gradients, then density from the contact
        //    velocities (seed 000 eq 22) and the deviator from the velocity gradient.
        //    Updating density and deviator before the forces that use them makes every
        //    sub-step symplectic Euler. The opposite order (forces from the old state,
        //    then density and deviator) is forward Euler, whose amplification factor
        //    |1 + i w dt| > 1 lets waves grow wherever the Riemann dissipation vanishes:
        //    always in the deviatoric step, and in smooth flow with MUSCL.
        let [_, _, deviatoric, hydro] = &EXCHANGES;
        kinematics::<D, E, X>(sys, ws, params, exec, halo);
        let stiff = hourglass::on::<D, E>(params);
        if stiff {
            // from the start-of-step velocities and positions, as the deviator
            hourglass::update::<D, X>(sys, ws.geom, ws.aux, ws.hg, params, exec);
        }
        let (geom, fac): (&[PairGeom<D>], &[Real]) = (ws.geom, ws.fac);
        let hg_mut: &mut [Hourglass<D>] = if stiff { ws.hg } else { &mut [] };
        exec.run(
            (sys.reborrow(), (&ws.sums[..], Optional(hg_mut))),
            |_, (mut s, (sums, hg)): (System<'_, D>, (&[PairSums<D>], Optional<Hourglass<D>>))| {
                for k in 0..s.len() {
                    let mat = &params.materials[s.mat[k] as usize];
                    s.rho[k] *= real::exp(-dt * sums[k].div);
                    if E::STRENGTH {
                        // with the stiffness, the corrected gradient (module docs), and
                        // the tensor of the fused force from the advanced deviator
                        match hg.0.get_mut(k) {
                            Some(r) => {
                                let xi = params.options.hourglass;
                                hourglass::advance_deviator::<D, E>(&mut s, k, mat, r, xi, dt);
                                hourglass::fuse_stress(r, &s.s[k]);
                            }
                            None => advance_deviator::<D, E>(&mut s, k, mat, &sums[k].grad_v, dt),
                        }
                    }
                    refresh_pressure(&mut s, k, mat);
                }
            },
        );
        halo_exchange!(params, halo, deviatoric, sys, ws);
        let hg: &[Hourglass<D>] = if stiff { ws.hg } else { &[] };
        // 2. Deviatoric step (with strength or artificial stress): no dissipation.
        refresh_aux::<D, false, X>(sys, ws.aux, params, exec);
        let art_on = params.has::<E>(EffectSet::ARTIFICIAL_STRESS);
        if art_on {
            artificial_stress_tensors::<D, E, X>(sys, ws.art, params, exec);
        }
        if E::STRENGTH || art_on {
            if stiff && !art_on {
                // the deviator's and the stiffness's forces in one pass
                hourglass::stress_forces::<D, X>(sys, geom, hg, ws.sums, params, exec);
            } else {
                deviatoric_pass::<D, E, X>(
                    sys, geom, ws.aux, ws.art, fac, hg, ws.sums, params, exec,
                );
                if stiff {
                    hourglass::add_forces::<D, X, false>(sys, geom, hg, ws.sums, params, exec);
                }
            }
            exec.run(
                (sys.reborrow(), &ws.sums[..]),
                |_, (mut s, sums): (System<'_, D>, &[PairSums<D>])| {
                    for k in 0..s.len() {
                        let ps = &sums[k];
                        let dv = ps.acc * dt;
                        let xdot = s.v[k] + dv * 0.5;
                        s.e[k] += dt * (ps.power - ps.acc.dot(&xdot));
                        s.v[k] += dv;
                        let mat = &params.materials[s.mat[k] as usize];
                        refresh_pressure(&mut s, k, mat);
                    }
                },
            );
        }
        // 3. Hydrodynamic step with the new pressure (reconstruction slopes from step 1).
        halo_exchange!(params, halo, hydro, sys, ws);
        hydro_pass::<D, E, X>(
            sys, ws.grad, geom, ws.aux, ws.ts_star, ws.rec, ws.sums, params, exec,
        );
        exec.run(
            (sys.reborrow(), &ws.sums[..]),
            |_, (mut s, sums): (System<'_, D>, &[PairSums<D>])| {
                for k in 0..s.len() {
                    let mat = &params.materials[s.mat[k] as usize];
                    let ps = &sums[k];
                    let dv = ps.acc * dt;
                    let xdot = s.v[k] + dv * 0.5;
                    s.e[k] += dt * (ps.power - ps.acc.dot(&xdot));
                    s.v[k] += dv;
                    s.x[k] += (ps.v0 + s.v[k]) * (0.5 * dt);
                    if params.has::<E>(EffectSet::PERIODIC) {
                        s.x[k] = params.periodic.wrap(s.x[k]);
                    }
                    refresh_eos(&mut s, k, mat, params);
                }
            },
        );
        Ok(())
    }
}

/// The kinematic sums of the state in `sys` (the split's step 1 and the leap-frog's
/// rates): pair geometry, aux, the front gradients and the divergence from the contact
/// velocities into `ws.sums`, with their halo exchanges.
pub(super) fn kinematics<const D: usize, E: Effects, X: Executor>(
    sys: &mut System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
    halo: &mut dyn Halo<D>,
) {
    let [front, continuity, _, _] = &EXCHANGES;
    halo_exchange!(params, halo, front, sys, ws);
    geometry_pass::<D, E, X>(sys.x, sys.h, params, ws.geom, ws.fac, exec);
    let geom: &[PairGeom<D>] = ws.geom;
    refresh_aux::<D, false, X>(sys, ws.aux, params, exec);
    front_gradient_pass::<D, E, X>(sys, geom, ws.aux, ws.sums, ws.grad, params, exec);
    halo_exchange!(params, halo, continuity, sys, ws);
    continuity_pass::<D, E, X>(
        sys, ws.grad, geom, ws.aux, ws.ts_star, ws.rec, ws.sums, params, exec,
    );
}

#[cfg(test)]
mod tests;
