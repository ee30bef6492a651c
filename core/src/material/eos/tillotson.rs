//! Tillotson EOS (J. H. Tillotson, "Metallic equations of state for hypervelocity impact",
//! General Atomic report GA-3216, 1962), in the form of Melosh, "Impact Cratering" (1989),
//! and Benz & Asphaug 1999 (Icarus 142, 5–20). With `eta = rho/rho0`, `mu = eta - 1`,
//! `z = rho0/rho - 1` and `w = e/(E0 eta²) + 1`:
//!
//! * compressed (`rho >= rho0`), or expanded and cold (`rho < rho0`, `e <= E_iv`):
//!   `P_c = [a + b/w] rho e + A mu + B mu²`;
//! * expanded and hot (`rho < rho0`, `e >= E_cv`):
//!   `P_e = a rho e + [b rho e/w + A mu exp(-beta z)] exp(-alpha z²)`;
//! * between (`rho < rho0`, `E_iv < e < E_cv`): `P = y P_e + (1 - y) P_c` with
//!   `y = (e - E_iv)/(E_cv - E_iv)`.
//!
//! `B mu²` is kept wherever `P_c` applies, in the cold expanded states too (where `mu < 0`),
//! as in the formulas above and the Tillotson library of Reinhardt & Stadel; some codes drop
//! it below `rho0`. The labels of `alpha` and `beta` follow the formulas above (`alpha` in
//! the Gaussian `exp(-alpha z²)`, `beta` in `exp(-beta z)`); published transcriptions of
//! `P_e` differ in which constant is which, which matters only when `alpha != beta`. The
//! forms were not checked against Tillotson's report or Melosh's book here.
//!
//! ## Derivatives
//! With `g = b rho e/w` (note `dw/drho|_e = -2 (w-1)/rho`, `dw/de|_rho = 1/(E0 eta²)`):
//! `dg/drho|_e = b e/w (3 - 2/w)`, `dg/de|_rho = b rho/w²`;
//! `dP_c/drho = a e + dg/drho + (A + 2 B mu)/rho0`, `dP_c/de = a rho + dg/de`.
//! With `h = A mu exp(-beta z)`, `G = exp(-alpha z²)` and `dz/drho = -1/(rho0 eta²)`:
//! `dh/drho = A exp(-beta z)/rho0 (1 + beta mu/eta²)`, `dG/drho = G 2 alpha z/(rho0 eta²)`;
//! `dP_e/drho = a e + (dg/drho + dh/drho) G + (g + h) dG/drho`, `dP_e/de = a rho + G dg/de`.
//! In between, the interpolation is differentiated, the energy dependence of the weight
//! included: `dP/drho = y dP_e/drho + (1-y) dP_c/drho`,
//! `dP/de = y dP_e/de + (1-y) dP_c/de + (P_e - P_c)/(E_cv - E_iv)`. Then
//! `c² = dP/drho + P/rho² dP/de` (module doc of the parent).
//!
//! ## Continuity and limits
//! At `rho = rho0` (`z = 0`, `mu = 0`) `P_e = P_c` and `dP_e/drho = dP_c/drho`, so `P` is C¹
//! across `rho0` at every energy. `P` is continuous across `e = E_iv` and `e = E_cv`; `c²`
//! jumps there (the weight's slope `1/(E_cv - E_iv)` switches on and off), as in every
//! Tillotson implementation. Far in expansion the hot branch tends to the ideal gas
//! `P = a rho e`.
//!
//! Negative energies (below the reference state, where the fit means nothing; `w` would
//! vanish at `e = -E0 eta²`) continue `P_c` along its tangent in `e` at `e = 0`:
//! `P = A mu + B mu² + (a + b) rho e`, a Mie–Grüneisen form with `Gamma = a + b`, so `P`
//! and `c²` are continuous at `e = 0` and finite for every energy.
//!
//! The cold branch reaches `c² <= 0` in tension (`A + 2 B mu < 0` below
//! `eta = 1 - A/(2B)`, and a negative `P` times `dP/de`); there `c²` is floored at
//! [`super::C2_FLOOR_FRACTION`] times the reference `c0² = A/rho0` (parent module).

use super::state::{floor_c2, EosState};
use crate::material::params::ranges::*;
use crate::material::params::{check, non_negative, physical, positive, ParamError, Rule};
use crate::math::{real, Real};

/// Parameters of the Tillotson EOS (Tillotson 1962; Melosh 1989; Benz & Asphaug 1999).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(deny_unknown_fields)
)]
pub struct Tillotson {
    /// Reference density rho0, kg/m³.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub rho0: Real,
    /// Tillotson `a` (Grüneisen-like constant of the `rho e` term), dimensionless.
    pub a: Real,
    /// Tillotson `b` (its energy-dependent part, `a + b` is Gamma at `rho0`, `e = 0`),
    /// dimensionless.
    pub b: Real,
    /// Tillotson `A` (bulk modulus at `rho0`), Pa.
    pub big_a: Real,
    /// Tillotson `B` (coefficient of `mu²`), Pa.
    pub big_b: Real,
    /// Tillotson `alpha` (Gaussian decay `exp(-alpha z²)` of the hot expanded states),
    /// dimensionless.
    pub alpha: Real,
    /// Tillotson `beta` (decay `exp(-beta z)` of the `A mu` term in hot expansion),
    /// dimensionless.
    pub beta: Real,
    /// Tillotson `E0` (energy scale of `w = e/(E0 eta²) + 1`), J/kg.
    pub e0: Real,
    /// Energy of incipient vaporisation `E_iv` (cold/intermediate boundary below rho0),
    /// J/kg.
    pub e_iv: Real,
    /// Energy of complete vaporisation `E_cv` (intermediate/hot boundary below rho0),
    /// J/kg; `E_cv > E_iv`.
    pub e_cv: Real,
}

/// `(P, dP/drho|_e, dP/de|_rho)` of one branch, Pa, m²/s², kg/m³.
type Branch = (Real, Real, Real);

impl Tillotson {
    /// Checks the parameters (all but `rho0`, the material's): the rules the model's
    /// formulas need ([`crate::material::params`]).
    pub fn check(&self) -> Result<(), ParamError> {
        for (key, v) in [
            ("a", self.a),
            ("b", self.b),
            ("alpha", self.alpha),
            ("beta", self.beta),
        ] {
            non_negative(key, v)?;
            physical(key, v, COEFFICIENT, "")?;
        }
        positive("big_a", self.big_a)?;
        physical("big_a", self.big_a, BULK_MODULUS, "Pa")?;
        physical("big_b", self.big_b, SIGNED_MODULUS, "Pa")?;
        positive("e0", self.e0)?;
        physical("e0", self.e0, SPECIFIC_ENERGY, "J/kg")?;
        non_negative("e_iv", self.e_iv)?;
        physical("e_iv", self.e_iv, SPECIFIC_ENERGY, "J/kg")?;
        physical("e_cv", self.e_cv, SPECIFIC_ENERGY, "J/kg")?;
        check(
            "e_cv",
            self.e_cv,
            Rule::Exceeds {
                other: "e_iv",
                bound: self.e_iv,
                unit: "J/kg",
            },
        )
    }

    /// The compressed / cold-expanded branch `P_c` and its derivatives at `rho` (kg/m³),
    /// `e >= 0` (J/kg).
    #[inline]
    fn cold(&self, rho: Real, e: Real) -> Branch {
        let eta = rho / self.rho0;
        let mu = eta - 1.0;
        let (g, dg_drho, dg_de) = self.g_term(rho, e, eta);
        (
            self.a * rho * e + g + (self.big_a + self.big_b * mu) * mu,
            self.a * e + dg_drho + (self.big_a + 2.0 * self.big_b * mu) / self.rho0,
            self.a * rho + dg_de,
        )
    }

    /// The hot expanded branch `P_e` and its derivatives at `rho < rho0` (kg/m³), `e >= 0`
    /// (J/kg).
    #[inline]
    fn hot(&self, rho: Real, e: Real) -> Branch {
        let eta = rho / self.rho0;
        let mu = eta - 1.0;
        let z = 1.0 / eta - 1.0;
        let (g, dg_drho, dg_de) = self.g_term(rho, e, eta);
        let decay = real::exp(-self.beta * z);
        let gauss = real::exp(-self.alpha * z * z);
        let inv_r0e2 = 1.0 / (self.rho0 * eta * eta);
        let h = self.big_a * mu * decay;
        let dh_drho = self.big_a * decay / self.rho0 * (1.0 + self.beta * mu / (eta * eta));
        let dgauss_drho = gauss * 2.0 * self.alpha * z * inv_r0e2;
        (
            self.a * rho * e + (g + h) * gauss,
            self.a * e + (dg_drho + dh_drho) * gauss + (g + h) * dgauss_drho,
            self.a * rho + dg_de * gauss,
        )
    }

    /// `g = b rho e/w`, `dg/drho|_e`, `dg/de|_rho` (`w = e/(E0 eta²) + 1`, `e >= 0`),
    /// written with `1/w` so that `w = inf` (vast `e/eta²`) gives 0, not NaN.
    #[inline]
    fn g_term(&self, rho: Real, e: Real, eta: Real) -> Branch {
        let x = if e > 0.0 {
            e / (self.e0 * eta * eta)
        } else {
            0.0
        };
        let iw = 1.0 / (x + 1.0);
        (
            self.b * rho * e * iw,
            self.b * e * iw * (3.0 - 2.0 * iw),
            self.b * rho * iw * iw,
        )
    }

    /// `(P, dP/drho|_e, dP/de|_rho)` at `rho` (kg/m³), `e` (J/kg), see the module doc for
    /// the regions and for `e < 0`.
    #[inline]
    fn branches(&self, rho: Real, e: Real) -> Branch {
        if e < 0.0 {
            // tangent of P_c in e at e = 0: dP_c/de = (a + b) rho, d²P_c/drho de = a + b
            let (p0, dp_drho0, dp_de0) = self.cold(rho, 0.0);
            return (p0 + dp_de0 * e, dp_drho0 + (self.a + self.b) * e, dp_de0);
        }
        if rho >= self.rho0 || e <= self.e_iv {
            return self.cold(rho, e);
        }
        if e >= self.e_cv {
            return self.hot(rho, e);
        }
        let (pc, pc_rho, pc_e) = self.cold(rho, e);
        let (pe, pe_rho, pe_e) = self.hot(rho, e);
        let inv_de = 1.0 / (self.e_cv - self.e_iv);
        let y = (e - self.e_iv) * inv_de;
        (
            y * pe + (1.0 - y) * pc,
            y * pe_rho + (1.0 - y) * pc_rho,
            y * pe_e + (1.0 - y) * pc_e + (pe - pc) * inv_de,
        )
    }

    /// Pressure (Pa) and `c²` (m²/s²) at `rho` (kg/m³), `e` (J/kg).
    #[inline]
    pub fn eval(&self, rho: Real, e: Real) -> EosState {
        let (p, dp_drho, dp_de) = self.branches(rho, e);
        let c2 = dp_drho + p / (rho * rho) * dp_de;
        EosState {
            p,
            c2: floor_c2(c2, self.big_a / self.rho0),
        }
    }
}

// Tolerances are for f64: the accuracy targets apply to f64 (DESIGN §1).
#[cfg(all(test, not(feature = "f32")))]
mod tests {
    use super::super::test_util::*;
    use super::super::C2_FLOOR_FRACTION;
    use super::*;

    /// Aluminium (Tillotson 1962 as tabulated by Melosh 1989 and Benz & Asphaug 1999;
    /// cases/materials/al_tillotson.toml).
    const AL: Tillotson = Tillotson {
        rho0: 2700.0,
        a: 0.5,
        b: 1.63,
        big_a: 75.2e9,
        big_b: 65.0e9,
        alpha: 5.0,
        beta: 5.0,
        e0: 5.0e6,
        e_iv: 3.0e6,
        e_cv: 13.9e6,
    };

    /// `P` straight from the formulas of the module doc (no shared code with `eval`).
    fn p_c(rho: Real, e: Real) -> Real {
        let eta = rho / 2700.0;
        let mu = eta - 1.0;
        (0.5 + 1.63 / (e / (5.0e6 * eta * eta) + 1.0)) * rho * e + 75.2e9 * mu + 65.0e9 * mu * mu
    }
    fn p_e(rho: Real, e: Real) -> Real {
        let eta = rho / 2700.0;
        let mu = eta - 1.0;
        let z = 2700.0 / rho - 1.0;
        0.5 * rho * e
            + (1.63 * rho * e / (e / (5.0e6 * eta * eta) + 1.0) + 75.2e9 * mu * (-5.0 * z).exp())
                * (-5.0 * z * z).exp()
    }

    #[test]
    fn hand_values_in_each_region() {
        // compressed: rho = 3240 (eta = 1.2, mu = 0.2), e = 1e6 J/kg.
        // w = 1e6/(5e6 * 1.44) + 1 = 41/36; b/w = 1.63 * 36/41 = 58.68/41;
        // rho e = 3.24e9: a rho e = 1.62e9, b rho e/w = 190.1232e9/41 = 4.637 151 219 512 195e9;
        // A mu = 15.04e9, B mu² = 65e9 * 0.04 = 2.6e9.
        // P = 1.62e9 + 4.637 151 219 512 195e9 + 15.04e9 + 2.6e9 = 23.897 151 219 512 195e9 Pa
        let s = AL.eval(3240.0, 1.0e6);
        assert_rel(
            s.p,
            1.62e9 + 190.1232e9 / 41.0 + 15.04e9 + 2.6e9,
            1e-14,
            "P_c",
        );
        assert_rel(s.p, 23.897_151_219_512_195e9, 1e-12, "P_c literal");

        // cold expanded: rho = 2430 (eta = 0.9, mu = -0.1), e = 1e6 <= E_iv.
        // w = 1e6/(5e6 * 0.81) + 1 = 101/81; b/w = 132.03/101; rho e = 2.43e9:
        // a rho e = 1.215e9, b rho e/w = 320.8329e9/101 = 3.176 563 366 336 634e9;
        // A mu = -7.52e9, B mu² = 65e9 * 0.01 = 0.65e9.
        // P = 1.215e9 + 3.176 563 366 336 634e9 - 7.52e9 + 0.65e9 = -2.478 436 633 663 366e9 Pa
        let s = AL.eval(2430.0, 1.0e6);
        assert_rel(
            s.p,
            1.215e9 + 320.8329e9 / 101.0 - 7.52e9 + 0.65e9,
            1e-14,
            "P cold",
        );
        assert_rel(s.p, -2.478_436_633_663_366e9, 1e-12, "P cold literal");

        // hot expanded: rho = 2160 (eta = 0.8, mu = -0.2, z = 0.25), e = 2e7 >= E_cv.
        // w = 2e7/(5e6 * 0.64) + 1 = 7.25; rho e = 4.32e10: a rho e = 2.16e10,
        // b rho e/w = 7.0416e10/7.25 = 9.712 551 724 137 931e9;
        // A mu exp(-beta z) = -15.04e9 exp(-1.25) = -15.04e9 * 0.286 504 796 860 190 10
        //   = -4.309 032 144 777 259e9; exp(-alpha z²) = exp(-0.3125) = 0.731 615 628 946 641 79.
        // P = 2.16e10 + (9.712 551 724 137 931e9 - 4.309 032 144 777 259e9) * 0.731 615 628 946 641 79
        //   = 2.16e10 + 5.403 519 579 360 672e9 * 0.731 615 628 946 641 79
        //   = 25.553 299 375 579 451e9 Pa
        let s = AL.eval(2160.0, 2.0e7);
        assert_rel(s.p, 25.553_299_375_579_451e9, 1e-12, "P hot literal");

        // intermediate: rho = 2430 (eta = 0.9, mu = -0.1, z = 1/9), e = 8e6,
        // y = (8 - 3)/(13.9 - 3) = 50/109. w = 8e6/(5e6 * 0.81) + 1 = 241/81; rho e = 1.944e10:
        // a rho e = 9.72e9, b rho e/w = 1.944e10 * 132.03/241 = 10.650 054 771 784 232e9.
        // P_c = 9.72e9 + 10.650 054 771 784 232e9 - 7.52e9 + 0.65e9 = 13.500 054 771 784 232e9;
        // A mu exp(-beta z) = -7.52e9 exp(-5/9) = -7.52e9 * 0.573 753 420 737 432 80
        //   = -4.314 625 723 945 495e9; exp(-alpha z²) = exp(-5/81) = 0.940 138 198 294 901 46;
        // P_e = 9.72e9 + (10.650 054 771 784 232e9 - 4.314 625 723 945 495e9) * 0.940 138 198 294 901 46
        //   = 15.676 178 850 460 294e9;
        // P = (50 P_e + 59 P_c)/109 = 14.498 276 826 222 793e9 Pa
        let s = AL.eval(2430.0, 8.0e6);
        assert_rel(
            s.p,
            (50.0 * 15.676_178_850_460_294e9 + 59.0 * 13.500_054_771_784_232e9) / 109.0,
            1e-12,
            "P intermediate",
        );
        assert_rel(
            s.p,
            14.498_276_826_222_793e9,
            1e-12,
            "P intermediate literal",
        );
    }

    #[test]
    fn alpha_and_beta_sit_where_the_module_doc_says() {
        // hot expanded with alpha = 3, beta = 8: rho = 2160 (z = 0.25), e = 2e7 as above;
        // A mu exp(-beta z) = -15.04e9 exp(-2) = -15.04e9 * 0.135 335 283 236 612 69
        //   = -2.035 442 659 878 655e9; exp(-alpha z²) = exp(-0.1875) = 0.829 029 118 180 400 34;
        // P = 2.16e10 + (9.712 551 724 137 931e9 - 2.035 442 659 878 655e9) * 0.829 029 118 180 400 34
        //   = 27.964 546 957 717 626e9 Pa (swapped, exp(-0.75) and exp(-0.5): 23.18e9 Pa)
        let m = Tillotson {
            alpha: 3.0,
            beta: 8.0,
            ..AL
        };
        assert_rel(
            m.eval(2160.0, 2.0e7).p,
            27.964_546_957_717_626e9,
            1e-12,
            "P hot",
        );
    }

    #[test]
    fn zero_at_reference() {
        let s = AL.eval(2700.0, 0.0);
        assert_eq!(s.p, 0.0);
        // c0² = A/rho0 (e = 0, P = 0)
        assert_eq!(s.c2, 75.2e9 / 2700.0);
    }

    #[test]
    fn continuous_across_rho0_and_at_the_interpolation_ends() {
        // across rho0 at every energy, cold (e <= E_iv), intermediate and hot
        for e in [0.0, 1.0e6, 3.0e6, 5.0e6, 8.0e6, 13.9e6, 2.0e7] {
            let mid = AL.eval(2700.0, e);
            let d = 1e-9 * 2700.0;
            let (lo, hi) = (AL.eval(2700.0 - d, e), AL.eval(2700.0 + d, e));
            let scale = mid.p.abs().max(75.2e9 * 1e-9);
            assert!(
                (lo.p - mid.p).abs() <= 2.0 * mid.c2 * d + 1e-12 * scale,
                "P below at e {e}"
            );
            assert!(
                (hi.p - mid.p).abs() <= 2.0 * mid.c2 * d + 1e-12 * scale,
                "P above at e {e}"
            );
            // the slopes meet too (C¹ across rho0)
            assert_rel(lo.c2, hi.c2, 1e-5, "c2 across rho0");
        }
        // the cold branch at rho0 from both sides, for e <= E_iv: both sides are P_c
        for e in [0.0, 1.0e6, 3.0e6] {
            for rho in [2700.0 * (1.0 - 1e-12), 2700.0 * (1.0 + 1e-12)] {
                assert_rel(AL.eval(rho, e).p, p_c(rho, e), 1e-13, "P_c near rho0");
            }
        }
        // interpolation ends: at E_iv it is P_c, at E_cv P_e, and approached from inside
        for rho in [2430.0, 2160.0, 1350.0, 270.0] {
            assert_rel(AL.eval(rho, 3.0e6).p, p_c(rho, 3.0e6), 1e-13, "P at E_iv");
            assert_rel(AL.eval(rho, 13.9e6).p, p_e(rho, 13.9e6), 1e-13, "P at E_cv");
            let inside_iv = AL.eval(rho, 3.0e6 * (1.0 + 1e-12)).p;
            let inside_cv = AL.eval(rho, 13.9e6 * (1.0 - 1e-12)).p;
            let scale = 75.2e9 * 1e-9;
            assert!(
                (inside_iv - p_c(rho, 3.0e6)).abs() <= 1e-9 * p_c(rho, 3.0e6).abs().max(scale),
                "just above E_iv at rho {rho}: {inside_iv}"
            );
            assert!(
                (inside_cv - p_e(rho, 13.9e6)).abs() <= 1e-9 * p_e(rho, 13.9e6).abs().max(scale),
                "just below E_cv at rho {rho}: {inside_cv}"
            );
        }
    }

    #[test]
    fn c2_is_isentropic_derivative_in_each_region() {
        let states = [
            // compressed
            (2700.0, 0.0),
            (3240.0, 1.0e6),
            (4000.0, 2.0e7),
            (5400.0, 0.0),
            // cold expanded
            (2430.0, 1.0e6),
            (2600.0, 0.0),
            // hot expanded
            (2160.0, 2.0e7),
            (1350.0, 5.0e7),
            (270.0, 1.5e7),
            // intermediate
            (2430.0, 8.0e6),
            (2160.0, 5.0e6),
            (1350.0, 1.2e7),
        ];
        check_c2(|r, e| AL.eval(r, e), &states);
        // alpha != beta, so a swapped pair of exponents in c² would show
        let m = Tillotson {
            alpha: 3.0,
            beta: 8.0,
            ..AL
        };
        check_c2(|r, e| m.eval(r, e), &states[6..]);
    }

    #[test]
    fn finite_everywhere_and_floored_in_deep_cold_tension() {
        // e_scale 2e7: hot (2e7), cold (2e6); 8e6: intermediate, cold; negatives -> e = 0
        check_finite(|r, e| AL.eval(r, e), 2700.0, 2.0e7);
        check_finite(|r, e| AL.eval(r, e), 2700.0, 8.0e6);
        // vast expansion, vast energies
        for rho in [1e-9, 1e-6, 1e-3, 1.0] {
            for e in [0.0, 1e3, 3.5e6, 1e7, 1e12, -1e12] {
                let s = AL.eval(rho, e);
                assert!(
                    s.p.is_finite() && s.c2.is_finite() && s.c2 > 0.0,
                    "{s:?} at {rho}, {e}"
                );
            }
        }
        // eta = 0.3, e = 0: A + 2 B mu = 75.2e9 - 91e9 < 0 and P < 0 -> floored
        assert_eq!(
            AL.eval(0.3 * 2700.0, 0.0).c2,
            C2_FLOOR_FRACTION * 75.2e9 / 2700.0
        );
        // negative energies: P_c(rho, 0) + (a + b) rho e; at rho = 2430, e = -1e5:
        // A mu + B mu² = -7.52e9 + 0.65e9 = -6.87e9, (a + b) rho e = 2.13 * 2430 * -1e5
        // = -5.1759e8, P = -7.38759e9 Pa
        assert_rel(AL.eval(2430.0, -1.0e5).p, -7.387_59e9, 1e-14, "P at e < 0");
        check_c2(|r, e| AL.eval(r, e), &[(2430.0, -1.0e5), (3000.0, -1.0e5)]);
    }
}
