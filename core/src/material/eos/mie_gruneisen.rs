//! Mie–Grüneisen EOS on a linear `Us = c0 + s1 up` Hugoniot with `rho Gamma = rho0 Gamma0`
//! (seed 000 eq 37), `eta = rho/rho0`, `mu = eta - 1`:
//!
//! * compression (`eta >= 1`):
//!   `P = rho0 c0² (eta-1) (eta - Gamma0/2 (eta-1)) / (eta - s1 (eta-1))² + rho0 Gamma0 e`,
//!   i.e. `Q(mu) = rho0 c0² mu (1 + a mu)/(1 - b mu)²` with `a = 1 - Gamma0/2`,
//!   `b = s1 - 1`. This is `P_H + rho0 Gamma0 (e - e_H)` with the Hugoniot `P_H` and
//!   `e_H = P_H (1/rho0 - 1/rho)/2` of [`super::hugoniot`];
//! * tension (`eta < 1`): `P = rho0 c0² (eta - 1) + rho0 Gamma0 e`.
//!
//! The two branches meet at `eta = 1` with equal value (`rho0 Gamma0 e`) and equal slope
//! `dP/drho|_e = c0²`, since `dQ/drho = c0² (1 + (2a + b) mu)/(1 - b mu)³` is `c0²` at
//! `mu = 0` (tested).
//!
//! Sound speed: `c² = dQ/drho + P rho0 Gamma0 / rho²` (`dP/de|_rho = rho0 Gamma0`). In deep
//! tension it reaches zero (with `e = 0`, `c² = c0² (1 - Gamma0 (1-eta)/eta²)`, negative
//! below `eta = 0.732` for `Gamma0 = 2`); there it is floored (parent module).
//!
//! Guard: the denominator `1 - b mu` vanishes at `eta = s1/(s1-1)`; beyond
//! [`super::guard_density`] `Q` continues along its tangent in `rho`, so `P` and `c²` stay
//! finite and continuous for every finite `rho`.

use super::state::{floor_c2, guard_density, EosState};
use crate::material::params::ranges::*;
use crate::material::params::{non_negative, physical, positive, ParamError};
use crate::math::Real;

/// Parameters of the Mie–Grüneisen EOS (seed 000 eq 37).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(deny_unknown_fields)
)]
pub struct MieGruneisen {
    /// Reference density rho0, kg/m³.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub rho0: Real,
    /// Bulk sound speed c0 (intercept of the `Us`–`up` fit), m/s.
    pub c0: Real,
    /// Slope s1 of the `Us`–`up` fit, dimensionless.
    pub s1: Real,
    /// Grüneisen coefficient Gamma0 at rho0, dimensionless.
    pub gamma0: Real,
}

impl MieGruneisen {
    /// Checks the parameters (all but `rho0`, the material's): the rules the model's
    /// formulas need ([`crate::material::params`]).
    pub fn check(&self) -> Result<(), ParamError> {
        positive("c0", self.c0)?;
        physical("c0", self.c0, SOUND_SPEED, "m/s")?;
        non_negative("s1", self.s1)?;
        physical("s1", self.s1, COEFFICIENT, "")?;
        physical("gamma0", self.gamma0, COEFFICIENT, "")
    }

    /// The cold part `Q` (Pa) and `dQ/drho` (m²/s²) at `rho` (kg/m³).
    #[inline]
    fn cold(&self, rho: Real) -> (Real, Real) {
        let c02 = self.c0 * self.c0;
        if rho < self.rho0 {
            return (c02 * (rho - self.rho0), c02);
        }
        let rho_g = guard_density(self.rho0, self.s1);
        let (r, ext) = if rho > rho_g {
            (rho_g, rho - rho_g)
        } else {
            (rho, 0.0)
        };
        let mu = r / self.rho0 - 1.0;
        let a = 1.0 - 0.5 * self.gamma0;
        let b = self.s1 - 1.0;
        let inv_d = 1.0 / (1.0 - b * mu);
        let q = self.rho0 * c02 * mu * (1.0 + a * mu) * inv_d * inv_d;
        let dq = c02 * (1.0 + (2.0 * a + b) * mu) * inv_d * inv_d * inv_d;
        (q + dq * ext, dq)
    }

    /// Pressure (Pa) and `c²` (m²/s²) at `rho` (kg/m³), `e` (J/kg).
    #[inline]
    pub fn eval(&self, rho: Real, e: Real) -> EosState {
        let (q, dq) = self.cold(rho);
        let rg = self.rho0 * self.gamma0;
        let p = q + rg * e;
        let c2 = dq + p * rg / (rho * rho);
        EosState {
            p,
            c2: floor_c2(c2, self.c0 * self.c0),
        }
    }
}

// Tolerances are for f64: the accuracy targets apply to f64 (DESIGN §1).
#[cfg(all(test, not(feature = "f32")))]
mod tests {
    use super::super::test_util::*;
    use super::super::C2_FLOOR_FRACTION;
    use super::*;

    const BE: MieGruneisen = MieGruneisen {
        rho0: 1845.0,
        c0: 12870.0,
        s1: 1.124,
        gamma0: 2.0,
    };

    #[test]
    fn hand_values() {
        // eta = 1.1, e = 0, Gamma0 = 2 (a = 0): rho0 c0² = 1845 * 165 636 900
        // = 305 600 080 500; P = 0.1 * 305 600 080 500 / (1 - 0.0124)² = 3.133 222 970 e10
        let s = BE.eval(1.1 * 1845.0, 0.0);
        assert_rel(s.p, 30_560_008_050.0 / (0.9876 * 0.9876), 1e-13, "P(1.1)");
        assert_rel(s.p, 3.133_222_970_3e10, 1e-9, "P(1.1) literal");
        // eta = 1.5, e = 2e5 J/kg, straight from eq 37
        let (eta, e) = (1.5, 2e5);
        let k = 1845.0 * 12870.0 * 12870.0;
        let p = k * (eta - 1.0) * (eta - 1.0 * (eta - 1.0))
            / ((eta - 1.124 * (eta - 1.0)) * (eta - 1.124 * (eta - 1.0)))
            + 1845.0 * 2.0 * e;
        assert_rel(BE.eval(eta * 1845.0, e).p, p, 1e-14, "P(1.5)");
        // tension: eta = 0.9, e = 1e4: P = -0.1 rho0 c0² + 2 rho0 e
        assert_rel(
            BE.eval(0.9 * 1845.0, 1e4).p,
            -0.1 * k + 3690.0 * 1e4,
            1e-13,
            "P(0.9)",
        );
    }

    #[test]
    fn zero_at_reference() {
        assert_eq!(BE.eval(1845.0, 0.0).p, 0.0);
        assert_eq!(BE.eval(1845.0, 0.0).c2, 12870.0 * 12870.0);
    }

    #[test]
    fn tension_branch_continuous_in_value_and_slope() {
        for e in [0.0, 1e5, -3e4] {
            let d = 1e-7 * 1845.0;
            let (lo, hi) = (BE.eval(1845.0 - d, e), BE.eval(1845.0 + d, e));
            let mid = BE.eval(1845.0, e);
            assert_rel(lo.p, mid.p - mid.c2 * d, 1e-6, "P below");
            assert_rel(hi.p, mid.p + mid.c2 * d, 1e-6, "P above");
            assert_rel(lo.c2, hi.c2, 1e-6, "c2 across eta = 1");
            let (q_lo, dq_lo) = BE.cold(1845.0 * (1.0 - 1e-12));
            let (q_hi, dq_hi) = BE.cold(1845.0 * (1.0 + 1e-12));
            let k = 1845.0 * 12870.0 * 12870.0;
            assert_rel(q_lo, -1e-12 * k, 1e-3, "Q just below");
            assert_rel(q_hi, 1e-12 * k, 1e-3, "Q just above");
            assert_rel(dq_lo, dq_hi, 1e-9, "dQ/drho across eta = 1");
        }
    }

    #[test]
    fn c2_is_isentropic_derivative() {
        let states = [
            (1845.0, 0.0),
            (1.05 * 1845.0, 1e5),
            (1.6 * 1845.0, 3e6),
            (2.5 * 1845.0, 0.0),
            (0.95 * 1845.0, 1e4),
            (0.8 * 1845.0, 5e5),
        ];
        check_c2(|r, e| BE.eval(r, e), &states);
    }

    #[test]
    fn on_hugoniot_energy_term_vanishes() {
        // P(rho_H, e_H) must equal rho0 Us up whatever Gamma0 is
        for up in [100.0, 1000.0, 4000.0] {
            let us = 12870.0 + 1.124 * up;
            let rho = 1845.0 * us / (us - up);
            assert_rel(
                BE.eval(rho, 0.5 * up * up).p,
                1845.0 * us * up,
                1e-12,
                "P_H",
            );
        }
    }

    #[test]
    fn finite_beyond_guard_and_floored_in_deep_tension() {
        check_finite(|r, e| BE.eval(r, e), 1845.0, 1e6);
        let pole = 1845.0 * 1.124 / 0.124;
        for rho in [
            pole * (1.0 - 1e-12),
            pole,
            pole * (1.0 + 1e-12),
            10.0 * pole,
        ] {
            let s = BE.eval(rho, 1e6);
            assert!(s.p.is_finite() && s.p > 0.0 && s.c2.is_finite() && s.c2 > 0.0);
        }
        // eta = 0.5, e = 0: c² = c0² (1 - 2 * 0.5 / 0.25) < 0 -> floor
        assert_eq!(
            BE.eval(0.5 * 1845.0, 0.0).c2,
            C2_FLOOR_FRACTION * 12870.0 * 12870.0
        );
    }
}
