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
//! factor `f_i = max(0, 1 - c_i dt / r_ij)` ([`MusclTime::CourantFactor`]); a genuine
//! half-step predictor is [`MusclTime::Predictor`]; the default is the spatial
//! reconstruction alone (`f = 1`, [`MusclTime::None`]): the most accurate of the three,
//! and with the bounded extrapolation and the symplectic-Euler ordering it keeps an
//! elastic standing wave bounded (measurements in docs/ts2_reconstruction.md).
//!
//! Failed particles (damage = 1; seed 000 Algorithm 1) are handled in
//! `riemann_states`: the place where first order is forced and tension is cut.

use super::artificial_stress::pair_acceleration;
use super::common::{
    advance_deviator, artificial_stress_tensors, failed, for_each_pair, geometry_pass,
    halo_exchange, min_sym_eigenvalue, outer, pair_pressure, refresh_aux, refresh_eos,
    refresh_pressure, solve_pairs,
};
use super::options::{read_if, why, NotRead, OptionKey};
use super::{Scheme, SchemeFamily};
use crate::effects::{EffectSet, Effects};
use crate::exec::{Executor, Optional};
use crate::halo::{Exchange, Fields, Halo};
use crate::limiter::bounded_extrapolation;
use crate::math::{det, inverse, real, Matrix, Real, Sym3, Vector};
use crate::riemann::{pressure_star, two_shock_star, PressureSide, ShockSide};
use crate::state::{
    Aux, Family, Gradients, Layout, MusclTime, PairGeom, PairSums, RiemannSolver, StepError,
    StepParams, System, TsStar, Workspace,
};

/// The halo exchanges of a `ts` step, in order (see [`crate::halo`]).
///
/// 1. Before the front gradients (and the pair geometry): x, h; v, rho, p, damage (the
///    gradients and the free-surface test; aux is recomputed locally from rho) and c (the
///    continuity pass's Riemann problems).
/// 2. Before the continuity pass, with MUSCL: the gradients (its reconstruction reads the
///    slopes of both sides of every pair).
/// 3. After the continuity update (rho, S, p, c, damage changed): the deviatoric pass reads
///    S, p, damage and aux (from rho); without it the hydro pass is next and reads rho, p,
///    c, damage.
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
            .with(Fields::DAMAGE),
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

/// Gradients at the start of the step: the velocity gradient
/// `dv_a/dx_b = sum_j V_j (v_j - v_i)_a (grad_i W_ij)_b` (for the deviator) and, with MUSCL,
/// grad rho and grad P for the reconstruction; also records the start-of-step velocity,
/// and whether the particle is a free-surface particle of the continuity equation (see
/// [`continuity_pass`]; [`PairSums::set_surface`]).
fn front_gradient_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    sums: &mut [PairSums<D>],
    grad: &mut [Gradients<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let (lam, eps) = (params.options.surface_lambda, params.options.det_epsilon);
    exec.run(
        (&mut *sums, Optional(grad)),
        |off, (chunk, g): (&mut [PairSums<D>], Optional<'_, Gradients<D>>)| {
            for (k, out) in chunk.iter_mut().enumerate() {
                let i = off + k;
                let vi = sys.v[i];
                out.v0 = vi;
                let mut gr = Gradients::<D>::default();
                let mut m = Matrix::<D>::zeros();
                let pi = pair_pressure::<D, E>(sys, i);
                for_each_pair(params, geom, i, |pr, _| {
                    let j = pr.j;
                    let gw = pr.grad * aux[j].vol;
                    m += outer(&gw, &(pr.n * pr.r));
                    if E::STRENGTH || E::MUSCL {
                        gr.v += outer(&(sys.v[j] - vi), &gw);
                    }
                    if E::MUSCL {
                        gr.rho += gw * (sys.rho[j] - sys.rho[i]);
                        gr.p += gw * (pair_pressure::<D, E>(sys, j) - pi);
                    }
                });
                out.set_surface(surface_divergence(&m, lam, eps) && !failed::<D, E>(sys, i));
                out.grad_v = gr.v;
                if E::MUSCL {
                    g.0[k] = gr;
                }
            }
        },
    );
}

/// True when a particle with `M = sum_j V_j grad_i W_ij ⊗ (x_j - x_i)` takes the consistent
/// divergence (seed 004's free-surface criterion; see [`continuity_pass`]).
#[inline(always)]
fn surface_divergence<const D: usize>(m: &Matrix<D>, lam: Real, eps: Real) -> bool {
    min_sym_eigenvalue(m) < lam && det(m) >= eps && inverse(m).is_some()
}

/// Continuity: `div_i = 2 sum_j m_j/rho_j (v*_ij - v_i) . grad_i W_ij` with the contact
/// velocities of the hydrodynamic Riemann problem at the start of the step (seed 000 eq
/// 22), `v*_ij = u*_ij n + (v_i + v_j)_t / 2` (the Riemann problem gives the normal
/// component; the tangential part, which the plain sum never sees, is the pair mean).
///
/// At a free surface the kernel support is cut and the plain sum is not consistent: for
/// `v = A x` it gives `tr(A M_i)` with `M_i = sum_j V_j grad_i W_ij ⊗ (x_j - x_i)` far from
/// the identity and anisotropic (the particle's own row counts fully along the surface,
/// the rows behind it only half across). In a converging shell the surface row is
/// compressed along the surface and stretched across it, so the plain sum compresses
/// it: measured on the beryllium ring, the inner row reached 8e-4 above the bulk density,
/// 0.2 GPa of spurious pressure that pushed it off the shell. So a free-surface particle
/// (seed 004's criterion: smallest eigenvalue of `M_i` below `surface_lambda`) uses the
/// first-order consistent divergence `tr(M_i^-1 K_i)`, `K_i = sum_j 2 V_j grad_i W_ij ⊗
/// (v*_ij - v_i)`, when `det M_i >= det_epsilon` and the particle has not failed. Failed
/// material (damage 1) has lost cohesion: its surfaces are cracks and debris, not the
/// surface of a continuous body, and the corrected divergence lets an isolated fragment
/// expand without bound. Interior particles keep the plain sum: it is the discrete adjoint
/// of the force sum, and correcting it alone breaks that pairing. Only the density update
/// changes; momentum and energy stay conserved to round-off. The measurements behind each
/// rule are in docs/ts2_reconstruction.md, "History of the ts code".
#[allow(clippy::too_many_arguments)] // the pass's inputs and its two outputs (pair stars, sums)
fn continuity_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    grad: &[Gradients<D>],
    geom: &[PairGeom<D>],
    aux: &[Aux],
    stars: &mut [TsStar],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    // each pair's contact velocity once, on the owner's side
    solve_pairs::<D, X, TsStar>(params, geom, stars, exec, |i, pr| {
        let (u, _) = star::<D, E>(sys, grad, params, i, pr.j, &pr.n, pr.r);
        TsStar { u, p: 0.0 }
    });
    let stars: &[TsStar] = stars;
    exec.run(sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let vi = sys.v[i];
            // the owner solved along its own axis: seen from i the component flips
            let seen = |u: Real, owner: bool| if owner { u } else { -u };
            if !out.surface() {
                // interior: the plain sum, (v*_ij - v_i) . grad_i W = (u* - v_i . n) |W'|
                let mut div = 0.0;
                for_each_pair(params, geom, i, |pr, e| {
                    let us = seen(stars[e.pair].u, e.owner);
                    div -= 2.0 * aux[pr.j].vol * pr.dw * (us - vi.dot(&pr.n));
                });
                out.div = div;
                continue;
            }
            let mut m = Matrix::<D>::zeros();
            let mut kk = Matrix::<D>::zeros();
            for_each_pair(params, geom, i, |pr, e| {
                let j = pr.j;
                let us = seen(stars[e.pair].u, e.owner);
                let gw = pr.grad * aux[j].vol;
                let mean = (vi + sys.v[j]) * 0.5;
                let vstar = mean + pr.n * (us - mean.dot(&pr.n));
                m += outer(&gw, &(pr.n * pr.r));
                kk += outer(&gw, &((vstar - vi) * 2.0));
            });
            out.div = match inverse(&m) {
                Some(inv) => (inv * kk).trace(),
                None => kk.trace(),
            };
        }
    });
}

/// The hydrodynamic star state `(u*, P*)` of pair (i, j) along `n`.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn star<const D: usize, E: Effects>(
    sys: &System<'_, D>,
    grad: &[Gradients<D>],
    params: &StepParams<'_, D>,
    i: usize,
    j: usize,
    n: &Vector<D>,
    r: Real,
) -> (Real, Real) {
    let ([ul, pl, rl], [ur, pr_, rr]) = riemann_states::<D, E>(sys, grad, params, i, j, n, r);
    let (us, ps) = match params.options.riemann {
        RiemannSolver::Acoustic => pressure_star(
            PressureSide {
                u: ul,
                p: pl,
                z: rl * sys.c[i],
            },
            PressureSide {
                u: ur,
                p: pr_,
                z: rr * sys.c[j],
            },
        ),
        RiemannSolver::TwoShock => {
            let mats = params.materials;
            two_shock_star(
                ShockSide {
                    u: ul,
                    p: pl,
                    rho: rl,
                    c: sys.c[i],
                    s: mats[sys.mat[i] as usize].eos.hugoniot_slope(),
                },
                ShockSide {
                    u: ur,
                    p: pr_,
                    rho: rr,
                    c: sys.c[j],
                    s: mats[sys.mat[j] as usize].eos.hugoniot_slope(),
                },
            )
        }
    };
    // seed 000 Algorithm 1: no tension across a pair with a failed particle
    if failed::<D, E>(sys, i) || failed::<D, E>(sys, j) {
        (us, real::max(ps, 0.0))
    } else {
        (us, ps)
    }
}

/// Deviatoric pass: `acc = sum F_ij/m_i`, `power = sum F_ij.vbar_ij/m_i`. With the effect
/// `artificial_stress`, `F_ij` gains `m_i m_j f_ij^n (R_i + R_j) . grad_i W_ij` (also for a
/// material without strength, whose deviatoric step then carries only that force).
#[allow(clippy::too_many_arguments)]
fn deviatoric_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    art: &[Matrix<D>],
    fac: &[Real],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let art_on = params.has::<E>(EffectSet::ARTIFICIAL_STRESS);
    exec.run(sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let vi = sys.v[i];
            let inv_i = aux[i].inv_rho;
            let si = if E::STRENGTH { sys.s[i] } else { Sym3::ZERO };
            let mut acc = Vector::<D>::zeros();
            let mut power = 0.0;
            for_each_pair(params, geom, i, |pr, e| {
                let j = pr.j;
                let (mj, vj) = (sys.m[j], sys.v[j]);
                let mut f = if E::STRENGTH {
                    (si + sys.s[j]).dot_vec(&pr.grad) * (mj * inv_i * aux[j].inv_rho)
                } else {
                    Vector::<D>::zeros()
                };
                if art_on {
                    f += pair_acceleration(mj, fac[e.pair], &art[i], &art[j], &pr.grad);
                }
                acc += f;
                power += f.dot(&((vi + vj) * 0.5));
            });
            out.acc = acc;
            out.power = power;
        }
    });
}

/// Limited reconstruction of one quantity at the contact: `(Q_l, Q_r)` from the (possibly
/// time-advanced) values `q_i`, `q_j` and the projected gradients `g_i = grad Q_i . n`,
/// `g_j = grad Q_j . n`. Each slope is limited with `phi(r_i)`, `r_i = g_j/g_i` (seed 000
/// eqs 24-26), scaled by `f_i`, `f_j`, and the extrapolation of each side is then bounded
/// by half the pair difference ([`bounded_extrapolation`]): `Q_l` lies between `Q_i` and
/// the pair mean, `Q_r` between the mean and `Q_j`, so the reconstructed jump `Q_r - Q_l`
/// has the sign of `Q_j - Q_i` and is never larger. Seed 000's limiter compares only the
/// two particles' gradients; with superbee (`phi` up to 2) the extrapolations overshoot
/// the pair mean, and an elastic standing wave then gains kinetic energy (+41 % in 14
/// periods when continuity and energy share the contact velocity; see the module docs).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn reconstruct(
    q_i: Real,
    q_j: Real,
    g_i: Real,
    g_j: Real,
    half_r: Real,
    f_i: Real,
    f_j: Real,
    lim: crate::limiter::Limiter,
) -> (Real, Real) {
    let half_jump = 0.5 * (q_j - q_i);
    let ext_i = bounded_extrapolation(half_r * f_i * lim.limit(g_i, g_j), half_jump);
    let ext_j = bounded_extrapolation(half_r * f_j * lim.limit(g_j, g_i), half_jump);
    (q_i + ext_i, q_j - ext_j)
}

/// `(u, p, rho)` of particle `i` along `n`, advanced half a step with the Lagrangian
/// acoustic equations when `MusclTime::Predictor` is selected (the MUSCL–Hancock predictor:
/// `du = -dt/2 (grad P . n)/rho`, `dP = -dt/2 rho c² div v`, `drho = -dt/2 rho div v`).
#[inline(always)]
fn predicted<const D: usize>(
    sys: &System<'_, D>,
    g: &Gradients<D>,
    i: usize,
    n: &Vector<D>,
    half_dt: Real,
    predict: bool,
) -> [Real; 3] {
    let (u, p, rho) = (sys.v[i].dot(n), sys.p[i], sys.rho[i]);
    if !predict {
        return [u, p, rho];
    }
    let div = g.v.trace();
    [
        u - half_dt * g.p.dot(n) / rho,
        p - half_dt * rho * sys.c[i] * sys.c[i] * div,
        rho * (1.0 - half_dt * div),
    ]
}

/// Left/right states of the hydrodynamic Riemann problem of pair (i, j) along `n`:
/// `(u, p, rho)` of each side. This is the single place where the failed-particle rules
/// of seed 000 Algorithm 1 (first order, no tension) act.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
fn riemann_states<const D: usize, E: Effects>(
    sys: &System<'_, D>,
    grad: &[Gradients<D>],
    params: &StepParams<'_, D>,
    i: usize,
    j: usize,
    n: &Vector<D>,
    r: Real,
) -> ([Real; 3], [Real; 3]) {
    let time = params.options.muscl_time;
    // Failed particles (seed 000 Algorithm 1): no reconstruction for the pair, and a failed
    // side carries no tension.
    let first_order = (
        [sys.v[i].dot(n), pair_pressure::<D, E>(sys, i), sys.rho[i]],
        [sys.v[j].dot(n), pair_pressure::<D, E>(sys, j), sys.rho[j]],
    );
    if !E::MUSCL || failed::<D, E>(sys, i) || failed::<D, E>(sys, j) {
        return first_order;
    }
    let lim = params.options.limiter;
    let dt = params.dt;
    let (f_i, f_j) = match time {
        MusclTime::CourantFactor => (
            real::max(0.0, 1.0 - sys.c[i] * dt / r),
            real::max(0.0, 1.0 - sys.c[j] * dt / r),
        ),
        MusclTime::Predictor | MusclTime::None => (1.0, 1.0),
    };
    let predict = time == MusclTime::Predictor;
    let (gi, gj) = (&grad[i], &grad[j]);
    let qi = predicted(sys, gi, i, n, 0.5 * dt, predict);
    let qj = predicted(sys, gj, j, n, 0.5 * dt, predict);
    let slopes_i = [n.dot(&(gi.v * n)), gi.p.dot(n), gi.rho.dot(n)];
    let slopes_j = [n.dot(&(gj.v * n)), gj.p.dot(n), gj.rho.dot(n)];
    let mut l = [0.0; 3];
    let mut rr = [0.0; 3];
    for q in 0..3 {
        (l[q], rr[q]) = reconstruct(
            qi[q],
            qj[q],
            slopes_i[q],
            slopes_j[q],
            0.5 * r,
            f_i,
            f_j,
            lim,
        );
    }
    // a reconstructed density must stay positive; otherwise that pair falls back to first order
    if !(l[2] > 0.0 && rr[2] > 0.0) {
        return first_order;
    }
    (l, rr)
}

/// Hydrodynamic pass: `acc = sum G_ij/m_i`, `power = sum G_ij.(u* n)/m_i`, each pair's
/// star state solved once on its owner's side.
#[allow(clippy::too_many_arguments)]
fn hydro_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    grad: &[Gradients<D>],
    geom: &[PairGeom<D>],
    aux: &[Aux],
    stars: &mut [TsStar],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    solve_pairs::<D, X, TsStar>(params, geom, stars, exec, |i, pr| {
        let (u, p) = star::<D, E>(sys, grad, params, i, pr.j, &pr.n, pr.r);
        TsStar { u, p }
    });
    let stars: &[TsStar] = stars;
    exec.run(sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let inv_i = aux[i].inv_rho;
            let mut acc = Vector::<D>::zeros();
            let mut power = 0.0;
            for_each_pair(params, geom, i, |pr, e| {
                let j = pr.j;
                let st = stars[e.pair];
                let us = if e.owner { st.u } else { -st.u };
                // G_ij/m_i = -2 m_j P* grad_i W /(rho_i rho_j), grad_i W = -n W'
                let g = 2.0 * sys.m[j] * st.p * pr.dw * (inv_i * aux[j].inv_rho);
                acc += pr.n * g;
                power += g * us;
            });
            out.acc = acc;
            out.power = power;
        }
    });
}

/// Whether a scheme of the time-split family (`ts1`, `ts2`) reads `key`, or why not
/// ([`crate::schemes::options`]).
pub(crate) fn reads(scheme: Scheme, key: OptionKey) -> Result<(), NotRead> {
    use OptionKey::*;
    let muscl = scheme.effects().contains(EffectSet::MUSCL);
    match key {
        AvAlpha | AvBeta => read_if(false, scheme, why::AV_ONLY),
        Limiter => read_if(muscl, scheme, why::NO_MUSCL),
        MusclTime => read_if(muscl, scheme, why::NO_MUSCL_TIME),
        Riemann | SurfaceLambda | DetEpsilon | ArtificialStress | ArtificialStressExponent => {
            Ok(())
        }
        Correction | Muscl => Err(NotRead::OnlyPm { scheme }),
    }
}

impl SchemeFamily for Ts {
    const FAMILY: Family = Family::Ts;
    const SUPPORTED: EffectSet = EffectSet::STRENGTH
        .union(EffectSet::PLASTICITY)
        .union(EffectSet::DAMAGE)
        .union(EffectSet::HEAT)
        .union(EffectSet::PERIODIC)
        .union(EffectSet::MUSCL)
        .union(EffectSet::ARTIFICIAL_STRESS);
    const EXCHANGES: &'static [Exchange] = &EXCHANGES;

    fn layout(effects: EffectSet) -> Layout {
        Layout {
            ts_star: true,
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
        // 1. Kinematics at the start of the step: gradients, then density from the contact
        //    velocities (seed 000 eq 22) and the deviator from the velocity gradient.
        //    Updating density and deviator before the forces that use them makes every
        //    sub-step symplectic Euler. The opposite order (forces from the old state,
        //    then density and deviator) is forward Euler, whose amplification factor
        //    |1 + i w dt| > 1 lets waves grow wherever the Riemann dissipation vanishes:
        //    always in the deviatoric step, and in smooth flow with MUSCL.
        let [front, continuity, deviatoric, hydro] = &EXCHANGES;
        halo_exchange!(params, halo, front, sys, ws);
        geometry_pass::<D, E, X>(sys.x, sys.h, params, ws.geom, ws.fac, exec);
        let (geom, fac): (&[PairGeom<D>], &[Real]) = (ws.geom, ws.fac);
        refresh_aux::<D, false, X>(sys, ws.aux, params, exec);
        front_gradient_pass::<D, E, X>(sys, geom, ws.aux, ws.sums, ws.grad, params, exec);
        halo_exchange!(params, halo, continuity, sys, ws);
        continuity_pass::<D, E, X>(
            sys, ws.grad, geom, ws.aux, ws.ts_star, ws.sums, params, exec,
        );
        exec.run(
            (sys.reborrow(), &ws.sums[..]),
            |_, (mut s, sums): (System<'_, D>, &[PairSums<D>])| {
                for k in 0..s.len() {
                    let mat = &params.materials[s.mat[k] as usize];
                    s.rho[k] *= real::exp(-dt * sums[k].div);
                    if E::STRENGTH {
                        advance_deviator::<D, E>(&mut s, k, mat, &sums[k].grad_v, dt);
                    }
                    refresh_pressure(&mut s, k, mat);
                }
            },
        );
        halo_exchange!(params, halo, deviatoric, sys, ws);
        // 2. Deviatoric step (with strength or artificial stress): no dissipation.
        refresh_aux::<D, false, X>(sys, ws.aux, params, exec);
        let art_on = params.has::<E>(EffectSet::ARTIFICIAL_STRESS);
        if art_on {
            artificial_stress_tensors::<D, E, X>(sys, ws.art, params, exec);
        }
        if E::STRENGTH || art_on {
            deviatoric_pass::<D, E, X>(sys, geom, ws.aux, ws.art, fac, ws.sums, params, exec);
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
            sys, ws.grad, geom, ws.aux, ws.ts_star, ws.sums, params, exec,
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

#[cfg(test)]
#[path = "ts_tests.rs"]
mod tests;
