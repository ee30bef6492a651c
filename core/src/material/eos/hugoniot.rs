//! The shock Hugoniot of the linear relation `Us = c0 + s1 up` used as a barotropic EOS:
//! the flyer plate's "isothermal Mie–Grüneisen" (Gamma = 0), seed 000 eq 36, corrected.
//!
//! `P = rho0 c0² x / (1 - s1 x)²`, `x = 1 - rho0/rho` (compression, `rho >= rho0`).
//!
//! **Derivation.** Across a steady shock into material at rest, mass and momentum give
//! `rho0 Us = rho (Us - up)`, i.e. `x = up/Us`, and `P = rho0 Us up`. With
//! `Us = c0 + s1 up = c0 + s1 x Us`: `Us = c0/(1 - s1 x)`, `up = c0 x/(1 - s1 x)`, so
//! `P = rho0 c0² x/(1 - s1 x)²` exactly. The specific energy jump is
//! `e_H = P (1/rho0 - 1/rho)/2 = up²/2 = c0² x² / (2 (1 - s1 x)²)`.
//!
//! **Erratum (seed 000 eq 36).** The seed prints `P = rho0 c0² zeta/(1 - (S1-1) zeta)`
//! with `zeta = rho/rho0 - 1`. Substituting `x = zeta/(1+zeta)` and
//! `1 - s1 x = (1 - (s1-1) zeta)/(1+zeta)` into the Hugoniot above gives
//! `P = rho0 c0² zeta (1+zeta) / (1 - (s1-1) zeta)²`: the printed form lost the factor
//! `(1+zeta)` and the square. Both agree to first order, `rho0 c0² zeta`, but the printed
//! one has the wrong curvature (`zeta + (s1-1) zeta²` instead of `zeta + (2 s1-1) zeta²`)
//! and is not the Hugoniot of the `Us`–`up` fit the paper quotes; tests show both facts.
//! In compression this model equals [`super::MieGruneisen`] with `gamma0 = 0`.
//!
//! **Tension** (`rho < rho0`): the Hugoniot has no meaning there, and the formula would
//! soften to a pressure minimum and `c² < 0` at `x = -1/s1`. We use the same linear branch
//! as [`super::MieGruneisen`], `P = c0² (rho - rho0)`, continuous in value and slope at
//! `rho0`, so `Hugoniot == MieGruneisen { gamma0: 0 }` everywhere and `c² >= c0² > 0`.
//!
//! **Guard:** beyond [`super::guard_density`] the curve continues along its tangent
//! (parent module doc).

use super::state::{guard_density, EosState};
use crate::material::params::ranges::*;
use crate::material::params::{non_negative, physical, positive, ParamError};
use crate::math::Real;

/// Parameters of the Hugoniot (isothermal Mie–Grüneisen) EOS.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(deny_unknown_fields)
)]
pub struct Hugoniot {
    /// Reference density rho0, kg/m³.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub rho0: Real,
    /// Bulk sound speed c0 (intercept of the `Us`–`up` fit), m/s.
    pub c0: Real,
    /// Slope s1 of the `Us`–`up` fit, dimensionless.
    pub s1: Real,
}

/// A reference curve and its density derivatives at one density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct RefCurve {
    /// Reference pressure, Pa.
    pub p: Real,
    /// dP_ref/drho, m²/s².
    pub dp: Real,
    /// Reference specific energy, J/kg.
    pub e: Real,
    /// de_ref/drho, J m³/kg².
    pub de: Real,
}

/// The Hugoniot of `Us = c + s up` at `rho >= rho0` (kg/m³, m/s): `P_H = rho0 c² y/(1-sy)²`,
/// `e_H = c² y²/(2 (1-sy)²)`, `y = 1 - rho0/rho`, with
/// `dP_H/dy = rho0 c² (1+sy)/(1-sy)³`, `de_H/dy = c² y/(1-sy)³`, `dy/drho = rho0/rho²`;
/// continued linearly in `rho` beyond the guard density.
#[inline]
pub(crate) fn linear_us_up_hugoniot(rho0: Real, c: Real, s: Real, rho: Real) -> RefCurve {
    let rho_g = guard_density(rho0, s);
    let (r, ext) = if rho > rho_g {
        (rho_g, rho - rho_g)
    } else {
        (rho, 0.0)
    };
    let y = 1.0 - rho0 / r;
    let inv_d = 1.0 / (1.0 - s * y);
    let c2 = c * c;
    let up = c * y * inv_d; // particle velocity behind the shock
    let dy = rho0 / (r * r);
    let dp = rho0 * c2 * (1.0 + s * y) * inv_d * inv_d * inv_d * dy;
    let de = c2 * y * inv_d * inv_d * inv_d * dy;
    RefCurve {
        p: rho0 * c * up * inv_d + dp * ext,
        dp,
        e: 0.5 * up * up + de * ext,
        de,
    }
}

impl Hugoniot {
    /// Checks the parameters (all but `rho0`, the material's): the rules the model's
    /// formulas need ([`crate::material::params`]).
    pub fn check(&self) -> Result<(), ParamError> {
        positive("c0", self.c0)?;
        physical("c0", self.c0, SOUND_SPEED, "m/s")?;
        non_negative("s1", self.s1)?;
        physical("s1", self.s1, COEFFICIENT, "")
    }

    /// Pressure (Pa) and `c²` (m²/s²) at `rho` (kg/m³); `e` (J/kg) is ignored (Gamma = 0).
    #[inline]
    pub fn eval(&self, rho: Real, e: Real) -> EosState {
        let _ = e;
        if rho >= self.rho0 {
            let h = linear_us_up_hugoniot(self.rho0, self.c0, self.s1, rho);
            EosState { p: h.p, c2: h.dp }
        } else {
            let c02 = self.c0 * self.c0;
            EosState {
                p: c02 * (rho - self.rho0),
                c2: c02,
            }
        }
    }
}

// Tolerances are for f64: the accuracy targets apply to f64 (DESIGN §1).
#[cfg(all(test, not(feature = "f32")))]
mod tests {
    use super::super::test_util::*;
    use super::super::MieGruneisen;
    use super::*;

    const FLYER: Hugoniot = Hugoniot {
        rho0: 6100.0,
        c0: 5077.0,
        s1: 1.201,
    };

    #[test]
    fn hand_values() {
        // up = 1000 m/s: Us = 6278 m/s, P = 6100 * 6278 * 1000 = 38 295 800 000 Pa
        let rho = 6100.0 * 6278.0 / 5278.0;
        assert_rel(
            FLYER.eval(rho, 0.0).p,
            38_295_800_000.0,
            1e-12,
            "P(up = 1 km/s)",
        );
        // rho = 7000: formula with plain arithmetic
        let x = 1.0 - 6100.0 / 7000.0;
        let p = 6100.0 * 5077.0 * 5077.0 * x / ((1.0 - 1.201 * x) * (1.0 - 1.201 * x));
        assert_rel(FLYER.eval(7000.0, 1e6).p, p, 1e-14, "P(7000)");
        // tension branch
        assert_eq!(FLYER.eval(6000.0, 0.0).p, 5077.0 * 5077.0 * -100.0);
    }

    #[test]
    fn is_the_shock_hugoniot_of_linear_us_up() {
        for up in [1.0, 50.0, 300.0, 1000.0, 2500.0, 6000.0] {
            let us = 5077.0 + 1.201 * up;
            let rho = 6100.0 * us / (us - up);
            assert_rel(
                FLYER.eval(rho, 0.0).p,
                6100.0 * us * up,
                1e-12,
                "P = rho0 Us up",
            );
            let h = linear_us_up_hugoniot(6100.0, 5077.0, 1.201, rho);
            // y = 1 - rho0/rho loses digits to cancellation at small up
            assert_rel(h.e, 0.5 * up * up, 1e-10, "e_H = up²/2");
        }
    }

    #[test]
    fn seed_eq36_is_garbled() {
        let (rho0, c0, s1) = (6100.0, 5077.0, 1.201);
        let up = 1000.0;
        let us = c0 + s1 * up;
        let zeta = us / (us - up) - 1.0;
        let corrected = rho0 * c0 * c0 * zeta * (1.0 + zeta)
            / ((1.0 - (s1 - 1.0) * zeta) * (1.0 - (s1 - 1.0) * zeta));
        let printed = rho0 * c0 * c0 * zeta / (1.0 - (s1 - 1.0) * zeta);
        assert_rel(corrected, rho0 * us * up, 1e-12, "corrected eq 36");
        assert!(
            (printed / (rho0 * us * up) - 1.0).abs() > 0.1,
            "printed eq 36 is off"
        );
    }

    #[test]
    fn zero_at_reference_and_smooth_there() {
        assert_eq!(FLYER.eval(6100.0, 0.0).p, 0.0);
        assert_eq!(FLYER.eval(6100.0, 0.0).c2, 5077.0 * 5077.0);
        let d = 1e-6;
        assert_rel(
            FLYER.eval(6100.0 + d, 0.0).c2,
            FLYER.eval(6100.0 - d, 0.0).c2,
            1e-6,
            "c²",
        );
    }

    #[test]
    fn c2_is_isentropic_derivative() {
        let states = [(6100.0, 0.0), (6500.0, 0.0), (9000.0, 1e5), (5500.0, 0.0)];
        check_c2(|r, e| FLYER.eval(r, e), &states);
    }

    #[test]
    fn equals_mie_gruneisen_without_gamma() {
        let mg = MieGruneisen {
            rho0: 6100.0,
            c0: 5077.0,
            s1: 1.201,
            gamma0: 0.0,
        };
        for eta in [0.3, 0.7, 0.99, 1.0, 1.2, 2.0, 4.0, 5.0, 8.0, 50.0] {
            let (a, b) = (FLYER.eval(eta * 6100.0, 3e5), mg.eval(eta * 6100.0, 3e5));
            assert_rel(a.p, b.p, 1e-12, "P");
            assert_rel(a.c2, b.c2, 1e-12, "c2");
        }
    }

    #[test]
    fn finite_beyond_guard() {
        check_finite(|r, e| FLYER.eval(r, e), 6100.0, 1e6);
        // pole at rho/rho0 = s1/(s1-1) = 5.975: still finite there and beyond, monotone
        let pole = 6100.0 * 1.201 / 0.201;
        let rho_g = guard_density(6100.0, 1.201);
        assert!(rho_g < pole);
        let mut prev = FLYER.eval(rho_g * (1.0 - 1e-9), 0.0);
        for rho in [rho_g, pole, 2.0 * pole, 1e3 * pole] {
            let s = FLYER.eval(rho, 0.0);
            assert!(s.p.is_finite() && s.p >= prev.p && s.c2 > 0.0);
            prev = s;
        }
        // continuous value and slope across the guard
        let (a, b) = (
            FLYER.eval(rho_g * (1.0 - 1e-12), 0.0),
            FLYER.eval(rho_g * (1.0 + 1e-12), 0.0),
        );
        assert_rel(a.p, b.p, 1e-9, "P at guard");
        assert_rel(a.c2, b.c2, 1e-9, "c2 at guard");
    }
}
