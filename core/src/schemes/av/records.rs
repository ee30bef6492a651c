//! The leap-frog rates `av` carries from one step to the next.

use crate::math::{Real, Sym3, Vector};

/// State of the leap-frog integration of `av` kept between steps.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AvRates<const D: usize> {
    /// dv/dt.
    pub acc: Vector<D>,
    /// de/dt.
    pub de: Real,
    /// drho/dt.
    pub drho: Real,
    /// dS/dt.
    pub ds: Sym3,
    /// Equivalent strain rate, 1/s (rate-dependent strength).
    pub rate: Real,
    /// Half-step velocity (scratch).
    pub v_half: Vector<D>,
    /// Half-step energy (scratch).
    pub e_half: Real,
    /// Half-step density (scratch).
    pub rho_half: Real,
    /// Half-step deviator (scratch).
    pub s_half: Sym3,
}

impl<const D: usize> Default for AvRates<D> {
    fn default() -> Self {
        AvRates {
            acc: Vector::<D>::zeros(),
            de: 0.0,
            drho: 0.0,
            ds: Sym3::ZERO,
            rate: 0.0,
            v_half: Vector::<D>::zeros(),
            e_half: 0.0,
            rho_half: 0.0,
            s_half: Sym3::ZERO,
        }
    }
}
