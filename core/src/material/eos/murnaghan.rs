//! Murnaghan (Tait) EOS, the weakly compressible SPH users' equation for liquids:
//! `P = (rho0 c0²/gamma) ((rho/rho0)^gamma - 1)` (Murnaghan 1944; Tait's form in Monaghan
//! 1994, Batchelor's water with `gamma = 7`). No energy dependence, so
//! `c² = dP/drho = c0² (rho/rho0)^(gamma - 1) > 0` for every `rho > 0` (no floor needed);
//! the bulk modulus `K = rho c² = rho0 c0² + gamma P` grows linearly with pressure
//! (`K' = gamma`), so the weak-shock slope is `(1 + gamma)/4` ([`super::Eos::hugoniot_slope`]).

use super::state::EosState;
use crate::material::params::ranges::*;
use crate::material::params::{physical, positive, ParamError};
use crate::math::{real, Real};

/// Parameters of the Murnaghan (Tait) EOS.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(deny_unknown_fields)
)]
pub struct Murnaghan {
    /// Reference density rho0, kg/m³.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub rho0: Real,
    /// Sound speed at `rho0`, m/s.
    pub c0: Real,
    /// Exponent gamma (`K'`, the pressure derivative of the bulk modulus), dimensionless.
    pub gamma: Real,
}

impl Murnaghan {
    /// Checks the parameters (all but `rho0`, the material's): `c0 > 0`, `gamma > 0`.
    pub fn check(&self) -> Result<(), ParamError> {
        positive("c0", self.c0)?;
        physical("c0", self.c0, SOUND_SPEED, "m/s")?;
        positive("gamma", self.gamma)?;
        physical("gamma", self.gamma, COEFFICIENT, "")
    }

    /// Pressure (Pa) and `c²` (m²/s²) at `rho` (kg/m³); `e` (J/kg) is ignored.
    #[inline]
    pub fn eval(&self, rho: Real, e: Real) -> EosState {
        let _ = e;
        // (eta^gamma - 1)/gamma as expm1(gamma ln eta)/gamma: exact to rounding for every
        // gamma, tending to the logarithmic EOS's ln eta as gamma -> 0 (where
        // eta^gamma - 1 rounds to 0)
        let ln_eta = real::ln(rho / self.rho0);
        let c02 = self.c0 * self.c0;
        EosState {
            p: self.rho0 * c02 * (real::expm1(self.gamma * ln_eta) / self.gamma),
            c2: c02 * real::exp((self.gamma - 1.0) * ln_eta),
        }
    }
}

// Tolerances are for f64: the accuracy targets apply to f64 (DESIGN §1).
#[cfg(all(test, not(feature = "f32")))]
mod tests {
    use super::super::test_util::*;
    use super::*;

    /// Batchelor's water: rho0 = 1000 kg/m³, c0 = 1480 m/s, gamma = 7.
    const WATER: Murnaghan = Murnaghan {
        rho0: 1000.0,
        c0: 1480.0,
        gamma: 7.0,
    };

    #[test]
    fn hand_values() {
        // B = rho0 c0² / gamma = 1000 * 2 190 400 / 7 = 312 914 285.714 Pa;
        // rho = 1.1 rho0: 1.1^7 = 1.948 717 1, P = B * 0.948 717 1 = 296 867 133.69 Pa,
        // 1.1^6 = 1.771 561, c² = 2 190 400 * 1.771 561 = 3 880 427.214 4 m²/s²
        let s = WATER.eval(1100.0, 123.0);
        assert_rel(s.p, 296_867_133.69, 1e-10, "P at 1.1 rho0");
        assert_rel(s.c2, 3_880_427.214_4, 1e-12, "c² at 1.1 rho0");
        // rho = 0.95 rho0 (tension): 0.95^7 = 0.698 337 296 9, P = B * -0.301 662 703 1
        let t = WATER.eval(950.0, 0.0);
        assert_rel(t.p, -94_394_569.52, 1e-9, "P at 0.95 rho0");
        assert_eq!(WATER.eval(1000.0, 0.0).p, 0.0);
        assert_eq!(WATER.eval(1000.0, 0.0).c2, 1480.0 * 1480.0);
    }

    #[test]
    fn c2_is_isentropic_derivative() {
        let states = [(1000.0, 0.0), (1100.0, 1e4), (950.0, 0.0), (1500.0, 1e5)];
        check_c2(|r, e| WATER.eval(r, e), &states);
    }

    #[test]
    fn finite_everywhere() {
        check_finite(|r, e| WATER.eval(r, e), 1000.0, 1e5);
    }

    /// As gamma -> 0 the pressure tends to the logarithmic EOS's `rho0 c0² ln eta` (the
    /// plain `eta^gamma - 1` rounds to 0 there), and gamma = 1 is the linear EOS.
    #[test]
    fn small_gamma_tends_to_the_logarithmic_eos() {
        let ln_p = 1000.0 * 1480.0 * 1480.0 * libm::log(1.1);
        for gamma in [1e-300, 1e-20, 1e-8] {
            let s = Murnaghan { gamma, ..WATER }.eval(1100.0, 0.0);
            assert_rel(s.p, ln_p, 1e-7, "P at gamma -> 0");
            assert_rel(s.c2, 1480.0 * 1480.0 / 1.1, 1e-7, "c² at gamma -> 0");
        }
        let lin = Murnaghan {
            gamma: 1.0,
            ..WATER
        }
        .eval(1100.0, 0.0);
        assert_rel(lin.p, 1480.0 * 1480.0 * 100.0, 1e-12, "P at gamma = 1");
    }

    #[test]
    fn parameters_are_checked() {
        assert_eq!(WATER.check(), Ok(()));
        let e = Murnaghan {
            gamma: 0.0,
            ..WATER
        }
        .check()
        .unwrap_err();
        assert_eq!((e.key, e.value), ("gamma", 0.0));
        let e = Murnaghan { c0: -1.0, ..WATER }.check().unwrap_err();
        assert_eq!(e.key, "c0");
        let g = super::super::Eos::from(WATER);
        assert_eq!((g.name(), g.hugoniot_slope()), ("murnaghan", 2.0));
    }
}
