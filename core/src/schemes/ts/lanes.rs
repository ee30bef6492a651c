//! The vectorised star states of the time-split family's pairs (`ts1`, `ts2`): four (AVX2)
//! or eight (AVX-512) pairs of one row per instruction, each lane doing the portable [`star`]'s IEEE operations in its
//! order (module docs of [`super`]). The owner's values are broadcast once per row; the
//! neighbours' come from their records ([`write_records`]), a register's records loaded
//! four reals at a time and transposed into lanes.
//!
//! Covered: the default time and dissipation options (`muscl_time = "none"`,
//! `dissipation = "full"`), the superbee and minmod limiters, the acoustic and two-shock
//! solvers. A lane the vectorised path does not cover (a failed particle, an impedance
//! that is not positive and finite, a two-shock answer that is not finite) is solved again
//! by the portable [`star`]; every other case runs the portable loop ([`covers`]).

use core::arch::x86_64::{__m256d, __m512d};

use crate::effects::{EffectSet, Effects};
use crate::exec::{for_each_record, Executor};
use crate::limiter::Limiter;
use crate::math::Real;
use crate::riemann::Dissipation;
use crate::schemes::common::failed;
use crate::schemes::options::{MusclTime, RiemannSolver, SchemeOptions};
use crate::schemes::ts::pairs::{star, StarRows};
use crate::schemes::ts::records::TsStar;
use crate::schemes::ts::records::{record_len, RecordAt};
use crate::schemes::workspace::StepParams;
#[cfg(test)]
use crate::simd::lanes::Emu;
use crate::simd::lanes::Lanes;
use crate::simd::ops::*;
use crate::simd::riemann::*;
use crate::simd::{Simd, SimdLevel};
use crate::state::{Gradients, PairGeom, System};

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
        muscl_time,
        // not read by ts's star (other passes, or other families)
        av_alpha: _,
        av_beta: _,
        transverse_dissipation: _,
        objective: _,
        corrected_slopes: _,
        integrator: _,
        surface_lambda: _,
        surface_scan: _,
        det_epsilon: _,
        specific_volume: _,
        energy_equation: _,
        artificial_stress: _,
        artificial_stress_exponent: _,
        constant_h: _,
        // the hourglass stiffness's own passes (portable), not the star
        hourglass: _,
        // tl's, refused by the table
        reference_update: _,
        // the effects the step is compiled with (`E`), not read from here
        correction: _,
        muscl: _,
    } = params.options;
    let limiter = match limiter {
        Limiter::Superbee | Limiter::Minmod => true,
        Limiter::MonotonizedCentral | Limiter::VanLeer | Limiter::Sweby(_) => false,
    };
    let riemann = match riemann {
        RiemannSolver::Acoustic | RiemannSolver::TwoShock => true,
    };
    let dissipation = match dissipation {
        Dissipation::Full => true,
        Dissipation::Compression => false,
    };
    let time = match muscl_time {
        MusclTime::None => true,
        MusclTime::Predictor | MusclTime::CourantFactor => false,
    };
    limiter && riemann && dissipation && time
}

/// Writes every particle's neighbour record ([`RecordAt`]) for [`star_row`]: its velocity,
/// pressure, density, sound speed, Hugoniot slope, whether it failed, and with MUSCL its
/// gradients, exactly the values the portable [`star`] reads.
pub(crate) fn write_records<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    grad: &[Gradients<D>],
    params: &StepParams<'_, D>,
    rec: &mut [Real],
    exec: &X,
) {
    let (at, width) = (RecordAt::of(D), record_len(D));
    let mats = params.materials;
    for_each_record(exec, rec, width, |i, r| {
        for a in 0..D {
            r[at.v + a] = sys.v[i][a];
        }
        r[at.p] = sys.p[i];
        r[at.rho] = sys.rho[i];
        r[at.c] = sys.c[i];
        r[at.slope] = shock_slope(&mats[sys.mat[i] as usize]);
        r[at.failed] = if failed::<D, E>(sys, i) { 1.0 } else { 0.0 };
        if E::MUSCL {
            let g = &grad[i];
            for a in 0..D {
                for b in 0..D {
                    r[at.grad_v + a * D + b] = g.v[(a, b)];
                }
                r[at.grad_p + a] = g.p[a];
                r[at.grad_rho + a] = g.rho[a];
            }
        }
    });
}

/// `ts::pairs::reconstruct` with `f_i = f_j = 1`.
#[inline(always)]
unsafe fn reconstruct<V: Lanes>(superbee: bool, qi: V, qj: V, gi: V, gj: V, half_r: V) -> (V, V) {
    let half_jump = mul(splat(0.5), sub(qj, qi));
    // half_r * f_i * limit with f_i = 1: (half_r * 1) * limit, and half_r * 1 = half_r
    let ext_i = minmod(mul(half_r, limit(superbee, gi, gj)), half_jump);
    let ext_j = minmod(mul(half_r, limit(superbee, gj, gi)), half_jump);
    (add(qi, ext_i), sub(qj, ext_j))
}

/// The slopes along `n` of `ts::pairs::riemann_states`: `n . (grad v n)`, `grad p . n`,
/// `grad rho . n`, with `grad v n` in nalgebra's gemv order (column 0 times `n_0`, then
/// each further column times its component, added on). `gv[b][a]` is `dv_a/dx_b`.
#[inline(always)]
unsafe fn slopes<V: Lanes, const D: usize>(
    n: &[V; 3],
    gv: &[[V; 3]; 3],
    gp: &[V; 3],
    gr: &[V; 3],
) -> [V; 3] {
    let mut gvn = [V::zero(); 3];
    for b in 0..D {
        for a in 0..D {
            let t = mul(gv[b][a], n[b]);
            gvn[a] = if b == 0 { t } else { add(t, gvn[a]) };
        }
    }
    [dot::<V, D>(n, &gvn), dot::<V, D>(gp, n), dot::<V, D>(gr, n)]
}

/// The star states of the pairs particle `i` owns (its neighbours `owned`, their stored
/// geometry `geom`), a register at a time, as the portable [`star`] gives them: `(u*, p*)` into
/// `out` (`p* = 0` unless `with_p`), the default record for a pair outside the support.
/// Returns how many pairs it did (all of them).
///
/// # Safety
/// The CPU must have the level of `V`, and the step's options must pass [`covers`]. (The
/// neighbour indices are checked; everything is indexed with bounds checks.)
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn star_row<V: Lanes, const D: usize, E: Effects>(
    rows: &StarRows<'_, D>,
    i: usize,
    geom: &[PairGeom<D>],
    owned: &[u32],
    out: &mut [TsStar],
) -> usize {
    let StarRows {
        sys,
        grad,
        rec,
        params,
        with_p,
    } = *rows;
    let n = owned.len().min(geom.len()).min(out.len());
    let zero = V::zero();
    let superbee = params.options.limiter == Limiter::Superbee;
    let two_shock_solver = params.options.riemann == RiemannSolver::TwoShock;
    let damage = E::RUNTIME.contains(EffectSet::DAMAGE);
    let mats = params.materials;
    let slope = |k: usize| shock_slope(&mats[sys.mat[k] as usize]);
    // the neighbours' records: the first-order fields, and the gradients with MUSCL
    let (at, width) = (RecordAt::of(D), record_len(D));
    let groups = if E::MUSCL {
        width / 4
    } else {
        at.first_order.div_ceil(4)
    };
    // the owner's values, broadcast
    let vi: [V; 3] = core::array::from_fn(|a| if a < D { splat(sys.v[i][a]) } else { zero });
    let (pi, rhoi, ci) = (splat(sys.p[i]), splat(sys.rho[i]), splat(sys.c[i]));
    let si = if two_shock_solver {
        splat(slope(i))
    } else {
        zero
    };
    // the owner's gradients, broadcast (read only with MUSCL)
    let gi = if E::MUSCL {
        grad[i]
    } else {
        Gradients::default()
    };
    let gvi: [[V; 3]; 3] = core::array::from_fn(|b| {
        core::array::from_fn(|a| {
            if a < D && b < D {
                splat(gi.v[(a, b)])
            } else {
                zero
            }
        })
    });
    let gpi: [V; 3] = core::array::from_fn(|a| if a < D { splat(gi.p[a]) } else { zero });
    let gri: [V; 3] = core::array::from_fn(|a| if a < D { splat(gi.rho[a]) } else { zero });
    let failed_i = failed::<D, E>(sys, i);
    let mut q0 = 0;
    while q0 < n {
        // a last, partial group repeats its last pair in the spare lanes (not stored)
        let lanes = (n - q0).min(V::N);
        let lane = |l: usize| q0 + l.min(lanes - 1);
        let js = V::arr(|l| owned[lane(l)] as usize);
        // the neighbours' records, transposed into lanes (room for the widest, 3D)
        let f: [V; record_len(3)] = records::<V, { record_len(3) }>(rec, width, groups, &js);
        let nv: [V; 3] = core::array::from_fn(|a| {
            if a < D {
                load(&V::arr(|l| geom[lane(l)].n[a]))
            } else {
                zero
            }
        });
        let r: V = load(&V::arr(|l| geom[lane(l)].r));
        let vj: [V; 3] = core::array::from_fn(|a| if a < D { f[at.v + a] } else { zero });
        let (pj, rhoj, cj) = (f[at.p], f[at.rho], f[at.c]);
        // first order: (v . n, p, rho) of each side
        let (ui, uj) = (dot::<V, D>(&vi, &nv), dot::<V, D>(&vj, &nv));
        let (mut l, mut rr) = ([ui, pi, rhoi], [uj, pj, rhoj]);
        if E::MUSCL {
            // the neighbours' gradients, per lane (the owner's are broadcast below)
            let gvj: [[V; 3]; 3] = core::array::from_fn(|b| {
                core::array::from_fn(|a| {
                    if a < D && b < D {
                        f[at.grad_v + a * D + b]
                    } else {
                        zero
                    }
                })
            });
            let gpj: [V; 3] = core::array::from_fn(|a| if a < D { f[at.grad_p + a] } else { zero });
            let grj: [V; 3] =
                core::array::from_fn(|a| if a < D { f[at.grad_rho + a] } else { zero });
            let own = slopes::<V, D>(&nv, &gvi, &gpi, &gri);
            let theirs = slopes::<V, D>(&nv, &gvj, &gpj, &grj);
            let half_r = mul(splat(0.5), r);
            let mut ml = [zero; 3];
            let mut mr = [zero; 3];
            for q in 0..3 {
                (ml[q], mr[q]) = reconstruct(superbee, l[q], rr[q], own[q], theirs[q], half_r);
            }
            // a reconstructed density must stay positive; otherwise first order
            let keep = V::and(gt(ml[2], zero), gt(mr[2], zero));
            for q in 0..3 {
                l[q] = select(keep, ml[q], l[q]);
                rr[q] = select(keep, mr[q], rr[q]);
            }
        }
        let [ul, pl, rl] = l;
        let [ur, pr, rhor] = rr;
        let (us, ps, redo) = if two_shock_solver {
            let sj = f[at.slope];
            two_shock(
                &Side {
                    u: ul,
                    p: pl,
                    rho: rl,
                    c: ci,
                    s: si,
                },
                &Side {
                    u: ur,
                    p: pr,
                    rho: rhor,
                    c: cj,
                    s: sj,
                },
            )
        } else {
            let (u, p) = pressure_star(ul, pl, mul(rl, ci), ur, pr, mul(rhor, cj));
            (u, p, V::none())
        };
        let (us, ps, redo, r) = (store(us), store(ps), V::bits(redo), store(r));
        let failed_j = store(f[at.failed]);
        for l in 0..lanes {
            let (q, j) = (q0 + l, js[l]);
            out[q] = if r[l] > 0.0 {
                let (u, p) = if redo & (1 << l) != 0 || (damage && (failed_i || failed_j[l] != 0.0))
                {
                    let g = &geom[q];
                    star::<D, E>(sys, grad, params, i, j, &g.n, g.r)
                } else {
                    (us[l], ps[l])
                };
                TsStar {
                    u,
                    p: if with_p { p } else { 0.0 },
                }
            } else {
                TsStar::default()
            };
        }
        q0 += lanes;
    }
    n
}

/// [`star_row`] in `W`'s lanes over the row's full groups of `W::N` pairs and in `N`'s
/// over the rest (a last, partial group of the wide register costs as much as a full
/// one): AVX-512's entry with `zmm` and `ymm` registers, and the tests' eight emulated
/// lanes with the same code.
///
/// # Safety
/// As [`star_row`], with both levels.
#[inline(always)]
unsafe fn star_row_wide<W: Lanes, N: Lanes, const D: usize, E: Effects>(
    rows: &StarRows<'_, D>,
    i: usize,
    geom: &[PairGeom<D>],
    owned: &[u32],
    out: &mut [TsStar],
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
    out: &mut [TsStar],
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
    out: &mut [TsStar],
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
    out: &mut [TsStar],
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
