//! The AVX2 loops: four pairs per instruction (module docs of [`super`]).

use core::arch::x86_64::*;

use crate::kernel::Kernel;
use crate::math::{Real, Vector};
use crate::state::PairGeom;

/// Whether [`geometry_row`] computes this kernel (the polynomial ones; the Gaussian's
/// `exp` is left to the portable loop).
#[inline(always)]
pub(crate) fn has_geometry(kernel: Kernel) -> bool {
    matches!(kernel, Kernel::CubicSpline | Kernel::WendlandC2)
}

#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn splat(x: Real) -> __m256d {
    _mm256_set1_pd(x)
}

/// `powi` of [`crate::math::real::powi`], lane by lane with the same operations.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn powi(x: __m256d, n: u32) -> __m256d {
    let (mut r, mut b, mut k) = (splat(1.0), x, n);
    while k > 0 {
        if k & 1 == 1 {
            r = _mm256_mul_pd(r, b);
        }
        b = _mm256_mul_pd(b, b);
        k >>= 1;
    }
    r
}

/// Lanes where `a < b`.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn lt_s(a: __m256d, b: Real) -> __m256d {
    _mm256_cmp_pd::<_CMP_LT_OQ>(a, splat(b))
}

/// `a` where `m` is set, else `b`.
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn select(m: __m256d, a: __m256d, b: __m256d) -> __m256d {
    _mm256_blendv_pd(b, a, m)
}

/// The kernel shape `(f, f')` of [`Kernel`]'s private `shape` for `q` (both branches
/// evaluated and blended; zero from the support on).
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn shape<const D: usize>(kernel: Kernel, q: __m256d) -> (__m256d, __m256d) {
    let zero = _mm256_setzero_pd();
    match kernel {
        Kernel::CubicSpline => {
            // q < 1: (1 - q q (1.5 - 0.75 q), q (2.25 q - 3))
            let inner = _mm256_mul_pd(
                _mm256_mul_pd(q, q),
                _mm256_sub_pd(splat(1.5), _mm256_mul_pd(splat(0.75), q)),
            );
            let f1 = _mm256_sub_pd(splat(1.0), inner);
            let d1 = _mm256_mul_pd(q, _mm256_sub_pd(_mm256_mul_pd(splat(2.25), q), splat(3.0)));
            // q < 2: t = 2 - q, (0.25 t t t, -0.75 t t)
            let t = _mm256_sub_pd(splat(2.0), q);
            let f2 = _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(splat(0.25), t), t), t);
            let d2 = _mm256_mul_pd(_mm256_mul_pd(splat(-0.75), t), t);
            let (m1, m2) = (lt_s(q, 1.0), lt_s(q, 2.0));
            (
                select(m1, f1, select(m2, f2, zero)),
                select(m1, d1, select(m2, d2, zero)),
            )
        }
        Kernel::WendlandC2 => {
            let t = _mm256_sub_pd(splat(1.0), _mm256_mul_pd(splat(0.5), q));
            let t2 = _mm256_mul_pd(t, t);
            let (f, d) = if D == 1 {
                // t³ (1.5 q + 1), -3 q t²
                (
                    _mm256_mul_pd(
                        _mm256_mul_pd(t2, t),
                        _mm256_add_pd(_mm256_mul_pd(splat(1.5), q), splat(1.0)),
                    ),
                    _mm256_mul_pd(_mm256_mul_pd(splat(-3.0), q), t2),
                )
            } else {
                // t⁴ (2 q + 1), -5 q t³
                (
                    _mm256_mul_pd(
                        _mm256_mul_pd(t2, t2),
                        _mm256_add_pd(_mm256_mul_pd(splat(2.0), q), splat(1.0)),
                    ),
                    _mm256_mul_pd(_mm256_mul_pd(_mm256_mul_pd(splat(-5.0), q), t2), t),
                )
            };
            let m = lt_s(q, 2.0);
            (select(m, f, zero), select(m, d, zero))
        }
        // not reached: `has_geometry` is checked first
        Kernel::Gaussian => (zero, zero),
    }
}

/// The pair geometry of four pairs (i, j) in lanes, seen from i, exactly as
/// [`PairGeometry::of`](crate::schemes::common::PairGeometry) computes it for a
/// non-periodic run: zero (+0) outside the kernel support.
#[derive(Clone, Copy)]
pub(super) struct GeomLanes {
    /// Unit vector from i to j (components past `D` unset).
    pub n: [__m256d; 3],
    pub r: __m256d,
    pub dw: __m256d,
    /// The artificial-stress factor (zero without).
    pub f: __m256d,
    /// The lanes inside the support.
    pub inside: __m256d,
    /// `h_ij = (h_i + h_j)/2`.
    pub hij: __m256d,
}

/// [`GeomLanes`] of particle i (at `xi`, `hi`) and the neighbours at `xj`, `hj` (lanes);
/// `kernel` must pass [`has_geometry`], `art` as [`geometry_row`] takes it.
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn pair_lanes<const D: usize>(
    kernel: Kernel,
    xi: &Vector<D>,
    hi: Real,
    xj: &[__m256d; 3],
    hj: __m256d,
    art: Option<(Real, u32)>,
) -> GeomLanes {
    let zero = _mm256_setzero_pd();
    // rij = xi - xj, r2 = |rij|² in nalgebra's order ((x0² + x1²) + x2²)
    let mut rij = [zero; 3];
    let mut r2 = zero;
    for a in 0..D {
        rij[a] = _mm256_sub_pd(splat(xi[a]), xj[a]);
        let sq = _mm256_mul_pd(rij[a], rij[a]);
        r2 = if a == 0 { sq } else { _mm256_add_pd(r2, sq) };
    }
    let hij = _mm256_mul_pd(splat(0.5), _mm256_add_pd(splat(hi), hj));
    let rmax = _mm256_mul_pd(splat(kernel.support()), hij);
    let inside = _mm256_and_pd(
        _mm256_cmp_pd::<_CMP_LT_OQ>(r2, _mm256_mul_pd(rmax, rmax)),
        _mm256_cmp_pd::<_CMP_GT_OQ>(r2, zero),
    );
    let r = _mm256_sqrt_pd(r2);
    // Kernel::shape_dw: zero from r >= support h on (compared in r)
    let beyond = _mm256_cmp_pd::<_CMP_GE_OQ>(r, rmax);
    let inv_h = _mm256_div_pd(splat(1.0), hij);
    let q = _mm256_mul_pd(r, inv_h);
    let (f, df) = shape::<D>(kernel, q);
    let norm = _mm256_mul_pd(splat(kernel.sigma(D)), powi(inv_h, D as u32));
    let dw = _mm256_mul_pd(_mm256_mul_pd(norm, inv_h), df);
    let (f, dw) = (select(beyond, zero, f), select(beyond, zero, dw));
    // everything outside `inside` is the default (zero) geometry
    let minus_inv_r = _mm256_div_pd(splat(-1.0), r);
    let mut n = [zero; 3];
    for (na, ra) in n.iter_mut().zip(&rij).take(D) {
        *na = _mm256_and_pd(inside, _mm256_mul_pd(*ra, minus_inv_r));
    }
    let f = match art {
        Some((inv_wref, exponent)) => {
            _mm256_and_pd(inside, powi(_mm256_mul_pd(f, splat(inv_wref)), exponent))
        }
        None => zero,
    };
    GeomLanes {
        n,
        r: _mm256_and_pd(inside, r),
        dw: _mm256_and_pd(inside, dw),
        f,
        inside,
        hij,
    }
}

/// The geometry of the pairs particle `i` owns (at `xi`, `hi`; its neighbours `owned`),
/// four at a time, exactly as the portable `geometry_pass` computes them for a
/// non-periodic run: into `out` and, with `art = Some((1/W_ref shape, n))`, the
/// artificial-stress factors into `fac`. Returns how many pairs it did (all of them).
///
/// # Safety
/// The CPU must have AVX2 and `kernel` must pass [`has_geometry`]. (The neighbour indices
/// are checked against `x` and `h`; `out` and `fac` are indexed with bounds checks.)
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn geometry_row<const D: usize>(
    kernel: Kernel,
    xi: &Vector<D>,
    hi: Real,
    x: &[Vector<D>],
    h: &[Real],
    owned: &[u32],
    out: &mut [PairGeom<D>],
    fac: &mut [Real],
    art: Option<(Real, u32)>,
) -> usize {
    let n = owned.len();
    let xp = x.as_ptr() as *const Real;
    let hp = h.as_ptr();
    let mut q0 = 0;
    while q0 < n {
        // a last, partial group repeats its last pair in the spare lanes (not stored)
        let lanes = (n - q0).min(4);
        let j: [i64; 4] = core::array::from_fn(|l| owned[q0 + l.min(lanes - 1)] as i64);
        // the gathers below read through raw pointers: every index checked
        assert!(j
            .iter()
            .all(|&j| (j as usize) < x.len() && (j as usize) < h.len()));
        let jv = _mm256_set_epi64x(j[3], j[2], j[1], j[0]);
        let mut xj = [_mm256_setzero_pd(); 3];
        for (a, xa) in xj.iter_mut().enumerate().take(D) {
            let idx = _mm256_add_epi64(
                _mm256_mul_epu32(jv, _mm256_set1_epi64x(D as i64)),
                _mm256_set1_epi64x(a as i64),
            );
            *xa = _mm256_i64gather_pd::<8>(xp, idx);
        }
        let hj = _mm256_i64gather_pd::<8>(hp, jv);
        let g = pair_lanes::<D>(kernel, xi, hi, &xj, hj, art);
        let mut n = [[0.0; 4]; 3];
        for (na, ga) in n.iter_mut().zip(&g.n).take(D) {
            _mm256_storeu_pd(na.as_mut_ptr(), *ga);
        }
        let (mut rr, mut ww) = ([0.0; 4], [0.0; 4]);
        _mm256_storeu_pd(rr.as_mut_ptr(), g.r);
        _mm256_storeu_pd(ww.as_mut_ptr(), g.dw);
        for l in 0..lanes {
            let g = &mut out[q0 + l];
            for (ga, na) in g.n.iter_mut().zip(&n) {
                *ga = na[l];
            }
            g.r = rr[l];
            g.dw = ww[l];
        }
        if art.is_some() {
            let mut fl = [0.0; 4];
            _mm256_storeu_pd(fl.as_mut_ptr(), g.f);
            fac[q0..q0 + lanes].copy_from_slice(&fl[..lanes]);
        }
        q0 += lanes;
    }
    n
}

/// Four records' reals `4 g .. 4 g + 4` (`p[l]` points at lane `l`'s record) as four lane
/// vectors, one per real.
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn transpose(p: &[*const Real; 4], g: usize) -> [__m256d; 4] {
    let (a, b, c, d) = (
        _mm256_loadu_pd(p[0].add(4 * g)),
        _mm256_loadu_pd(p[1].add(4 * g)),
        _mm256_loadu_pd(p[2].add(4 * g)),
        _mm256_loadu_pd(p[3].add(4 * g)),
    );
    // [a0 b0 a2 b2], [a1 b1 a3 b3], [c0 d0 c2 d2], [c1 d1 c3 d3]
    let (t0, t1) = (_mm256_unpacklo_pd(a, b), _mm256_unpackhi_pd(a, b));
    let (t2, t3) = (_mm256_unpacklo_pd(c, d), _mm256_unpackhi_pd(c, d));
    [
        _mm256_permute2f128_pd::<0x20>(t0, t2),
        _mm256_permute2f128_pd::<0x20>(t1, t3),
        _mm256_permute2f128_pd::<0x31>(t0, t2),
        _mm256_permute2f128_pd::<0x31>(t1, t3),
    ]
}

// The lane arithmetic of the pair loops: each function is one IEEE operation per lane,
// or the portable helper's rule exactly (named in its documentation).

#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn add(a: __m256d, b: __m256d) -> __m256d {
    _mm256_add_pd(a, b)
}
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn sub(a: __m256d, b: __m256d) -> __m256d {
    _mm256_sub_pd(a, b)
}
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn mul(a: __m256d, b: __m256d) -> __m256d {
    _mm256_mul_pd(a, b)
}
/// `math::real::max`: `a` if `a > b`, else `b` (`maxpd`'s rule exactly).
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn max(a: __m256d, b: __m256d) -> __m256d {
    _mm256_max_pd(a, b)
}
/// `math::real::min`: `a` if `a < b`, else `b` (`minpd`'s rule exactly).
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn min(a: __m256d, b: __m256d) -> __m256d {
    _mm256_min_pd(a, b)
}
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn gt(a: __m256d, b: __m256d) -> __m256d {
    _mm256_cmp_pd::<_CMP_GT_OQ>(a, b)
}
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn lt(a: __m256d, b: __m256d) -> __m256d {
    _mm256_cmp_pd::<_CMP_LT_OQ>(a, b)
}
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn and(a: __m256d, b: __m256d) -> __m256d {
    _mm256_and_pd(a, b)
}
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn or(a: __m256d, b: __m256d) -> __m256d {
    _mm256_or_pd(a, b)
}
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn not(a: __m256d) -> __m256d {
    _mm256_xor_pd(a, _mm256_castsi256_pd(_mm256_set1_epi64x(-1)))
}
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn neg(a: __m256d) -> __m256d {
    _mm256_xor_pd(a, splat(-0.0))
}
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn load(a: &[Real; 4]) -> __m256d {
    _mm256_loadu_pd(a.as_ptr())
}
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn store(a: __m256d) -> [Real; 4] {
    let mut out = [0.0; 4];
    _mm256_storeu_pd(out.as_mut_ptr(), a);
    out
}

/// `math::real::abs`: `-x` if `x < 0`, else `x` (so `-0` stays `-0`).
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn abs(x: __m256d) -> __m256d {
    select(lt(x, _mm256_setzero_pd()), neg(x), x)
}

/// `Vector::dot` in nalgebra's order: `(0 + a0 b0) + a1 b1 + …`.
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn dot<const D: usize>(a: &[__m256d; 3], b: &[__m256d; 3]) -> __m256d {
    let mut s = _mm256_setzero_pd();
    for k in 0..D {
        s = add(s, mul(a[k], b[k]));
    }
    s
}

/// [`Limiter::limit`] of superbee (`superbee`) or minmod, lane by lane.
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn limit(superbee: bool, a: __m256d, b: __m256d) -> __m256d {
    let zero = _mm256_setzero_pd();
    let same_sign = gt(mul(a, b), zero);
    let (p, q) = (abs(a), abs(b));
    let m = if superbee {
        let two = splat(2.0);
        max(min(mul(two, q), p), min(q, mul(two, p)))
    } else {
        min(p, q)
    };
    // m.copysign(a)
    let sign = splat(-0.0);
    let signed = or(_mm256_andnot_pd(sign, m), and(sign, a));
    and(same_sign, signed)
}

/// [`crate::limiter::minmod`], lane by lane.
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn minmod(a: __m256d, b: __m256d) -> __m256d {
    let zero = _mm256_setzero_pd();
    let pos = and(gt(a, zero), gt(b, zero));
    let negs = and(lt(a, zero), lt(b, zero));
    select(pos, min(a, b), select(negs, max(a, b), zero))
}

/// Lanes whose value is finite.
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn finite(x: __m256d) -> __m256d {
    // |x| < inf (false for inf and NaN)
    lt(_mm256_andnot_pd(splat(-0.0), x), splat(Real::INFINITY))
}

// The two-shock solver of `crate::riemann::two_shock`, lane by lane (the ts and tkc stars).

/// One side of the Riemann problem in four lanes.
#[derive(Clone, Copy)]
pub(super) struct Side {
    pub u: __m256d,
    pub p: __m256d,
    pub rho: __m256d,
    pub c: __m256d,
    /// `ShockSide::slope`: the Hugoniot slope, or 0 where negative or not finite.
    pub s: __m256d,
}

/// `ShockSide::hugoniot`: `rho (c + s max(w, 0)) w`.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn hugoniot(k: &Side, w: __m256d) -> __m256d {
    mul(
        mul(k.rho, add(k.c, mul(k.s, max(w, _mm256_setzero_pd())))),
        w,
    )
}

/// `f(u) = p_l + W_l(u_l - u) - p_r - W_r(u - u_r)` of the two-shock solver.
#[target_feature(enable = "avx2")]
#[inline]
unsafe fn gap(l: &Side, r: &Side, u: __m256d) -> __m256d {
    sub(
        sub(add(l.p, hugoniot(l, sub(l.u, u))), r.p),
        hugoniot(r, sub(u, r.u)),
    )
}

/// [`crate::riemann::two_shock_star`] where both impedances are usable; returns the star
/// state and the lanes the portable solver must redo (an impedance not positive and
/// finite, or an answer that is not finite: its acoustic fallbacks).
#[target_feature(enable = "avx2")]
#[inline]
pub(super) unsafe fn two_shock(l: &Side, r: &Side) -> (__m256d, __m256d, __m256d) {
    let zero = _mm256_setzero_pd();
    let (zl, zr) = (mul(l.rho, l.c), mul(r.rho, r.c));
    let usable_l = and(gt(zl, zero), finite(zl));
    let usable_r = and(gt(zr, zero), finite(zr));
    let bad = not(and(usable_l, usable_r));
    let ordered = _mm256_cmp_pd::<_CMP_LE_OQ>(l.u, r.u);
    let (lo, hi) = (select(ordered, l.u, r.u), select(ordered, r.u, l.u));
    let (f_lo, f_hi) = (gap(l, r, lo), gap(l, r, hi));
    let (kl_shock, kr_shock) = (mul(l.rho, l.s), mul(r.rho, r.s));
    let below = _mm256_cmp_pd::<_CMP_LE_OQ>(f_lo, zero);
    let above = _mm256_andnot_pd(below, _mm256_cmp_pd::<_CMP_GE_OQ>(f_hi, zero));
    let two = _mm256_andnot_pd(or(below, above), lt(r.u, l.u));
    let about_hi = or(above, and(two, gt(kl_shock, kr_shock)));
    let (u0, f0) = (select(about_hi, hi, lo), select(about_hi, f_hi, f_lo));
    let kl = and(or(below, two), kl_shock);
    let kr = and(or(above, two), kr_shock);
    let two_v = splat(2.0);
    let b = add(
        add(add(zl, zr), mul(mul(two_v, kl), sub(l.u, u0))),
        mul(mul(two_v, kr), sub(u0, r.u)),
    );
    let a = sub(kl, kr);
    let disc = max(sub(mul(b, b), mul(mul(splat(4.0), a), f0)), zero);
    let d = _mm256_div_pd(mul(two_v, f0), add(b, _mm256_sqrt_pd(disc)));
    let u = add(u0, d);
    let p = mul(
        splat(0.5),
        add(
            add(add(l.p, hugoniot(l, sub(l.u, u))), r.p),
            hugoniot(r, sub(u, r.u)),
        ),
    );
    let redo = or(bad, not(and(finite(u), finite(p))));
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
