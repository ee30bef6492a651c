//! The star state of each pair of the time-split family.

use crate::math::Real;

/// The star state of one pair of the time-split family's hydrodynamic Riemann problem,
/// solved on the side of the pair's owner (`u` along the axis from the owner to the other
/// particle).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TsStar {
    /// Contact velocity along the axis, m/s.
    pub u: Real,
    /// Contact pressure, Pa.
    pub p: Real,
}
