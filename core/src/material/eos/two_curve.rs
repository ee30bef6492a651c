//! Mie–Grüneisen EOS with two reference curves (seed 004 eqs 6–7), `x = rho0/rho`:
//!
//! `P = P_ref(x) + gamma rho (e - e_ref(x))`, with
//! * `x <= 1` (compression): `P_ref = rho0 c_a² (1-x) / (1 - s_a (1-x))²`,
//!   `e_ref = ½ [c_a (1-x) / (1 - s_a (1-x))]²` (the shock Hugoniot of
//!   `us = c_a + s_a up`, see [`super::hugoniot`]; `e_ref = up²/2`);
//! * `x > 1` (tension): `P_ref = rho0 c_a² (1-x)`, `e_ref = c_a² (1-x)² / 2`.
//!
//! The branches meet at `x = 1` with `P_ref = e_ref = 0`, `dP_ref/dx = -rho0 c_a²` and
//! `de_ref/dx = 0` on both sides.
//!
//! **Erratum (seed 004 eq 6).** The paper prints `P_ref` for `x <= 1` without the square
//! in the denominator. With `e_ref` as printed (`= up²/2`), the reference curve is the
//! Hugoniot only if the Rankine–Hugoniot energy relation
//! `e_ref = P_ref (1/rho0 - 1/rho)/2 = P_ref (1-x)/(2 rho0)` holds, which requires the
//! squared denominator (the printed form gives `c_a² (1-x)²/(2 (1-s_a(1-x)))`). We use
//! the squared form; a test checks the energy relation.
//!
//! Sound speed (`dP/de|_rho = gamma rho`):
//! `c² = dP_ref/drho + gamma (e - e_ref) - gamma rho de_ref/drho + gamma P/rho`, floored in
//! the unstable states of deep tension (parent module). Compression guard: the reference
//! curves continue along their tangents beyond [`super::guard_density`].

use super::hugoniot::{linear_us_up_hugoniot, RefCurve};
use super::state::{floor_c2, EosState};
use crate::material::params::ranges::*;
use crate::material::params::{non_negative, physical, positive, ParamError};
use crate::math::Real;

/// Parameters of the two-curve Mie–Grüneisen EOS (seed 004 eqs 6–7).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(deny_unknown_fields)
)]
pub struct TwoCurve {
    /// Reference density rho0, kg/m³.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub rho0: Real,
    /// Bulk sound speed c_a (intercept of `us = c_a + s_a up`), m/s.
    pub c_a: Real,
    /// Slope s_a of `us = c_a + s_a up`, dimensionless.
    pub s_a: Real,
    /// Grüneisen coefficient gamma (constant), dimensionless.
    pub gamma: Real,
}

impl TwoCurve {
    /// Checks the parameters (all but `rho0`, the material's): the rules the model's
    /// formulas need ([`crate::material::params`]).
    pub fn check(&self) -> Result<(), ParamError> {
        positive("c_a", self.c_a)?;
        physical("c_a", self.c_a, SOUND_SPEED, "m/s")?;
        non_negative("s_a", self.s_a)?;
        physical("s_a", self.s_a, COEFFICIENT, "")?;
        physical("gamma", self.gamma, COEFFICIENT, "")
    }

    /// Reference curves `P_ref`, `e_ref` and their `rho` derivatives at `rho` (kg/m³).
    #[inline]
    fn reference(&self, rho: Real) -> RefCurve {
        if rho >= self.rho0 {
            linear_us_up_hugoniot(self.rho0, self.c_a, self.s_a, rho)
        } else {
            let c2 = self.c_a * self.c_a;
            let y = 1.0 - self.rho0 / rho; // = 1 - x < 0
            let dy = self.rho0 / (rho * rho);
            RefCurve {
                p: self.rho0 * c2 * y,
                dp: self.rho0 * c2 * dy,
                e: 0.5 * c2 * y * y,
                de: c2 * y * dy,
            }
        }
    }

    /// Pressure (Pa) and `c²` (m²/s²) at `rho` (kg/m³), `e` (J/kg).
    #[inline]
    pub fn eval(&self, rho: Real, e: Real) -> EosState {
        let r = self.reference(rho);
        let g = self.gamma;
        let p = r.p + g * rho * (e - r.e);
        let dp_drho_e = r.dp + g * (e - r.e) - g * rho * r.de;
        let c2 = dp_drho_e + g * p / rho;
        EosState {
            p,
            c2: floor_c2(c2, self.c_a * self.c_a),
        }
    }
}

// Tolerances are for f64: the accuracy targets apply to f64 (DESIGN §1).
#[cfg(all(test, not(feature = "f32")))]
mod tests {
    use super::super::test_util::*;
    use super::*;

    const CU: TwoCurve = TwoCurve {
        rho0: 8960.0,
        c_a: 3930.0,
        s_a: 1.5,
        gamma: 1.7,
    };

    #[test]
    fn hand_values() {
        // x = 0.9: 3930² = 15 444 900, rho0 c_a² = 138 386 304 000,
        // P_ref = 0.1 * 138 386 304 000 / 0.85² = 19 153 813 702.42 Pa,
        // e_ref = ½ (393 / 0.85)² = 106 885.121 J/kg
        let rho = 8960.0 / 0.9;
        assert_rel(
            CU.eval(rho, 106_885.121_107_266_4).p,
            19_153_813_702.42,
            1e-12,
            "P_ref",
        );
        // e = 0: P = P_ref - gamma rho e_ref
        let p_ref = 8960.0 * 3930.0 * 3930.0 * 0.1 / (0.85 * 0.85);
        let e_ref = 0.5 * (3930.0 * 0.1 / 0.85) * (3930.0 * 0.1 / 0.85);
        assert_rel(
            CU.eval(rho, 0.0).p,
            p_ref - 1.7 * rho * e_ref,
            1e-13,
            "P(e=0)",
        );
        // tension, x = 1.2, e = 5e4
        let rho = 8960.0 / 1.2;
        let p = 8960.0 * 15_444_900.0 * -0.2 + 1.7 * rho * (5e4 - 15_444_900.0 * 0.04 / 2.0);
        assert_rel(CU.eval(rho, 5e4).p, p, 1e-13, "P tension");
    }

    #[test]
    fn zero_at_reference() {
        assert_eq!(CU.eval(8960.0, 0.0).p, 0.0);
        assert_eq!(CU.eval(8960.0, 0.0).c2, 3930.0 * 3930.0);
    }

    #[test]
    fn reference_curve_is_hugoniot_erratum() {
        // e_ref == P_ref (1/rho0 - 1/rho)/2 with the squared denominator, and
        // P_ref = rho0 us up on us = c_a + s_a up
        for up in [10.0, 200.0, 1000.0, 3000.0] {
            let us = 3930.0 + 1.5 * up;
            let rho = 8960.0 * us / (us - up);
            let r = CU.reference(rho);
            assert_rel(
                r.e,
                0.5 * r.p * (1.0 / 8960.0 - 1.0 / rho),
                1e-12,
                "RH energy",
            );
            assert_rel(r.p, 8960.0 * us * up, 1e-12, "P_ref = rho0 us up");
            // the printed (unsquared) form would violate the energy relation
            let y = 1.0 - 8960.0 / rho;
            let p_printed = 8960.0 * 3930.0 * 3930.0 * y / (1.0 - 1.5 * y);
            let e_rh_printed = 0.5 * p_printed * y / 8960.0;
            assert!((e_rh_printed / r.e - 1.0).abs() > 1e-3);
        }
    }

    #[test]
    fn branches_meet_smoothly() {
        let d = 1e-9 * 8960.0;
        let (lo, hi) = (CU.reference(8960.0 - d), CU.reference(8960.0 + d));
        assert_rel(lo.dp, hi.dp, 1e-7, "dP_ref/drho");
        // de_ref/drho = c_a² y rho0/rho² -> 0 on both sides
        let scale = 3930.0 * 3930.0 / 8960.0;
        assert!(lo.de.abs() < 1e-8 * scale && hi.de.abs() < 1e-8 * scale);
        assert!(
            lo.p.abs() < 1e-8 * 8960.0 * 3930.0 * 3930.0
                && hi.p.abs() < 1e-8 * 8960.0 * 3930.0 * 3930.0
        );
        let (a, b) = (CU.eval(8960.0 - d, 1e5), CU.eval(8960.0 + d, 1e5));
        assert_rel(a.c2, b.c2, 1e-7, "c2 across x = 1");
    }

    #[test]
    fn c2_is_isentropic_derivative() {
        // off rho0 itself: P_ref is only C1 there (d²P_ref/dy² jumps by 4 s_a rho0 c_a²),
        // which spoils a central difference straddling it
        let states = [
            (8970.0, 0.0),
            (8950.0, 1e3),
            (9500.0, 1e5),
            (12000.0, 0.0),
            (16000.0, 2e6),
            (8500.0, 1e4),
            (7000.0, 2e5),
        ];
        check_c2(|r, e| CU.eval(r, e), &states);
    }

    #[test]
    fn finite_beyond_guard() {
        check_finite(|r, e| CU.eval(r, e), 8960.0, 1e6);
        let pole = 8960.0 * 1.5 / 0.5;
        for rho in [pole * (1.0 - 1e-13), pole, 1.1 * pole, 1e3 * pole] {
            let s = CU.eval(rho, 0.0);
            assert!(s.p.is_finite() && s.c2.is_finite() && s.c2 > 0.0);
        }
    }
}
