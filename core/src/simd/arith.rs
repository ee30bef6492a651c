//! The arithmetic of a formula written once for the portable loops and the lanes
//! ([`Arith`]): one lane (`Real`: the portable path, any target, f32 included) or a
//! register of lanes (`super::lanes::Lanes`, x86-64). The acoustic Riemann solve is
//! written this way (`crate::riemann::acoustic::acoustic_in`): the portable
//! `acoustic_star` and the star rows' lanes run the same function (issue 44, "the rapier
//! route"; docs/performance.md says what it cost).

use crate::math::Real;

/// The operations [`crate::riemann::acoustic::acoustic_in`] needs, each one IEEE
/// operation per lane (the lanes' rule exactly: `select` chooses, `finite` is false for
/// infinities and NaN).
///
/// # Safety
/// A register type's methods need its level's instructions (`super::lanes::Lanes`);
/// `Real`'s need nothing.
pub(crate) trait Arith: Copy {
    /// Lanes chosen by a comparison (`bool` for one lane).
    type Mask: Copy;
    unsafe fn zero() -> Self;
    unsafe fn splat(x: Real) -> Self;
    unsafe fn add(a: Self, b: Self) -> Self;
    unsafe fn sub(a: Self, b: Self) -> Self;
    unsafe fn mul(a: Self, b: Self) -> Self;
    unsafe fn div(a: Self, b: Self) -> Self;
    unsafe fn gt(a: Self, b: Self) -> Self::Mask;
    unsafe fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// Lanes whose value is finite.
    unsafe fn finite(a: Self) -> Self::Mask;
    /// `a` where `m` is set, else `b`.
    unsafe fn select(m: Self::Mask, a: Self, b: Self) -> Self;
}

impl Arith for Real {
    type Mask = bool;
    #[inline(always)]
    unsafe fn zero() -> Self {
        0.0
    }
    #[inline(always)]
    unsafe fn splat(x: Real) -> Self {
        x
    }
    #[inline(always)]
    unsafe fn add(a: Self, b: Self) -> Self {
        a + b
    }
    #[inline(always)]
    unsafe fn sub(a: Self, b: Self) -> Self {
        a - b
    }
    #[inline(always)]
    unsafe fn mul(a: Self, b: Self) -> Self {
        a * b
    }
    #[inline(always)]
    unsafe fn div(a: Self, b: Self) -> Self {
        a / b
    }
    #[inline(always)]
    unsafe fn gt(a: Self, b: Self) -> bool {
        a > b
    }
    #[inline(always)]
    unsafe fn and(a: bool, b: bool) -> bool {
        a && b
    }
    #[inline(always)]
    unsafe fn finite(a: Self) -> bool {
        a.is_finite()
    }
    #[inline(always)]
    unsafe fn select(m: bool, a: Self, b: Self) -> Self {
        if m {
            a
        } else {
            b
        }
    }
}

#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
impl<V: super::lanes::Lanes> Arith for V {
    type Mask = V::Mask;
    #[inline(always)]
    unsafe fn zero() -> Self {
        V::zero()
    }
    #[inline(always)]
    unsafe fn splat(x: Real) -> Self {
        V::splat(x)
    }
    #[inline(always)]
    unsafe fn add(a: Self, b: Self) -> Self {
        V::add(a, b)
    }
    #[inline(always)]
    unsafe fn sub(a: Self, b: Self) -> Self {
        V::sub(a, b)
    }
    #[inline(always)]
    unsafe fn mul(a: Self, b: Self) -> Self {
        V::mul(a, b)
    }
    #[inline(always)]
    unsafe fn div(a: Self, b: Self) -> Self {
        V::div(a, b)
    }
    #[inline(always)]
    unsafe fn gt(a: Self, b: Self) -> V::Mask {
        V::gt(a, b)
    }
    #[inline(always)]
    unsafe fn and(a: V::Mask, b: V::Mask) -> V::Mask {
        V::and(a, b)
    }
    #[inline(always)]
    unsafe fn finite(a: Self) -> V::Mask {
        super::ops::finite(a)
    }
    #[inline(always)]
    unsafe fn select(m: V::Mask, a: Self, b: Self) -> Self {
        V::select(m, a, b)
    }
}
