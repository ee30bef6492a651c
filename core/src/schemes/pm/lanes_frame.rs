//! The lane arithmetic of the contact family's star states (`pm_star`): vectors and
//! matrices in lanes, the MUSCL reconstruction in the pair's frame and the vector elastic
//! Riemann problem, each the portable `pm::pairs` helper named in its documentation, lane
//! by lane with the same IEEE operations in the same order.

use core::arch::x86_64::{__m256d, __m512d};

use crate::simd::lanes::Lanes;
use crate::simd::ops::*;
use crate::simd::riemann::*;

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

/// The emulated lanes of the tests call the same code, compiled for no level.
#[cfg(test)]
impl<const N: usize> Calls for crate::simd::lanes::Emu<N> {
    unsafe fn frame<const D: usize>(
        superbee: bool,
        basis: &[Vl<Self>; 3],
        wi: &Vl<Self>,
        wj: &Vl<Self>,
        di: &Vl<Self>,
        dj: &Vl<Self>,
    ) -> (Vl<Self>, Vl<Self>) {
        muscl_frame::<Self, D>(superbee, basis, wi, wj, di, dj)
    }
    unsafe fn vector<const D: usize>(
        n: &Vl<Self>,
        v_l: &Vl<Self>,
        t_l: &Vl<Self>,
        zl: (Self, Self),
        v_r: &Vl<Self>,
        t_r: &Vl<Self>,
        zr: (Self, Self),
        shock: Option<(&Side<Self>, &Side<Self>)>,
    ) -> (Vl<Self>, Vl<Self>, Self::Mask) {
        star_vector::<Self, D>(n, v_l, t_l, zl.0, zl.1, v_r, t_r, zr.0, zr.1, shock)
    }
}
