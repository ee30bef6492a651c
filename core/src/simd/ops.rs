//! The lane arithmetic the vectorised loops share, generic over the register width
//! ([`Lanes`]): the operations, the kernel shapes, the limiters, vectors and matrices in
//! lanes (module docs of [`super`]; the Riemann solvers are in [`super::riemann`]). Each function is one IEEE operation per lane, or the portable helper's rule
//! exactly (named in its documentation); all are `#[inline(always)]` into the loops.

use super::lanes::Lanes;
use crate::kernel::Kernel;
use crate::math::Real;

// The level's operations as free functions, so that the loops read as formulas.

#[inline(always)]
pub(crate) unsafe fn splat<V: Lanes>(x: Real) -> V {
    V::splat(x)
}
#[inline(always)]
pub(crate) unsafe fn add<V: Lanes>(a: V, b: V) -> V {
    V::add(a, b)
}
#[inline(always)]
pub(crate) unsafe fn sub<V: Lanes>(a: V, b: V) -> V {
    V::sub(a, b)
}
#[inline(always)]
pub(crate) unsafe fn mul<V: Lanes>(a: V, b: V) -> V {
    V::mul(a, b)
}
#[inline(always)]
pub(crate) unsafe fn div<V: Lanes>(a: V, b: V) -> V {
    V::div(a, b)
}
/// `math::real::max`: `a` if `a > b`, else `b`.
#[inline(always)]
pub(crate) unsafe fn max<V: Lanes>(a: V, b: V) -> V {
    V::max(a, b)
}
/// `math::real::min`: `a` if `a < b`, else `b`.
#[inline(always)]
pub(crate) unsafe fn min<V: Lanes>(a: V, b: V) -> V {
    V::min(a, b)
}
#[inline(always)]
pub(crate) unsafe fn gt<V: Lanes>(a: V, b: V) -> V::Mask {
    V::gt(a, b)
}
#[inline(always)]
pub(crate) unsafe fn lt<V: Lanes>(a: V, b: V) -> V::Mask {
    V::lt(a, b)
}
#[inline(always)]
pub(crate) unsafe fn neg<V: Lanes>(a: V) -> V {
    V::neg(a)
}
#[inline(always)]
pub(crate) unsafe fn load<V: Lanes>(a: &V::Arr<Real>) -> V {
    V::load(a)
}
#[inline(always)]
pub(crate) unsafe fn store<V: Lanes>(a: V) -> V::Arr<Real> {
    V::store(a)
}
/// `a` where `m` is set, else `b`.
#[inline(always)]
pub(crate) unsafe fn select<V: Lanes>(m: V::Mask, a: V, b: V) -> V {
    V::select(m, a, b)
}

/// `powi` of [`crate::math::real::powi`], lane by lane with the same operations.
#[inline(always)]
pub(crate) unsafe fn powi<V: Lanes>(x: V, n: u32) -> V {
    let (mut r, mut b, mut k) = (splat::<V>(1.0), x, n);
    while k > 0 {
        if k & 1 == 1 {
            r = mul(r, b);
        }
        b = mul(b, b);
        k >>= 1;
    }
    r
}

/// Lanes where `a < b`.
#[inline(always)]
unsafe fn lt_s<V: Lanes>(a: V, b: Real) -> V::Mask {
    V::lt(a, splat(b))
}

/// The kernel shape `(f, f')` of [`Kernel`]'s private `shape` for `q` (both branches
/// evaluated and blended; zero from the support on).
#[inline(always)]
pub(crate) unsafe fn shape<V: Lanes, const D: usize>(kernel: Kernel, q: V) -> (V, V) {
    let zero = V::zero();
    match kernel {
        Kernel::CubicSpline => {
            // q < 1: (1 - q q (1.5 - 0.75 q), q (2.25 q - 3))
            let inner = mul(mul(q, q), sub(splat(1.5), mul(splat(0.75), q)));
            let f1 = sub(splat(1.0), inner);
            let d1 = mul(q, sub(mul(splat(2.25), q), splat(3.0)));
            // q < 2: t = 2 - q, (0.25 t t t, -0.75 t t)
            let t = sub(splat(2.0), q);
            let f2 = mul(mul(mul(splat(0.25), t), t), t);
            let d2 = mul(mul(splat(-0.75), t), t);
            let (m1, m2) = (lt_s(q, 1.0), lt_s(q, 2.0));
            (
                select(m1, f1, V::keep(m2, f2)),
                select(m1, d1, V::keep(m2, d2)),
            )
        }
        Kernel::WendlandC2 => {
            let t = sub(splat(1.0), mul(splat(0.5), q));
            let t2 = mul(t, t);
            let (f, d) = if D == 1 {
                // t³ (1.5 q + 1), -3 q t²
                (
                    mul(mul(t2, t), add(mul(splat(1.5), q), splat(1.0))),
                    mul(mul(splat(-3.0), q), t2),
                )
            } else {
                // t⁴ (2 q + 1), -5 q t³
                (
                    mul(mul(t2, t2), add(mul(splat(2.0), q), splat(1.0))),
                    mul(mul(mul(splat(-5.0), q), t2), t),
                )
            };
            let m = lt_s(q, 2.0);
            (V::keep(m, f), V::keep(m, d))
        }
        // not reached: ``schemes::lanes::has_geometry` is checked first
        Kernel::Gaussian => (zero, zero),
    }
}

/// The neighbour records of the lanes' particles `js`, `width` reals each in `rec`, their
/// first `4 groups` reals transposed into lanes: `f[k]` holds real `k` of each lane's
/// record (the rest of `f` zero; `W` is room for the widest record). Panics if a record
/// lies outside `rec`: the loads read through raw pointers.
#[inline(always)]
pub(crate) unsafe fn records<V: Lanes, const W: usize>(
    rec: &[Real],
    width: usize,
    groups: usize,
    js: &V::Arr<usize>,
) -> [V; W] {
    assert!(js.as_ref().iter().all(|&j| (j + 1) * width <= rec.len()));
    let p = V::arr(|l| rec.as_ptr().add(js[l] * width));
    let mut f = [V::zero(); W];
    for g in 0..groups {
        f[4 * g..4 * g + 4].copy_from_slice(&V::transpose(&p, g));
    }
    f
}

/// `math::real::abs`: `-x` if `x < 0`, else `x` (so `-0` stays `-0`).
#[inline(always)]
pub(crate) unsafe fn abs<V: Lanes>(x: V) -> V {
    select(lt(x, V::zero()), neg(x), x)
}

/// `Vector::dot` in nalgebra's order: `(0 + a0 b0) + a1 b1 + …`.
#[inline(always)]
pub(crate) unsafe fn dot<V: Lanes, const D: usize>(a: &[V; 3], b: &[V; 3]) -> V {
    let mut s = V::zero();
    for k in 0..D {
        s = add(s, mul(a[k], b[k]));
    }
    s
}

/// [`Limiter::limit`](crate::limiter::Limiter) of superbee (`superbee`) or minmod, lane by
/// lane.
#[inline(always)]
pub(crate) unsafe fn limit<V: Lanes>(superbee: bool, a: V, b: V) -> V {
    let zero = V::zero();
    let same_sign = gt(mul(a, b), zero);
    let (p, q) = (abs(a), abs(b));
    let m = if superbee {
        let two = splat(2.0);
        max(min(mul(two, q), p), min(q, mul(two, p)))
    } else {
        min(p, q)
    };
    V::keep(same_sign, V::copysign(m, a))
}

/// [`crate::limiter::minmod`], lane by lane.
#[inline(always)]
pub(crate) unsafe fn minmod<V: Lanes>(a: V, b: V) -> V {
    let zero = V::zero();
    let pos = V::and(gt(a, zero), gt(b, zero));
    let negs = V::and(lt(a, zero), lt(b, zero));
    select(pos, min(a, b), V::keep(negs, max(a, b)))
}

/// Lanes whose value is finite.
#[inline(always)]
pub(crate) unsafe fn finite<V: Lanes>(x: V) -> V::Mask {
    // |x| < inf (false for inf and NaN)
    lt(V::magnitude(x), splat(Real::INFINITY))
}

/// Lanes of a `D`-vector (components past `D` unused).
pub(crate) type Vl<V> = [V; 3];
/// Lanes of a `D x D` matrix, by columns: `m[b][a]` is element `(a, b)`.
pub(crate) type Ml<V> = [[V; 3]; 3];

/// `m x` in nalgebra's gemv order: column 0 times `x_0`, then each further column times
/// its component, added on.
#[inline(always)]
pub(crate) unsafe fn gemv<V: Lanes, const D: usize>(m: &Ml<V>, x: &Vl<V>) -> Vl<V> {
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
pub(crate) unsafe fn scale<V: Lanes, const D: usize>(v: &Vl<V>, s: V) -> Vl<V> {
    let mut out = *v;
    for a in 0..D {
        out[a] = mul(v[a], s);
    }
    out
}

/// `Sym3::dot_vec`: row `a` is `(0 + s_a0 x_0) + s_a1 x_1 + …`; `s[a][b]` is the
/// component `(a, b)`.
#[inline(always)]
pub(crate) unsafe fn sym_dot<V: Lanes, const D: usize>(s: &Ml<V>, x: &Vl<V>) -> Vl<V> {
    let mut out = [V::zero(); 3];
    for (a, o) in out.iter_mut().enumerate().take(D) {
        for b in 0..D {
            *o = add(*o, mul(s[a][b], x[b]));
        }
    }
    out
}
