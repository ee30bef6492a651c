//! Linear EOS with an optional Grüneisen-like energy term (seed 004):
//! `P = c0² (rho - rho0) + (gamma - 1) rho e`.
//!
//! `gamma = 1` is the barotropic linear EOS of seed 004's sound wave; `gamma = 2` is seed
//! 004's Verney shell. Sound speed (`dP/drho|_e = c0² + (gamma-1) e`,
//! `dP/de|_rho = (gamma-1) rho`):
//! `c² = c0² + (gamma - 1) (e + P/rho)`.
//! With `gamma > 1` this reaches zero in deep tension (`rho < rho0/2` for `gamma = 2`,
//! `e = 0`) or at negative energies; there `c²` is floored (see the parent module).

use super::state::{floor_c2, EosState};
use crate::material::params::ranges::*;
use crate::material::params::{physical, positive, ParamError};
use crate::math::Real;

/// Parameters of the linear EOS.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(deny_unknown_fields)
)]
pub struct Linear {
    /// Reference density rho0, kg/m³.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub rho0: Real,
    /// Reference bulk sound speed c0, m/s.
    pub c0: Real,
    /// Grüneisen-like exponent gamma, dimensionless (1 for a barotropic EOS).
    #[cfg_attr(feature = "serde", serde(default = "crate::material::params::one"))]
    pub gamma: Real,
}

impl Linear {
    /// Checks the parameters (all but `rho0`, the material's): the rules the model's
    /// formulas need ([`crate::material::params`]).
    pub fn check(&self) -> Result<(), ParamError> {
        positive("c0", self.c0)?;
        physical("c0", self.c0, SOUND_SPEED, "m/s")?;
        physical("gamma", self.gamma, COEFFICIENT, "")
    }

    /// Pressure (Pa) and `c²` (m²/s²) at `rho` (kg/m³), `e` (J/kg).
    #[inline]
    pub fn eval(&self, rho: Real, e: Real) -> EosState {
        let c02 = self.c0 * self.c0;
        let g1 = self.gamma - 1.0;
        let p = c02 * (rho - self.rho0) + g1 * rho * e;
        let c2 = c02 + g1 * (e + p / rho);
        EosState {
            p,
            c2: floor_c2(c2, c02),
        }
    }
}

// Tolerances are for f64: the accuracy targets apply to f64 (DESIGN §1).
#[cfg(all(test, not(feature = "f32")))]
mod tests {
    use super::super::test_util::*;
    use super::*;

    const CU: Linear = Linear {
        rho0: 8960.0,
        c0: 4148.0,
        gamma: 1.0,
    };
    const CU2: Linear = Linear {
        rho0: 8960.0,
        c0: 4148.0,
        gamma: 2.0,
    };

    #[test]
    fn hand_values() {
        // 4148² = 17 205 904; (9000 - 8960) * 17 205 904 = 688 236 160 Pa
        let s = CU.eval(9000.0, 123.0);
        assert_eq!(s.p, 688_236_160.0);
        assert_eq!(s.c2, 17_205_904.0);
        // gamma = 2, e = 1000: P = 688 236 160 + 9000 * 1000 = 697 236 160 Pa,
        // c² = 17 205 904 + 1000 + 697 236 160 / 9000 = 17 284 374.684 44...
        let s = CU2.eval(9000.0, 1000.0);
        assert_rel(s.p, 697_236_160.0, 1e-15, "P");
        assert_rel(s.c2, 17_284_374.684_444_4, 1e-12, "c2");
        // tension, independent arithmetic from the formula
        let (rho, e) = (8000.0, 2.0e5);
        let p = 4148.0 * 4148.0 * (rho - 8960.0) + rho * e;
        assert_rel(CU2.eval(rho, e).p, p, 1e-14, "P tension");
    }

    #[test]
    fn zero_at_reference() {
        assert_eq!(CU.eval(8960.0, 0.0).p, 0.0);
        assert_eq!(CU2.eval(8960.0, 0.0).p, 0.0);
    }

    #[test]
    fn c2_is_isentropic_derivative() {
        let states = [(8960.0, 0.0), (9500.0, 1e5), (8500.0, 3e4), (12000.0, 1e6)];
        check_c2(|r, e| CU.eval(r, e), &states);
        check_c2(|r, e| CU2.eval(r, e), &states);
    }

    #[test]
    fn finite_and_floored() {
        check_finite(|r, e| CU.eval(r, e), 8960.0, 1e6);
        check_finite(|r, e| CU2.eval(r, e), 8960.0, 1e6);
        // gamma = 2, e = 0: c² = c0² (2 - rho0/rho) < 0 below rho0/2 -> floor
        let s = CU2.eval(0.4 * 8960.0, 0.0);
        assert_eq!(s.c2, super::super::C2_FLOOR_FRACTION * 4148.0 * 4148.0);
    }
}
