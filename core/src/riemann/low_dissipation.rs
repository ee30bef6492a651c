//! Dissipation only where the flow compresses: the low-dissipation limiter of Zhang, Hu &
//! Adams (2017, J. Comput. Phys. 340, "A weakly compressible SPH method based on a
//! low-dissipation Riemann solver"; SPHinXsys' `DissipativeRiemannSolver`).
//!
//! The acoustic star state of a pair splits into a central part and a dissipative part:
//!
//! ```text
//! u* = (Z_l u_l + Z_r u_r)/(Z_l + Z_r)  +  (s_r - s_l)/(Z_l + Z_r),
//! s* = (Z_r s_l + Z_l s_r)/(Z_l + Z_r)  +  Z_l Z_r (u_r - u_l)/(Z_l + Z_r).
//! ```
//!
//! The central parts are the impedance-weighted means a plain SPH pair would use; the
//! jumps are what makes a Godunov scheme dissipate: the velocity jump in the traction (the
//! force and the energy), the traction jump in the contact velocity (continuity and the
//! deviator rate). With [`Dissipation::Compression`] both jumps are multiplied by
//!
//! ```text
//! beta = min(eta max(u_l - u_r, 0)/c, 1),   eta = 3,
//! ```
//!
//! the approach speed of the pair along its axis over the sound speed: zero where the pair
//! separates or slides (a rigid rotation moves neighbours only across their axis, so no
//! channel sees a jump), quadratic in a weak compression like a von Neumann–Richtmyer
//! viscosity, and the full Riemann dissipation (beta = 1) once the approach exceeds a third
//! of the sound speed, i.e. in every shock of the bundled cases. Zhang, Hu & Adams limit
//! the velocity jump of the pressure only; here every channel is limited (the transverse
//! waves of the contact family included), with the one compression measure of the pair.
//! For the two-shock solver the same blend acts on its star state:
//! `star = central + beta (star_solver - central)`.

use crate::math::{real, Real, Vector};

/// Zhang, Hu & Adams' eta: the approach Mach number at which the full dissipation applies
/// is 1/eta.
pub const ETA: Real = 3.0;

/// How much of the Riemann solver's dissipation a pair gets (`options.dissipation`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Dissipation {
    /// Only on compression, weighted by the approach Mach number (Zhang, Hu & Adams 2017).
    Compression,
    /// The solver's whole dissipation on every pair (the seeds' schemes).
    Full,
}

impl Dissipation {
    /// The name in a scene.
    pub const fn name(self) -> &'static str {
        match self {
            Dissipation::Compression => "compression",
            Dissipation::Full => "full",
        }
    }

    /// The dissipation of a name, if it is one.
    pub fn from_name(name: &str) -> Option<Dissipation> {
        match name {
            "compression" => Some(Dissipation::Compression),
            "full" => Some(Dissipation::Full),
            _ => None,
        }
    }

    /// The weight of the dissipative part for a pair approaching at `u_l - u_r` (along the
    /// axis from l to r) with sound speed `c`: 1 for [`Dissipation::Full`].
    #[inline(always)]
    pub fn weight(self, u_l: Real, u_r: Real, c: Real) -> Real {
        match self {
            Dissipation::Full => 1.0,
            Dissipation::Compression => {
                let approach = real::max(u_l - u_r, 0.0);
                if c > 0.0 {
                    real::min(ETA * approach / c, 1.0)
                } else if approach > 0.0 {
                    1.0
                } else {
                    0.0
                }
            }
        }
    }
}

impl core::fmt::Display for Dissipation {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// The central (non-dissipative) part of a star state along an axis: the impedance-weighted
/// means `((Z_l u_l + Z_r u_r)/(Z_l + Z_r), (Z_r s_l + Z_l s_r)/(Z_l + Z_r))`; the plain
/// means where `Z_l + Z_r` is not positive and finite.
#[inline(always)]
pub fn central(u_l: Real, s_l: Real, z_l: Real, u_r: Real, s_r: Real, z_r: Real) -> (Real, Real) {
    let zs = z_l + z_r;
    if zs > 0.0 && zs.is_finite() {
        ((z_l * u_l + z_r * u_r) / zs, (z_r * s_l + z_l * s_r) / zs)
    } else {
        (0.5 * (u_l + u_r), 0.5 * (s_l + s_r))
    }
}

/// `central + beta (star - central)` for a scalar pair `(u, s)`.
#[inline(always)]
pub fn blend(star: (Real, Real), central: (Real, Real), beta: Real) -> (Real, Real) {
    if beta == 1.0 {
        return star;
    }
    (
        central.0 + beta * (star.0 - central.0),
        central.1 + beta * (star.1 - central.1),
    )
}

/// The central part of the vector star state of the contact family (velocity, traction):
/// along `n` with the longitudinal impedances, across it with the transverse ones (the
/// traction across it is zero, as the solver's, where neither side has a shear impedance).
#[inline(always)]
#[allow(clippy::too_many_arguments)] // the two sides of the vector problem
pub fn central_vector<const D: usize>(
    n: &Vector<D>,
    v_l: &Vector<D>,
    t_l: &Vector<D>,
    zl_long: Real,
    zl_trans: Real,
    v_r: &Vector<D>,
    t_r: &Vector<D>,
    zr_long: Real,
    zr_trans: Real,
) -> (Vector<D>, Vector<D>) {
    let (vln, tln, vrn, trn) = (v_l.dot(n), t_l.dot(n), v_r.dot(n), t_r.dot(n));
    let (u_n, s_n) = central(vln, tln, zl_long, vrn, trn, zr_long);
    let (vlt, tlt) = (*v_l - *n * vln, *t_l - *n * tln);
    let (vrt, trt) = (*v_r - *n * vrn, *t_r - *n * trn);
    let zs = zl_trans + zr_trans;
    let (v_t, t_t) = if zs > 0.0 && zs.is_finite() {
        let inv = 1.0 / zs;
        (
            (vlt * zl_trans + vrt * zr_trans) * inv,
            (tlt * zr_trans + trt * zl_trans) * inv,
        )
    } else {
        ((vlt + vrt) * 0.5, Vector::<D>::zeros())
    };
    (*n * u_n + v_t, *n * s_n + t_t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::riemann::{acoustic_star, AcousticSide};

    #[test]
    fn weight_is_zero_apart_quadratic_weak_and_full_strong() {
        let d = Dissipation::Compression;
        assert_eq!(d.weight(-1.0, 1.0, 100.0), 0.0); // separating
        assert_eq!(d.weight(1.0, 1.0, 100.0), 0.0); // no jump
        assert_eq!(d.weight(1.0, 0.0, 100.0), 0.03); // 3 x 1/100
        assert_eq!(d.weight(40.0, 0.0, 100.0), 1.0); // beyond c/3
        assert_eq!(Dissipation::Full.weight(-1.0, 1.0, 100.0), 1.0);
    }

    /// The full weight gives the acoustic star back; the zero weight its central part,
    /// whose energy flux has no dissipation: `s* (u_r - u_l)` is then the jump of the
    /// mean, not `-Z Δu²`.
    #[test]
    fn blend_spans_central_to_acoustic() {
        let (ul, sl, zl, ur, sr, zr) = (3.0, -2e6, 4e6, -1.0, 5e5, 6e6);
        let star = acoustic_star(
            AcousticSide {
                u: ul,
                s: sl,
                z: zl,
            },
            AcousticSide {
                u: ur,
                s: sr,
                z: zr,
            },
        );
        let c = central(ul, sl, zl, ur, sr, zr);
        assert_eq!(blend(star, c, 1.0), star);
        assert_eq!(blend(star, c, 0.0), c);
        // the dissipative parts are exactly the jumps of the module docs
        let zs = zl + zr;
        assert!((star.0 - c.0 - (sr - sl) / zs).abs() < 1e-12);
        assert!((star.1 - c.1 - zl * zr * (ur - ul) / zs).abs() < 1e-3);
    }
}
