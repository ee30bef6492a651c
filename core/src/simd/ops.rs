//! The lane arithmetic the vectorised loops share, generic over the register width
//! ([`Lanes`]): the pair geometry, the limiters and the two-shock solver (module docs of
//! [`super`]). Each function is one IEEE operation per lane, or the portable helper's rule
//! exactly (named in its documentation); all are `#[inline(always)]` into the loops.

use core::arch::x86_64::{__m256d, __m512d};

use super::lanes::Lanes;
use crate::kernel::Kernel;
use crate::math::{Real, Vector};
use crate::schemes::common::PairGeometry;
use crate::state::PairGeom;

/// Whether [`geometry_row`] computes this kernel (the polynomial ones; the Gaussian's
/// `exp` is left to the portable loop).
#[inline(always)]
pub(crate) fn has_geometry(kernel: Kernel) -> bool {
    matches!(kernel, Kernel::CubicSpline | Kernel::WendlandC2)
}

// The level's operations as free functions, so that the loops read as formulas.

#[inline(always)]
pub(super) unsafe fn splat<V: Lanes>(x: Real) -> V {
    V::splat(x)
}
#[inline(always)]
pub(super) unsafe fn add<V: Lanes>(a: V, b: V) -> V {
    V::add(a, b)
}
#[inline(always)]
pub(super) unsafe fn sub<V: Lanes>(a: V, b: V) -> V {
    V::sub(a, b)
}
#[inline(always)]
pub(super) unsafe fn mul<V: Lanes>(a: V, b: V) -> V {
    V::mul(a, b)
}
#[inline(always)]
pub(super) unsafe fn div<V: Lanes>(a: V, b: V) -> V {
    V::div(a, b)
}
/// `math::real::max`: `a` if `a > b`, else `b`.
#[inline(always)]
pub(super) unsafe fn max<V: Lanes>(a: V, b: V) -> V {
    V::max(a, b)
}
/// `math::real::min`: `a` if `a < b`, else `b`.
#[inline(always)]
pub(super) unsafe fn min<V: Lanes>(a: V, b: V) -> V {
    V::min(a, b)
}
#[inline(always)]
pub(super) unsafe fn gt<V: Lanes>(a: V, b: V) -> V::Mask {
    V::gt(a, b)
}
#[inline(always)]
pub(super) unsafe fn lt<V: Lanes>(a: V, b: V) -> V::Mask {
    V::lt(a, b)
}
#[inline(always)]
pub(super) unsafe fn neg<V: Lanes>(a: V) -> V {
    V::neg(a)
}
#[inline(always)]
pub(super) unsafe fn load<V: Lanes>(a: &V::Arr<Real>) -> V {
    V::load(a)
}
#[inline(always)]
pub(super) unsafe fn store<V: Lanes>(a: V) -> V::Arr<Real> {
    V::store(a)
}
/// `a` where `m` is set, else `b`.
#[inline(always)]
pub(super) unsafe fn select<V: Lanes>(m: V::Mask, a: V, b: V) -> V {
    V::select(m, a, b)
}

/// `powi` of [`crate::math::real::powi`], lane by lane with the same operations.
#[inline(always)]
unsafe fn powi<V: Lanes>(x: V, n: u32) -> V {
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
unsafe fn shape<V: Lanes, const D: usize>(kernel: Kernel, q: V) -> (V, V) {
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
        // not reached: `has_geometry` is checked first
        Kernel::Gaussian => (zero, zero),
    }
}

/// The pair geometry of a register of pairs (i, j), seen from i, exactly as
/// [`PairGeometry::of`] computes it (the minimum image on periodic axes): zero (+0) outside
/// the kernel support.
#[derive(Clone, Copy)]
pub(super) struct GeomLanes<V: Lanes> {
    /// Unit vector from i to j (components past `D` unset).
    pub n: [V; 3],
    pub r: V,
    pub dw: V,
    /// The artificial-stress factor (zero without).
    pub f: V,
    /// The lanes inside the support.
    pub inside: V::Mask,
    /// `h_ij = (h_i + h_j)/2`.
    pub hij: V,
}

/// [`GeomLanes`] of particle i (at `xi`, `hi`) and the neighbours at `xj`, `hj` (lanes);
/// `pg.kernel` must pass [`has_geometry`]. `WRAP`: whether `pg` has a periodic box (a
/// parameter of the loop's code, so that the loops of a run without one are not slowed by
/// the minimum image: av's row on the rings took 1.35 times as long with it tested at run
/// time).
#[inline(always)]
pub(super) unsafe fn pair_lanes<V: Lanes, const D: usize, const WRAP: bool>(
    pg: &PairGeometry<D>,
    xi: &Vector<D>,
    hi: Real,
    xj: &[V; 3],
    hj: V,
) -> GeomLanes<V> {
    let (kernel, art) = (pg.kernel, pg.art);
    let zero = V::zero();
    // rij = xi - xj (the minimum image on periodic axes, `Periodic::min_image`), r2 =
    // |rij|² in nalgebra's order ((x0² + x1²) + x2²)
    let mut rij = [zero; 3];
    let mut r2 = zero;
    for a in 0..D {
        rij[a] = sub(splat(xi[a]), xj[a]);
        if let Some(p) = pg.periodic.as_ref().filter(|p| WRAP && p.axes[a]) {
            let (d, l) = (rij[a], splat(p.len[a]));
            let wrapped = select(V::lt(d, splat(-0.5 * p.len[a])), add(d, l), d);
            rij[a] = select(V::gt(d, splat(0.5 * p.len[a])), sub(d, l), wrapped);
        }
        let sq = mul(rij[a], rij[a]);
        r2 = if a == 0 { sq } else { add(r2, sq) };
    }
    let hij = mul(splat(0.5), add(splat(hi), hj));
    let rmax = mul(splat(kernel.support()), hij);
    let inside = V::and(V::lt(r2, mul(rmax, rmax)), V::gt(r2, zero));
    let r = V::sqrt(r2);
    // Kernel::shape_dw: zero from r >= support h on (compared in r)
    let beyond = V::ge(r, rmax);
    let inv_h = div(splat(1.0), hij);
    let q = mul(r, inv_h);
    let (f, df) = shape::<V, D>(kernel, q);
    let norm = mul(splat(kernel.sigma(D)), powi(inv_h, D as u32));
    let dw = mul(mul(norm, inv_h), df);
    let (f, dw) = (select(beyond, zero, f), select(beyond, zero, dw));
    // everything outside `inside` is the default (zero) geometry
    let minus_inv_r = div(splat(-1.0), r);
    let mut n = [zero; 3];
    for (na, ra) in n.iter_mut().zip(&rij).take(D) {
        *na = V::keep(inside, mul(*ra, minus_inv_r));
    }
    let f = match art {
        Some((inv_wref, exponent)) => V::keep(inside, powi(mul(f, splat(inv_wref)), exponent)),
        None => zero,
    };
    GeomLanes {
        n,
        r: V::keep(inside, r),
        dw: V::keep(inside, dw),
        f,
        inside,
        hij,
    }
}

/// The geometry of the pairs particle `i` owns (at `xi`, `hi`; its neighbours `owned`),
/// a register at a time, exactly as the portable `geometry_pass` computes them: into `out`
/// and, with `pg.art = Some((1/W_ref shape, n))`, the artificial-stress factors into
/// `fac`. Returns how many pairs it did (all of them).
///
/// # Safety
/// The CPU must have the level of `V` and `pg.kernel` must pass [`has_geometry`]. (The
/// neighbour indices are checked against `x` and `h`; `out` and `fac` are indexed with
/// bounds checks.)
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn geometry_row<V: Lanes, const D: usize, const WRAP: bool>(
    pg: &PairGeometry<D>,
    xi: &Vector<D>,
    hi: Real,
    x: &[Vector<D>],
    h: &[Real],
    owned: &[u32],
    out: &mut [PairGeom<D>],
    fac: &mut [Real],
) -> usize {
    let n = owned.len();
    let xp = x.as_ptr() as *const Real;
    let hp = h.as_ptr();
    let mut q0 = 0;
    while q0 < n {
        // a last, partial group repeats its last pair in the spare lanes (not stored)
        let lanes = (n - q0).min(V::N);
        let j = V::arr(|l| owned[q0 + l.min(lanes - 1)] as usize);
        // the gathers below read through raw pointers: every index checked
        assert!(j.as_ref().iter().all(|&j| j < x.len() && j < h.len()));
        let mut xj = [V::zero(); 3];
        for (a, xa) in xj.iter_mut().enumerate().take(D) {
            *xa = V::gather(xp, &j, D, a);
        }
        let hj = V::gather(hp, &j, 1, 0);
        let g = pair_lanes::<V, D, WRAP>(pg, xi, hi, &xj, hj);
        let n: [V::Arr<Real>; 3] = core::array::from_fn(|a| store(g.n[a]));
        let (rr, ww) = (store(g.r), store(g.dw));
        for l in 0..lanes {
            let g = &mut out[q0 + l];
            for (ga, na) in g.n.iter_mut().zip(&n) {
                *ga = na[l];
            }
            g.r = rr[l];
            g.dw = ww[l];
        }
        if pg.art.is_some() {
            let fl = store(g.f);
            fac[q0..q0 + lanes].copy_from_slice(&fl.as_ref()[..lanes]);
        }
        q0 += lanes;
    }
    n
}

/// [`geometry_row`] with four pairs per AVX2 instruction.
///
/// # Safety
/// The CPU must have AVX2 and `pg.kernel` must pass [`has_geometry`].
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn geometry_row_avx2<const D: usize>(
    pg: &PairGeometry<D>,
    xi: &Vector<D>,
    hi: Real,
    x: &[Vector<D>],
    h: &[Real],
    owned: &[u32],
    out: &mut [PairGeom<D>],
    fac: &mut [Real],
) -> usize {
    if pg.periodic.is_some() {
        geometry_row::<__m256d, D, true>(pg, xi, hi, x, h, owned, out, fac)
    } else {
        geometry_row::<__m256d, D, false>(pg, xi, hi, x, h, owned, out, fac)
    }
}

/// [`geometry_row`] with eight pairs per AVX-512 instruction.
///
/// # Safety
/// The CPU must have AVX-512F and `pg.kernel` must pass [`has_geometry`].
#[target_feature(enable = "avx512f")]
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn geometry_row_avx512<const D: usize>(
    pg: &PairGeometry<D>,
    xi: &Vector<D>,
    hi: Real,
    x: &[Vector<D>],
    h: &[Real],
    owned: &[u32],
    out: &mut [PairGeom<D>],
    fac: &mut [Real],
) -> usize {
    // the full groups of eight in zmm registers, the rest in ymm ones (a last, partial
    // group of eight would cost as much as a full one)
    let m = owned.len() / 8 * 8;
    let (o8, o4) = out.split_at_mut(m.min(out.len()));
    let (f8, f4) = fac.split_at_mut(m.min(fac.len()));
    let wrap = pg.periodic.is_some();
    let wide = match (m > 0, wrap) {
        (false, _) => 0,
        (true, true) => geometry_row::<__m512d, D, true>(pg, xi, hi, x, h, &owned[..m], o8, f8),
        (true, false) => geometry_row::<__m512d, D, false>(pg, xi, hi, x, h, &owned[..m], o8, f8),
    };
    wide + if wrap {
        geometry_row::<__m256d, D, true>(pg, xi, hi, x, h, &owned[m..], o4, f4)
    } else {
        geometry_row::<__m256d, D, false>(pg, xi, hi, x, h, &owned[m..], o4, f4)
    }
}

/// The neighbour records of the lanes' particles `js`, `width` reals each in `rec`, their
/// first `4 groups` reals transposed into lanes: `f[k]` holds real `k` of each lane's
/// record (the rest of `f` zero; `W` is room for the widest record). Panics if a record
/// lies outside `rec`: the loads read through raw pointers.
#[inline(always)]
pub(super) unsafe fn records<V: Lanes, const W: usize>(
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
pub(super) unsafe fn abs<V: Lanes>(x: V) -> V {
    select(lt(x, V::zero()), neg(x), x)
}

/// `Vector::dot` in nalgebra's order: `(0 + a0 b0) + a1 b1 + …`.
#[inline(always)]
pub(super) unsafe fn dot<V: Lanes, const D: usize>(a: &[V; 3], b: &[V; 3]) -> V {
    let mut s = V::zero();
    for k in 0..D {
        s = add(s, mul(a[k], b[k]));
    }
    s
}

/// [`Limiter::limit`](crate::limiter::Limiter) of superbee (`superbee`) or minmod, lane by
/// lane.
#[inline(always)]
pub(super) unsafe fn limit<V: Lanes>(superbee: bool, a: V, b: V) -> V {
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
pub(super) unsafe fn minmod<V: Lanes>(a: V, b: V) -> V {
    let zero = V::zero();
    let pos = V::and(gt(a, zero), gt(b, zero));
    let negs = V::and(lt(a, zero), lt(b, zero));
    select(pos, min(a, b), V::keep(negs, max(a, b)))
}

/// Lanes whose value is finite.
#[inline(always)]
pub(super) unsafe fn finite<V: Lanes>(x: V) -> V::Mask {
    // |x| < inf (false for inf and NaN)
    lt(V::magnitude(x), splat(Real::INFINITY))
}

// The two-shock solver of `crate::riemann::two_shock`, lane by lane (the ts and tkc stars).

/// One side of the Riemann problem in lanes.
#[derive(Clone, Copy)]
pub(super) struct Side<V> {
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
pub(super) unsafe fn two_shock<V: Lanes>(l: &Side<V>, r: &Side<V>) -> (V, V, V::Mask) {
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
pub(super) fn shock_slope(m: &crate::material::Material) -> Real {
    let s = m.eos.hugoniot_slope();
    if s.is_finite() {
        crate::math::real::max(s, 0.0)
    } else {
        0.0
    }
}
