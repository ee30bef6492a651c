//! Logarithmic EOS (seed 004 eq 24): `P = B ln(rho/rho0) = B ln(V0/V)`, with
//! `B = rho0 c_a²`. No energy dependence, so `c² = dP/drho = B / rho > 0` for every
//! `rho > 0` (no floor needed). Seed 004 eq 36 drops the factor `B` (DESIGN §8); here it
//! is kept.

use super::state::EosState;
use crate::material::params::ranges::*;
use crate::material::params::{physical, positive, ParamError};
use crate::math::{real, Real};

/// Parameters of the logarithmic EOS.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(deny_unknown_fields)
)]
pub struct Logarithmic {
    /// Reference density rho0, kg/m³.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub rho0: Real,
    /// Bulk modulus B, Pa.
    pub bulk_modulus: Real,
}

impl Logarithmic {
    /// Checks the parameters (all but `rho0`, the material's): the rules the model's
    /// formulas need ([`crate::material::params`]).
    pub fn check(&self) -> Result<(), ParamError> {
        positive("bulk_modulus", self.bulk_modulus)?;
        physical("bulk_modulus", self.bulk_modulus, BULK_MODULUS, "Pa")
    }

    /// Pressure (Pa) and `c²` (m²/s²) at `rho` (kg/m³); `e` (J/kg) is ignored.
    #[inline]
    pub fn eval(&self, rho: Real, e: Real) -> EosState {
        let _ = e;
        EosState {
            p: self.bulk_modulus * real::ln(rho / self.rho0),
            c2: self.bulk_modulus / rho,
        }
    }
}

// Tolerances are for f64: the accuracy targets apply to f64 (DESIGN §1).
#[cfg(all(test, not(feature = "f32")))]
mod tests {
    use super::super::test_util::*;
    use super::*;

    const AL: Logarithmic = Logarithmic {
        rho0: 2688.9,
        bulk_modulus: 73e9,
    };

    #[test]
    fn hand_values() {
        // rho = 2 rho0: P = 73e9 ln 2 = 5.059 974 418 e10 Pa; c² = 73e9 / 5377.8
        let s = AL.eval(2.0 * 2688.9, 0.0);
        assert_rel(s.p, 5.059_974_418e10, 1e-9, "P");
        assert_rel(s.c2, 73e9 / 5377.8, 1e-15, "c2");
        assert_rel(s.c2, 1.357_432_407_3e7, 1e-9, "c2 literal");
        // tension, independently from the formula
        let rho = 2500.0;
        assert_rel(
            AL.eval(rho, 7.0).p,
            73e9 * real::ln(rho / 2688.9),
            1e-15,
            "P",
        );
        assert!(AL.eval(rho, 0.0).p < 0.0);
    }

    #[test]
    fn zero_at_reference() {
        assert_eq!(AL.eval(2688.9, 0.0).p, 0.0);
    }

    #[test]
    fn c2_is_isentropic_derivative() {
        let states = [(2688.9, 0.0), (3000.0, 1e5), (2400.0, 0.0), (5000.0, 1e6)];
        check_c2(|r, e| AL.eval(r, e), &states);
        // at rho0 the sound speed is sqrt(B/rho0)
        assert_rel(AL.eval(2688.9, 0.0).c2, 73e9 / 2688.9, 1e-15, "c_a²");
    }

    #[test]
    fn finite_everywhere() {
        check_finite(|r, e| AL.eval(r, e), 2688.9, 1e6);
    }
}
