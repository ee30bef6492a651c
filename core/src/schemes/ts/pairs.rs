//! The pair interactions of the time-split family: continuity and deviatoric passes from
//! the contact velocities, the reconstructed Riemann states and the hydrodynamic pass.

use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::limiter::bounded_extrapolation;
use crate::math::{inverse, real, Matrix, Real, Sym3, Vector};
use crate::riemann::low_dissipation::{blend, central};
use crate::riemann::{pressure_star, two_shock_star, PressureSide, ShockSide};
use crate::schemes::artificial_stress::pair_acceleration;
use crate::schemes::common::{failed, outer, pair_pressure};
use crate::schemes::options::{MusclTime, RiemannSolver};
use crate::schemes::pairs::{for_each_pair, solve_pair_rows};
use crate::schemes::ts::records::TsStar;
use crate::schemes::workspace::StepParams;
use crate::state::{Aux, Gradients, Hourglass, PairGeom, PairSums, System};

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
pub(super) fn continuity_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    grad: &[Gradients<D>],
    geom: &[PairGeom<D>],
    aux: &[Aux],
    stars: &mut [TsStar],
    rec: &mut [Real],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    // each pair's contact velocity once, on the owner's side
    solve_stars::<D, E, X>(sys, grad, geom, stars, rec, params, exec, false);
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

/// Every pair's star state once, on its owner's side ([`star`]; `p* = 0` unless `with_p`),
/// a row four pairs at a time where the SIMD level and the options allow
/// ([`ts_star_row`], reading the neighbour records it has `rec` written
/// first), bitwise the same.
#[allow(clippy::too_many_arguments)]
fn solve_stars<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    grad: &[Gradients<D>],
    geom: &[PairGeom<D>],
    stars: &mut [TsStar],
    rec: &mut [Real],
    params: &StepParams<'_, D>,
    exec: &X,
    with_p: bool,
) {
    let records = ts_records::<D, E, X>(sys, grad, params, rec, exec);
    let rows = StarRows {
        sys,
        grad,
        rec,
        params,
        with_p,
    };
    solve_pair_rows::<D, X, TsStar>(
        params,
        geom,
        stars,
        exec,
        |i, geom, owned, out| {
            if records {
                ts_star_row::<D, E>(&rows, i, geom, owned, out)
            } else {
                0
            }
        },
        |i, pr| {
            let (u, p) = star::<D, E>(sys, grad, params, i, pr.j, &pr.n, pr.r);
            TsStar {
                u,
                p: if with_p { p } else { 0.0 },
            }
        },
    );
}

/// The hydrodynamic star state `(u*, P*)` of pair (i, j) along `n`.
///
/// Lane twin: `star_row` in `schemes/ts/lanes.rs` (entered by [`ts_star_row`]), held
/// bitwise equal by `schemes/star_tests.rs`; a change here is a change there.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn star<const D: usize, E: Effects>(
    sys: &System<'_, D>,
    grad: &[Gradients<D>],
    params: &StepParams<'_, D>,
    i: usize,
    j: usize,
    n: &Vector<D>,
    r: Real,
) -> (Real, Real) {
    let ([ul, pl, rl], [ur, pr_, rr]) = riemann_states::<D, E>(sys, grad, params, i, j, n, r);
    let solved = match params.options.riemann {
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
    // the dissipative part only where the pair compresses (`options.dissipation`)
    let beta = params
        .options
        .dissipation
        .weight(ul, ur, 0.5 * (sys.c[i] + sys.c[j]));
    let (us, ps) = if beta == 1.0 {
        solved
    } else {
        let (zl, zr) = (rl * sys.c[i], rr * sys.c[j]);
        blend(solved, central(ul, pl, zl, ur, pr_, zr), beta)
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
///
/// With the records of the hourglass stiffness (`hg` not empty), the deviator was
/// advanced with the kernel-corrected gradient `L_i = sum_j V_j (v_j - v_i) ⊗ C_i grad_i W_ij`,
/// and `F_ij = V_i V_j (S_i C_i + S_j C_j) grad_i W_ij` is that gradient's adjoint: the
/// forces' power is exactly `-sum_i V_i S_i : L_i`, the stress power that stores the
/// strain energy, and their torque vanishes (`S : W = 0` for the rigid rotation the
/// corrected gradient reproduces). The seed's uncorrected gradient sees a rigid rotation
/// as strain in the rows of a free surface; without dissipation to wipe it out, a
/// spinning ring with the stiffness lost 35 % of its angular momentum in a turn.
#[allow(clippy::too_many_arguments)]
pub(super) fn deviatoric_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    art: &[Matrix<D>],
    fac: &[Real],
    hg: &[Hourglass<D>],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let art_on = params.has::<E>(EffectSet::ARTIFICIAL_STRESS);
    let corrected = !hg.is_empty();
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
                let mut f = if E::STRENGTH && corrected {
                    (si.dot_vec(&(hg[i].c * pr.grad)) + sys.s[j].dot_vec(&(hg[j].c * pr.grad)))
                        * (mj * inv_i * aux[j].inv_rho)
                } else if E::STRENGTH {
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
pub(super) fn reconstruct(
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
pub(super) fn predicted<const D: usize>(
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
pub(super) fn riemann_states<const D: usize, E: Effects>(
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
pub(super) fn hydro_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    grad: &[Gradients<D>],
    geom: &[PairGeom<D>],
    aux: &[Aux],
    stars: &mut [TsStar],
    rec: &mut [Real],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    solve_stars::<D, E, X>(sys, grad, geom, stars, rec, params, exec, true);
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

/// Writes every particle's neighbour record for [`ts_star_row`] into `rec` where the
/// level and the step's options allow the vectorised row and it pays (AVX2 or AVX-512;
/// `super::lanes::covers` and `pays`) and `rec` has the room (`state::record_len`); returns
/// whether it did (false: the rows run the portable loop).
#[inline(always)]
#[allow(unused_variables)]
pub(crate) fn ts_records<const D: usize, E: crate::effects::Effects, X: crate::exec::Executor>(
    sys: &crate::state::System<'_, D>,
    grad: &[crate::state::Gradients<D>],
    params: &crate::schemes::workspace::StepParams<'_, D>,
    rec: &mut [crate::math::Real],
    exec: &X,
) -> bool {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if params.simd.vectorised()
        && super::lanes::covers(params)
        && crate::schemes::pairs::stars_pay::<D, E>(params)
        && rec.len() == sys.x.len() * crate::schemes::ts::record_len(D)
    {
        super::lanes::write_records::<D, E, X>(sys, grad, params, rec, exec);
        return true;
    }
    false
}

/// The star states of the pairs particle `i` owns (`ts1`, `ts2`: its neighbours `owned`,
/// their geometry `geom`) into `out` by the vectorised loop, from the neighbour records
/// `rows.rec` [`ts_records`] wrote (call only where it returned true). Returns how many pairs it
/// did (0: none; the portable loop does the rest), each bitwise as
/// [`crate::schemes::ts::pairs::star`] gives it (`p* = 0` unless `with_p`).
#[inline(always)]
#[allow(unused_variables)]
pub(crate) fn ts_star_row<const D: usize, E: crate::effects::Effects>(
    rows: &StarRows<'_, D>,
    i: usize,
    geom: &[PairGeom<D>],
    owned: &[u32],
    out: &mut [TsStar],
) -> usize {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if rows.params.simd.vectorised()
        && super::lanes::covers(rows.params)
        && crate::schemes::pairs::stars_pay::<D, E>(rows.params)
    {
        // SAFETY: `params.simd` vouches for the instructions (`SimdLevel::assume`) and
        // `covers` holds
        return unsafe {
            super::lanes::star_row_at::<D, E>(rows.params.simd, rows, i, geom, owned, out)
        };
    }
    0
}

/// What every star row of a pass reads besides its own pairs: the portable [`star`]'s
/// inputs and the neighbour records of its lane twin.
#[derive(Clone, Copy)]
// read by the lane rows alone (x86_64, f64): a build without them only fills it
#[cfg_attr(
    not(all(target_arch = "x86_64", not(feature = "f32"))),
    allow(dead_code)
)]
pub(crate) struct StarRows<'a, const D: usize> {
    pub sys: &'a System<'a, D>,
    pub grad: &'a [Gradients<D>],
    /// The neighbour records [`ts_records`] wrote.
    pub rec: &'a [Real],
    pub params: &'a StepParams<'a, D>,
    /// Whether the stars keep `p*` (`p* = 0` otherwise).
    pub with_p: bool,
}
