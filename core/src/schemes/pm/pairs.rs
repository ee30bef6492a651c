//! The pair interactions of the contact family: the elastic Riemann problem of each pair
//! (its MUSCL states), the star states and their sums.

use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::limiter::{bounded_extrapolation, Limiter};
use crate::math::{Matrix, Real, Sym3, Vector};
use crate::riemann::low_dissipation::central_vector;
use crate::riemann::{acoustic_star_vector, elastic_star_vector, two_shock_star, ShockSide};
use crate::schemes::artificial_stress::pair_acceleration;
use crate::schemes::common::{cauchy, failed, for_each_pair, outer, solve_pairs, Pair};
use crate::state::{
    Aux, Correction, Gradients, PairGeom, PairSums, PmStar, RiemannSolver, StepParams, System,
    Workspace,
};

/// Reconstructed contact values of a pair: `Phi_l = Phi_i + phi(r) (grad Phi_i . r_ji)/2`
/// with `r = (Phi_j - Phi_i)/(grad Phi_i . r_ji)` (and likewise for j), each side's
/// extrapolation bounded by half the pair difference ([`bounded_extrapolation`]). With
/// the minmod limiter (tkc's, seed 004 eqs 13-15) this is exactly
/// `Phi_i + minmod(Phi_j - Phi_i, grad Phi_i . r_ji)/2` and the bound never acts; the
/// other limiters of [`Limiter`] may extrapolate up to the pair mean.
#[inline(always)]
pub(super) fn muscl_pair(
    lim: Limiter,
    phi_i: Real,
    phi_j: Real,
    gi_rji: Real,
    gj_rji: Real,
) -> (Real, Real) {
    let half_jump = 0.5 * (phi_j - phi_i);
    let d = phi_j - phi_i;
    if let Limiter::Minmod = lim {
        // the same values without the limiter dispatch and the bound (which never acts
        // for minmod): tkc's hot path, 22 reconstructions per side of every pair
        return (
            phi_i + 0.5 * Limiter::Minmod.limit(gi_rji, d),
            phi_j - 0.5 * Limiter::Minmod.limit(gj_rji, d),
        );
    }
    (
        phi_i + bounded_extrapolation(0.5 * lim.limit(gi_rji, d), half_jump),
        phi_j - bounded_extrapolation(0.5 * lim.limit(gj_rji, d), half_jump),
    )
}

/// One pass over the pairs: every pair's star state solved once on its owner's side
/// ([`pair_star`]), then the sums of each particle gathered in canonical order
/// ([`gather`]).
pub(super) fn pair_pass<
    const D: usize,
    E: Effects,
    X: Executor,
    const KIN: bool,
    const DYN: bool,
>(
    sys: &System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let corr: &[Correction<D>] = ws.corr;
    let grad: &[Gradients<D>] = ws.grad;
    let grad_s: &[[Vector<D>; 6]] = ws.grad_stress;
    let geom: &[PairGeom<D>] = ws.geom;
    let art: &[Matrix<D>] = ws.art;
    let (fac, aux): (&[Real], &[Aux]) = (ws.fac, ws.aux);
    solve_pairs::<D, X, PmStar<D>>(params, geom, ws.pm_star, exec, |i, pr| {
        pair_star::<D, E>(sys, aux, corr, grad, grad_s, params, i, pr)
    });
    let stars: &[PmStar<D>] = ws.pm_star;
    let ctx = GatherCtx {
        geom,
        aux,
        corr,
        art,
        fac,
        stars,
    };
    // the run-time flag chosen outside the pair loop, so that the loop without it has
    // none of its code
    let art_on = params.has::<E>(EffectSet::ARTIFICIAL_STRESS);
    exec.run(&mut *ws.sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let new = if art_on {
                gather::<D, E, KIN, DYN, true>(sys, &ctx, params, i)
            } else {
                gather::<D, E, KIN, DYN, false>(sys, &ctx, params, i)
            };
            if KIN {
                out.div = new.div;
                out.grad_v = new.grad_v;
            }
            if DYN {
                out.acc = new.acc;
                out.power = new.power;
            }
        }
    });
}

/// What the gather of the pair sums reads besides the particles.
#[derive(Clone, Copy)]
pub(super) struct GatherCtx<'a, const D: usize> {
    geom: &'a [PairGeom<D>],
    aux: &'a [Aux],
    corr: &'a [Correction<D>],
    art: &'a [Matrix<D>],
    fac: &'a [Real],
    stars: &'a [PmStar<D>],
}

/// The star state of pair (i, j) with `i` on the left (`pr` seen from `i`): MUSCL states
/// (with `E::MUSCL`), tractions on the (corrected, with `E::CORRECTION`) axis, the elastic
/// Riemann problem, and no tension across the contact of a failed particle.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(super) fn pair_star<const D: usize, E: Effects>(
    sys: &System<'_, D>,
    aux: &[Aux],
    corr: &[Correction<D>],
    grad: &[Gradients<D>],
    grad_s: &[[Vector<D>; 6]],
    params: &StepParams<'_, D>,
    i: usize,
    pr: &Pair<D>,
) -> PmStar<D> {
    let mats = params.materials;
    let j = pr.j;
    let (vi, rhoi, rhoj) = (sys.v[i], sys.rho[i], sys.rho[j]);
    let (ct_i, ct_j) = (aux[i].ct, aux[j].ct);
    let sig_i = cauchy::<D, E>(sys, i);
    let sig_j = cauchy::<D, E>(sys, j);
    let (mut rho_l, mut rho_r) = (rhoi, rhoj);
    let (mut cl_l, mut cl_r) = (sys.cl[i], sys.cl[j]);
    let (mut ct_l, mut ct_r) = (ct_i, ct_j);
    let (mut v_l, mut v_r) = (vi, sys.v[j]);
    let (mut s_l, mut s_r) = (sig_i, sig_j);
    let failed_pair = failed::<D, E>(sys, i) || failed::<D, E>(sys, j);
    if E::MUSCL && !failed_pair {
        let lim = params.options.limiter;
        let rji = pr.n * pr.r;
        let (gi, gj) = (&grad[i], &grad[j]);
        (rho_l, rho_r) = muscl_pair(lim, rhoi, rhoj, gi.rho.dot(&rji), gj.rho.dot(&rji));
        (cl_l, cl_r) = muscl_pair(lim, cl_l, cl_r, gi.cl.dot(&rji), gj.cl.dot(&rji));
        (ct_l, ct_r) = muscl_pair(lim, ct_l, ct_r, gi.ct.dot(&rji), gj.ct.dot(&rji));
        let dvi = gi.v * rji;
        let dvj = gj.v * rji;
        for a in 0..D {
            (v_l[a], v_r[a]) = muscl_pair(lim, vi[a], sys.v[j][a], dvi[a], dvj[a]);
        }
        if E::STRENGTH {
            let (si, sj) = (sig_i.to_array(), sig_j.to_array());
            let (mut al, mut ar) = ([0.0; 6], [0.0; 6]);
            for c in 0..6 {
                (al[c], ar[c]) = muscl_pair(
                    lim,
                    si[c],
                    sj[c],
                    grad_s[i][c].dot(&rji),
                    grad_s[j][c].dot(&rji),
                );
            }
            (s_l, s_r) = (Sym3::from_array(al), Sym3::from_array(ar));
        } else {
            let (pl, pr_) = muscl_pair(lim, sys.p[i], sys.p[j], gi.p.dot(&rji), gj.p.dot(&rji));
            (s_l, s_r) = (Sym3::isotropic(-pl), Sym3::isotropic(-pr_));
        }
    }
    let axis = if E::CORRECTION {
        (corr[i].l_inv + corr[j].l_inv) * pr.n * 0.5
    } else {
        pr.n
    };
    let t_l = s_l.dot_vec(&axis);
    let t_r = s_r.dot_vec(&axis);
    let (zl_long, zl_trans) = (rho_l * cl_l, rho_l * ct_l);
    let (zr_long, zr_trans) = (rho_r * cl_r, rho_r * ct_r);
    let (mut vs, mut ts) = match params.options.riemann {
        RiemannSolver::Acoustic => acoustic_star_vector(
            &pr.n, &v_l, &t_l, zl_long, zl_trans, &v_r, &t_r, zr_long, zr_trans,
        ),
        // the longitudinal wave as a shock or expansion with Us = c_l + s up (the
        // EOS's Hugoniot slope), the transverse waves acoustic
        RiemannSolver::TwoShock => elastic_star_vector(
            &pr.n,
            &v_l,
            &t_l,
            zl_trans,
            &v_r,
            &t_r,
            zr_trans,
            |ul, sl, ur, sr| {
                let side = |u: Real, s: Real, rho: Real, c: Real, m: usize| ShockSide {
                    u,
                    p: -s,
                    rho,
                    c,
                    s: mats[sys.mat[m] as usize].eos.hugoniot_slope(),
                };
                let (u, p) =
                    two_shock_star(side(ul, sl, rho_l, cl_l, i), side(ur, sr, rho_r, cl_r, j));
                (u, -p)
            },
        ),
    };
    // the dissipative parts only where the pair compresses along its axis: every
    // channel's with `options.dissipation`, the transverse channels' with
    // `options.transverse_dissipation` (a sliding or rotating pair's tangential jumps)
    let (u_l, u_r) = (v_l.dot(&pr.n), v_r.dot(&pr.n));
    let c_pair = 0.5 * (cl_l + cl_r);
    let beta = params.options.dissipation.weight(u_l, u_r, c_pair);
    let beta_t = beta
        * params
            .options
            .transverse_dissipation
            .weight(u_l, u_r, c_pair);
    if beta != 1.0 || beta_t != 1.0 {
        let (vc, tc) = central_vector(
            &pr.n, &v_l, &t_l, zl_long, zl_trans, &v_r, &t_r, zr_long, zr_trans,
        );
        let (dv, dt) = (vs - vc, ts - tc);
        let (dvn, dtn) = (pr.n * dv.dot(&pr.n), pr.n * dt.dot(&pr.n));
        vs = vc + dvn * beta + (dv - dvn) * beta_t;
        ts = tc + dtn * beta + (dt - dtn) * beta_t;
    }
    if failed_pair {
        // seed 000 Algorithm 1, in the full-stress Riemann problem: no tension across
        // the contact of a failed particle
        let tn = ts.dot(&pr.n);
        if tn > 0.0 {
            ts -= pr.n * tn;
        }
    }
    PmStar { v: vs, t: ts }
}

/// The pair sums of particle i from the solved star states: the kinematic sums (velocity
/// divergence and gradient from the contact velocities) when `KIN`, the dynamic sums
/// (acceleration and power at the contacts) when `DYN`. With correction (`tkc`, seed 004
/// eq 11) `power` is the total energy rate `sum f_ij . V*_ij`; otherwise (`pm`, seed 000
/// eq 16) the internal energy rate `sum f_ij . (V*_ij - v_i)`.
#[inline(always)]
pub(super) fn gather<
    const D: usize,
    E: Effects,
    const KIN: bool,
    const DYN: bool,
    const ART: bool,
>(
    sys: &System<'_, D>,
    ctx: &GatherCtx<'_, D>,
    params: &StepParams<'_, D>,
    i: usize,
) -> PairSums<D> {
    let GatherCtx {
        geom,
        aux,
        corr,
        art,
        fac,
        stars,
    } = *ctx;
    let vi = sys.v[i];
    let inv_i = aux[i].inv_rho;
    let mut out = PairSums::<D>::default();
    for_each_pair(params, geom, i, |pr, e| {
        let j = pr.j;
        let st = &stars[e.pair];
        // the owner's traction acts on the face whose normal points away from it
        let (vs, ts) = (st.v, if e.owner { st.t } else { -st.t });
        let (mj, inv_j) = (sys.m[j], aux[j].inv_rho);
        let dv = vs - vi;
        if DYN {
            let f = -2.0 * mj * pr.dw * (inv_i * inv_j);
            out.acc += ts * f;
            out.power += f * ts.dot(if E::CORRECTION { &vs } else { &dv });
            if ART {
                // a pair force outside the Riemann problem: its work at the pair's mean
                // velocity (total energy form with correction, internal otherwise)
                let a = pair_acceleration(mj, fac[e.pair], &art[i], &art[j], &pr.grad);
                let vbar = (vi + sys.v[j]) * 0.5;
                out.acc += a;
                out.power += a.dot(&if E::CORRECTION { vbar } else { vbar - vi });
            }
        }
        if KIN {
            let gw = if E::CORRECTION {
                corr[i].l_inv * pr.grad
            } else {
                pr.grad
            };
            let w = 2.0 * mj * inv_j;
            out.div += w * dv.dot(&gw);
            if E::STRENGTH {
                out.grad_v += outer(&dv, &gw) * w;
            }
        }
    });
    out
}
