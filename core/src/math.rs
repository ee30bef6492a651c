//! Everything that depends on precision or dimension: the float type [`Real`], small
//! fixed-size vectors and matrices, the symmetric 3x3 tensor [`Sym3`] used for stresses,
//! and the scalar functions (`sqrt`, `exp`, `ln`, ...) that `no_std` code must take from
//! `libm` (or `micromath` with the `fast-math` feature).
//!
//! Conventions (DESIGN §2): SI units; Cauchy stress `sigma = S - P I`, tension positive,
//! pressure positive in compression. 1D is uniaxial strain, 2D plane strain, 3D full. The
//! deviator is always the full symmetric 3x3 tensor, so the out-of-plane components are
//! carried in 1D and 2D as well.

use core::ops::{Add, AddAssign, Mul, Neg, Sub, SubAssign};

/// The float type of all physics: `f64` by default, `f32` with the `f32` feature.
#[cfg(not(feature = "f32"))]
pub type Real = f64;
/// The float type of all physics: `f64` by default, `f32` with the `f32` feature.
#[cfg(feature = "f32")]
pub type Real = f32;

/// A vector of the simulation's dimension `D` (1, 2 or 3).
pub type Vector<const D: usize> = nalgebra::SVector<Real, D>;
/// A `D x D` matrix.
pub type Matrix<const D: usize> = nalgebra::SMatrix<Real, D, D>;

/// pi in the working precision.
#[cfg(not(feature = "f32"))]
pub const PI: Real = core::f64::consts::PI;
/// pi in the working precision.
#[cfg(feature = "f32")]
pub const PI: Real = core::f32::consts::PI;

/// A small deterministic generator for the tests (no crate needed): a 64-bit linear
/// congruential generator, the top 53 bits as the fraction.
#[cfg(test)]
pub(crate) struct Lcg(pub u64);

#[cfg(test)]
impl Lcg {
    /// Uniform in [0, 1).
    pub fn unit(&mut self) -> Real {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as Real / (1u64 << 53) as Real
    }
    /// Uniform in [-1, 1).
    pub fn next(&mut self) -> Real {
        self.unit() * 2.0 - 1.0
    }
}

/// Scalar maths for `no_std`: thin wrappers over `libm` (or `micromath`).
#[allow(missing_docs)]
pub mod real {
    use super::Real;

    #[cfg(not(feature = "f32"))]
    mod imp {
        use super::Real;
        #[inline(always)]
        pub fn sqrt(x: Real) -> Real {
            libm::sqrt(x)
        }
        #[inline(always)]
        pub fn exp(x: Real) -> Real {
            libm::exp(x)
        }
        #[inline(always)]
        pub fn ln(x: Real) -> Real {
            libm::log(x)
        }
        #[inline(always)]
        pub fn expm1(x: Real) -> Real {
            libm::expm1(x)
        }
        #[inline(always)]
        pub fn powf(x: Real, y: Real) -> Real {
            libm::pow(x, y)
        }
        #[inline(always)]
        pub fn erf(x: Real) -> Real {
            libm::erf(x)
        }
        #[inline(always)]
        pub fn cbrt(x: Real) -> Real {
            libm::cbrt(x)
        }
        #[inline(always)]
        pub fn sin(x: Real) -> Real {
            libm::sin(x)
        }
        #[inline(always)]
        pub fn cos(x: Real) -> Real {
            libm::cos(x)
        }
        #[inline(always)]
        pub fn atan2(y: Real, x: Real) -> Real {
            libm::atan2(y, x)
        }
    }

    #[cfg(all(feature = "f32", not(feature = "fast-math")))]
    mod imp {
        use super::Real;
        #[inline(always)]
        pub fn sqrt(x: Real) -> Real {
            libm::sqrtf(x)
        }
        #[inline(always)]
        pub fn exp(x: Real) -> Real {
            libm::expf(x)
        }
        #[inline(always)]
        pub fn ln(x: Real) -> Real {
            libm::logf(x)
        }
        #[inline(always)]
        pub fn expm1(x: Real) -> Real {
            libm::expm1f(x)
        }
        #[inline(always)]
        pub fn powf(x: Real, y: Real) -> Real {
            libm::powf(x, y)
        }
        #[inline(always)]
        pub fn erf(x: Real) -> Real {
            libm::erff(x)
        }
        #[inline(always)]
        pub fn cbrt(x: Real) -> Real {
            libm::cbrtf(x)
        }
        #[inline(always)]
        pub fn sin(x: Real) -> Real {
            libm::sinf(x)
        }
        #[inline(always)]
        pub fn cos(x: Real) -> Real {
            libm::cosf(x)
        }
        #[inline(always)]
        pub fn atan2(y: Real, x: Real) -> Real {
            libm::atan2f(y, x)
        }
    }

    #[cfg(feature = "fast-math")]
    mod imp {
        use super::Real;
        use micromath::F32Ext;
        #[inline(always)]
        pub fn sqrt(x: Real) -> Real {
            F32Ext::sqrt(x)
        }
        #[inline(always)]
        pub fn exp(x: Real) -> Real {
            F32Ext::exp(x)
        }
        #[inline(always)]
        pub fn ln(x: Real) -> Real {
            F32Ext::ln(x)
        }
        #[inline(always)]
        pub fn expm1(x: Real) -> Real {
            libm::expm1f(x)
        }
        #[inline(always)]
        pub fn powf(x: Real, y: Real) -> Real {
            F32Ext::powf(x, y)
        }
        #[inline(always)]
        pub fn erf(x: Real) -> Real {
            libm::erff(x)
        }
        #[inline(always)]
        pub fn cbrt(x: Real) -> Real {
            F32Ext::cbrt(x)
        }
        #[inline(always)]
        pub fn sin(x: Real) -> Real {
            F32Ext::sin(x)
        }
        #[inline(always)]
        pub fn cos(x: Real) -> Real {
            F32Ext::cos(x)
        }
        #[inline(always)]
        pub fn atan2(y: Real, x: Real) -> Real {
            F32Ext::atan2(y, x)
        }
    }

    pub use imp::*;

    #[inline(always)]
    pub fn abs(x: Real) -> Real {
        if x < 0.0 {
            -x
        } else {
            x
        }
    }
    #[inline(always)]
    pub fn max(a: Real, b: Real) -> Real {
        if a > b {
            a
        } else {
            b
        }
    }
    #[inline(always)]
    pub fn min(a: Real, b: Real) -> Real {
        if a < b {
            a
        } else {
            b
        }
    }
    #[inline(always)]
    pub fn signum(x: Real) -> Real {
        if x > 0.0 {
            1.0
        } else if x < 0.0 {
            -1.0
        } else {
            0.0
        }
    }
    /// `x^n` for a small integer power, by repeated squaring (`x^4 = (x²)²`: two
    /// multiplications, whatever the exponent's value at run time).
    #[inline(always)]
    pub fn powi(x: Real, n: u32) -> Real {
        let (mut r, mut b, mut k) = (1.0, x, n);
        while k > 0 {
            if k & 1 == 1 {
                r *= b;
            }
            b *= b;
            k >>= 1;
        }
        r
    }
}

/// A symmetric 3x3 tensor in Voigt order (xx, yy, zz, xy, xz, yz), used for the stress
/// deviator and for strain rates. Always full 3x3, whatever the dimension of the run.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Sym3 {
    /// xx component
    pub xx: Real,
    /// yy component
    pub yy: Real,
    /// zz component
    pub zz: Real,
    /// xy component
    pub xy: Real,
    /// xz component
    pub xz: Real,
    /// yz component
    pub yz: Real,
}

impl Sym3 {
    /// The zero tensor.
    pub const ZERO: Sym3 = Sym3 {
        xx: 0.0,
        yy: 0.0,
        zz: 0.0,
        xy: 0.0,
        xz: 0.0,
        yz: 0.0,
    };

    /// Builds a tensor from its six Voigt components.
    #[inline]
    pub const fn new(xx: Real, yy: Real, zz: Real, xy: Real, xz: Real, yz: Real) -> Self {
        Sym3 {
            xx,
            yy,
            zz,
            xy,
            xz,
            yz,
        }
    }

    /// `s * I`.
    #[inline]
    pub const fn isotropic(s: Real) -> Self {
        Sym3 {
            xx: s,
            yy: s,
            zz: s,
            xy: 0.0,
            xz: 0.0,
            yz: 0.0,
        }
    }

    /// The index of component `(a, b)` (indices 0..3) in the Voigt order of
    /// [`Sym3::to_array`] (`xx yy zz xy xz yz`).
    pub const fn voigt(a: usize, b: usize) -> usize {
        match (a, b) {
            (0, 0) => 0,
            (1, 1) => 1,
            (2, 2) => 2,
            (0, 1) | (1, 0) => 3,
            (0, 2) | (2, 0) => 4,
            _ => 5,
        }
    }

    /// Component `(a, b)`, indices 0..3.
    #[inline]
    pub fn get(&self, a: usize, b: usize) -> Real {
        match (a, b) {
            (0, 0) => self.xx,
            (1, 1) => self.yy,
            (2, 2) => self.zz,
            (0, 1) | (1, 0) => self.xy,
            (0, 2) | (2, 0) => self.xz,
            _ => self.yz,
        }
    }

    /// The six components as an array in Voigt order.
    #[inline]
    pub const fn to_array(&self) -> [Real; 6] {
        [self.xx, self.yy, self.zz, self.xy, self.xz, self.yz]
    }

    /// From six components in Voigt order.
    #[inline]
    pub const fn from_array(a: [Real; 6]) -> Self {
        Sym3 {
            xx: a[0],
            yy: a[1],
            zz: a[2],
            xy: a[3],
            xz: a[4],
            yz: a[5],
        }
    }

    /// Trace.
    #[inline]
    pub fn trace(&self) -> Real {
        self.xx + self.yy + self.zz
    }

    /// Deviatoric part `A - tr(A)/3 I`.
    #[inline]
    pub fn deviator(&self) -> Self {
        let m = self.trace() / 3.0;
        Sym3 {
            xx: self.xx - m,
            yy: self.yy - m,
            zz: self.zz - m,
            ..*self
        }
    }

    /// Double contraction `A : B`.
    #[inline]
    pub fn ddot(&self, o: &Sym3) -> Real {
        self.xx * o.xx
            + self.yy * o.yy
            + self.zz * o.zz
            + 2.0 * (self.xy * o.xy + self.xz * o.xz + self.yz * o.yz)
    }

    /// Von Mises equivalent of a deviator `S`: `sqrt(3/2 S:S)`.
    #[inline]
    pub fn von_mises(&self) -> Real {
        real::sqrt(1.5 * self.ddot(self))
    }

    /// The symmetric part of a `D x D` matrix, embedded in 3x3 (missing rows/columns zero).
    #[inline]
    pub fn sym_of<const D: usize>(m: &Matrix<D>) -> Self {
        let g = |a: usize, b: usize| {
            if a < D && b < D {
                0.5 * (m[(a, b)] + m[(b, a)])
            } else {
                0.0
            }
        };
        Sym3 {
            xx: g(0, 0),
            yy: g(1, 1),
            zz: g(2, 2),
            xy: g(0, 1),
            xz: g(0, 2),
            yz: g(1, 2),
        }
    }

    /// The in-plane block as a `D x D` matrix.
    #[inline]
    pub fn block<const D: usize>(&self) -> Matrix<D> {
        Matrix::<D>::from_fn(|a, b| self.get(a, b))
    }

    /// `A . n` for a vector of the run's dimension: the traction on a plane with normal
    /// `n` (only the in-plane components, which are the ones that act on particles).
    #[inline]
    pub fn dot_vec<const D: usize>(&self, n: &Vector<D>) -> Vector<D> {
        Vector::<D>::from_fn(|a, _| {
            let mut s = 0.0;
            for b in 0..D {
                s += self.get(a, b) * n[b];
            }
            s
        })
    }

    /// `n . A . n`.
    #[inline]
    pub fn normal<const D: usize>(&self, n: &Vector<D>) -> Real {
        self.dot_vec(n).dot(n)
    }

    /// Largest absolute component (for finiteness and size checks).
    #[inline]
    pub fn max_abs(&self) -> Real {
        let mut m: Real = 0.0;
        for c in self.to_array() {
            m = real::max(m, real::abs(c));
        }
        m
    }

    /// True if every component is finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        self.to_array().iter().all(|c| c.is_finite())
    }

    /// Jaumann co-rotational rate term `W.S - S.W` for the spin `W = (grad v - grad v^T)/2`
    /// given as the antisymmetric part of a `D x D` velocity gradient `L_ab = dv_a/dx_b`.
    #[inline]
    pub fn jaumann<const D: usize>(&self, grad_v: &Matrix<D>) -> Sym3 {
        // spin components w_ab = (L_ab - L_ba)/2, zero outside the D x D block
        let w = |a: usize, b: usize| -> Real {
            if a < D && b < D {
                0.5 * (grad_v[(a, b)] - grad_v[(b, a)])
            } else {
                0.0
            }
        };
        let mut out = [[0.0 as Real; 3]; 3];
        for (a, row) in out.iter_mut().enumerate() {
            for (b, o) in row.iter_mut().enumerate() {
                let mut s = 0.0;
                for k in 0..3 {
                    s += w(a, k) * self.get(k, b) - self.get(a, k) * w(k, b);
                }
                *o = s;
            }
        }
        Sym3 {
            xx: out[0][0],
            yy: out[1][1],
            zz: out[2][2],
            xy: out[0][1],
            xz: out[0][2],
            yz: out[1][2],
        }
    }
}

impl Add for Sym3 {
    type Output = Sym3;
    #[inline]
    fn add(self, o: Sym3) -> Sym3 {
        Sym3 {
            xx: self.xx + o.xx,
            yy: self.yy + o.yy,
            zz: self.zz + o.zz,
            xy: self.xy + o.xy,
            xz: self.xz + o.xz,
            yz: self.yz + o.yz,
        }
    }
}
impl Sub for Sym3 {
    type Output = Sym3;
    #[inline]
    fn sub(self, o: Sym3) -> Sym3 {
        self + (-o)
    }
}
impl Neg for Sym3 {
    type Output = Sym3;
    #[inline]
    fn neg(self) -> Sym3 {
        self * -1.0
    }
}
impl Mul<Real> for Sym3 {
    type Output = Sym3;
    #[inline]
    fn mul(self, s: Real) -> Sym3 {
        Sym3 {
            xx: self.xx * s,
            yy: self.yy * s,
            zz: self.zz * s,
            xy: self.xy * s,
            xz: self.xz * s,
            yz: self.yz * s,
        }
    }
}
impl AddAssign for Sym3 {
    #[inline]
    fn add_assign(&mut self, o: Sym3) {
        *self = *self + o;
    }
}
impl SubAssign for Sym3 {
    #[inline]
    fn sub_assign(&mut self, o: Sym3) {
        *self = *self - o;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deviator_is_traceless_and_von_mises_of_uniaxial_deviator() {
        let a = Sym3::new(3.0, -1.0, 0.5, 0.2, -0.3, 0.7);
        assert!(a.deviator().trace().abs() < 1e-14);
        // uniaxial-strain deviator S = diag(-2s/3... ) with S_xx = -2 S_yy = -2 S_zz
        let s = Sym3::new(-2.0, 1.0, 1.0, 0.0, 0.0, 0.0);
        assert!((s.von_mises() - 3.0).abs() < 1e-14);
    }

    #[test]
    fn traction_in_2d_uses_in_plane_block() {
        let a = Sym3::new(1.0, 2.0, 3.0, 4.0, 5.0, 6.0);
        let n = Vector::<2>::new(0.0, 1.0);
        let t = a.dot_vec(&n);
        assert_eq!(t, Vector::<2>::new(4.0, 2.0));
        assert_eq!(a.normal(&n), 2.0);
    }

    #[test]
    fn jaumann_term_of_pure_rotation_rotates_stress() {
        // rigid rotation about z with rate w: grad v = [[0,-w],[w,0]]
        let w = 0.3;
        let l = Matrix::<2>::new(0.0, -w, w, 0.0);
        let s = Sym3::new(1.0, -1.0, 0.0, 0.0, 0.0, 0.0);
        let r = s.jaumann(&l);
        // d/dt of R S R^T at t=0 for S=diag(1,-1): xy component = w*(1 - (-1)) = 2w
        assert!((r.xy - 2.0 * w).abs() < 1e-14);
        assert!(r.xx.abs() < 1e-14 && r.yy.abs() < 1e-14);
        // the spin term preserves the von Mises norm to first order
        assert!(s.ddot(&r).abs() < 1e-14);
    }
}

/// Determinant of a `D x D` matrix (D <= 3), closed form.
pub fn det<const D: usize>(m: &Matrix<D>) -> Real {
    match D {
        1 => m[(0, 0)],
        2 => m[(0, 0)] * m[(1, 1)] - m[(0, 1)] * m[(1, 0)],
        _ => {
            m[(0, 0)] * (m[(1, 1)] * m[(2, 2)] - m[(1, 2)] * m[(2, 1)])
                - m[(0, 1)] * (m[(1, 0)] * m[(2, 2)] - m[(1, 2)] * m[(2, 0)])
                + m[(0, 2)] * (m[(1, 0)] * m[(2, 1)] - m[(1, 1)] * m[(2, 0)])
        }
    }
}

/// Inverse of a `D x D` matrix (D <= 3) by the adjugate; `None` if the determinant is zero
/// or not finite.
pub fn inverse<const D: usize>(m: &Matrix<D>) -> Option<Matrix<D>> {
    let d = det(m);
    if d == 0.0 || !d.is_finite() {
        return None;
    }
    let inv_d = 1.0 / d;
    Some(match D {
        1 => Matrix::<D>::from_fn(|_, _| inv_d),
        2 => Matrix::<D>::from_fn(|a, b| {
            let v = match (a, b) {
                (0, 0) => m[(1, 1)],
                (1, 1) => m[(0, 0)],
                (0, 1) => -m[(0, 1)],
                _ => -m[(1, 0)],
            };
            v * inv_d
        }),
        _ => Matrix::<D>::from_fn(|a, b| {
            // cofactor of (b, a)
            let (r0, r1) = ((b + 1) % 3, (b + 2) % 3);
            let (c0, c1) = ((a + 1) % 3, (a + 2) % 3);
            (m[(r0, c0)] * m[(r1, c1)] - m[(r0, c1)] * m[(r1, c0)]) * inv_d
        }),
    })
}

#[cfg(test)]
mod det_tests {
    use super::*;

    #[test]
    fn inverse_times_matrix_is_identity() {
        let m3 = Matrix::<3>::new(2.0, 1.0, 0.5, -1.0, 3.0, 0.2, 0.1, 0.4, 1.5);
        let i3 = inverse(&m3).unwrap() * m3;
        assert!((i3 - Matrix::<3>::identity()).norm() < 1e-14);
        let m2 = Matrix::<2>::new(2.0, 1.0, -1.0, 3.0);
        assert!((inverse(&m2).unwrap() * m2 - Matrix::<2>::identity()).norm() < 1e-14);
        assert!((det(&m2) - 7.0).abs() < 1e-14);
        let m1 = Matrix::<1>::new(4.0);
        assert_eq!(inverse(&m1).unwrap()[(0, 0)], 0.25);
        assert!(inverse(&Matrix::<2>::zeros()).is_none());
    }
}
