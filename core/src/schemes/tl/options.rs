//! The `[options]` keys `tl` answers for itself ([`crate::schemes::options`]; the table
//! answers the rest).

use crate::schemes::options::{NotRead, OptionKey, SchemeOptions};
use crate::schemes::scheme::Scheme;

/// tl's defaults: the table's, with `det_epsilon = 1e-4`. Its correction is that of the
/// reference configuration, where every particle of a body has a neighbourhood in full
/// rank: the smallest det of a lattice site is a 3D box's corner, 0.023 (Wendland C2, h =
/// 1.3 dx; a 2D corner 0.135), below the updated-Lagrangian schemes' 0.05, which left the
/// corners uncorrected, their F wrong for every motion, and folded the twisting column's
/// top corners (pairs at 0.40 dx after 0.04 s; 0.77 dx over the run with the correction).
/// The threshold guards only against a degenerate neighbourhood (a lone particle, a line).
pub(crate) fn defaults() -> SchemeOptions {
    SchemeOptions {
        det_epsilon: 1e-4,
        ..SchemeOptions::default()
    }
}

/// Why `tl` does not read a key it has a reason of its own for.
mod why {
    pub const RECONSTRUCTION: &str =
        "its reconstruction extrapolates each side's velocity with its reference gradient dF/dt, bounded by half the pair's jump: there is no limiter function to choose";
    pub const ACOUSTIC: &str =
        "its Riemann problem is the longitudinal acoustic one of the (p, F) system";
    pub const ONE_DISSIPATION: &str =
        "it solves no transverse Riemann problem (measured to break angular momentum; its hourglass stiffness holds the zero-energy modes)";
    pub const OBJECTIVE: &str =
        "its reconstruction is objective by construction: a rigid rotation's pair jumps are reconstructed away";
    pub const SLOPES: &str = "its slopes dF/dt are corrected everywhere";
    pub const INTEGRATOR: &str =
        "it steps with its own velocity Verlet (half kick, drift, deformation, forces, half kick) only";
    pub const SURFACE: &str =
        "its correction is fixed in the reference configuration and applied everywhere: there is no free-surface switch";
    pub const NO_TENSILE: &str =
        "its kernel and neighbours are fixed in the reference configuration, so it has no tensile instability to delay";
}

/// Scheme `tl`'s own answer for `key` where the table's is not its (`None`: the table's).
pub(crate) fn reads(scheme: Scheme, key: OptionKey) -> Option<Result<(), NotRead>> {
    use OptionKey::*;
    let no = |why: &'static str| Some(Err(NotRead::Because { scheme, why }));
    match key {
        Limiter => no(why::RECONSTRUCTION),
        Riemann => no(why::ACOUSTIC),
        TransverseDissipation => no(why::ONE_DISSIPATION),
        Objective => no(why::OBJECTIVE),
        CorrectedSlopes => no(why::SLOPES),
        Integrator => no(why::INTEGRATOR),
        SurfaceLambda | SurfaceScan => no(why::SURFACE),
        ArtificialStress | ArtificialStressExponent => no(why::NO_TENSILE),
        _ => None,
    }
}
