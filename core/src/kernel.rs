//! Smoothing kernels (STUB: to be implemented; API fixed).
use crate::math::{Real, Vector};

/// Smoothing kernel shape. Support radius is `support() * h`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kernel {
    /// Cubic B-spline (M4), support 2h.
    CubicSpline,
    /// Wendland C2, support 2h.
    WendlandC2,
    /// Gaussian-like: truncated Gaussian, support 3h.
    Gaussian,
}

impl Kernel {
    /// Support radius in units of h.
    pub const fn support(self) -> Real {
        match self {
            Kernel::CubicSpline | Kernel::WendlandC2 => 2.0,
            Kernel::Gaussian => 3.0,
        }
    }
    /// W(r, h) in dimension D.
    pub fn w<const D: usize>(self, r: Real, h: Real) -> Real {
        let _ = (r, h);
        todo!()
    }
    /// dW/dr (r, h) in dimension D (non-positive).
    pub fn dw<const D: usize>(self, r: Real, h: Real) -> Real {
        let _ = (r, h);
        todo!()
    }
    /// grad_i W(x_i - x_j) given `rij = x_i - x_j` and `r = |rij| > 0`.
    pub fn gradient<const D: usize>(self, rij: &Vector<D>, r: Real, h: Real) -> Vector<D> {
        rij * (self.dw::<D>(r, h) / r)
    }
}
