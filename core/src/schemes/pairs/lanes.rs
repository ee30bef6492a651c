//! The pair geometry in lanes, the lane twin of [`PairGeometry::of`] and
//! [`super::geometry_pass`] (`schemes/pairs/lanes_tests.rs` holds them bitwise equal):
//! used by the geometry pass of the `pm` and `ts` families and inside `av`'s one pair loop
//! (module docs of [`crate::simd`]).

use core::arch::x86_64::{__m256d, __m512d};

use super::PairGeometry;
use crate::kernel::Kernel;
use crate::math::{Real, Vector};
#[cfg(test)]
use crate::simd::lanes::Emu;
use crate::simd::lanes::Lanes;
use crate::simd::ops::*;
use crate::state::PairGeom;

/// Whether [`geometry_row`] computes this kernel (the polynomial ones; the Gaussian's
/// `exp` is left to the portable loop).
#[inline(always)]
pub(crate) fn has_geometry(kernel: Kernel) -> bool {
    matches!(kernel, Kernel::CubicSpline | Kernel::WendlandC2)
}

/// The pair geometry of a register of pairs (i, j), seen from i, exactly as
/// [`PairGeometry::of`] computes it (the minimum image on periodic axes): zero (+0) outside
/// the kernel support.
#[derive(Clone, Copy)]
pub(crate) struct GeomLanes<V: Lanes> {
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
pub(crate) unsafe fn pair_lanes<V: Lanes, const D: usize, const WRAP: bool>(
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

/// [`geometry_row`] in `V`'s lanes, with or without a periodic box as `pg` has one.
///
/// # Safety
/// As [`geometry_row`].
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn geometry_row_in<V: Lanes, const D: usize>(
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
        geometry_row::<V, D, true>(pg, xi, hi, x, h, owned, out, fac)
    } else {
        geometry_row::<V, D, false>(pg, xi, hi, x, h, owned, out, fac)
    }
}

/// [`geometry_row`] in `W`'s lanes over the row's full groups of `W::N` pairs and in `N`'s
/// over the rest (a last, partial group of the wide register costs as much as a full one):
/// AVX-512's entry with `zmm` and `ymm` registers, and the tests' eight emulated lanes with
/// the same code.
///
/// # Safety
/// As [`geometry_row`], with both levels.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn geometry_row_wide<W: Lanes, N: Lanes, const D: usize>(
    pg: &PairGeometry<D>,
    xi: &Vector<D>,
    hi: Real,
    x: &[Vector<D>],
    h: &[Real],
    owned: &[u32],
    out: &mut [PairGeom<D>],
    fac: &mut [Real],
) -> usize {
    let m = owned.len() / W::N * W::N;
    let (o_w, o_n) = out.split_at_mut(m.min(out.len()));
    let (f_w, f_n) = fac.split_at_mut(m.min(fac.len()));
    let wide = if m > 0 {
        geometry_row_in::<W, D>(pg, xi, hi, x, h, &owned[..m], o_w, f_w)
    } else {
        0
    };
    wide + geometry_row_in::<N, D>(pg, xi, hi, x, h, &owned[m..], o_n, f_n)
}

/// [`geometry_row`] with four pairs per AVX2 instruction.
///
/// # Safety
/// The CPU must have AVX2 and `pg.kernel` must pass [`has_geometry`].
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)]
unsafe fn geometry_row_avx2<const D: usize>(
    pg: &PairGeometry<D>,
    xi: &Vector<D>,
    hi: Real,
    x: &[Vector<D>],
    h: &[Real],
    owned: &[u32],
    out: &mut [PairGeom<D>],
    fac: &mut [Real],
) -> usize {
    geometry_row_in::<__m256d, D>(pg, xi, hi, x, h, owned, out, fac)
}

/// [`geometry_row_wide`] with eight pairs per AVX-512 instruction, the rest four per AVX2
/// one.
///
/// # Safety
/// The CPU must have AVX-512F and `pg.kernel` must pass [`has_geometry`].
#[target_feature(enable = "avx512f")]
#[allow(clippy::too_many_arguments)]
unsafe fn geometry_row_avx512<const D: usize>(
    pg: &PairGeometry<D>,
    xi: &Vector<D>,
    hi: Real,
    x: &[Vector<D>],
    h: &[Real],
    owned: &[u32],
    out: &mut [PairGeom<D>],
    fac: &mut [Real],
) -> usize {
    geometry_row_wide::<__m512d, __m256d, D>(pg, xi, hi, x, h, owned, out, fac)
}

/// [`geometry_row`] at `level` (0 pairs at the baseline level).
///
/// # Safety
/// `level` must be one the CPU has (`SimdLevel::assume`) and `pg.kernel` must pass
/// [`has_geometry`].
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn geometry_row_at<const D: usize>(
    level: crate::simd::SimdLevel,
    pg: &PairGeometry<D>,
    xi: &Vector<D>,
    hi: Real,
    x: &[Vector<D>],
    h: &[Real],
    owned: &[u32],
    out: &mut [PairGeom<D>],
    fac: &mut [Real],
) -> usize {
    use crate::simd::Simd;
    match level.get() {
        Simd::Avx512 => geometry_row_avx512::<D>(pg, xi, hi, x, h, owned, out, fac),
        Simd::Avx2 => geometry_row_avx2::<D>(pg, xi, hi, x, h, owned, out, fac),
        Simd::Baseline => 0,
        #[cfg(test)]
        Simd::Emu4 => geometry_row_in::<Emu<4>, D>(pg, xi, hi, x, h, owned, out, fac),
        #[cfg(test)]
        Simd::Emu8 => geometry_row_wide::<Emu<8>, Emu<4>, D>(pg, xi, hi, x, h, owned, out, fac),
    }
}
