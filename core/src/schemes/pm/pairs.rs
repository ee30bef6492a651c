//! The pair interactions of the contact family: the elastic Riemann problem of each pair
//! (its MUSCL states), the star states and their sums.

use super::volume::pair_v2;
use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::limiter::{bounded_extrapolation, Limiter};
use crate::math::{Matrix, Real, Sym3, Vector};
use crate::riemann::low_dissipation::central_vector;
use crate::riemann::{acoustic_star_vector, elastic_star_vector, two_shock_star, ShockSide};
use crate::schemes::artificial_stress::pair_acceleration;
use crate::schemes::common::{cauchy, failed, outer, pair_pressure};
use crate::schemes::options::{RiemannSolver, SpecificVolume};
use crate::schemes::pairs::{for_each_pair, solve_pair_rows, Pair};
use crate::schemes::pm::records::PmStar;
use crate::schemes::workspace::{StepParams, Workspace};
use crate::state::{Aux, Correction, Gradients, Hourglass, PairGeom, PairSums, System};

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

/// The traction axis of pair (i, j): `n`, or with correction `(L_i^-1 + L_j^-1)/2 n`.
#[inline(always)]
fn traction_axis<const D: usize, E: Effects>(
    corr: &[Correction<D>],
    i: usize,
    j: usize,
    pr: &Pair<D>,
) -> Vector<D> {
    if E::CORRECTION {
        (corr[i].l_inv + corr[j].l_inv) * pr.n * 0.5
    } else {
        pr.n
    }
}

/// The basis a pair's vectors are limited in: in 2D the pair's frame, `n` and its normal
/// `(-n_y, n_x)`, which turns and mirrors with the pair (the limiters are odd, so the
/// normal's sign does not matter); in 1D `n`. In 3D the scene's axes, as Rublev & Murzov:
/// a tangent basis that turns with the pair would have to come from the data (a fixed
/// construction of the tangent plane does not mirror with it), and the one tried, the
/// direction of the tangential jump, broke the bit-for-bit equality of a quarter model
/// with symmetry planes and the whole body (`host/tests/walls.rs`) by 2e-2 spacings.
#[inline(always)]
fn pair_basis<const D: usize>(n: &Vector<D>) -> [Vector<D>; D] {
    let mut b = [Vector::<D>::zeros(); D];
    if D == 2 {
        b[0] = *n;
        b[1][0] = -n[1];
        b[1][1] = n[0];
    } else {
        for (a, e) in b.iter_mut().enumerate() {
            e[a] = 1.0;
        }
    }
    b
}

/// MUSCL of a vector quantity component by component in the pair's frame ([`pair_basis`]):
/// the limiter sees the normal and tangential parts, whatever the axes of the scene.
///
/// Lane twin: `muscl_frame` in `schemes/pm/lanes_frame.rs`.
#[inline(always)]
fn muscl_frame<const D: usize>(
    lim: Limiter,
    basis: &[Vector<D>; D],
    wi: &Vector<D>,
    wj: &Vector<D>,
    di: &Vector<D>,
    dj: &Vector<D>,
) -> (Vector<D>, Vector<D>) {
    let (mut l, mut r) = (Vector::<D>::zeros(), Vector::<D>::zeros());
    for e in basis {
        let (a, b) = muscl_pair(lim, wi.dot(e), wj.dot(e), di.dot(e), dj.dot(e));
        l += e * a;
        r += e * b;
    }
    (l, r)
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
    // the neighbour records of the vectorised rows (written where they run)
    let records = pm_records::<D, E, X>(sys, aux, corr, grad, grad_s, params, ws.rec, exec);
    let rows = StarRows {
        sys,
        aux,
        corr,
        grad,
        grad_s,
        rec: ws.rec,
        params,
    };
    solve_pair_rows::<D, X, PmStar<D>>(
        params,
        geom,
        ws.pm_star,
        exec,
        |i, geom, owned, out| {
            if records {
                pm_star_row::<D, E>(&rows, i, geom, owned, out)
            } else {
                0
            }
        },
        |i, pr| pair_star::<D, E>(sys, aux, corr, grad, grad_s, params, i, pr),
    );
    let stars: &[PmStar<D>] = ws.pm_star;
    // options.specific_volume: the kernel product's <s^2> per h_i h_j (super::volume)
    let mu = match params.options.specific_volume {
        SpecificVolume::Product => None,
        SpecificVolume::Interpolated => {
            Some(params.kernel.second_moment::<D>() / (4.0 * D as Real))
        }
    };
    let hg: &[Hourglass<D>] = if E::STRENGTH && super::split_stress::<D, E>(params) {
        ws.hg
    } else {
        &[]
    };
    let ctx = GatherCtx {
        geom,
        aux,
        corr,
        art,
        fac,
        stars,
        grad,
        mu,
        hg,
    };
    // the run-time flags chosen outside the pair loop, so that the loop without one has
    // none of its code (the energy equation's choice inside the loop cost pm's 2D impact
    // 4 %, interleaved rounds)
    let art_on = params.has::<E>(EffectSet::ARTIFICIAL_STRESS);
    let total = super::total_energy::<D, E>(params);
    exec.run(&mut *ws.sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let new = match (art_on, total) {
                (true, true) => gather::<D, E, KIN, DYN, true, true>(sys, &ctx, params, i),
                (true, false) => gather::<D, E, KIN, DYN, true, false>(sys, &ctx, params, i),
                (false, true) => gather::<D, E, KIN, DYN, false, true>(sys, &ctx, params, i),
                (false, false) => gather::<D, E, KIN, DYN, false, false>(sys, &ctx, params, i),
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
    grad: &'a [Gradients<D>],
    /// `Some(<s^2>/(h_i h_j))` with `options.specific_volume = "interpolated"`.
    mu: Option<Real>,
    /// The hourglass stiffness's records where the deviator acts through the central
    /// adjoint force (`super::split_stress`); empty otherwise.
    hg: &'a [Hourglass<D>],
}

/// The star state of pair (i, j) with `i` on the left (`pr` seen from `i`): MUSCL states
/// (with `E::MUSCL`), tractions on the (corrected, with `E::CORRECTION`) axis, the elastic
/// Riemann problem, and no tension across the contact of a failed particle.
///
/// Lane twin: `star_row` in `schemes/pm/lanes.rs` (entered by [`pm_star_row`]; the MUSCL
/// frame and the vector Riemann problem in `lanes_frame.rs` and `simd/riemann.rs`), held
/// bitwise equal by `schemes/star_tests.rs`; a change here is a change there.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) fn pair_star<const D: usize, E: Effects>(
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
    // with the hourglass stiffness the deviator acts through the central force of
    // `gather` (the adjoint of the corrected gradient that advances it), and the Riemann
    // problem carries the pressure (see the module `super`)
    let split = E::STRENGTH && super::split_stress::<D, E>(params);
    let (sig_i, sig_j) = if split {
        (
            Sym3::isotropic(-pair_pressure::<D, E>(sys, i)),
            Sym3::isotropic(-pair_pressure::<D, E>(sys, j)),
        )
    } else {
        (cauchy::<D, E>(sys, i), cauchy::<D, E>(sys, j))
    };
    let (mut rho_l, mut rho_r) = (rhoi, rhoj);
    let (mut cl_l, mut cl_r) = (sys.cl[i], sys.cl[j]);
    let (mut ct_l, mut ct_r) = (ct_i, ct_j);
    let (mut v_l, mut v_r) = (vi, sys.v[j]);
    let failed_pair = failed::<D, E>(sys, i) || failed::<D, E>(sys, j);
    let rji = pr.n * pr.r;
    // options.objective: both velocities taken to the pair's midpoint along the pair's
    // mean rigid rotation W, v_i + W r_ji/2 and v_j - W r_ji/2 (the MUSCL slopes less W),
    // so that a rigid rotation leaves no jump. W r_ji is normal to n: only the transverse
    // problems change.
    let mut spin = Matrix::<D>::zeros();
    if super::gradients::objective::<D, E>(params) {
        spin = (grad[i].w + grad[j].w) * 0.5;
        let half = spin * rji * 0.5;
        v_l += half;
        v_r -= half;
    }
    let axis = traction_axis::<D, E>(corr, i, j, pr);
    let (mut t_l, mut t_r) = (sig_i.dot_vec(&axis), sig_j.dot_vec(&axis));
    if E::MUSCL && !failed_pair {
        let lim = params.options.limiter;
        let (gi, gj) = (&grad[i], &grad[j]);
        (rho_l, rho_r) = muscl_pair(lim, rhoi, rhoj, gi.rho.dot(&rji), gj.rho.dot(&rji));
        (cl_l, cl_r) = muscl_pair(lim, cl_l, cl_r, gi.cl.dot(&rji), gj.cl.dot(&rji));
        (ct_l, ct_r) = muscl_pair(lim, ct_l, ct_r, gi.ct.dot(&rji), gj.ct.dot(&rji));
        let dvi = (gi.v - spin) * rji;
        let dvj = (gj.v - spin) * rji;
        let (wi, wj) = (v_l, v_r);
        (v_l, v_r) = muscl_frame(lim, &pair_basis(&pr.n), &wi, &wj, &dvi, &dvj);
        if split {
            // the pressure alone, from its own slope (`gradient_pass`)
            let (pl, pr_) = muscl_pair(lim, -sig_i.xx, -sig_j.xx, gi.p.dot(&rji), gj.p.dot(&rji));
            (t_l, t_r) = (axis * -pl, axis * -pr_);
        } else if E::STRENGTH {
            // the tractions on the axis, reconstructed in the pair's frame like the
            // velocity: D reconstructions instead of the six stress components'
            let slope = |g: &[Vector<D>; 6]| {
                let mut a = [0.0; 6];
                for c in 0..6 {
                    a[c] = g[c].dot(&rji);
                }
                Sym3::from_array(a).dot_vec(&axis)
            };
            (t_l, t_r) = muscl_frame(
                lim,
                &pair_basis(&pr.n),
                &t_l,
                &t_r,
                &slope(&grad_s[i]),
                &slope(&grad_s[j]),
            );
        } else {
            let (pl, pr_) = muscl_pair(lim, sys.p[i], sys.p[j], gi.p.dot(&rji), gj.p.dot(&rji));
            (t_l, t_r) = (axis * -pl, axis * -pr_);
        }
    }
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
/// eq 11) or `options.energy_equation = "total"` `power` is the total energy rate
/// `sum f_ij . V*_ij`; otherwise (`pm`, seed 000 eq 16) the internal energy rate
/// `sum f_ij . (V*_ij - v_i)` (`TOTAL`: [`super::total_energy`]).
#[inline(always)]
pub(super) fn gather<
    const D: usize,
    E: Effects,
    const KIN: bool,
    const DYN: bool,
    const ART: bool,
    const TOTAL: bool,
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
        grad,
        mu,
        hg,
    } = *ctx;
    let split = E::STRENGTH && !hg.is_empty();
    let vi = sys.v[i];
    let inv_i = aux[i].inv_rho;
    let mut out = PairSums::<D>::default();
    let mut grad_v = Matrix::<D>::zeros();
    for_each_pair(params, geom, i, |pr, e| {
        let j = pr.j;
        let st = &stars[e.pair];
        // the owner's traction acts on the face whose normal points away from it
        let (vs, ts) = (st.v, if e.owner { st.t } else { -st.t });
        let (mj, inv_j) = (sys.m[j], aux[j].inv_rho);
        let dv = vs - vi;
        if DYN {
            let vv = match mu {
                Some(mu) if pr.r > 0.0 => {
                    // V' = e . grad V with e = (x_i - x_j)/r = -n; cubic where the
                    // pair's normal traction is tension (super::volume)
                    let cubic = ts.dot(&pr.n) > 0.0;
                    let (vpi, vpj) = (-grad[i].sv.dot(&pr.n), -grad[j].sv.dot(&pr.n));
                    let mu = mu * sys.h[i] * sys.h[j];
                    pair_v2(inv_i, inv_j, vpi, vpj, pr.r, mu, cubic)
                }
                _ => inv_i * inv_j,
            };
            let f = -2.0 * mj * pr.dw * vv;
            out.acc += ts * f;
            out.power += f * ts.dot(if TOTAL { &vs } else { &dv });
            if split {
                // the deviator's central force, the adjoint of the corrected gradient
                // that advances it: V_i V_j (S_i C_i + S_j C_j) grad_i W / m_i, its work
                // at the pair's mean velocity
                let a = (sys.s[i].dot_vec(&(hg[i].c * pr.grad))
                    + sys.s[j].dot_vec(&(hg[j].c * pr.grad)))
                    * (mj * inv_i * inv_j);
                let vbar = (vi + sys.v[j]) * 0.5;
                out.acc += a;
                out.power += a.dot(&if TOTAL { vbar } else { vbar - vi });
            }
            if ART {
                // a pair force outside the Riemann problem: its work at the pair's mean
                // velocity (total energy form with correction, internal otherwise)
                let a = pair_acceleration(mj, fac[e.pair], &art[i], &art[j], &pr.grad);
                let vbar = (vi + sys.v[j]) * 0.5;
                out.acc += a;
                out.power += a.dot(&if TOTAL { vbar } else { vbar - vi });
            }
        }
        if KIN {
            let w = 2.0 * mj * inv_j;
            if E::CORRECTION {
                // uncorrected here, `L^-1` once below
                grad_v += outer(&dv, &pr.grad) * w;
            } else {
                out.div += w * dv.dot(&pr.grad);
                if E::STRENGTH {
                    out.grad_v += outer(&dv, &pr.grad) * w;
                }
            }
        }
    });
    if KIN && E::CORRECTION {
        // sum w dv ⊗ (L^-1 grad W) = (sum w dv ⊗ grad W) L^-T, and the divergence is its
        // trace (the same sums as correcting each kernel gradient, to round-off)
        let g = grad_v * corr[i].l_inv.transpose();
        out.div = g.trace();
        if E::STRENGTH {
            out.grad_v = g;
        }
    }
    out
}

/// Writes every particle's neighbour record for [`pm_star_row`] into `rec` where the
/// level and the step's options allow the vectorised row and it pays (AVX2 or AVX-512;
/// `super::lanes::covers` and `pays`) and `rec` has the room (`state::record_len`); returns
/// whether it did (false: the rows run the portable loop).
#[inline(always)]
#[allow(clippy::too_many_arguments, unused_variables)]
pub(crate) fn pm_records<const D: usize, E: crate::effects::Effects, X: crate::exec::Executor>(
    sys: &crate::state::System<'_, D>,
    aux: &[crate::state::Aux],
    corr: &[crate::state::Correction<D>],
    grad: &[crate::state::Gradients<D>],
    grad_s: &[[crate::math::Vector<D>; 6]],
    params: &crate::schemes::workspace::StepParams<'_, D>,
    rec: &mut [crate::math::Real],
    exec: &X,
) -> bool {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if params.simd.vectorised()
        && super::lanes::covers(params)
        && crate::schemes::pairs::stars_pay::<D, E>(params)
        && rec.len() == sys.x.len() * crate::schemes::pm::record_len(D)
    {
        super::lanes::write_records::<D, E, X>(sys, aux, corr, grad, grad_s, params, rec, exec);
        return true;
    }
    false
}

/// The star states of the pairs particle `i` owns (`pm`, `tkc`: its neighbours `owned`,
/// their geometry `geom`) into `out` by the vectorised loop, from the neighbour records
/// `rec` [`pm_records`] wrote (call only where it returned true). Returns how many pairs it
/// did (0: none; the portable loop does the rest), each bitwise as
/// [`crate::schemes::pm::pairs::pair_star`] gives it.
#[inline(always)]
#[allow(unused_variables)]
pub(crate) fn pm_star_row<const D: usize, E: crate::effects::Effects>(
    rows: &StarRows<'_, D>,
    i: usize,
    geom: &[PairGeom<D>],
    owned: &[u32],
    out: &mut [PmStar<D>],
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

/// What every star row of a pass reads besides its own pairs: the portable
/// [`pair_star`]'s inputs and the neighbour records of its lane twin.
#[derive(Clone, Copy)]
// read by the lane rows alone (x86_64, f64): a build without them only fills it
#[cfg_attr(
    not(all(target_arch = "x86_64", not(feature = "f32"))),
    allow(dead_code)
)]
pub(crate) struct StarRows<'a, const D: usize> {
    pub sys: &'a System<'a, D>,
    pub aux: &'a [Aux],
    pub corr: &'a [Correction<D>],
    pub grad: &'a [Gradients<D>],
    pub grad_s: &'a [[Vector<D>; 6]],
    /// The neighbour records [`pm_records`] wrote.
    pub rec: &'a [Real],
    pub params: &'a StepParams<'a, D>,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rotate(a: Real, v: &Vector<2>) -> Vector<2> {
        let (s, c) = (crate::math::real::sin(a), crate::math::real::cos(a));
        Vector::<2>::new(c * v[0] - s * v[1], s * v[0] + c * v[1])
    }

    /// The reconstruction in the pair's frame does not depend on the scene's axes: rotating
    /// the pair, both states and both slopes rotates the reconstructed states, for every
    /// limiter (to round-off). In the scene's axes, component by component, it does not.
    #[test]
    fn muscl_in_the_pair_frame_is_indifferent_to_the_axes() {
        let n = Vector::<2>::new(0.6, 0.8);
        let (wi, wj) = (Vector::<2>::new(1.0, -2.0), Vector::<2>::new(1.5, -0.5));
        let (di, dj) = (Vector::<2>::new(0.2, 2.5), Vector::<2>::new(0.9, 0.1));
        for lim in [
            Limiter::Minmod,
            Limiter::Superbee,
            Limiter::MonotonizedCentral,
            Limiter::VanLeer,
        ] {
            let (l, r) = muscl_frame(lim, &pair_basis(&n), &wi, &wj, &di, &dj);
            let mut axes_differ = false;
            for a in [0.3, 1.1, 2.9] {
                let rot = |v: &Vector<2>| rotate(a, v);
                let (lr, rr) = muscl_frame(
                    lim,
                    &pair_basis(&rot(&n)),
                    &rot(&wi),
                    &rot(&wj),
                    &rot(&di),
                    &rot(&dj),
                );
                assert!((lr - rot(&l)).norm() < 1e-13, "{lim} {a}");
                assert!((rr - rot(&r)).norm() < 1e-13, "{lim} {a}");
                // component by component in the scene's axes
                let (mut lc, mut rc) = (Vector::<2>::zeros(), Vector::<2>::zeros());
                let (wir, wjr, dir, djr) = (rot(&wi), rot(&wj), rot(&di), rot(&dj));
                for c in 0..2 {
                    (lc[c], rc[c]) = muscl_pair(lim, wir[c], wjr[c], dir[c], djr[c]);
                }
                axes_differ |= (lc - rot(&l)).norm() > 1e-6 || (rc - rot(&r)).norm() > 1e-6;
            }
            assert!(axes_differ, "{lim}: the test cannot tell the frames apart");
        }
    }

    /// The 2D basis is orthonormal and starts with `n`; the 3D one is the scene's axes.
    #[test]
    fn the_pair_basis_is_orthonormal() {
        let n2 = Vector::<2>::new(0.6, -0.8);
        let b2 = pair_basis(&n2);
        assert_eq!(b2[0], n2);
        assert!(b2[0].dot(&b2[1]).abs() < 1e-15 && (b2[1].norm() - 1.0).abs() < 1e-15);
        let b3 = pair_basis(&Vector::<3>::new(0.48, 0.6, 0.64));
        assert_eq!(b3, [Vector::<3>::x(), Vector::<3>::y(), Vector::<3>::z()]);
    }

    /// In 3D the reconstruction mirrors with the data, bit for bit: a pair and its mirror
    /// image in a coordinate plane (a symmetry wall) give mirrored states. (So does 2D.)
    #[test]
    fn muscl_in_the_pair_frame_mirrors_bit_for_bit_in_3d() {
        let n = Vector::<3>::new(0.48, 0.6, 0.64);
        let (wi, wj) = (
            Vector::<3>::new(1.0, -2.0, 0.5),
            Vector::<3>::new(1.5, -0.5, 0.25),
        );
        let (di, dj) = (
            Vector::<3>::new(0.2, 2.5, -0.3),
            Vector::<3>::new(0.9, 0.1, 0.7),
        );
        for axis in 0..3 {
            let m = |v: &Vector<3>| {
                let mut r = *v;
                r[axis] = -r[axis];
                r
            };
            for lim in [Limiter::Minmod, Limiter::Superbee] {
                let (l, r) = muscl_frame(lim, &pair_basis(&n), &wi, &wj, &di, &dj);
                let (lm, rm) =
                    muscl_frame(lim, &pair_basis(&m(&n)), &m(&wi), &m(&wj), &m(&di), &m(&dj));
                assert_eq!((lm, rm), (m(&l), m(&r)), "{lim} axis {axis}");
            }
        }
    }
}
