//! The star state of each pair of the contact family.

use crate::math::Vector;

/// The star state of one pair of the contact family's elastic Riemann problem, solved on
/// the side of the pair's owner (traction on the contact plane whose normal points from
/// the owner to the other particle; seen from the other side it is `-t`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PmStar<const D: usize> {
    /// Contact velocity, m/s.
    pub v: Vector<D>,
    /// Contact traction, Pa (tension positive).
    pub t: Vector<D>,
}

impl<const D: usize> Default for PmStar<D> {
    fn default() -> Self {
        PmStar {
            v: Vector::<D>::zeros(),
            t: Vector::<D>::zeros(),
        }
    }
}
