//! The vectorised star states of the contact family's pairs (`pm`, `tkc`): four (AVX2) or
//! eight (AVX-512) pairs of one row per instruction, each lane doing the portable
//! [`pair_star`]'s IEEE operations in its order (module docs of [`super`]; the lane
//! arithmetic in `pm_lanes.rs`): the rotation of `options.objective`, the corrected
//! traction axis, the MUSCL reconstruction in the pair's frame and the acoustic elastic
//! Riemann problem. The owner's values are broadcast once per row; the neighbours' come
//! from their records ([`write_records`]), a register's records loaded four reals at a time
//! and transposed into lanes.
//!
//! Covered: the acoustic and two-shock solvers with full dissipation on every channel and
//! the minmod or superbee limiter ([`covers`]). A lane with a failed particle, or whose
//! two-shock answer falls back to the acoustic one (an impedance not positive and finite,
//! an answer not finite), is solved again by the portable [`pair_star`].

use core::arch::x86_64::{__m256d, __m512d};

use super::lanes_frame::{muscl_pair, Calls};
use crate::effects::Effects;
use crate::exec::{for_each_record, Executor};
use crate::limiter::Limiter;
use crate::math::{Real, Sym3};
use crate::riemann::Dissipation;
use crate::schemes::av::records::sym_at;
use crate::schemes::common::failed;
use crate::schemes::options::{RiemannSolver, SchemeOptions};
use crate::schemes::pairs::Pair;
use crate::schemes::pm::gradients::objective;
use crate::schemes::pm::pairs::{pair_star, StarRows};
use crate::schemes::pm::records::PmStar;
use crate::schemes::pm::records::{record_len, RecordAt};
use crate::schemes::workspace::StepParams;
#[cfg(test)]
use crate::simd::lanes::Emu;
use crate::simd::ops::*;
use crate::simd::riemann::*;
use crate::simd::{Simd, SimdLevel};
use crate::state::{Aux, Correction, Gradients, PairGeom, System};

/// Writes every particle's neighbour record ([`RecordAt`]) for [`star_row`]: exactly the
/// values the portable [`pair_star`] reads of a neighbour (its Cauchy stress as the row's
/// `sig` forms it); the fields of arrays the case does not have (`corr`, `grad`, `grad_s`
/// empty) stay as they are, unread.
#[allow(clippy::too_many_arguments)]
pub(crate) fn write_records<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    aux: &[Aux],
    corr: &[Correction<D>],
    grad: &[Gradients<D>],
    grad_s: &[[crate::math::Vector<D>; 6]],
    params: &StepParams<'_, D>,
    rec: &mut [Real],
    exec: &X,
) {
    let (at, width) = (RecordAt::of(D), record_len(D));
    let mats = params.materials;
    for_each_record(exec, rec, width, |i, r| {
        r[at.rho] = sys.rho[i];
        r[at.cl] = sys.cl[i];
        r[at.ct] = aux[i].ct;
        r[at.slope] = shock_slope(&mats[sys.mat[i] as usize]);
        r[at.failed] = if failed::<D, E>(sys, i) { 1.0 } else { 0.0 };
        r[at.p] = sys.p[i];
        for a in 0..D {
            r[at.v + a] = sys.v[i][a];
            for b in 0..D {
                r[at.sig + a * D + b] = stress::<D, E>(sys, i, a, b);
            }
        }
        if let Some(c) = corr.get(i) {
            for a in 0..D {
                for b in 0..D {
                    r[at.l_inv + a * D + b] = c.l_inv[(a, b)];
                }
            }
        }
        if let Some(g) = grad.get(i) {
            for a in 0..D {
                r[at.grad_rho + a] = g.rho[a];
                r[at.grad_cl + a] = g.cl[a];
                r[at.grad_ct + a] = g.ct[a];
                r[at.grad_p + a] = g.p[a];
                for b in 0..D {
                    r[at.w + a * D + b] = g.w[(a, b)];
                    r[at.grad_v + a * D + b] = g.v[(a, b)];
                }
            }
        }
        if let Some(gs) = grad_s.get(i) {
            for a in 0..D {
                for b in a..D {
                    for c in 0..D {
                        r[at.grad_s + sym_at(D, a, b) * D + c] = gs[Sym3::voigt(a, b)][c];
                    }
                }
            }
        }
    });
}

/// The Cauchy stress `S - P I` of particle `k` as the pairs see it (`-P I` without
/// strength): off the diagonal `S + (-0) = S`.
#[inline(always)]
fn stress<const D: usize, E: Effects>(sys: &System<'_, D>, k: usize, a: usize, b: usize) -> Real {
    let p = sys.p[k];
    if E::STRENGTH {
        let s = sys.s[k].get(a, b);
        s + if a == b { -p } else { -0.0 }
    } else if a == b {
        -p
    } else {
        0.0
    }
}

/// Whether [`star_row`] covers the options of this step. Every option is named (no `..`)
/// and every choice of the ones the star reads is matched: an option or a choice added
/// to the scheme is a compile error here until the lanes implement it or decline it.
#[inline(always)]
pub(crate) fn covers<const D: usize>(params: &StepParams<'_, D>) -> bool {
    let SchemeOptions {
        // read by the star, implemented below
        limiter,
        riemann,
        dissipation,
        transverse_dissipation,
        // read by the star through the spin of the gradient pass (`gradients::objective`),
        // which the rows rotate by as the portable star does
        objective: _,
        // read by the passes that fill the records (the corrected slopes, the surface
        // flags, L^-1), not by the star
        corrected_slopes: _,
        surface_lambda: _,
        surface_scan: _,
        det_epsilon: _,
        // read by the pair force, the energy sums and the integrator, not by the star
        specific_volume: _,
        energy_equation: _,
        integrator: _,
        artificial_stress: _,
        artificial_stress_exponent: _,
        constant_h: _,
        // the hourglass stiffness: its own passes, and the star's pressure-only
        // tractions, which the rows decline (the effect, below)
        hourglass: _,
        // tl's, refused by the table
        reference_update: _,
        // the effects the step is compiled with (`E`), not read from here
        correction: _,
        muscl: _,
        // other families'
        av_alpha: _,
        av_beta: _,
        muscl_time: _,
    } = params.options;
    let limiter = match limiter {
        Limiter::Superbee | Limiter::Minmod => true,
        Limiter::MonotonizedCentral | Limiter::VanLeer | Limiter::Sweby(_) => false,
    };
    let riemann = match riemann {
        RiemannSolver::Acoustic | RiemannSolver::TwoShock => true,
    };
    let full = |d| match d {
        Dissipation::Full => true,
        Dissipation::Compression => false,
    };
    // with the hourglass stiffness the star carries the pressure only (the portable
    // `pair_star`); the rows carry the full stress
    let stiff = params
        .effects
        .contains(crate::effects::EffectSet::HOURGLASS);
    limiter && riemann && full(dissipation) && full(transverse_dissipation) && !stiff
}

/// The star states of the pairs particle `i` owns (its neighbours `owned`, their stored
/// geometry `geom`), a register at a time, as the portable [`pair_star`] gives them, into `out`;
/// the default record for a pair outside the support. Returns how many pairs it did (all).
///
/// # Safety
/// The CPU must have the level of `V`, and the step's options must pass [`covers`].
/// (Everything is indexed with bounds checks.)
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn star_row<V: Calls, const D: usize, E: Effects>(
    rows: &StarRows<'_, D>,
    i: usize,
    geom: &[PairGeom<D>],
    owned: &[u32],
    out: &mut [PmStar<D>],
) -> usize {
    let StarRows {
        sys,
        aux,
        corr,
        grad,
        grad_s,
        rec,
        params,
    } = *rows;
    let n_pairs = owned.len().min(geom.len()).min(out.len());
    let zero = V::zero();
    let superbee = params.options.limiter == Limiter::Superbee;
    let rotate = objective::<D, E>(params);
    let two_shock_solver = params.options.riemann == RiemannSolver::TwoShock;
    let mats = params.materials;
    let slope = |k: usize| shock_slope(&mats[sys.mat[k] as usize]);
    let slope_i: V = splat(if two_shock_solver { slope(i) } else { 0.0 });
    // the owner's values, broadcast
    let bv = |f: &dyn Fn(usize) -> Real| -> Vl<V> {
        core::array::from_fn(|a| if a < D { splat(f(a)) } else { zero })
    };
    let bm = |f: &dyn Fn(usize, usize) -> Real| -> Ml<V> {
        core::array::from_fn(|b| {
            core::array::from_fn(|a| if a < D && b < D { splat(f(a, b)) } else { zero })
        })
    };
    let vi = bv(&|a| sys.v[i][a]);
    let (rhoi, cli, cti, pi) = (
        splat(sys.rho[i]),
        splat(sys.cl[i]),
        splat(aux[i].ct),
        splat(sys.p[i]),
    );
    let sig_i = bm(&|a, b| stress::<D, E>(sys, i, a, b));
    let (at, width) = (RecordAt::of(D), record_len(D));
    let gi = if E::MUSCL || rotate {
        grad[i]
    } else {
        Gradients::default()
    };
    let li = if E::CORRECTION {
        corr[i].l_inv
    } else {
        crate::math::Matrix::<D>::identity()
    };
    let li_m = bm(&|a, b| li[(a, b)]);
    let wi_m = bm(&|a, b| gi.w[(a, b)]);
    let gvi_m = bm(&|a, b| gi.v[(a, b)]);
    let (g_rho_i, g_cl_i, g_ct_i, g_p_i) = (
        bv(&|a| gi.rho[a]),
        bv(&|a| gi.cl[a]),
        bv(&|a| gi.ct[a]),
        bv(&|a| gi.p[a]),
    );
    // the owner's stress gradients (Voigt component, axis), broadcast
    let gs_i: [Vl<V>; 6] = core::array::from_fn(|k| {
        if E::MUSCL && E::STRENGTH {
            bv(&|c| grad_s[i][k][c])
        } else {
            [zero; 3]
        }
    });
    let mut q0 = 0;
    while q0 < n_pairs {
        // a last, partial group repeats its last pair in the spare lanes (not stored)
        let lanes = (n_pairs - q0).min(V::N);
        let lane = |l: usize| q0 + l.min(lanes - 1);
        let js = V::arr(|l| owned[lane(l)] as usize);
        // the neighbours' records, transposed into lanes (room for the widest, 3D)
        let f: [V; record_len(3)] = records::<V, { record_len(3) }>(rec, width, width / 4, &js);
        // a record's vector at `o` and matrix at `o` (row by row) as lanes
        let vec_at =
            |o: usize| -> Vl<V> { core::array::from_fn(|a| if a < D { f[o + a] } else { zero }) };
        let mat_at = |o: usize| -> Ml<V> {
            core::array::from_fn(|b| {
                core::array::from_fn(|a| {
                    if a < D && b < D {
                        f[o + a * D + b]
                    } else {
                        zero
                    }
                })
            })
        };
        let n: Vl<V> = core::array::from_fn(|a| {
            if a < D {
                load(&V::arr(|l| geom[lane(l)].n[a]))
            } else {
                zero
            }
        });
        let r: V = load(&V::arr(|l| geom[lane(l)].r));
        let vj: Vl<V> = vec_at(at.v);
        let (rhoj, clj, ctj) = (f[at.rho], f[at.cl], f[at.ct]);
        let rji = scale::<V, D>(&n, r);
        let (mut v_l, mut v_r) = (vi, vj);
        // options.objective: the pair's mean spin W = (W_i + W_j)/2, the velocities taken
        // to the midpoint along it: v_i + W r_ji/2, v_j - W r_ji/2
        let mut spin: Ml<V> = [[zero; 3]; 3];
        if rotate {
            let wj_m: Ml<V> = mat_at(at.w);
            let half = splat(0.5);
            for b in 0..D {
                for a in 0..D {
                    spin[b][a] = mul(add(wi_m[b][a], wj_m[b][a]), half);
                }
            }
            let h = scale::<V, D>(&gemv::<V, D>(&spin, &rji), half);
            for a in 0..D {
                v_l[a] = add(v_l[a], h[a]);
                v_r[a] = sub(v_r[a], h[a]);
            }
        }
        // the traction axis: n, or with correction (L_i^-1 + L_j^-1) n / 2
        let axis = if E::CORRECTION {
            let lj_m: Ml<V> = mat_at(at.l_inv);
            let mut m = [[zero; 3]; 3];
            for b in 0..D {
                for a in 0..D {
                    m[b][a] = add(li_m[b][a], lj_m[b][a]);
                }
            }
            scale::<V, D>(&gemv::<V, D>(&m, &n), splat(0.5))
        } else {
            n
        };
        // (by rows: sig_j[a][b] is component (a, b))
        let sig_j: Ml<V> = core::array::from_fn(|a| {
            core::array::from_fn(|b| {
                if a < D && b < D {
                    f[at.sig + a * D + b]
                } else {
                    zero
                }
            })
        });
        // (the stress is symmetric: by rows or by columns alike)
        let (mut t_l, mut t_r) = (
            sym_dot::<V, D>(&sig_i, &axis),
            sym_dot::<V, D>(&sig_j, &axis),
        );
        let (mut rho_l, mut rho_r) = (rhoi, rhoj);
        let (mut cl_l, mut cl_r) = (cli, clj);
        let (mut ct_l, mut ct_r) = (cti, ctj);
        if E::MUSCL {
            let g_rho_j: Vl<V> = vec_at(at.grad_rho);
            let g_cl_j: Vl<V> = vec_at(at.grad_cl);
            let g_ct_j: Vl<V> = vec_at(at.grad_ct);
            (rho_l, rho_r) = muscl_pair(
                superbee,
                rhoi,
                rhoj,
                dot::<V, D>(&g_rho_i, &rji),
                dot::<V, D>(&g_rho_j, &rji),
            );
            (cl_l, cl_r) = muscl_pair(
                superbee,
                cli,
                clj,
                dot::<V, D>(&g_cl_i, &rji),
                dot::<V, D>(&g_cl_j, &rji),
            );
            (ct_l, ct_r) = muscl_pair(
                superbee,
                cti,
                ctj,
                dot::<V, D>(&g_ct_i, &rji),
                dot::<V, D>(&g_ct_j, &rji),
            );
            // (grad v - W) r_ji of each side (less nothing without the rotation: x - 0 = x)
            let gvj_m: Ml<V> = mat_at(at.grad_v);
            let (mut gi_w, mut gj_w) = (gvi_m, gvj_m);
            if rotate {
                for b in 0..D {
                    for a in 0..D {
                        gi_w[b][a] = sub(gvi_m[b][a], spin[b][a]);
                        gj_w[b][a] = sub(gvj_m[b][a], spin[b][a]);
                    }
                }
            }
            let (dvi, dvj) = (gemv::<V, D>(&gi_w, &rji), gemv::<V, D>(&gj_w, &rji));
            // pair_basis: in 2D n and (-n_y, n_x), otherwise the scene's axes
            let mut basis: [Vl<V>; 3] = [[zero; 3]; 3];
            if D == 2 {
                basis[0] = n;
                basis[1][0] = neg(n[1]);
                basis[1][1] = n[0];
            } else {
                for (a, e) in basis.iter_mut().enumerate().take(D) {
                    e[a] = splat(1.0);
                }
            }
            (v_l, v_r) = V::frame::<D>(superbee, &basis, &v_l, &v_r, &dvi, &dvj);
            if E::STRENGTH {
                // the slopes of the traction: Sym3 of the stress gradients along r_ji
                // (only the components a, b < D enter), dotted with the axis
                // (loops, not closures: a closure does not inherit this function's
                // target features, and these were left as calls, their lanes passed
                // through memory)
                let (mut slope_i, mut slope_j): (Ml<V>, Ml<V>) = ([[zero; 3]; 3], [[zero; 3]; 3]);
                for a in 0..D {
                    for b in 0..D {
                        slope_i[a][b] = dot::<V, D>(&gs_i[Sym3::voigt(a, b)], &rji);
                        let g: Vl<V> = vec_at(at.grad_s + sym_at(D, a, b) * D);
                        slope_j[a][b] = dot::<V, D>(&g, &rji);
                    }
                }
                let (si, sj) = (
                    sym_dot::<V, D>(&slope_i, &axis),
                    sym_dot::<V, D>(&slope_j, &axis),
                );
                (t_l, t_r) = V::frame::<D>(superbee, &basis, &t_l, &t_r, &si, &sj);
            } else {
                let pj = f[at.p];
                let g_p_j: Vl<V> = vec_at(at.grad_p);
                let (pl, pr) = muscl_pair(
                    superbee,
                    pi,
                    pj,
                    dot::<V, D>(&g_p_i, &rji),
                    dot::<V, D>(&g_p_j, &rji),
                );
                (t_l, t_r) = (scale::<V, D>(&axis, neg(pl)), scale::<V, D>(&axis, neg(pr)));
            }
        }
        let sides = if two_shock_solver {
            let left = Side {
                u: zero,
                p: zero,
                rho: rho_l,
                c: cl_l,
                s: slope_i,
            };
            let right = Side {
                u: zero,
                p: zero,
                rho: rho_r,
                c: cl_r,
                s: f[at.slope],
            };
            Some((left, right))
        } else {
            None
        };
        let (vs, ts, redo) = V::vector::<D>(
            &n,
            &v_l,
            &t_l,
            (mul(rho_l, cl_l), mul(rho_l, ct_l)),
            &v_r,
            &t_r,
            (mul(rho_r, cl_r), mul(rho_r, ct_r)),
            match &sides {
                Some((l, r)) => Some((l, r)),
                None => None,
            },
        );
        let redo = V::bits(redo);
        let vs: [V::Arr<Real>; 3] = core::array::from_fn(|a| store(vs[a]));
        let ts: [V::Arr<Real>; 3] = core::array::from_fn(|a| store(ts[a]));
        let r = store(r);
        let failed_i = failed::<D, E>(sys, i);
        let failed_j = store(f[at.failed]);
        for l in 0..lanes {
            let (q, j) = (q0 + l, js[l]);
            out[q] = if r[l] > 0.0 {
                if redo & (1 << l) != 0 || failed_i || failed_j[l] != 0.0 {
                    let g = &geom[q];
                    let pr = Pair {
                        j,
                        r: g.r,
                        n: g.n,
                        dw: g.dw,
                        grad: g.n * (-g.dw),
                    };
                    pair_star::<D, E>(sys, aux, corr, grad, grad_s, params, i, &pr)
                } else {
                    let mut st = PmStar::<D>::default();
                    for a in 0..D {
                        st.v[a] = vs[a][l];
                        st.t[a] = ts[a][l];
                    }
                    st
                }
            } else {
                PmStar::default()
            };
        }
        q0 += lanes;
    }
    n_pairs
}

/// [`star_row`] in `W`'s lanes over the row's full groups of `W::N` pairs and in `N`'s
/// over the rest (a last, partial group of the wide register costs as much as a full
/// one): AVX-512's entry with `zmm` and `ymm` registers, and the tests' eight emulated
/// lanes with the same code.
///
/// # Safety
/// As [`star_row`], with both levels.
#[inline(always)]
unsafe fn star_row_wide<W: Calls, N: Calls, const D: usize, E: Effects>(
    rows: &StarRows<'_, D>,
    i: usize,
    geom: &[PairGeom<D>],
    owned: &[u32],
    out: &mut [PmStar<D>],
) -> usize {
    let n = owned.len().min(geom.len()).min(out.len());
    let m = n / W::N * W::N;
    let (o_w, o_n) = out[..n].split_at_mut(m);
    let (g_w, g_n) = geom[..n].split_at(m);
    let (w_w, w_n) = owned[..n].split_at(m);
    let wide = if m > 0 {
        star_row::<W, D, E>(rows, i, g_w, w_w, o_w)
    } else {
        0
    };
    wide + star_row::<N, D, E>(rows, i, g_n, w_n, o_n)
}

/// [`star_row`] with four pairs per AVX2 instruction.
///
/// # Safety
/// As [`star_row`], with AVX2.
#[target_feature(enable = "avx2")]
unsafe fn star_row_avx2<const D: usize, E: Effects>(
    rows: &StarRows<'_, D>,
    i: usize,
    geom: &[PairGeom<D>],
    owned: &[u32],
    out: &mut [PmStar<D>],
) -> usize {
    star_row::<__m256d, D, E>(rows, i, geom, owned, out)
}

/// [`star_row_wide`] with eight pairs per AVX-512 instruction, the rest four per AVX2 one.
///
/// # Safety
/// As [`star_row`], with AVX-512F.
#[target_feature(enable = "avx512f")]
unsafe fn star_row_avx512<const D: usize, E: Effects>(
    rows: &StarRows<'_, D>,
    i: usize,
    geom: &[PairGeom<D>],
    owned: &[u32],
    out: &mut [PmStar<D>],
) -> usize {
    star_row_wide::<__m512d, __m256d, D, E>(rows, i, geom, owned, out)
}

/// [`star_row`] at `level`: its AVX2 or AVX-512 entry (0 pairs at the baseline level).
///
/// # Safety
/// `level` must be one the CPU has (`SimdLevel::assume`), and the step's options must pass
/// [`covers`].
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn star_row_at<const D: usize, E: Effects>(
    level: SimdLevel,
    rows: &StarRows<'_, D>,
    i: usize,
    geom: &[PairGeom<D>],
    owned: &[u32],
    out: &mut [PmStar<D>],
) -> usize {
    match level.get() {
        Simd::Avx512 => star_row_avx512::<D, E>(rows, i, geom, owned, out),
        Simd::Avx2 => star_row_avx2::<D, E>(rows, i, geom, owned, out),
        Simd::Baseline => 0,
        #[cfg(test)]
        Simd::Emu4 => star_row::<Emu<4>, D, E>(rows, i, geom, owned, out),
        #[cfg(test)]
        Simd::Emu8 => star_row_wide::<Emu<8>, Emu<4>, D, E>(rows, i, geom, owned, out),
    }
}
