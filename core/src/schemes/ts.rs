//! The time-split family: `ts1` and `ts2` (seed 000 §3.3–3.4).
//!
//! Each step is a Lie–Trotter split: a deviatoric step without dissipation, then a
//! hydrodynamic step with a longitudinal Riemann problem per pair. With
//! `F_ij = m_i m_j (S_i + S_j)/(rho_i rho_j) . grad_i W_ij` (antisymmetric) and
//! `G_ij = -2 m_i m_j P*_ij/(rho_i rho_j) grad_i W_ij` (antisymmetric):
//!
//! ```text
//! deviatoric:  m_i dv_i = dt sum_j F_ij,            xdot_i = v_i + dv_i/2
//!              m_i de_i = dt sum_j F_ij . (vbar_ij - xdot_i),  vbar_ij = (v_i + v_j)/2   (eq 32)
//! hydro:       m_i dv_i = dt sum_j G_ij,            xdot_i = v~_i + dv_i/2
//!              m_i de_i = dt sum_j G_ij . (u*_ij n_ij - xdot_i)                           (eq 34)
//!              rho_i   <- rho_i exp(-dt div_i),  div_i = 2 sum_j m_j/rho_j (u*_ij n_ij - v~_i) . grad_i W_ij
//! ```
//!
//! Energy is conserved to round-off: in each sub-step the kinetic energy change is
//! `sum_i m_i dv_i . xdot_i` exactly (because `xdot_i = v_i + dv_i/2`), which cancels the
//! `-xdot_i` term of the energy equation, and what is left, `sum_ij F_ij . vbar_ij` or
//! `sum_ij G_ij . u*_ij n_ij`, vanishes because `F`, `G` are antisymmetric and `vbar`,
//! `u* n` symmetric under i <-> j (seed 000 eqs 30–35).
//!
//! The hydrodynamic Riemann problem uses the bulk sound speed (it carries pressure only)
//! and is either acoustic or two-shock. `ts2` reconstructs P, rho and the normal velocity
//! at the contact (seed 000 eq 23): `Q_l = Q_i + (r/2) phi(r_i) (grad Q_i . n) f_i` with
//! `r_i = (grad Q_j . n)/(grad Q_i . n)` (eq 25) and the MUSCL–Hancock factor
//! `f_i = max(0, 1 - c_i dt / r_ij)`. Seed 000 prints `[1 - c_i dt]`, which has units of
//! length; dividing by the pair distance makes it the dimensionless Courant number of the
//! pair, as in MUSCL–Hancock (Toro §14.4), where the face value is advanced half a step
//! along the characteristic.
//!
//! Failed particles (damage = 1; seed 000 Algorithm 1) are handled in
//! `riemann_states`: the place where first order is forced and tension is cut.

use super::common::{advance_deviator, for_each_pair, outer, refresh_eos};
use super::SchemeFamily;
use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::math::{real, Matrix, Real, Vector};
use crate::riemann::{pressure_star, two_shock_star, PressureSide, ShockSide};
use crate::state::{
    Family, Gradients, PairSums, RiemannSolver, StepError, StepParams, System, Workspace,
};

/// The time-split family (`ts1`, `ts2`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Ts;

/// Deviatoric pass: `acc = sum F_ij/m_i`, `power = sum F_ij.vbar_ij/m_i`, velocity gradient.
fn deviatoric_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    exec.run(sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let (vi, si, rhoi) = (sys.v[i], sys.s[i], sys.rho[i]);
            let mut acc = Vector::<D>::zeros();
            let mut power = 0.0;
            let mut grad_v = Matrix::<D>::zeros();
            for_each_pair::<D, E>(sys.x, sys.h, params, i, |pr| {
                let j = pr.j;
                let (mj, rhoj, vj) = (sys.m[j], sys.rho[j], sys.v[j]);
                let f = (si + sys.s[j]).dot_vec(&pr.grad) * (mj / (rhoi * rhoj));
                acc += f;
                power += f.dot(&((vi + vj) * 0.5));
                grad_v += outer(&(vj - vi), &pr.grad) * (mj / rhoj);
            });
            out.acc = acc;
            out.power = power;
            out.grad_v = grad_v;
            out.v0 = vi;
        }
    });
}

/// SPH gradients of rho, P and v (for `ts2`).
fn gradient_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    grad: &mut [Gradients<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    exec.run(grad, |off, chunk: &mut [Gradients<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let mut g = Gradients::<D>::default();
            for_each_pair::<D, E>(sys.x, sys.h, params, i, |pr| {
                let j = pr.j;
                let gw = pr.grad * (sys.m[j] / sys.rho[j]);
                g.rho += gw * (sys.rho[j] - sys.rho[i]);
                g.p += gw * (sys.p[j] - sys.p[i]);
                g.v += outer(&(sys.v[j] - sys.v[i]), &gw);
            });
            *out = g;
        }
    });
}

/// Limited, MUSCL–Hancock reconstructed contact values of one quantity:
/// `(Q_l, Q_r)` from `Q_i`, `Q_j` and the projected gradients `g_i = grad Q_i . n`,
/// `g_j = grad Q_j . n`.
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
    let slope_i = if g_i != 0.0 {
        lim.phi(g_j / g_i) * g_i
    } else {
        0.0
    };
    let slope_j = if g_j != 0.0 {
        lim.phi(g_i / g_j) * g_j
    } else {
        0.0
    };
    (q_i + half_r * slope_i * f_i, q_j - half_r * slope_j * f_j)
}

/// Left/right states of the hydrodynamic Riemann problem of pair (i, j) along `n`:
/// `(u, p, rho)` of each side. This is the single place where the failed-particle rules
/// of seed 000 Algorithm 1 (first order, no tension) will act.
#[inline(always)]
fn riemann_states<const D: usize, E: Effects>(
    sys: &System<'_, D>,
    grad: &[Gradients<D>],
    params: &StepParams<'_, D>,
    i: usize,
    j: usize,
    n: &Vector<D>,
    r: Real,
) -> ([Real; 3], [Real; 3]) {
    let (ui, uj) = (sys.v[i].dot(n), sys.v[j].dot(n));
    let mut l = [ui, sys.p[i], sys.rho[i]];
    let mut rr = [uj, sys.p[j], sys.rho[j]];
    if E::MUSCL {
        let lim = params.options.limiter;
        let (f_i, f_j) = if params.options.hancock {
            (
                real::max(0.0, 1.0 - sys.c[i] * params.dt / r),
                real::max(0.0, 1.0 - sys.c[j] * params.dt / r),
            )
        } else {
            (1.0, 1.0)
        };
        let (gi, gj) = (&grad[i], &grad[j]);
        let h = 0.5 * r;
        (l[0], rr[0]) = reconstruct(
            ui,
            uj,
            n.dot(&(gi.v * n)),
            n.dot(&(gj.v * n)),
            h,
            f_i,
            f_j,
            lim,
        );
        (l[1], rr[1]) = reconstruct(
            sys.p[i],
            sys.p[j],
            gi.p.dot(n),
            gj.p.dot(n),
            h,
            f_i,
            f_j,
            lim,
        );
        let (rl, rrr) = reconstruct(
            sys.rho[i],
            sys.rho[j],
            gi.rho.dot(n),
            gj.rho.dot(n),
            h,
            f_i,
            f_j,
            lim,
        );
        // a reconstructed density must stay positive; otherwise fall back to first order
        if rl > 0.0 && rrr > 0.0 {
            l[2] = rl;
            rr[2] = rrr;
        }
    }
    (l, rr)
}

/// Hydrodynamic pass: `acc = sum G_ij/m_i`, `power = sum G_ij.(u* n)/m_i`, divergence.
fn hydro_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    grad: &[Gradients<D>],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let mats = params.materials;
    exec.run(sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let (vi, rhoi) = (sys.v[i], sys.rho[i]);
            let mut acc = Vector::<D>::zeros();
            let mut power = 0.0;
            let mut div = 0.0;
            for_each_pair::<D, E>(sys.x, sys.h, params, i, |pr| {
                let j = pr.j;
                let ([ul, pl, rl], [ur, pr_, rr]) =
                    riemann_states::<D, E>(sys, grad, params, i, j, &pr.n, pr.r);
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
                    RiemannSolver::TwoShock => two_shock_star(
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
                    ),
                };
                let (mj, rhoj) = (sys.m[j], sys.rho[j]);
                // G_ij/m_i = -2 m_j P* grad_i W /(rho_i rho_j), grad_i W = -n W'
                let g = 2.0 * mj * ps * pr.dw / (rhoi * rhoj);
                acc += pr.n * g;
                power += g * us;
                // div: 2 V_j (u* n - v_i) . grad_i W = -2 V_j W' (u* - v_i . n)
                div -= 2.0 * (mj / rhoj) * pr.dw * (us - vi.dot(&pr.n));
            });
            out.acc = acc;
            out.power = power;
            out.div = div;
        }
    });
}

impl SchemeFamily for Ts {
    const FAMILY: Family = Family::Ts;
    const SUPPORTED: EffectSet = EffectSet::STRENGTH
        .union(EffectSet::PLASTICITY)
        .union(EffectSet::DAMAGE)
        .union(EffectSet::HEAT)
        .union(EffectSet::PERIODIC)
        .union(EffectSet::MUSCL);

    fn step<const D: usize, E: Effects, X: Executor>(
        sys: &mut System<'_, D>,
        ws: &mut Workspace<'_, D>,
        params: &StepParams<'_, D>,
        exec: &X,
    ) -> Result<(), StepError> {
        let n = sys.len();
        if ws.sums.len() != n || (E::MUSCL && ws.grad.len() != n) {
            return Err(StepError::Storage { field: "workspace" });
        }
        let dt = params.dt;
        // 1. Deviatoric step (only with strength).
        if E::STRENGTH {
            deviatoric_pass::<D, E, X>(sys, ws.sums, params, exec);
            exec.run(
                (sys.reborrow(), &ws.sums[..]),
                |_, (s, sums): (System<'_, D>, &[PairSums<D>])| {
                    for k in 0..s.len() {
                        let ps = &sums[k];
                        let dv = ps.acc * dt;
                        let xdot = s.v[k] + dv * 0.5;
                        s.e[k] += dt * (ps.power - ps.acc.dot(&xdot));
                        s.v[k] += dv;
                        let st = params.materials[s.mat[k] as usize].eos(s.rho[k], s.e[k]);
                        s.p[k] = st.p;
                        s.c[k] = real::sqrt(real::max(st.c2, 0.0));
                    }
                },
            );
        } else {
            exec.run(
                (&*sys.v, &mut ws.sums[..]),
                |_, (v, sums): (&[Vector<D>], &mut [PairSums<D>])| {
                    for (o, vk) in sums.iter_mut().zip(v) {
                        o.v0 = *vk;
                    }
                },
            );
        }
        // 2. Hydrodynamic step.
        if E::MUSCL {
            gradient_pass::<D, E, X>(sys, ws.grad, params, exec);
        }
        hydro_pass::<D, E, X>(sys, ws.grad, ws.sums, params, exec);
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
                    s.rho[k] *= real::exp(-dt * ps.div);
                    s.x[k] += (ps.v0 + s.v[k]) * (0.5 * dt);
                    if E::PERIODIC {
                        s.x[k] = params.periodic.wrap(s.x[k]);
                    }
                    if E::STRENGTH {
                        let (snew, deps) = advance_deviator::<D, E>(&s.s[k], mat, &ps.grad_v, dt);
                        s.s[k] = snew;
                        if E::PLASTICITY {
                            s.eps_p[k] += deps;
                        }
                    }
                    refresh_eos(&mut s, k, mat, params.h_factor);
                }
            },
        );
        Ok(())
    }
}
