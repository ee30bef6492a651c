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
//! quantity Phi (stress components, rho, c_l, c_t, velocity) is extrapolated to the
//! contact with `Phi_l = Phi_i + minmod(Phi_j - Phi_i, grad Phi_i . r_ji)/2` and
//! `Phi_r = Phi_j - minmod(grad Phi_j . r_ji, Phi_j - Phi_i)/2` (004 eqs 13–15).

use super::artificial_stress::pair_acceleration;
use super::common::{
    advance_deviator, artificial_stress_tensors, cauchy, failed, for_each_pair, geometry_pass,
    halo_exchange, min_sym_eigenvalue, outer, refresh_aux, refresh_eos, refresh_pressure,
    solve_pairs, Pair,
};
use super::options::{read_if, why, NotRead, OptionKey};
use super::{Scheme, SchemeFamily};
use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::halo::{Exchange, Fields, Halo};
use crate::limiter::{bounded_extrapolation, Limiter};
use crate::math::{det, inverse, Matrix, Real, Sym3, Vector};
use crate::riemann::{acoustic_star_vector, elastic_star_vector, two_shock_star, ShockSide};
use crate::state::{
    Aux, Correction, Family, Gradients, Layout, PairGeom, PairSums, PmStar, RiemannSolver,
    SchemeOptions, StepError, StepParams, System, Workspace,
};

/// The halo exchanges of a `pm`/`tkc` step, in order (see [`crate::halo`]).
///
/// 1. At the start: x, h (pair geometry); v, rho, p, c_l, S, damage (the kernel
///    correction, the gradients, the Riemann problems; aux and c_t are recomputed locally
///    from rho).
/// 2. Before the pair pass, with correction or MUSCL: the corrections and gradients of
///    both sides of every pair.
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
        fields: Fields::CORR.with(Fields::GRAD).with(Fields::GRAD_STRESS),
        needs: EffectSet::HYDRO,
        needs_any: EffectSet::CORRECTION.union(EffectSet::MUSCL),
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

/// Reconstructed contact values of a pair: `Phi_l = Phi_i + phi(r) (grad Phi_i . r_ji)/2`
/// with `r = (Phi_j - Phi_i)/(grad Phi_i . r_ji)` (and likewise for j), each side's
/// extrapolation bounded by half the pair difference ([`bounded_extrapolation`]). With
/// the minmod limiter (tkc's, seed 004 eqs 13-15) this is exactly
/// `Phi_i + minmod(Phi_j - Phi_i, grad Phi_i . r_ji)/2` and the bound never acts; the
/// other limiters of [`Limiter`] may extrapolate up to the pair mean.
#[inline(always)]
fn muscl_pair(lim: Limiter, phi_i: Real, phi_j: Real, gi_rji: Real, gj_rji: Real) -> (Real, Real) {
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

/// Relative tolerance of the near-surface test: a boundary particle at `r <= h (1 + tol)`
/// counts as within the smoothing length `h`.
///
/// Seed 004 sets `L = I` for a particle "with a boundary particle within its smoothing
/// length". At its theta = 0.5 (h_factor 1) the first neighbour shell of a regular lattice
/// lies at exactly `h`, so `r < h` decided by round-off (`5.000000000000004e-4` against
/// `5e-4`) whether the row next to a free surface was flagged, and the answer changed with
/// the resolution. A neighbour at `h` counts as within: then theta = 0.5 flags that row as
/// theta = 0.6–0.7 do. 1e-9 is far above round-off in `r` and `h` and far below any lattice
/// irregularity (a polar lattice's rings differ from `h` by ~1e-4 relative).
pub const NEAR_SURFACE_TOLERANCE: Real = 1e-9;

/// Kernel correction: L_i, its inverse and the free-surface flags (2: smallest
/// eigenvalue of L below `surface_lambda`; 1: a flag-2 particle within `h_i`, up to
/// [`NEAR_SURFACE_TOLERANCE`]; 0 otherwise).
pub(crate) fn correction_pass<const D: usize, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    corr: &mut [Correction<D>],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let lam = params.options.surface_lambda;
    let eps = params.options.det_epsilon;
    exec.run(&mut *corr, |off, chunk: &mut [Correction<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let mut l = Matrix::<D>::zeros();
            for_each_pair(params, geom, i, |pr, _| {
                let vol = aux[pr.j].vol;
                // L = sum V_j grad_i W_ij ⊗ (x_j - x_i), with x_j - x_i = r n
                l += outer(&pr.grad, &(pr.n * pr.r)) * vol;
            });
            let lam_min = min_sym_eigenvalue(&l);
            out.lambda_min = lam_min;
            out.boundary = if lam_min < lam { 2 } else { 0 };
            out.l_inv = match inverse(&l) {
                Some(inv) if det(&l) >= eps => inv,
                _ => Matrix::<D>::identity(),
            };
        }
    });
    // Particles with a boundary particle within their smoothing length use L = I
    // (marked with `PairSums::set_surface`).
    let within = 1.0 + NEAR_SURFACE_TOLERANCE;
    let c: &[Correction<D>] = corr;
    exec.run(&mut *sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let mut near = c[i].boundary == 2;
            let reach = sys.h[i] * within;
            for_each_pair(params, geom, i, |pr, _| {
                if c[pr.j].boundary == 2 && pr.r > 0.0 && pr.r <= reach {
                    near = true;
                }
            });
            out.set_surface(near);
        }
    });
    let s: &[PairSums<D>] = sums;
    exec.run(corr, |off, chunk: &mut [Correction<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            if s[off + k].surface() {
                if out.boundary == 0 {
                    out.boundary = 1;
                }
                out.l_inv = Matrix::<D>::identity();
            }
        }
    });
}

/// Gradients of the reconstructed quantities (corrected when `E::CORRECTION`).
#[allow(clippy::too_many_arguments)]
fn gradient_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    corr: &[Correction<D>],
    grad: &mut [Gradients<D>],
    grad_stress: &mut [[Vector<D>; 6]],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    exec.run(
        (grad, grad_stress),
        |off, (g, gs): (&mut [Gradients<D>], &mut [[Vector<D>; 6]])| {
            for (k, out) in g.iter_mut().enumerate() {
                let i = off + k;
                let mut acc = Gradients::<D>::default();
                let mut acc_s = [Vector::<D>::zeros(); 6];
                let si = cauchy::<D, E>(sys, i).to_array();
                let cti = aux[i].ct;
                for_each_pair(params, geom, i, |pr, _| {
                    let j = pr.j;
                    let vol = aux[j].vol;
                    let gw = if E::CORRECTION {
                        corr[i].l_inv * pr.grad
                    } else {
                        pr.grad
                    } * vol;
                    acc.rho += gw * (sys.rho[j] - sys.rho[i]);
                    acc.p += gw * (sys.p[j] - sys.p[i]);
                    acc.cl += gw * (sys.cl[j] - sys.cl[i]);
                    acc.ct += gw * (aux[j].ct - cti);
                    acc.v += outer(&(sys.v[j] - sys.v[i]), &gw);
                    if E::STRENGTH {
                        let sj = cauchy::<D, E>(sys, j).to_array();
                        for c in 0..6 {
                            acc_s[c] += gw * (sj[c] - si[c]);
                        }
                    }
                });
                *out = acc;
                if E::STRENGTH {
                    gs[k] = acc_s;
                }
            }
        },
    );
}

/// Whether a scheme of the contact family (`pm`, `tkc`) reads `key` with `effects` (its
/// own and those the scene's `correction` and `muscl` ask for), or why not
/// ([`crate::schemes::options`]).
pub(crate) fn reads(scheme: Scheme, key: OptionKey, effects: EffectSet) -> Result<(), NotRead> {
    use OptionKey::*;
    match key {
        AvAlpha | AvBeta => read_if(false, scheme, why::AV_ONLY),
        Limiter => read_if(effects.contains(EffectSet::MUSCL), scheme, why::NO_MUSCL),
        Riemann | ArtificialStress | ArtificialStressExponent => Ok(()),
        MusclTime => read_if(false, scheme, why::NO_MUSCL_TIME),
        SurfaceLambda | DetEpsilon => read_if(
            effects.contains(EffectSet::CORRECTION),
            scheme,
            why::NO_SURFACE,
        ),
        Correction if scheme == Scheme::Tkc => Err(NotRead::Always { what: "correction" }),
        Muscl if scheme == Scheme::Tkc => Err(NotRead::Always { what: "MUSCL" }),
        Correction | Muscl => Ok(()),
    }
}

/// The options a scheme of the contact family starts from: `tkc` limits with minmod
/// (Rublev & Murzov), `pm` with MUSCL keeps the seeds' superbee.
pub(crate) fn defaults(scheme: Scheme) -> SchemeOptions {
    let mut o = SchemeOptions::default();
    if scheme == Scheme::Tkc {
        o.limiter = Limiter::Minmod;
    }
    o
}

impl SchemeFamily for Pm {
    const FAMILY: Family = Family::Pm;
    const SUPPORTED: EffectSet = EffectSet::STRENGTH
        .union(EffectSet::PLASTICITY)
        .union(EffectSet::DAMAGE)
        .union(EffectSet::HEAT)
        .union(EffectSet::PERIODIC)
        .union(EffectSet::CORRECTION)
        .union(EffectSet::MUSCL)
        .union(EffectSet::ARTIFICIAL_STRESS);
    const EXCHANGES: &'static [Exchange] = &EXCHANGES;

    fn layout(effects: EffectSet) -> Layout {
        Layout {
            grad_stress: effects.contains(EffectSet::MUSCL)
                && effects.contains(EffectSet::STRENGTH),
            pm_star: true,
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
        let [start, pair, dynamic] = &EXCHANGES;
        halo_exchange!(params, halo, start, sys, ws);
        geometry_pass::<D, E, X>(sys.x, sys.h, params, ws.geom, ws.fac, exec);
        refresh_aux::<D, true, X>(sys, ws.aux, params, exec);
        {
            let sysr: &System<'_, D> = sys;
            let geom: &[PairGeom<D>] = ws.geom;
            if E::CORRECTION {
                correction_pass::<D, X>(sysr, geom, ws.aux, ws.corr, ws.sums, params, exec);
            }
            if E::MUSCL {
                gradient_pass::<D, E, X>(
                    sysr,
                    geom,
                    ws.aux,
                    ws.corr,
                    ws.grad,
                    ws.grad_stress,
                    params,
                    exec,
                );
            }
        }
        halo_exchange!(params, halo, pair, sys, ws);
        if E::MUSCL {
            // With MUSCL the Riemann dissipation nearly vanishes in smooth flow, and the
            // explicit Euler of the seed (forces and strain rates from the same old state)
            // amplifies waves: a sound pulse gained 6 % kinetic energy in 1 us. So, as in
            // `ts`, density and deviator are advanced first from the contact velocities of
            // the old state, and the forces then use the new stresses (symplectic Euler);
            // the reconstruction slopes of the second pass are those of the first.
            pair_pass::<D, E, X, true, false>(sys, ws, params, exec);
            exec.run(
                (sys.reborrow(), &ws.sums[..]),
                |_, (mut s, sums): (System<'_, D>, &[PairSums<D>])| {
                    for k in 0..s.len() {
                        let mat = &params.materials[s.mat[k] as usize];
                        kinematic_update::<D, E>(&mut s, k, mat, &sums[k], dt);
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
            exec.run(
                (sys.reborrow(), &ws.sums[..]),
                |_, (mut s, sums): (System<'_, D>, &[PairSums<D>])| {
                    for k in 0..s.len() {
                        let mat = &params.materials[s.mat[k] as usize];
                        // explicit Euler (seed 000): every rate from the same old state
                        dynamic_update::<D, E>(&mut s, k, &sums[k], params);
                        kinematic_update::<D, E>(&mut s, k, mat, &sums[k], dt);
                        refresh_eos(&mut s, k, mat, params);
                    }
                },
            );
        }
        Ok(())
    }
}

/// One pass over the pairs: every pair's star state solved once on its owner's side
/// ([`pair_star`]), then the sums of each particle gathered in canonical order
/// ([`gather`]).
fn pair_pass<const D: usize, E: Effects, X: Executor, const KIN: bool, const DYN: bool>(
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

/// Density (eq 16) and deviator (Hooke + Jaumann + return) of local particle `k`.
#[inline(always)]
fn kinematic_update<const D: usize, E: Effects>(
    s: &mut System<'_, D>,
    k: usize,
    mat: &crate::material::Material,
    ps: &PairSums<D>,
    dt: Real,
) {
    s.rho[k] *= crate::math::real::exp(-dt * ps.div);
    if E::STRENGTH {
        advance_deviator::<D, E>(s, k, mat, &ps.grad_v, dt);
    }
}

/// Velocity, energy and position of local particle `k`. With correction the energy
/// equation is seed 004's total energy, `E += dt sum f.V*`, which with
/// `e = E - v²/2` is `de = dt (power - acc . (v + dv/2))`: exactly conservative.
#[inline(always)]
fn dynamic_update<const D: usize, E: Effects>(
    s: &mut System<'_, D>,
    k: usize,
    ps: &PairSums<D>,
    params: &StepParams<'_, D>,
) {
    let dt = params.dt;
    let dv = ps.acc * dt;
    if E::CORRECTION {
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

/// What the gather of the pair sums reads besides the particles.
#[derive(Clone, Copy)]
struct GatherCtx<'a, const D: usize> {
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
fn pair_star<const D: usize, E: Effects>(
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
    let (vs, mut ts) = match params.options.riemann {
        RiemannSolver::Acoustic => acoustic_star_vector(
            &pr.n,
            &v_l,
            &t_l,
            rho_l * cl_l,
            rho_l * ct_l,
            &v_r,
            &t_r,
            rho_r * cl_r,
            rho_r * ct_r,
        ),
        // the longitudinal wave as a shock or expansion with Us = c_l + s up (the
        // EOS's Hugoniot slope), the transverse waves acoustic
        RiemannSolver::TwoShock => elastic_star_vector(
            &pr.n,
            &v_l,
            &t_l,
            rho_l * ct_l,
            &v_r,
            &t_r,
            rho_r * ct_r,
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
fn gather<const D: usize, E: Effects, const KIN: bool, const DYN: bool, const ART: bool>(
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
