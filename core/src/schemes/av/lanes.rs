//! `av`'s pair loop, four neighbours per AVX2 instruction or eight per AVX-512 one (module
//! docs of [`super`]).
//!
//! Each neighbour's fields come from its compact record (`Workspace::rec`): a register's
//! records are loaded four reals at a time and transposed into lanes, so a neighbour
//! costs a few vector loads instead of a dozen scattered scalar ones. The lanes compute
//! each pair's terms with the portable loop's operations in its order; the particle's
//! sums then add them lane by lane in the order of its list, as the portable loop does.

use core::arch::x86_64::{__m256d, __m512d};

use crate::effects::Effects;
use crate::math::Real;
use crate::schemes::av::pairs::{Owner, Sums};
use crate::schemes::av::records::{record_len, sym_at, RecordAt};
use crate::schemes::options::SchemeOptions;
use crate::schemes::pairs::lanes::pair_lanes;
use crate::schemes::pairs::PairGeometry;
#[cfg(test)]
use crate::simd::lanes::Emu;
use crate::simd::lanes::Lanes;
use crate::simd::ops::*;

/// Whether [`rates_row`] covers these options. Every option is named (no `..`): an option
/// added to the scheme is a compile error here until the lanes implement it or decline it.
#[inline(always)]
pub(crate) fn covers(o: &SchemeOptions) -> bool {
    let SchemeOptions {
        // read by av's pair loop, implemented (the viscosity; the artificial stress
        // through the pair geometry's factor and the tensors' records)
        av_alpha: _,
        av_beta: _,
        artificial_stress: _,
        artificial_stress_exponent: _,
        // read by av's other passes (the smoothing length update), not by the pairs
        constant_h: _,
        // the Godunov families'
        hourglass: _,
        // tl's, refused by the table
        reference_update: _,
        limiter: _,
        riemann: _,
        dissipation: _,
        transverse_dissipation: _,
        objective: _,
        corrected_slopes: _,
        integrator: _,
        muscl_time: _,
        surface_lambda: _,
        surface_scan: _,
        det_epsilon: _,
        specific_volume: _,
        energy_equation: _,
        correction: _,
        muscl: _,
    } = *o;
    true
}

/// The pair sums of particle `own` over its list `row` (entries from `lower` on are the
/// pairs it owns), from the neighbours' records `rec`, into `s`: bitwise the portable
/// loop of `av`'s `rates`.
///
/// # Safety
/// The CPU must have the level of `V` and `pg.kernel` must pass
/// [`crate::schemes::pairs::lanes::has_geometry`]. (The neighbour indices are checked against `rec`.)
#[inline(always)]
// the sums index each lane across the terms' arrays
#[allow(clippy::too_many_arguments, clippy::needless_range_loop)]
unsafe fn rates_row<V: Lanes, const D: usize, E: Effects, const WRAP: bool>(
    pg: &PairGeometry<D>,
    alpha: Real,
    beta: Real,
    rec: &[Real],
    row: &[u32],
    lower: usize,
    own: &Owner<D>,
    s: &mut Sums<D>,
) {
    let (at, width) = (RecordAt::of(D), record_len(D));
    let groups = width / 4;
    let zero = V::zero();
    let n = row.len();
    let mut q0 = 0;
    while q0 < n {
        // a last, partial group repeats its last neighbour in the spare lanes (not summed)
        let lanes = (n - q0).min(V::N);
        let j = V::arr(|l| row[q0 + l.min(lanes - 1)] as usize);
        // the neighbours' records, transposed into lanes (room for the widest, 3D)
        let f: [V; record_len(3)] = records::<V, { record_len(3) }>(rec, width, groups, &j);
        let xj: [V; 3] = core::array::from_fn(|a| f[at.x + a.min(D - 1)]);
        let geo = pair_lanes::<V, D, WRAP>(pg, &own.x, own.h, &xj, f[at.h]);
        // outside the support `seen_from_i` gives n = +0 on the owner's side, -0 on the
        // other
        let side = V::load(&V::arr(|l| if q0 + l >= lower { 0.0 } else { -0.0 }));
        let mut nv = [zero; 3];
        let mut grad = [zero; 3];
        let minus_dw = neg(geo.dw);
        let mut vij = [zero; 3];
        for a in 0..D {
            nv[a] = select(geo.inside, geo.n[a], side);
            grad[a] = mul(nv[a], minus_dw);
            vij[a] = sub(splat(own.v[a]), f[at.v + a]);
        }
        // (v_i - v_j).(x_i - x_j) = -r (v_ij . n); the viscosity where it is negative
        let r = geo.r;
        let vr = mul(neg(r), dot::<V, D>(&vij, &nv));
        let approaching = lt(vr, zero);
        // the two divisions only where some lane approaches
        let pi = if V::bits(approaching) == 0 {
            zero
        } else {
            let hij = geo.hij;
            let mu = div(
                mul(hij, vr),
                add(mul(r, r), mul(mul(splat(0.01), hij), hij)),
            );
            let cij = mul(splat(0.5), add(splat(own.cl), f[at.cl]));
            let pi = div(
                add(
                    mul(mul(splat(-alpha), cij), mu),
                    mul(mul(splat(beta), mu), mu),
                ),
                mul(splat(0.5), add(splat(own.rho), f[at.rho])),
            );
            select(approaching, pi, zero)
        };
        // t = (sig_i + sig_j) . grad / (rho_i rho_j) - Pi grad (+ the artificial stress)
        let k = mul(splat(own.inv_rho), f[at.inv_rho]);
        let mut t = [zero; 3];
        for a in 0..D {
            let mut sg = zero;
            for b in 0..D {
                let sab = add(splat(own.sig.get(a, b)), f[at.sig + sym_at(D, a, b)]);
                sg = add(sg, mul(sab, grad[b]));
            }
            t[a] = sub(mul(sg, k), mul(grad[a], pi));
        }
        if pg.art.is_some() {
            // ((R_i + R_j) grad) f, nalgebra's gemv: column by column
            for (a, ta) in t.iter_mut().enumerate().take(D) {
                let mut y = zero;
                for b in 0..D {
                    let m = add(splat(own.art[(a, b)]), f[at.art + a * D + b]);
                    y = if b == 0 {
                        mul(m, grad[0])
                    } else {
                        add(mul(m, grad[b]), y)
                    };
                }
                *ta = add(*ta, mul(y, geo.f));
            }
        }
        let mj = f[at.m];
        let vol = mul(mj, f[at.inv_rho]);
        let mut acc = [V::arr(|_| 0.0); 3];
        for (ca, ta) in acc.iter_mut().zip(&t).take(D) {
            *ca = store(mul(*ta, mj));
        }
        let de = store(mul(mul(splat(0.5), mj), dot::<V, D>(&vij, &t)));
        let dv = store(mul(vol, dot::<V, D>(&vij, &grad)));
        let mut gv = [[V::arr(|_| 0.0); 3]; 3];
        if E::STRENGTH {
            for (ga, va) in gv.iter_mut().zip(&vij).take(D) {
                for (gab, gb) in ga.iter_mut().zip(&grad).take(D) {
                    *gab = store(mul(mul(*va, *gb), vol));
                }
            }
        }
        for l in 0..lanes {
            for a in 0..D {
                s.acc[a] += acc[a][l];
            }
            s.de -= de[l];
            s.div -= dv[l];
            if E::STRENGTH {
                for a in 0..D {
                    for b in 0..D {
                        s.grad_v[(a, b)] -= gv[a][b][l];
                    }
                }
            }
        }
        q0 += lanes;
    }
}

/// [`rates_row`] in `V`'s lanes, with or without a periodic box as `pg` has one.
///
/// # Safety
/// As [`rates_row`].
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn rates_row_in<V: Lanes, const D: usize, E: Effects>(
    pg: &PairGeometry<D>,
    alpha: Real,
    beta: Real,
    rec: &[Real],
    row: &[u32],
    lower: usize,
    own: &Owner<D>,
    s: &mut Sums<D>,
) {
    if pg.periodic.is_some() {
        rates_row::<V, D, E, true>(pg, alpha, beta, rec, row, lower, own, s)
    } else {
        rates_row::<V, D, E, false>(pg, alpha, beta, rec, row, lower, own, s)
    }
}

/// [`rates_row`] in `W`'s lanes over the row's full groups of `W::N` neighbours and in
/// `N`'s over the rest (a last, partial group of the wide register costs as much as a full
/// one), the sums in the list's order: AVX-512's entry with `zmm` and `ymm` registers, and
/// the tests' eight emulated lanes with the same code.
///
/// # Safety
/// As [`rates_row`], with both levels.
#[inline(always)]
#[allow(clippy::too_many_arguments)]
unsafe fn rates_row_wide<W: Lanes, N: Lanes, const D: usize, E: Effects>(
    pg: &PairGeometry<D>,
    alpha: Real,
    beta: Real,
    rec: &[Real],
    row: &[u32],
    lower: usize,
    own: &Owner<D>,
    s: &mut Sums<D>,
) {
    let m = row.len() / W::N * W::N;
    let (wide, rest) = (&row[..m], &row[m..]);
    if m > 0 {
        rates_row_in::<W, D, E>(pg, alpha, beta, rec, wide, lower, own, s);
    }
    rates_row_in::<N, D, E>(pg, alpha, beta, rec, rest, lower.saturating_sub(m), own, s)
}

/// [`rates_row`] with four neighbours per AVX2 instruction.
///
/// # Safety
/// As [`rates_row`], with AVX2.
#[target_feature(enable = "avx2")]
#[allow(clippy::too_many_arguments)]
unsafe fn rates_row_avx2<const D: usize, E: Effects>(
    pg: &PairGeometry<D>,
    alpha: Real,
    beta: Real,
    rec: &[Real],
    row: &[u32],
    lower: usize,
    own: &Owner<D>,
    s: &mut Sums<D>,
) {
    rates_row_in::<__m256d, D, E>(pg, alpha, beta, rec, row, lower, own, s)
}

/// [`rates_row_wide`] with eight neighbours per AVX-512 instruction, the rest four per
/// AVX2 one.
///
/// # Safety
/// As [`rates_row`], with AVX-512F.
#[target_feature(enable = "avx512f")]
#[allow(clippy::too_many_arguments)]
unsafe fn rates_row_avx512<const D: usize, E: Effects>(
    pg: &PairGeometry<D>,
    alpha: Real,
    beta: Real,
    rec: &[Real],
    row: &[u32],
    lower: usize,
    own: &Owner<D>,
    s: &mut Sums<D>,
) {
    rates_row_wide::<__m512d, __m256d, D, E>(pg, alpha, beta, rec, row, lower, own, s)
}

/// [`rates_row`] at `level` (nothing at the baseline level).
///
/// # Safety
/// `level` must be one the CPU has (`SimdLevel::assume`) and `pg.kernel` must pass
/// [`crate::schemes::pairs::lanes::has_geometry`].
#[allow(clippy::too_many_arguments)]
pub(crate) unsafe fn rates_row_at<const D: usize, E: Effects>(
    level: crate::simd::SimdLevel,
    pg: &PairGeometry<D>,
    alpha: Real,
    beta: Real,
    rec: &[Real],
    row: &[u32],
    lower: usize,
    own: &Owner<D>,
    s: &mut Sums<D>,
) {
    use crate::simd::Simd;
    match level.get() {
        Simd::Avx512 => rates_row_avx512::<D, E>(pg, alpha, beta, rec, row, lower, own, s),
        Simd::Avx2 => rates_row_avx2::<D, E>(pg, alpha, beta, rec, row, lower, own, s),
        Simd::Baseline => {}
        #[cfg(test)]
        Simd::Emu4 => rates_row_in::<Emu<4>, D, E>(pg, alpha, beta, rec, row, lower, own, s),
        #[cfg(test)]
        Simd::Emu8 => {
            rates_row_wide::<Emu<8>, Emu<4>, D, E>(pg, alpha, beta, rec, row, lower, own, s)
        }
    }
}
