//! The Riemann solvers in lanes, each once: the acoustic solver, the two-shock solver and
//! the vector (normal and tangential) elastic problem, each `crate::riemann`'s function named in
//! its documentation, lane by lane with the same IEEE operations in the same order.

use super::lanes::Lanes;
use super::ops::{add, div, dot, finite, gt, lt, max, mul, neg, select, splat, sub, Vl};
use crate::math::Real;

// The two-shock solver of `crate::riemann::two_shock`, lane by lane (the ts and tkc stars).

/// One side of the Riemann problem in lanes.
#[derive(Clone, Copy)]
pub(crate) struct Side<V> {
    pub u: V,
    pub p: V,
    pub rho: V,
    pub c: V,
    /// `ShockSide::slope`: the Hugoniot slope, or 0 where negative or not finite.
    pub s: V,
}

/// `ShockSide::hugoniot`: `rho (c + s max(w, 0)) w`.
#[inline(always)]
unsafe fn hugoniot<V: Lanes>(k: &Side<V>, w: V) -> V {
    mul(mul(k.rho, add(k.c, mul(k.s, max(w, V::zero())))), w)
}

/// `f(u) = p_l + W_l(u_l - u) - p_r - W_r(u - u_r)` of the two-shock solver.
#[inline(always)]
unsafe fn gap<V: Lanes>(l: &Side<V>, r: &Side<V>, u: V) -> V {
    sub(
        sub(add(l.p, hugoniot(l, sub(l.u, u))), r.p),
        hugoniot(r, sub(u, r.u)),
    )
}

/// [`crate::riemann::two_shock_star`] where both impedances are usable; returns the star
/// state and the lanes the portable solver must redo (an impedance not positive and
/// finite, or an answer that is not finite: its acoustic fallbacks).
#[inline(always)]
pub(crate) unsafe fn two_shock<V: Lanes>(l: &Side<V>, r: &Side<V>) -> (V, V, V::Mask) {
    let zero = V::zero();
    let (zl, zr) = (mul(l.rho, l.c), mul(r.rho, r.c));
    let usable_l = V::and(gt(zl, zero), finite(zl));
    let usable_r = V::and(gt(zr, zero), finite(zr));
    let bad = V::not(V::and(usable_l, usable_r));
    let ordered = V::le(l.u, r.u);
    let (lo, hi) = (select(ordered, l.u, r.u), select(ordered, r.u, l.u));
    let (f_lo, f_hi) = (gap(l, r, lo), gap(l, r, hi));
    let (kl_shock, kr_shock) = (mul(l.rho, l.s), mul(r.rho, r.s));
    let below = V::le(f_lo, zero);
    let above = V::and_not(below, V::ge(f_hi, zero));
    let two = V::and_not(V::or(below, above), lt(r.u, l.u));
    let about_hi = V::or(above, V::and(two, gt(kl_shock, kr_shock)));
    let (u0, f0) = (select(about_hi, hi, lo), select(about_hi, f_hi, f_lo));
    let kl = V::keep(V::or(below, two), kl_shock);
    let kr = V::keep(V::or(above, two), kr_shock);
    let two_v = splat(2.0);
    let b = add(
        add(add(zl, zr), mul(mul(two_v, kl), sub(l.u, u0))),
        mul(mul(two_v, kr), sub(u0, r.u)),
    );
    let a = sub(kl, kr);
    let disc = max(sub(mul(b, b), mul(mul(splat(4.0), a), f0)), zero);
    let d = div(mul(two_v, f0), add(b, V::sqrt(disc)));
    let u = add(u0, d);
    let p = mul(
        splat(0.5),
        add(
            add(add(l.p, hugoniot(l, sub(l.u, u))), r.p),
            hugoniot(r, sub(u, r.u)),
        ),
    );
    let redo = V::or(bad, V::not(V::and(finite(u), finite(p))));
    (u, p, redo)
}

/// `ShockSide::slope` of material `m`'s Hugoniot slope: the slope, or 0 where it is
/// negative or not finite.
#[inline(always)]
pub(crate) fn shock_slope(m: &crate::material::Material) -> Real {
    let s = m.eos.hugoniot_slope();
    if s.is_finite() {
        crate::math::real::max(s, 0.0)
    } else {
        0.0
    }
}

/// `acoustic_star` along the axis: `(u*, s*)`, the mean of the sides where `z_l + z_r` is
/// not positive and finite: the portable solver itself, run on the lanes
/// ([`crate::riemann::acoustic::acoustic_in`]).
#[inline(always)]
pub(crate) unsafe fn acoustic<V: Lanes>(ul: V, sl: V, zl: V, ur: V, sr: V, zr: V) -> (V, V) {
    crate::riemann::acoustic::acoustic_in::<V>(ul, sl, zl, ur, sr, zr)
}

/// [`crate::riemann::pressure_star`]: [`acoustic`] with `s = -p` (the same operations:
/// the sides' stresses negated, the star stress negated back), impedances `zl`, `zr`;
/// lanes where `zl + zr` is not positive and finite take the mean of the sides.
#[inline(always)]
pub(crate) unsafe fn pressure_star<V: Lanes>(ul: V, pl: V, zl: V, ur: V, pr: V, zr: V) -> (V, V) {
    let (u, s) = acoustic(ul, neg(pl), zl, ur, neg(pr), zr);
    (u, neg(s))
}

/// `acoustic_star_vector`: the normal problem with the longitudinal impedances, the
/// tangential one with the transverse impedances; `(V*, T*)` and the lanes the portable
/// code must redo. With `shock` (each side's density, sound speed and slope) the normal
/// problem is the two-shock one (`elastic_star_vector` with `two_shock_star`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn star_vector<V: Lanes, const D: usize>(
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
