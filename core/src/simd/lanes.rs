//! The lane types of the vectorised loops: four `f64` pairs per AVX2 register, eight per
//! AVX-512 register, behind one trait so that each loop is written once.
//!
//! Every method is one IEEE operation per lane, or a named portable helper's rule exactly,
//! and every method is `#[inline(always)]`: the loops are generic over [`Lanes`] and
//! `#[inline(always)]` as well, and each is entered through a function compiled for the
//! level (`#[target_feature(enable = "avx2")]` or `"avx512f"`), into which the whole loop,
//! these methods and the intrinsics they call are inlined. (A method left as a call would
//! pass its lanes through memory; `scripts/profile.sh` and `objdump` show none.)
//!
//! Masks are the level's own: all-ones lanes of a vector for AVX2, a `k` register for
//! AVX-512. A mask zeroes a value with [`Lanes::keep`], chooses with [`Lanes::select`].

use core::arch::x86_64::*;
use core::ops::{Index, IndexMut};

use crate::math::Real;

/// A register of `N` lanes of `f64` and the operations the pair loops perform on it.
///
/// # Safety
/// Every method needs the level's instructions (AVX2 for `__m256d`, AVX-512F for
/// `__m512d`): call them only from code entered through a function compiled for it.
pub(crate) trait Lanes: Copy {
    /// Lanes per register.
    const N: usize;
    /// Lanes chosen by a comparison.
    type Mask: Copy;
    /// One value per lane, in memory (`[T; N]`).
    type Arr<T: Copy>: Copy + Index<usize, Output = T> + IndexMut<usize> + AsRef<[T]>;

    /// `[f(0), …, f(N - 1)]`.
    fn arr<T: Copy>(f: impl FnMut(usize) -> T) -> Self::Arr<T>;

    unsafe fn zero() -> Self;
    unsafe fn splat(x: Real) -> Self;
    unsafe fn load(a: &Self::Arr<Real>) -> Self;
    unsafe fn store(a: Self) -> Self::Arr<Real>;
    /// Lane `l` from `base[j[l] * stride + offset]` (the indices checked by the caller).
    unsafe fn gather(base: *const Real, j: &Self::Arr<usize>, stride: usize, offset: usize)
        -> Self;
    /// Reals `4 g .. 4 g + 4` of the records `p[l]` points at (one per lane) as four
    /// registers, one per real.
    unsafe fn transpose(p: &Self::Arr<*const Real>, g: usize) -> [Self; 4];

    unsafe fn add(a: Self, b: Self) -> Self;
    unsafe fn sub(a: Self, b: Self) -> Self;
    unsafe fn mul(a: Self, b: Self) -> Self;
    unsafe fn div(a: Self, b: Self) -> Self;
    unsafe fn sqrt(a: Self) -> Self;
    /// `math::real::max`: `a` if `a > b`, else `b` (`maxpd`'s rule exactly).
    unsafe fn max(a: Self, b: Self) -> Self;
    /// `math::real::min`: `a` if `a < b`, else `b` (`minpd`'s rule exactly).
    unsafe fn min(a: Self, b: Self) -> Self;
    /// The sign bit flipped.
    unsafe fn neg(a: Self) -> Self;
    /// The sign bit cleared.
    unsafe fn magnitude(a: Self) -> Self;
    /// `m` with the sign bit of `s` (`copysign`).
    unsafe fn copysign(m: Self, s: Self) -> Self;

    /// Ordered comparisons (false where either side is NaN).
    unsafe fn lt(a: Self, b: Self) -> Self::Mask;
    unsafe fn le(a: Self, b: Self) -> Self::Mask;
    unsafe fn gt(a: Self, b: Self) -> Self::Mask;
    unsafe fn ge(a: Self, b: Self) -> Self::Mask;
    unsafe fn and(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    unsafe fn or(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    unsafe fn not(a: Self::Mask) -> Self::Mask;
    /// `!a & b`.
    unsafe fn and_not(a: Self::Mask, b: Self::Mask) -> Self::Mask;
    /// No lane set.
    unsafe fn none() -> Self::Mask;
    /// Whether lane `l` is set, for each lane: bit `l`.
    unsafe fn bits(m: Self::Mask) -> u32;
    /// `a` where `m` is set, else `b`.
    unsafe fn select(m: Self::Mask, a: Self, b: Self) -> Self;
    /// `a` where `m` is set, else `+0`.
    unsafe fn keep(m: Self::Mask, a: Self) -> Self;
}

impl Lanes for __m256d {
    const N: usize = 4;
    type Mask = __m256d;
    type Arr<T: Copy> = [T; 4];

    #[inline(always)]
    fn arr<T: Copy>(f: impl FnMut(usize) -> T) -> [T; 4] {
        core::array::from_fn(f)
    }
    #[inline(always)]
    unsafe fn zero() -> Self {
        _mm256_setzero_pd()
    }
    #[inline(always)]
    unsafe fn splat(x: Real) -> Self {
        _mm256_set1_pd(x)
    }
    #[inline(always)]
    unsafe fn load(a: &[Real; 4]) -> Self {
        _mm256_loadu_pd(a.as_ptr())
    }
    #[inline(always)]
    unsafe fn store(a: Self) -> [Real; 4] {
        let mut out = [0.0; 4];
        _mm256_storeu_pd(out.as_mut_ptr(), a);
        out
    }
    #[inline(always)]
    unsafe fn gather(base: *const Real, j: &[usize; 4], stride: usize, offset: usize) -> Self {
        let jv = _mm256_set_epi64x(j[3] as i64, j[2] as i64, j[1] as i64, j[0] as i64);
        let idx = _mm256_add_epi64(
            _mm256_mul_epu32(jv, _mm256_set1_epi64x(stride as i64)),
            _mm256_set1_epi64x(offset as i64),
        );
        _mm256_i64gather_pd::<8>(base, idx)
    }
    #[inline(always)]
    unsafe fn transpose(p: &[*const Real; 4], g: usize) -> [Self; 4] {
        transpose4(p[0], p[1], p[2], p[3], g)
    }
    #[inline(always)]
    unsafe fn add(a: Self, b: Self) -> Self {
        _mm256_add_pd(a, b)
    }
    #[inline(always)]
    unsafe fn sub(a: Self, b: Self) -> Self {
        _mm256_sub_pd(a, b)
    }
    #[inline(always)]
    unsafe fn mul(a: Self, b: Self) -> Self {
        _mm256_mul_pd(a, b)
    }
    #[inline(always)]
    unsafe fn div(a: Self, b: Self) -> Self {
        _mm256_div_pd(a, b)
    }
    #[inline(always)]
    unsafe fn sqrt(a: Self) -> Self {
        _mm256_sqrt_pd(a)
    }
    #[inline(always)]
    unsafe fn max(a: Self, b: Self) -> Self {
        _mm256_max_pd(a, b)
    }
    #[inline(always)]
    unsafe fn min(a: Self, b: Self) -> Self {
        _mm256_min_pd(a, b)
    }
    #[inline(always)]
    unsafe fn neg(a: Self) -> Self {
        _mm256_xor_pd(a, _mm256_set1_pd(-0.0))
    }
    #[inline(always)]
    unsafe fn magnitude(a: Self) -> Self {
        _mm256_andnot_pd(_mm256_set1_pd(-0.0), a)
    }
    #[inline(always)]
    unsafe fn copysign(m: Self, s: Self) -> Self {
        let sign = _mm256_set1_pd(-0.0);
        _mm256_or_pd(_mm256_andnot_pd(sign, m), _mm256_and_pd(sign, s))
    }
    #[inline(always)]
    unsafe fn lt(a: Self, b: Self) -> Self {
        _mm256_cmp_pd::<_CMP_LT_OQ>(a, b)
    }
    #[inline(always)]
    unsafe fn le(a: Self, b: Self) -> Self {
        _mm256_cmp_pd::<_CMP_LE_OQ>(a, b)
    }
    #[inline(always)]
    unsafe fn gt(a: Self, b: Self) -> Self {
        _mm256_cmp_pd::<_CMP_GT_OQ>(a, b)
    }
    #[inline(always)]
    unsafe fn ge(a: Self, b: Self) -> Self {
        _mm256_cmp_pd::<_CMP_GE_OQ>(a, b)
    }
    #[inline(always)]
    unsafe fn and(a: Self, b: Self) -> Self {
        _mm256_and_pd(a, b)
    }
    #[inline(always)]
    unsafe fn or(a: Self, b: Self) -> Self {
        _mm256_or_pd(a, b)
    }
    #[inline(always)]
    unsafe fn not(a: Self) -> Self {
        _mm256_xor_pd(a, _mm256_castsi256_pd(_mm256_set1_epi64x(-1)))
    }
    #[inline(always)]
    unsafe fn and_not(a: Self, b: Self) -> Self {
        _mm256_andnot_pd(a, b)
    }
    #[inline(always)]
    unsafe fn none() -> Self {
        _mm256_setzero_pd()
    }
    #[inline(always)]
    unsafe fn bits(m: Self) -> u32 {
        _mm256_movemask_pd(m) as u32
    }
    #[inline(always)]
    unsafe fn select(m: Self, a: Self, b: Self) -> Self {
        _mm256_blendv_pd(b, a, m)
    }
    #[inline(always)]
    unsafe fn keep(m: Self, a: Self) -> Self {
        _mm256_and_pd(m, a)
    }
}

/// Four records' reals `4 g .. 4 g + 4` as four registers, one per real.
#[inline(always)]
unsafe fn transpose4(
    p0: *const Real,
    p1: *const Real,
    p2: *const Real,
    p3: *const Real,
    g: usize,
) -> [__m256d; 4] {
    let (a, b, c, d) = (
        _mm256_loadu_pd(p0.add(4 * g)),
        _mm256_loadu_pd(p1.add(4 * g)),
        _mm256_loadu_pd(p2.add(4 * g)),
        _mm256_loadu_pd(p3.add(4 * g)),
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

#[inline(always)]
unsafe fn bits512(a: __m512d) -> __m512i {
    _mm512_castpd_si512(a)
}

impl Lanes for __m512d {
    const N: usize = 8;
    type Mask = __mmask8;
    type Arr<T: Copy> = [T; 8];

    #[inline(always)]
    fn arr<T: Copy>(f: impl FnMut(usize) -> T) -> [T; 8] {
        core::array::from_fn(f)
    }
    #[inline(always)]
    unsafe fn zero() -> Self {
        _mm512_setzero_pd()
    }
    #[inline(always)]
    unsafe fn splat(x: Real) -> Self {
        _mm512_set1_pd(x)
    }
    #[inline(always)]
    unsafe fn load(a: &[Real; 8]) -> Self {
        _mm512_loadu_pd(a.as_ptr())
    }
    #[inline(always)]
    unsafe fn store(a: Self) -> [Real; 8] {
        let mut out = [0.0; 8];
        _mm512_storeu_pd(out.as_mut_ptr(), a);
        out
    }
    #[inline(always)]
    unsafe fn gather(base: *const Real, j: &[usize; 8], stride: usize, offset: usize) -> Self {
        let jv = _mm512_set_epi64(
            j[7] as i64,
            j[6] as i64,
            j[5] as i64,
            j[4] as i64,
            j[3] as i64,
            j[2] as i64,
            j[1] as i64,
            j[0] as i64,
        );
        let idx = _mm512_add_epi64(
            _mm512_mul_epu32(jv, _mm512_set1_epi64(stride as i64)),
            _mm512_set1_epi64(offset as i64),
        );
        _mm512_i64gather_pd::<8>(idx, base)
    }
    #[inline(always)]
    unsafe fn transpose(p: &[*const Real; 8], g: usize) -> [Self; 4] {
        let lo = transpose4(p[0], p[1], p[2], p[3], g);
        let hi = transpose4(p[4], p[5], p[6], p[7], g);
        core::array::from_fn(|k| _mm512_insertf64x4::<1>(_mm512_castpd256_pd512(lo[k]), hi[k]))
    }
    #[inline(always)]
    unsafe fn add(a: Self, b: Self) -> Self {
        _mm512_add_pd(a, b)
    }
    #[inline(always)]
    unsafe fn sub(a: Self, b: Self) -> Self {
        _mm512_sub_pd(a, b)
    }
    #[inline(always)]
    unsafe fn mul(a: Self, b: Self) -> Self {
        _mm512_mul_pd(a, b)
    }
    #[inline(always)]
    unsafe fn div(a: Self, b: Self) -> Self {
        _mm512_div_pd(a, b)
    }
    #[inline(always)]
    unsafe fn sqrt(a: Self) -> Self {
        _mm512_sqrt_pd(a)
    }
    #[inline(always)]
    unsafe fn max(a: Self, b: Self) -> Self {
        _mm512_max_pd(a, b)
    }
    #[inline(always)]
    unsafe fn min(a: Self, b: Self) -> Self {
        _mm512_min_pd(a, b)
    }
    #[inline(always)]
    unsafe fn neg(a: Self) -> Self {
        _mm512_castsi512_pd(_mm512_xor_si512(bits512(a), bits512(_mm512_set1_pd(-0.0))))
    }
    #[inline(always)]
    unsafe fn magnitude(a: Self) -> Self {
        _mm512_castsi512_pd(_mm512_andnot_si512(
            bits512(_mm512_set1_pd(-0.0)),
            bits512(a),
        ))
    }
    #[inline(always)]
    unsafe fn copysign(m: Self, s: Self) -> Self {
        let sign = bits512(_mm512_set1_pd(-0.0));
        _mm512_castsi512_pd(_mm512_or_si512(
            _mm512_andnot_si512(sign, bits512(m)),
            _mm512_and_si512(sign, bits512(s)),
        ))
    }
    #[inline(always)]
    unsafe fn lt(a: Self, b: Self) -> __mmask8 {
        _mm512_cmp_pd_mask::<_CMP_LT_OQ>(a, b)
    }
    #[inline(always)]
    unsafe fn le(a: Self, b: Self) -> __mmask8 {
        _mm512_cmp_pd_mask::<_CMP_LE_OQ>(a, b)
    }
    #[inline(always)]
    unsafe fn gt(a: Self, b: Self) -> __mmask8 {
        _mm512_cmp_pd_mask::<_CMP_GT_OQ>(a, b)
    }
    #[inline(always)]
    unsafe fn ge(a: Self, b: Self) -> __mmask8 {
        _mm512_cmp_pd_mask::<_CMP_GE_OQ>(a, b)
    }
    #[inline(always)]
    unsafe fn and(a: __mmask8, b: __mmask8) -> __mmask8 {
        a & b
    }
    #[inline(always)]
    unsafe fn or(a: __mmask8, b: __mmask8) -> __mmask8 {
        a | b
    }
    #[inline(always)]
    unsafe fn not(a: __mmask8) -> __mmask8 {
        !a
    }
    #[inline(always)]
    unsafe fn and_not(a: __mmask8, b: __mmask8) -> __mmask8 {
        !a & b
    }
    #[inline(always)]
    unsafe fn none() -> __mmask8 {
        0
    }
    #[inline(always)]
    unsafe fn bits(m: __mmask8) -> u32 {
        m as u32
    }
    #[inline(always)]
    unsafe fn select(m: __mmask8, a: Self, b: Self) -> Self {
        _mm512_mask_blend_pd(m, b, a)
    }
    #[inline(always)]
    unsafe fn keep(m: __mmask8, a: Self) -> Self {
        _mm512_maskz_mov_pd(m, a)
    }
}

/// Emulated lanes (the core's unit tests only): `N` lanes of `f64` in a plain array, each
/// operation the instruction's rule written out lane by lane (`maxpd`'s `a > b ? a : b`,
/// the sign bit for `neg`, `magnitude` and `copysign`, ordered comparisons, the correctly
/// rounded square root). The rows run on them through the same generic code as on the
/// registers, so that a CPU without AVX-512 still tests the eight-lane rows
/// ([`super::Simd::Emu8`], [`super::Simd::Emu4`]). Each operation is a call
/// (`#[inline(never)]`): inlined, the rows instantiated on these lanes took the core's test
/// build from 31 to 81 s; as calls, 50 s (release, this 2-core VM).
#[cfg(test)]
#[derive(Clone, Copy, Debug)]
pub(crate) struct Emu<const N: usize>(pub [Real; N]);

#[cfg(test)]
impl<const N: usize> Emu<N> {
    #[inline(always)]
    fn map(a: Self, f: impl Fn(Real) -> Real) -> Self {
        Emu(core::array::from_fn(|l| f(a.0[l])))
    }
    #[inline(always)]
    fn zip(a: Self, b: Self, f: impl Fn(Real, Real) -> Real) -> Self {
        Emu(core::array::from_fn(|l| f(a.0[l], b.0[l])))
    }
    #[inline(always)]
    fn cmp(a: Self, b: Self, f: impl Fn(Real, Real) -> bool) -> [bool; N] {
        core::array::from_fn(|l| f(a.0[l], b.0[l]))
    }
}

#[cfg(test)]
const SIGN: u64 = 1 << 63;

#[cfg(test)]
impl<const N: usize> Lanes for Emu<N> {
    const N: usize = N;
    type Mask = [bool; N];
    type Arr<T: Copy> = [T; N];

    #[inline(never)]
    fn arr<T: Copy>(f: impl FnMut(usize) -> T) -> [T; N] {
        core::array::from_fn(f)
    }
    #[inline(never)]
    unsafe fn zero() -> Self {
        Emu([0.0; N])
    }
    #[inline(never)]
    unsafe fn splat(x: Real) -> Self {
        Emu([x; N])
    }
    #[inline(never)]
    unsafe fn load(a: &[Real; N]) -> Self {
        Emu(*a)
    }
    #[inline(never)]
    unsafe fn store(a: Self) -> [Real; N] {
        a.0
    }
    #[inline(never)]
    unsafe fn gather(base: *const Real, j: &[usize; N], stride: usize, offset: usize) -> Self {
        Emu(core::array::from_fn(|l| *base.add(j[l] * stride + offset)))
    }
    #[inline(never)]
    unsafe fn transpose(p: &[*const Real; N], g: usize) -> [Self; 4] {
        core::array::from_fn(|k| Emu(core::array::from_fn(|l| *p[l].add(4 * g + k))))
    }
    #[inline(never)]
    unsafe fn add(a: Self, b: Self) -> Self {
        Self::zip(a, b, |x, y| x + y)
    }
    #[inline(never)]
    unsafe fn sub(a: Self, b: Self) -> Self {
        Self::zip(a, b, |x, y| x - y)
    }
    #[inline(never)]
    unsafe fn mul(a: Self, b: Self) -> Self {
        Self::zip(a, b, |x, y| x * y)
    }
    #[inline(never)]
    unsafe fn div(a: Self, b: Self) -> Self {
        Self::zip(a, b, |x, y| x / y)
    }
    #[inline(never)]
    unsafe fn sqrt(a: Self) -> Self {
        Self::map(a, crate::math::real::sqrt)
    }
    #[inline(never)]
    unsafe fn max(a: Self, b: Self) -> Self {
        Self::zip(a, b, |x, y| if x > y { x } else { y })
    }
    #[inline(never)]
    unsafe fn min(a: Self, b: Self) -> Self {
        Self::zip(a, b, |x, y| if x < y { x } else { y })
    }
    #[inline(never)]
    unsafe fn neg(a: Self) -> Self {
        Self::map(a, |x| Real::from_bits(x.to_bits() ^ SIGN))
    }
    #[inline(never)]
    unsafe fn magnitude(a: Self) -> Self {
        Self::map(a, |x| Real::from_bits(x.to_bits() & !SIGN))
    }
    #[inline(never)]
    unsafe fn copysign(m: Self, s: Self) -> Self {
        Self::zip(m, s, |x, y| {
            Real::from_bits((x.to_bits() & !SIGN) | (y.to_bits() & SIGN))
        })
    }
    #[inline(never)]
    unsafe fn lt(a: Self, b: Self) -> [bool; N] {
        Self::cmp(a, b, |x, y| x < y)
    }
    #[inline(never)]
    unsafe fn le(a: Self, b: Self) -> [bool; N] {
        Self::cmp(a, b, |x, y| x <= y)
    }
    #[inline(never)]
    unsafe fn gt(a: Self, b: Self) -> [bool; N] {
        Self::cmp(a, b, |x, y| x > y)
    }
    #[inline(never)]
    unsafe fn ge(a: Self, b: Self) -> [bool; N] {
        Self::cmp(a, b, |x, y| x >= y)
    }
    #[inline(never)]
    unsafe fn and(a: [bool; N], b: [bool; N]) -> [bool; N] {
        core::array::from_fn(|l| a[l] && b[l])
    }
    #[inline(never)]
    unsafe fn or(a: [bool; N], b: [bool; N]) -> [bool; N] {
        core::array::from_fn(|l| a[l] || b[l])
    }
    #[inline(never)]
    unsafe fn not(a: [bool; N]) -> [bool; N] {
        core::array::from_fn(|l| !a[l])
    }
    #[inline(never)]
    unsafe fn and_not(a: [bool; N], b: [bool; N]) -> [bool; N] {
        core::array::from_fn(|l| !a[l] && b[l])
    }
    #[inline(never)]
    unsafe fn none() -> [bool; N] {
        [false; N]
    }
    #[inline(never)]
    unsafe fn bits(m: [bool; N]) -> u32 {
        (0..N).filter(|&l| m[l]).map(|l| 1u32 << l).sum()
    }
    #[inline(never)]
    unsafe fn select(m: [bool; N], a: Self, b: Self) -> Self {
        Emu(core::array::from_fn(|l| if m[l] { a.0[l] } else { b.0[l] }))
    }
    #[inline(never)]
    unsafe fn keep(m: [bool; N], a: Self) -> Self {
        Emu(core::array::from_fn(|l| if m[l] { a.0[l] } else { 0.0 }))
    }
}
