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

/// The reals of one particle's neighbour record (`Workspace::rec`) for the time-split
/// family's vectorised star states in `d` dimensions: the fields of `RecordAt`, padded to
/// whole groups of four (one AVX2 load each).
pub const fn record_len(d: usize) -> usize {
    RecordAt::of(d).end.div_ceil(4) * 4
}

/// Where each field of a neighbour record lies in `D` dimensions: what particle j gives
/// the star states of its pairs. The first-order fields come first (the MUSCL gradients
/// after them are loaded only with MUSCL).
#[derive(Clone, Copy, Debug)]
#[cfg_attr(
    not(all(target_arch = "x86_64", not(feature = "f32"))),
    allow(dead_code)
)]
pub(crate) struct RecordAt {
    /// Velocity (D).
    pub v: usize,
    pub p: usize,
    pub rho: usize,
    pub c: usize,
    /// The Hugoniot slope of its material (`simd::ops::shock_slope`).
    pub slope: usize,
    /// 1 for a failed particle, else 0.
    pub failed: usize,
    /// The velocity gradient, `D x D` row by row.
    pub grad_v: usize,
    /// The pressure gradient (D).
    pub grad_p: usize,
    /// The density gradient (D).
    pub grad_rho: usize,
    /// The reals up to the last first-order field.
    pub first_order: usize,
    /// The reals the fields take (the record is padded to whole groups of four).
    pub end: usize,
}

#[cfg_attr(
    not(all(target_arch = "x86_64", not(feature = "f32"))),
    allow(dead_code)
)]
impl RecordAt {
    pub const fn of(d: usize) -> RecordAt {
        RecordAt {
            v: 0,
            p: d,
            rho: d + 1,
            c: d + 2,
            slope: d + 3,
            failed: d + 4,
            grad_v: d + 5,
            grad_p: d + 5 + d * d,
            grad_rho: 2 * d + 5 + d * d,
            first_order: d + 5,
            end: 3 * d + 5 + d * d,
        }
    }
}
