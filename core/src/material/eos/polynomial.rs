//! Polynomial EOS (seed 000 eq 39, SiC, bulking off), `z = rho/rho0 - 1`:
//! `P = k1 z + k2 z² + k3 z³` in compression (`z >= 0`), `P = k1 z` in tension.
//!
//! No energy dependence, so `c² = dP/drho = (k1 + 2 k2 z + 3 k3 z²)/rho0` (compression),
//! `k1/rho0` (tension); the branches meet with equal value and slope at `z = 0`. The floor
//! of the parent module applies only if the fit's coefficients make `dP/drho <= 0` (a
//! negative `k3` at large `z`), where the fit is outside its range.

use super::state::{floor_c2, EosState};
use crate::material::params::ranges::*;
use crate::material::params::{physical, positive, ParamError};
use crate::math::Real;

/// Parameters of the polynomial EOS (seed 000 eq 39).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(deny_unknown_fields)
)]
pub struct Polynomial {
    /// Reference density rho0, kg/m³.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub rho0: Real,
    /// Linear coefficient k1 (bulk modulus), Pa.
    pub k1: Real,
    /// Quadratic coefficient k2, Pa.
    #[cfg_attr(feature = "serde", serde(default))]
    pub k2: Real,
    /// Cubic coefficient k3, Pa.
    #[cfg_attr(feature = "serde", serde(default))]
    pub k3: Real,
}

impl Polynomial {
    /// Checks the parameters (all but `rho0`, the material's): the rules the model's
    /// formulas need ([`crate::material::params`]).
    pub fn check(&self) -> Result<(), ParamError> {
        positive("k1", self.k1)?;
        physical("k1", self.k1, BULK_MODULUS, "Pa")?;
        physical("k2", self.k2, SIGNED_MODULUS, "Pa")?;
        physical("k3", self.k3, SIGNED_MODULUS, "Pa")
    }

    /// Pressure (Pa) and `c²` (m²/s²) at `rho` (kg/m³); `e` (J/kg) is ignored.
    #[inline]
    pub fn eval(&self, rho: Real, e: Real) -> EosState {
        let _ = e;
        let z = rho / self.rho0 - 1.0;
        let inv_rho0 = 1.0 / self.rho0;
        let (p, dp_dz) = if z >= 0.0 {
            (
                z * (self.k1 + z * (self.k2 + z * self.k3)),
                self.k1 + z * (2.0 * self.k2 + 3.0 * z * self.k3),
            )
        } else {
            (self.k1 * z, self.k1)
        };
        EosState {
            p,
            c2: floor_c2(dp_dz * inv_rho0, self.k1 * inv_rho0),
        }
    }
}

// Tolerances are for f64: the accuracy targets apply to f64 (DESIGN §1).
#[cfg(all(test, not(feature = "f32")))]
mod tests {
    use super::super::test_util::*;
    use super::*;

    const SIC: Polynomial = Polynomial {
        rho0: 3215.0,
        k1: 2.2e11,
        k2: 3.61e11,
        k3: 0.0,
    };

    #[test]
    fn hand_values() {
        // z = 0.1: P = 2.2e10 + 3.61e9 = 2.561e10 Pa; c² = (2.2e11 + 7.22e10)/3215
        let s = SIC.eval(1.1 * 3215.0, 0.0);
        assert_rel(s.p, 2.561e10, 1e-13, "P(0.1)");
        assert_rel(s.c2, 2.922e11 / 3215.0, 1e-13, "c2(0.1)");
        // z = -0.1: P = -2.2e10, c² = k1/rho0
        let s = SIC.eval(0.9 * 3215.0, 1e6);
        assert_rel(s.p, -2.2e10, 1e-13, "P(-0.1)");
        assert_rel(s.c2, 2.2e11 / 3215.0, 1e-15, "c2(-0.1)");
        // with a cubic term, straight from the formula
        let m = Polynomial { k3: -1.0e11, ..SIC };
        let z = 0.3;
        let p = 2.2e11 * z + 3.61e11 * z * z - 1.0e11 * z * z * z;
        assert_rel(m.eval((1.0 + z) * 3215.0, 0.0).p, p, 1e-13, "P cubic");
    }

    #[test]
    fn zero_at_reference() {
        assert_eq!(SIC.eval(3215.0, 0.0).p, 0.0);
        assert_eq!(SIC.eval(3215.0, 0.0).c2, 2.2e11 / 3215.0);
    }

    #[test]
    fn c2_is_isentropic_derivative() {
        let states = [(3215.0, 0.0), (3500.0, 1e5), (6000.0, 0.0), (3000.0, 1e4)];
        check_c2(|r, e| SIC.eval(r, e), &states);
        let m = Polynomial { k3: 2.0e11, ..SIC };
        check_c2(|r, e| m.eval(r, e), &states);
    }

    #[test]
    fn finite_everywhere() {
        check_finite(|r, e| SIC.eval(r, e), 3215.0, 1e6);
        // a negative k3 turns dP/drho negative at large z: floored, still finite
        let m = Polynomial { k3: -1.0e11, ..SIC };
        check_finite(|r, e| m.eval(r, e), 3215.0, 1e6);
    }
}
