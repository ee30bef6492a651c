//! The lane arithmetic of the contact family's star states (`pm_star`): vectors and
//! matrices in lanes, the MUSCL reconstruction in the pair's frame and the vector elastic
//! Riemann problem, each the portable `pm::pairs` helper named in its documentation, lane
//! by lane with the same IEEE operations in the same order.

use core::arch::x86_64::{__m256d, __m512d};

use super::lanes::Lanes;
use super::ops::{
    add, div, dot, finite, gt, limit, minmod, mul, neg, select, splat, sub, two_shock, Side,
};

/// Lanes of a `D`-vector (components past `D` unused).
pub(super) type Vl<V> = [V; 3];
/// Lanes of a `D x D` matrix, by columns: `m[b][a]` is element `(a, b)`.
pub(super) type Ml<V> = [[V; 3]; 3];

/// `m x` in nalgebra's gemv order: column 0 times `x_0`, then each further column times
/// its component, added on.
#[inline(always)]
pub(super) unsafe fn gemv<V: Lanes, const D: usize>(m: &Ml<V>, x: &Vl<V>) -> Vl<V> {
    let mut out = [V::zero(); 3];
    for b in 0..D {
        for a in 0..D {
            let t = mul(m[b][a], x[b]);
            out[a] = if b == 0 { t } else { add(t, out[a]) };
        }
    }
    out
}

/// `v * s`, component by component.
#[inline(always)]
pub(super) unsafe fn scale<V: Lanes, const D: usize>(v: &Vl<V>, s: V) -> Vl<V> {
    let mut out = *v;
    for a in 0..D {
        out[a] = mul(v[a], s);
    }
    out
}

/// `muscl_pair` of `pm::pairs`: minmod (`phi + minmod(...)/2`), or superbee with each
/// extrapolation bounded by half the pair difference.
#[inline(always)]
pub(super) unsafe fn muscl_pair<V: Lanes>(
    superbee: bool,
    phi_i: V,
    phi_j: V,
    gi: V,
    gj: V,
) -> (V, V) {
    let half = splat(0.5);
    let d = sub(phi_j, phi_i);
    if superbee {
        let half_jump = mul(half, d);
        (
            add(phi_i, minmod(mul(half, limit(true, gi, d)), half_jump)),
            sub(phi_j, minmod(mul(half, limit(true, gj, d)), half_jump)),
        )
    } else {
        (
            add(phi_i, mul(half, limit(false, gi, d))),
            sub(phi_j, mul(half, limit(false, gj, d))),
        )
    }
}

/// `muscl_frame` of `pm::pairs`: the reconstruction component by component in the basis
/// `basis` (`pair_basis`: in 2D `n` and its normal, otherwise the scene's axes).
#[inline(always)]
unsafe fn muscl_frame<V: Lanes, const D: usize>(
    superbee: bool,
    basis: &[Vl<V>; 3],
    wi: &Vl<V>,
    wj: &Vl<V>,
    di: &Vl<V>,
    dj: &Vl<V>,
) -> (Vl<V>, Vl<V>) {
    let zero = V::zero();
    let (mut l, mut r) = ([zero; 3], [zero; 3]);
    for e in basis.iter().take(D) {
        let (a, b) = muscl_pair(
            superbee,
            dot::<V, D>(wi, e),
            dot::<V, D>(wj, e),
            dot::<V, D>(di, e),
            dot::<V, D>(dj, e),
        );
        for c in 0..D {
            l[c] = add(l[c], mul(e[c], a));
            r[c] = add(r[c], mul(e[c], b));
        }
    }
    (l, r)
}

/// `Sym3::dot_vec`: row `a` is `(0 + s_a0 x_0) + s_a1 x_1 + …`; `s[a][b]` is the
/// component `(a, b)`.
#[inline(always)]
pub(super) unsafe fn sym_dot<V: Lanes, const D: usize>(s: &Ml<V>, x: &Vl<V>) -> Vl<V> {
    let mut out = [V::zero(); 3];
    for (a, o) in out.iter_mut().enumerate().take(D) {
        for b in 0..D {
            *o = add(*o, mul(s[a][b], x[b]));
        }
    }
    out
}

/// `acoustic_star` along the axis: `(u*, s*)`, the mean of the sides where `z_l + z_r` is
/// not positive and finite.
#[inline(always)]
unsafe fn acoustic<V: Lanes>(ul: V, sl: V, zl: V, ur: V, sr: V, zr: V) -> (V, V) {
    let zs = add(zl, zr);
    let ok = V::and(gt(zs, V::zero()), finite(zs));
    let inv = div(splat(1.0), zs);
    let u = mul(sub(add(add(mul(zl, ul), mul(zr, ur)), sr), sl), inv);
    let s = mul(
        add(add(mul(zr, sl), mul(zl, sr)), mul(mul(zl, zr), sub(ur, ul))),
        inv,
    );
    let half = splat(0.5);
    (
        select(ok, u, mul(half, add(ul, ur))),
        select(ok, s, mul(half, add(sl, sr))),
    )
}

/// `acoustic_star_vector`: the normal problem with the longitudinal impedances, the
/// tangential one with the transverse impedances; `(V*, T*)` and the lanes the portable
/// code must redo. With `shock` (each side's density, sound speed and slope) the normal
/// problem is the two-shock one (`elastic_star_vector` with `two_shock_star`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn star_vector<V: Lanes, const D: usize>(
    n: &Vl<V>,
    v_l: &Vl<V>,
    t_l: &Vl<V>,
    zl_long: V,
    zl_trans: V,
    v_r: &Vl<V>,
    t_r: &Vl<V>,
    zr_long: V,
    zr_trans: V,
    shock: Option<(&Side<V>, &Side<V>)>,
) -> (Vl<V>, Vl<V>, V::Mask) {
    let zero = V::zero();
    let (vln, tln, vrn, trn) = (
        dot::<V, D>(v_l, n),
        dot::<V, D>(t_l, n),
        dot::<V, D>(v_r, n),
        dot::<V, D>(t_r, n),
    );
    // the longitudinal problem: acoustic, or the two-shock solver on pressures `-s`
    let (u_n, s_n, redo) = match shock {
        None => {
            let (u, s) = acoustic(vln, tln, zl_long, vrn, trn, zr_long);
            (u, s, V::none())
        }
        Some((l, r)) => {
            let (u, p, redo) = two_shock(
                &Side {
                    u: vln,
                    p: neg(tln),
                    ..*l
                },
                &Side {
                    u: vrn,
                    p: neg(trn),
                    ..*r
                },
            );
            (u, neg(p), redo)
        }
    };
    let zs = add(zl_trans, zr_trans);
    let ok = V::and(gt(zs, zero), finite(zs));
    let inv = div(splat(1.0), zs);
    let zz = mul(zl_trans, zr_trans);
    let half = splat(0.5);
    let (mut vs, mut ts) = ([zero; 3], [zero; 3]);
    for a in 0..D {
        let vlt = sub(v_l[a], mul(n[a], vln));
        let tlt = sub(t_l[a], mul(n[a], tln));
        let vrt = sub(v_r[a], mul(n[a], vrn));
        let trt = sub(t_r[a], mul(n[a], trn));
        let v_t = mul(
            sub(add(add(mul(vlt, zl_trans), mul(vrt, zr_trans)), trt), tlt),
            inv,
        );
        let t_t = mul(
            add(
                add(mul(tlt, zr_trans), mul(trt, zl_trans)),
                mul(sub(vrt, vlt), zz),
            ),
            inv,
        );
        let v_t = select(ok, v_t, mul(add(vlt, vrt), half));
        let t_t = V::keep(ok, t_t);
        vs[a] = add(mul(n[a], u_n), v_t);
        ts[a] = add(mul(n[a], s_n), t_t);
    }
    (vs, ts, redo)
}

/// [`muscl_frame`] and [`star_vector`] as calls of their own, compiled for the level
/// (`#[inline]`: the compiler keeps them out of the row, as the row's size asks).
pub(super) trait Calls: Lanes {
    unsafe fn frame<const D: usize>(
        superbee: bool,
        basis: &[Vl<Self>; 3],
        wi: &Vl<Self>,
        wj: &Vl<Self>,
        di: &Vl<Self>,
        dj: &Vl<Self>,
    ) -> (Vl<Self>, Vl<Self>);
    #[allow(clippy::too_many_arguments)]
    unsafe fn vector<const D: usize>(
        n: &Vl<Self>,
        v_l: &Vl<Self>,
        t_l: &Vl<Self>,
        zl: (Self, Self),
        v_r: &Vl<Self>,
        t_r: &Vl<Self>,
        zr: (Self, Self),
        shock: Option<(&Side<Self>, &Side<Self>)>,
    ) -> (Vl<Self>, Vl<Self>, Self::Mask);
}

macro_rules! calls {
    ($v:ty, $feature:literal) => {
        impl Calls for $v {
            #[target_feature(enable = $feature)]
            #[inline]
            unsafe fn frame<const D: usize>(
                superbee: bool,
                basis: &[Vl<$v>; 3],
                wi: &Vl<$v>,
                wj: &Vl<$v>,
                di: &Vl<$v>,
                dj: &Vl<$v>,
            ) -> (Vl<$v>, Vl<$v>) {
                muscl_frame::<$v, D>(superbee, basis, wi, wj, di, dj)
            }
            #[target_feature(enable = $feature)]
            #[inline]
            unsafe fn vector<const D: usize>(
                n: &Vl<$v>,
                v_l: &Vl<$v>,
                t_l: &Vl<$v>,
                zl: ($v, $v),
                v_r: &Vl<$v>,
                t_r: &Vl<$v>,
                zr: ($v, $v),
                shock: Option<(&Side<$v>, &Side<$v>)>,
            ) -> (Vl<$v>, Vl<$v>, <$v as Lanes>::Mask) {
                star_vector::<$v, D>(n, v_l, t_l, zl.0, zl.1, v_r, t_r, zr.0, zr.1, shock)
            }
        }
    };
}
calls!(__m256d, "avx2");
calls!(__m512d, "avx512f");
