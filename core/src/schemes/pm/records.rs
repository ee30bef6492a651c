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

/// The reals of one particle's neighbour record (`Workspace::rec`) for the contact
/// family's vectorised star states in `d` dimensions: the fields of `RecordAt`, padded
/// to whole groups of four (one AVX2 load each).
pub const fn record_len(d: usize) -> usize {
    RecordAt::of(d).end.div_ceil(4) * 4
}

/// Where each field of a neighbour record lies in `D` dimensions: what particle j gives
/// the star states of its pairs (the fields a case does not use hold zeros).
#[derive(Clone, Copy, Debug)]
#[cfg_attr(
    not(all(target_arch = "x86_64", not(feature = "f32"))),
    allow(dead_code)
)]
pub(crate) struct RecordAt {
    /// Velocity (D).
    pub v: usize,
    pub rho: usize,
    pub cl: usize,
    /// The transverse sound speed (`Aux::ct`).
    pub ct: usize,
    /// The Hugoniot slope of its material.
    pub slope: usize,
    /// 1 for a failed particle, else 0.
    pub failed: usize,
    pub p: usize,
    /// The Cauchy stress `S - P I`, `D x D` row by row.
    pub sig: usize,
    /// The spin gradient `W`, `D x D` row by row.
    pub w: usize,
    /// The corrected kernel's `L^-1`, `D x D` row by row.
    pub l_inv: usize,
    /// The gradients of rho, c_l, c_t and p (D each).
    pub grad_rho: usize,
    pub grad_cl: usize,
    pub grad_ct: usize,
    pub grad_p: usize,
    /// The velocity gradient, `D x D` row by row.
    pub grad_v: usize,
    /// The stress gradients: component `(a, b)` (`av::records::sym_at`) times D, plus axis.
    pub grad_s: usize,
    /// The reals the fields take (the record is padded to whole groups of four).
    pub end: usize,
}

#[cfg_attr(
    not(all(target_arch = "x86_64", not(feature = "f32"))),
    allow(dead_code)
)]
impl RecordAt {
    pub const fn of(d: usize) -> RecordAt {
        let sig = d + 6;
        let grad_rho = sig + 3 * d * d;
        RecordAt {
            v: 0,
            rho: d,
            cl: d + 1,
            ct: d + 2,
            slope: d + 3,
            failed: d + 4,
            p: d + 5,
            sig,
            w: sig + d * d,
            l_inv: sig + 2 * d * d,
            grad_rho,
            grad_cl: grad_rho + d,
            grad_ct: grad_rho + 2 * d,
            grad_p: grad_rho + 3 * d,
            grad_v: grad_rho + 4 * d,
            grad_s: grad_rho + 4 * d + d * d,
            end: grad_rho + 4 * d + d * d + d * d * (d + 1) / 2,
        }
    }
}
