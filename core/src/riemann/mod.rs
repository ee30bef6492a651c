//! Riemann solvers (STUB: to be implemented; API fixed).
use crate::math::Real;

/// One side of the linearised (acoustic) Riemann problem along the pair axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AcousticSide {
    /// Velocity component along the axis, m/s.
    pub u: Real,
    /// Traction component along the axis (normal stress, tension positive), Pa.
    pub s: Real,
    /// Impedance rho*c, kg/(m² s).
    pub z: Real,
}

/// Star state of the acoustic Riemann problem: left side `l` (particle i), right side `r`
/// (particle j), axis pointing from l to r. Returns `(u*, s*)`.
pub fn acoustic_star(l: AcousticSide, r: AcousticSide) -> (Real, Real) {
    let _ = (l, r);
    todo!()
}
