//! `av`'s pair loop, four neighbours per AVX2 instruction (module docs of [`super`]).
//!
//! Each neighbour's fields come from its compact record (`Workspace::rec`): four
//! records are loaded four reals at a time and transposed into lanes, so a neighbour
//! costs a few vector loads instead of a dozen scattered scalar ones. The lanes compute
//! each pair's terms with the portable loop's operations in its order; the particle's
//! sums then add them lane by lane in the order of its list, as the portable loop does.

use core::arch::x86_64::*;

use super::avx2::{add, dot, lt, mul, neg, pair_lanes, select, splat, store, sub, transpose};
use crate::effects::Effects;
use crate::kernel::Kernel;
use crate::math::Real;
use crate::schemes::av::pairs::{Owner, Sums};
use crate::schemes::av::records::{record_len, sym_at, RecordAt};

/// The pair sums of particle `own` over its list `row` (entries from `lower` on are the
/// pairs it owns), from the neighbours' records `rec`, into `s`: bitwise the portable
/// loop of `av`'s `rates`.
///
/// # Safety
/// The CPU must have AVX2, `kernel` must pass [`super::avx2::has_geometry`] and the run
/// must have no periodic images. (The neighbour indices are checked against `rec`.)
#[target_feature(enable = "avx2")]
// the sums index each lane across the terms' arrays
#[allow(clippy::too_many_arguments, clippy::needless_range_loop)]
pub(crate) unsafe fn rates_row<const D: usize, E: Effects>(
    kernel: Kernel,
    art: Option<(Real, u32)>,
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
    let zero = _mm256_setzero_pd();
    let n = row.len();
    let mut q0 = 0;
    while q0 < n {
        // a last, partial group repeats its last neighbour in the spare lanes (not summed)
        let lanes = (n - q0).min(4);
        let j: [usize; 4] = core::array::from_fn(|l| row[q0 + l.min(lanes - 1)] as usize);
        // the loads below read through raw pointers: every record checked
        assert!(j.iter().all(|&j| (j + 1) * width <= rec.len()));
        let p: [*const Real; 4] = core::array::from_fn(|l| rec.as_ptr().add(j[l] * width));
        // room for the widest record (3D)
        let mut f = [zero; record_len(3)];
        for g in 0..groups {
            f[4 * g..4 * g + 4].copy_from_slice(&transpose(&p, g));
        }
        let xj: [__m256d; 3] = core::array::from_fn(|a| f[at.x + a.min(D - 1)]);
        let geo = pair_lanes::<D>(kernel, &own.x, own.h, &xj, f[at.h], art);
        // outside the support `seen_from_i` gives n = +0 on the owner's side, -0 on the
        // other
        let side: [Real; 4] = core::array::from_fn(|l| if q0 + l >= lower { 0.0 } else { -0.0 });
        let side = _mm256_loadu_pd(side.as_ptr());
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
        let vr = mul(neg(r), dot::<D>(&vij, &nv));
        let approaching = lt(vr, zero);
        // the two divisions only where some lane approaches
        let pi = if _mm256_movemask_pd(approaching) == 0 {
            zero
        } else {
            let hij = geo.hij;
            let mu = _mm256_div_pd(
                mul(hij, vr),
                add(mul(r, r), mul(mul(splat(0.01), hij), hij)),
            );
            let cij = mul(splat(0.5), add(splat(own.cl), f[at.cl]));
            let pi = _mm256_div_pd(
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
        if art.is_some() {
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
        let mut acc = [[0.0; 4]; 3];
        for (ca, ta) in acc.iter_mut().zip(&t).take(D) {
            *ca = store(mul(*ta, mj));
        }
        let de = store(mul(mul(splat(0.5), mj), dot::<D>(&vij, &t)));
        let div = store(mul(vol, dot::<D>(&vij, &grad)));
        let mut gv = [[[0.0; 4]; 3]; 3];
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
            s.div -= div[l];
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
