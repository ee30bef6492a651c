//! Johnson–Holmquist JH1 ceramic model (Johnson & Holmquist 1992; seed 000 §5, eq 41,
//! Table 4, figs 6–7) and the no-tension pressure of failed pairs (seed 000 Algorithm 1).
//!
//! Pressure `P` is positive in compression (DESIGN §2); the tensile limit `T` is stored as the
//! (negative) pressure at which the material fails in hydrostatic tension: Table 4's
//! "T = -750 MPa" means `P = -0.75 GPa`.
//!
//! # Curves (all strengths are von Mises equivalent stresses, Pa)
//!
//! * Intact (fig 6): piecewise linear through `(T, 0)`, `(P1, sigma_i1)`, `(P2, sigma_i2)`;
//!   beyond `P2` the second segment continues with the same slope (no cap: JH1 has no
//!   maximum intact strength, only the failed curve is capped); 0 at or below `T`.
//! * Failed (fig 6): `min(c_f P, sigma_f_max)` for `P > 0`, 0 in tension (failed material
//!   carries no tension).
//! * Both are multiplied by the strain-rate factor `1 + C ln(max(rate/rate0, 1))` (JH1 applies
//!   it to intact and failed strength). `rate` is the equivalent strain rate supplied by the
//!   caller (JH1 uses the total equivalent strain rate, so the return stays explicit); the
//!   ratio is floored at 1, so slow loading never softens.
//! * Failure strain (fig 7): `eps_f(P) = eps_f_max clamp((P - T)/(P_max - T), 0, 1)`: 0 at
//!   `P = T`, linear in `P`, `eps_f_max` at and beyond `P_max`.
//!
//! # Damage (seed 000 eq 41)
//!
//! `D = sum dEps_p / eps_f(P)`, monotonic, capped at 1; `D = 1` as soon as `P <= T`. While
//! `D < 1` the intact curve applies; at `D = 1` the material fails instantaneously (JH1,
//! unlike the gradual softening of JH2) and follows the failed curve. When the increment that
//! completes the damage happens within a step, the deviator is returned onto the failed
//! curve in that same step (its extra plastic strain and work are reported).
use super::von_mises::radial_return;
use crate::material::params::ranges::*;
use crate::material::params::{check, exceeds, non_negative, physical, positive, ParamError, Rule};
use crate::math::real::{ln, max, min};
use crate::math::{Real, Sym3};

/// JH1 parameters (SI units). The shear modulus (SiC: 1.93 Mbar = 193 GPa) belongs to the
/// material, not to this struct.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(deny_unknown_fields)
)]
pub struct Jh1 {
    /// Intact strength at `p1`, Pa.
    pub sigma_i1: Real,
    /// First pressure of the intact curve, Pa.
    pub p1: Real,
    /// Intact strength at `p2`, Pa.
    pub sigma_i2: Real,
    /// Second pressure of the intact curve, Pa (> `p1`).
    pub p2: Real,
    /// Maximum strength of the failed material, Pa.
    pub sigma_f_max: Real,
    /// Slope of the failed curve `sigma_f = c_f P` (dimensionless).
    pub c_f: Real,
    /// Tensile limit T as a pressure, Pa (negative: hydrostatic tension).
    pub tensile_limit: Real,
    /// Failure strain at and beyond `p_max` (dimensionless).
    pub eps_f_max: Real,
    /// Pressure at which the failure strain reaches `eps_f_max`, Pa.
    pub p_max: Real,
    /// Strain-rate coefficient C (dimensionless).
    pub c: Real,
    /// Reference strain rate, 1/s (1 in JH1).
    #[cfg_attr(feature = "serde", serde(default = "crate::material::params::one"))]
    pub eps_dot0: Real,
}

/// Result of one JH1 update.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Jh1Update {
    /// Deviator after the return, Pa.
    pub s: Sym3,
    /// Equivalent plastic strain increment of this step (>= 0).
    pub d_eps_p: Real,
    /// Damage after the step, in `[damage_in, 1]`.
    pub damage: Real,
    /// Plastic work per unit volume of this step, J/m³ (>= 0).
    pub plastic_work: Real,
    /// True if the material is failed (`damage == 1`).
    pub failed: bool,
}

impl Jh1 {
    /// Checks the parameters: strengths, `p1`, `eps_f_max`, `p_max`, `eps_dot0` > 0;
    /// `p2 > p1`; `sigma_f_max`, `c_f`, `c` >= 0; `tensile_limit` < 0.
    pub fn check(&self) -> Result<(), ParamError> {
        for (key, v) in [
            ("sigma_i1", self.sigma_i1),
            ("p1", self.p1),
            ("sigma_i2", self.sigma_i2),
            ("p_max", self.p_max),
        ] {
            positive(key, v)?;
            physical(key, v, STRESS, "Pa")?;
        }
        exceeds("p2", self.p2, "p1", self.p1, "Pa")?;
        physical("p2", self.p2, STRESS, "Pa")?;
        non_negative("sigma_f_max", self.sigma_f_max)?;
        physical("sigma_f_max", self.sigma_f_max, STRESS, "Pa")?;
        non_negative("c_f", self.c_f)?;
        physical("c_f", self.c_f, COEFFICIENT, "")?;
        let tension = Rule::Negative {
            meaning: "a hydrostatic tension",
        };
        check("tensile_limit", self.tensile_limit, tension)?;
        physical("tensile_limit", self.tensile_limit, TENSION, "Pa")?;
        positive("eps_f_max", self.eps_f_max)?;
        physical("eps_f_max", self.eps_f_max, COEFFICIENT, "")?;
        non_negative("c", self.c)?;
        physical("c", self.c, COEFFICIENT, "")?;
        positive("eps_dot0", self.eps_dot0)?;
        physical("eps_dot0", self.eps_dot0, STRAIN_RATE, "1/s")
    }

    /// Silicon carbide of seed 000 Table 4: sigma_i1 7.1 GPa, P1 2.5 GPa, sigma_i2 12.2 GPa,
    /// P2 10.0 GPa, sigma_f_max 1.3 GPa, c_f 0.4, T -0.75 GPa, eps_f_max 0.8,
    /// P_max 99.75 GPa, C 0.009, rate0 1/s (shear modulus 1.93 Mbar = 193 GPa, on the material).
    pub const fn sic_seed000() -> Self {
        Jh1 {
            sigma_i1: 7.1e9,
            p1: 2.5e9,
            sigma_i2: 12.2e9,
            p2: 10.0e9,
            sigma_f_max: 1.3e9,
            c_f: 0.4,
            tensile_limit: -0.75e9,
            eps_f_max: 0.8,
            p_max: 99.75e9,
            c: 0.009,
            eps_dot0: 1.0,
        }
    }

    /// Static intact strength (fig 6), Pa, at pressure `p` (Pa): `sigma_i1 (P - T)/(P1 - T)`
    /// on `T < P < P1`, `sigma_i1 + (sigma_i2 - sigma_i1)(P - P1)/(P2 - P1)` for `P >= P1`
    /// (extrapolated beyond P2, and never below 0: a softening curve, `sigma_i2 < sigma_i1`,
    /// stops at 0), 0 at or below T (and for a NaN pressure).
    pub fn intact_strength(&self, p: Real) -> Real {
        let t = self.tensile_limit;
        if p.is_nan() || p <= t {
            0.0
        } else if p < self.p1 {
            self.sigma_i1 * (p - t) / (self.p1 - t)
        } else {
            let s = self.sigma_i1
                + (self.sigma_i2 - self.sigma_i1) * (p - self.p1) / (self.p2 - self.p1);
            max(s, 0.0)
        }
    }

    /// Static failed strength (fig 6), Pa: `min(c_f P, sigma_f_max)` for `P > 0`, 0 otherwise.
    pub fn failed_strength(&self, p: Real) -> Real {
        if p > 0.0 {
            min(self.c_f * p, self.sigma_f_max)
        } else {
            0.0
        }
    }

    /// Failure strain (fig 7): `eps_f_max clamp((P - T)/(P_max - T), 0, 1)` (dimensionless);
    /// 0 at or below T and for a NaN pressure.
    pub fn failure_strain(&self, p: Real) -> Real {
        let t = self.tensile_limit;
        self.eps_f_max * min(max((p - t) / (self.p_max - t), 0.0), 1.0)
    }

    /// Strain-rate factor `1 + C ln(max(rate/rate0, 1))` of the equivalent strain rate
    /// `strain_rate` (1/s); NaN or slow rates give 1.
    #[inline]
    pub fn rate_factor(&self, strain_rate: Real) -> Real {
        1.0 + self.c * ln(max(strain_rate / self.eps_dot0, 1.0))
    }

    /// Current strength, Pa: intact (`failed == false`) or failed curve at `p`, times the
    /// strain-rate factor.
    pub fn strength(&self, p: Real, failed: bool, strain_rate: Real) -> Real {
        let s = if failed {
            self.failed_strength(p)
        } else {
            self.intact_strength(p)
        };
        s * self.rate_factor(strain_rate)
    }

    /// One JH1 step: radial return (see [`radial_return`]) of the trial deviator `s_trial`
    /// (Pa) with shear modulus `shear_modulus` (Pa) at pressure `p` (Pa, compression
    /// positive), damage `damage` at the start of the step and equivalent strain rate
    /// `strain_rate` (1/s).
    ///
    /// * `P <= T` (or a NaN pressure), or `damage >= 1` (or NaN): failed; `D = 1`, return onto
    ///   the failed curve (no deviator in tension).
    /// * otherwise return onto the intact curve and accumulate
    ///   `D += d_eps_p / eps_f(P)` (seed 000 eq 41, `D = 1` if `eps_f = 0`), capped at 1; if
    ///   D reaches 1 the deviator is returned again onto the failed curve in the same step.
    ///
    /// The damage never decreases; the plastic work is `Y d_eps_p` of each return.
    pub fn update(
        &self,
        s_trial: Sym3,
        shear_modulus: Real,
        p: Real,
        damage: Real,
        strain_rate: Real,
    ) -> Jh1Update {
        let d0 = if damage.is_nan() {
            1.0
        } else {
            min(max(damage, 0.0), 1.0)
        };
        let rf = self.rate_factor(strain_rate);
        let failed_strength = self.failed_strength(p) * rf;
        if d0 >= 1.0 || p.is_nan() || p <= self.tensile_limit {
            let m = radial_return(s_trial, failed_strength, shear_modulus);
            return Jh1Update {
                s: m.s,
                d_eps_p: m.d_eps_p,
                damage: 1.0,
                plastic_work: m.plastic_work,
                failed: true,
            };
        }
        let m = radial_return(s_trial, self.intact_strength(p) * rf, shear_modulus);
        let mut d = d0;
        if m.d_eps_p > 0.0 {
            let ef = self.failure_strain(p);
            d = if ef > 0.0 {
                min(d0 + m.d_eps_p / ef, 1.0)
            } else {
                1.0
            };
        }
        if d < 1.0 {
            return Jh1Update {
                s: m.s,
                d_eps_p: m.d_eps_p,
                damage: d,
                plastic_work: m.plastic_work,
                failed: false,
            };
        }
        // instantaneous failure within this step
        let f = radial_return(m.s, failed_strength, shear_modulus);
        Jh1Update {
            s: f.s,
            d_eps_p: m.d_eps_p + f.d_eps_p,
            damage: 1.0,
            plastic_work: m.plastic_work + f.plastic_work,
            failed: true,
        }
    }
}

/// Pressure a particle presents to the pair Riemann problem (seed 000 Algorithm 1): a failed
/// particle sustains no hydrostatic tension, so `max(p, 0)` (Pa; NaN -> 0); otherwise `p`.
#[inline]
pub fn failed_pair_pressure(p: Real, failed: bool) -> Real {
    if failed {
        max(p, 0.0)
    } else {
        p
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const G: Real = 193e9;
    const GPA: Real = 1e9;

    fn sic() -> Jh1 {
        Jh1::sic_seed000()
    }

    fn trial(svm: Real) -> Sym3 {
        let d = Sym3::new(0.8, -0.5, -0.3, 0.2, 0.1, -0.4).deviator();
        d * (svm / d.von_mises())
    }

    fn close(a: Real, b: Real) -> bool {
        (a - b).abs() <= 1e-12 * b.abs().max(1.0)
    }

    #[test]
    fn intact_curve_at_hand_computed_points() {
        let j = sic();
        // (T, 0) -> (P1, 7.1): slope 7.1/(2.5 + 0.75) = 2.184615...; at P = 0: 7.1 * 0.75/3.25
        assert_eq!(j.intact_strength(-0.75 * GPA), 0.0);
        assert_eq!(j.intact_strength(-2.0 * GPA), 0.0);
        assert!(close(j.intact_strength(0.0), 1.638_461_538_461_538_5 * GPA));
        assert!(close(
            j.intact_strength(-0.5 * GPA),
            7.1 * 0.25 / 3.25 * GPA
        ));
        // kink at P1: continuous, slopes 7.1/3.25 below and 5.1/7.5 = 0.68 above
        assert!(close(j.intact_strength(2.5 * GPA), 7.1 * GPA));
        let h = 1e6;
        let below = (j.intact_strength(2.5 * GPA) - j.intact_strength(2.5 * GPA - h)) / h;
        let above = (j.intact_strength(2.5 * GPA + h) - j.intact_strength(2.5 * GPA)) / h;
        assert!((below - 7.1 / 3.25).abs() < 1e-6 && (above - 0.68).abs() < 1e-6);
        // 6.25 GPa: 7.1 + 5.1 * 3.75/7.5 = 9.65; P2: 12.2; beyond P2 extrapolated:
        // 20 GPa: 12.2 + 0.68 * 10 = 19.0
        assert!(close(j.intact_strength(6.25 * GPA), 9.65 * GPA));
        assert!(close(j.intact_strength(10.0 * GPA), 12.2 * GPA));
        assert!(close(j.intact_strength(20.0 * GPA), 19.0 * GPA));
        // strain-rate factor: rate 1e3/s -> 1 + 0.009 ln 1000 = 1.062169797510839
        assert!(close(
            j.strength(2.5 * GPA, false, 1e3),
            7.1 * GPA * (1.0 + 0.009 * 6.907_755_278_982_137)
        ));
        for slow in [0.0, 0.5, -3.0, Real::NAN] {
            assert_eq!(j.rate_factor(slow), 1.0);
        }
    }

    /// Found by the `strength` fuzz target: a softening intact curve (`sigma_i2 < sigma_i1`,
    /// which the scene validator accepts) extrapolated to a negative strength.
    #[test]
    fn softening_intact_curve_stops_at_zero() {
        let j = Jh1 {
            sigma_i2: 5.0 * GPA,
            ..sic()
        };
        // 7.1 - 2.1 (P - 2.5)/7.5 reaches 0 at P = 27.857 GPa
        assert!(close(j.intact_strength(10.0 * GPA), 5.0 * GPA));
        assert!(j.intact_strength(27.0 * GPA) > 0.0);
        assert_eq!(j.intact_strength(28.0 * GPA), 0.0);
        assert_eq!(j.strength(1e3 * GPA, false, 1e5), 0.0);
        let u = j.update(trial(1.0 * GPA), G, 1e3 * GPA, 0.0, 0.0);
        assert_eq!(u.s.von_mises(), 0.0);
    }

    #[test]
    fn failed_curve_and_failure_strain_at_hand_computed_points() {
        let j = sic();
        // 0.4 * 2 GPa = 0.8 GPa; 0.4 * 5 GPa = 2 GPa capped at 1.3; no tension
        assert!(close(j.failed_strength(2.0 * GPA), 0.8 * GPA));
        assert_eq!(j.failed_strength(5.0 * GPA), 1.3 * GPA);
        assert_eq!(j.failed_strength(3.25 * GPA), 1.3 * GPA);
        assert_eq!(j.failed_strength(0.0), 0.0);
        assert_eq!(j.failed_strength(-0.1 * GPA), 0.0);
        assert!(close(j.strength(2.0 * GPA, true, 1.0), 0.8 * GPA));
        // eps_f = 0.8 (P + 0.75 GPa)/(100.5 GPa), capped at 0.8
        assert_eq!(j.failure_strain(-0.75 * GPA), 0.0);
        assert_eq!(j.failure_strain(-5.0 * GPA), 0.0);
        assert!(close(j.failure_strain(0.0), 0.8 * 0.75 / 100.5));
        assert!(close(j.failure_strain(49.5 * GPA), 0.4));
        assert!(close(j.failure_strain(99.75 * GPA), 0.8));
        assert_eq!(j.failure_strain(500.0 * GPA), 0.8);
        assert_eq!(j.failure_strain(Real::NAN), 0.0);
    }

    #[test]
    fn damage_accumulates_as_sum_of_plastic_strain_over_failure_strain() {
        let j = sic();
        let (mut s, mut d, mut expected) = (Sym3::ZERO, 0.0, 0.0);
        let mut steps_plastic = 0;
        for k in 0..200 {
            // pressure 0.2..0.8 GPa: eps_f ~ 0.008..0.013, intact strength ~ 2.2..3.5 GPa
            let p = (0.5 + 0.3 * crate::math::real::sin(k as Real)) * GPA;
            let st = s + trial(3e-3 * G);
            let u = j.update(st, G, p, d, 1.0);
            assert!(u.damage >= d, "damage decreased");
            if u.failed {
                assert_eq!(u.damage, 1.0);
                assert!(steps_plastic >= 3, "{steps_plastic}");
                assert!(expected + u.d_eps_p / j.failure_strain(p) >= 1.0 - 1e-12);
                assert!(u.s.von_mises() <= j.failed_strength(p) * (1.0 + 1e-12));
                return;
            }
            if u.d_eps_p > 0.0 {
                steps_plastic += 1;
                assert!(close(u.s.von_mises(), j.intact_strength(p)));
            }
            expected += u.d_eps_p / j.failure_strain(p);
            assert!(
                (u.damage - expected).abs() < 1e-12,
                "{k}: {} {expected}",
                u.damage
            );
            s = u.s;
            d = u.damage;
        }
        panic!("never failed ({steps_plastic} plastic steps, D = {d})");
    }

    #[test]
    fn damage_jumps_to_one_at_the_tensile_limit() {
        let j = sic();
        for p in [-0.75 * GPA, -GPA, Real::NAN] {
            let u = j.update(trial(0.1 * GPA), G, p, 0.0, 1.0);
            assert!(u.failed && u.damage == 1.0);
            assert_eq!(u.s.von_mises(), 0.0);
        }
        // just above the limit an elastic state keeps its damage and deviator
        let st = trial(0.01 * GPA);
        let u = j.update(st, G, -0.7 * GPA, 0.3, 1.0);
        assert_eq!((u.s, u.damage, u.failed, u.d_eps_p), (st, 0.3, false, 0.0));
    }

    #[test]
    fn failed_material_has_no_tension_strength_and_capped_compression_strength() {
        let j = sic();
        let st = trial(5.0 * GPA);
        for (p, y) in [
            (-0.5 * GPA, 0.0),
            (0.0, 0.0),
            (1.0 * GPA, 0.4 * GPA),
            (3.0 * GPA, 1.2 * GPA),
            (8.0 * GPA, 1.3 * GPA),
        ] {
            let u = j.update(st, G, p, 1.0, 1.0);
            assert!(u.failed && u.damage == 1.0);
            assert!(close(u.s.von_mises(), y), "{p}: {}", u.s.von_mises());
            assert!(u.s.von_mises() <= min(j.c_f * max(p, 0.0), j.sigma_f_max) + 1e-3);
        }
        // a failing step lands on the failed curve in the same step (instantaneous failure)
        let u = j.update(trial(9.0 * GPA), G, 2.5 * GPA, 0.999, 1.0);
        assert!(u.failed && close(u.s.von_mises(), 1.0 * GPA));
        assert!(close(u.d_eps_p, 8.0 * GPA / (3.0 * G)));
    }

    #[test]
    fn damage_never_decreases_and_outputs_are_finite() {
        let j = sic();
        let pressures = [-1e12, -0.74 * GPA, 0.0, 3.0 * GPA, 1e13, Real::INFINITY];
        for p in pressures {
            for d in [0.0, 0.2, 0.99, 1.0, 7.0, -1.0, Real::NAN] {
                for svm in [0.0, 1e8, 1e10, 1e20] {
                    for g in [G, 0.0, Real::INFINITY, Real::NAN] {
                        for rate in [0.0, 1e6, Real::NAN] {
                            let u = j.update(trial(svm), g, p, d, rate);
                            assert!(u.damage >= min(max(d, 0.0), 1.0) || d.is_nan());
                            assert!(u.damage <= 1.0 && u.failed == (u.damage == 1.0));
                            assert!(u.s.is_finite() && u.d_eps_p.is_finite());
                            assert!(u.d_eps_p >= 0.0 && u.plastic_work >= 0.0);
                            assert!(u.plastic_work.is_finite() || p.is_infinite());
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn failed_pairs_carry_no_tension() {
        assert_eq!(failed_pair_pressure(-2.0e8, true), 0.0);
        assert_eq!(failed_pair_pressure(3.0e9, true), 3.0e9);
        assert_eq!(failed_pair_pressure(-2.0e8, false), -2.0e8);
        assert_eq!(failed_pair_pressure(3.0e9, false), 3.0e9);
        assert_eq!(failed_pair_pressure(Real::NAN, true), 0.0);
    }
}
