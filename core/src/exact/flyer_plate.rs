//! The 1D flyer-plate impact of seed 000 §4.1: two identical elastic–perfectly-plastic
//! plates, the flyer (`x < x0`) moving at `v` into the target at rest.
//!
//! EOS: seed 000's eq 36, `P = rho0 c0² zeta / (1 - (S1 - 1) zeta)` with
//! `zeta = rho/rho0 - 1`, is garbled: the shock Hugoniot of the quoted linear
//! `Us = c0 + S1 up` material is `rho0 c0² zeta (1 + zeta) / (1 - (S1 - 1) zeta)²`, and the
//! printed form (missing the factor `1 + zeta` and the square) agrees with it only to first
//! order in `zeta` (`zeta + (S1 - 1) zeta²` against `zeta + (2 S1 - 1) zeta²`). We use the
//! Hugoniot form of the Mie–Grüneisen EOS with `Gamma = 0` (so pressure is a function of
//! density only and the energy equation is not needed):
//!
//! `P(rho) = rho0 c0² x / (1 - S1 x)²`, `x = 1 - rho0/rho = zeta / (1 + zeta)`,
//!
//! which is exactly the Hugoniot of `Us = c0 + S1 up` (DESIGN §8).
//!
//! Strength: uniaxial strain with `dS_xx = (4G/3) dV/V`, yield at `S_xx = -2Y/3`. In the
//! target the elastic precursor (shock, from rest) reaches the Hugoniot elastic limit
//! `V_e = V0 exp(-Y/(2G))`, `sigma_e = -P(V_e) - 2Y/3`; the Rayleigh line gives its mass
//! flux `W_e² = sigma_e/(V_e - V0)`, particle velocity `u_e = W_e (V0 - V_e)` and speed
//! `D_e = V0 W_e`. A plastic shock (on `sigma = -P(V) - 2Y/3`) follows from the HEL state
//! to the final state, whose particle velocity is `v/2` exactly (symmetric impact): `V_f`
//! solves `u_e + sqrt((sigma_f - sigma_e)(V_f - V_e)) = v/2` and `D_p = u_e + W_p V_e` with
//! `W_p² = (sigma_f - sigma_e)/(V_f - V_e)`.
//!
//! The flyer is the mirror image about the contact `x_c(t) = x0 + v t/2` in the centre of
//! mass frame: `sigma(x_c - s) = sigma(x_c + s)`, `rho` likewise, and
//! `u(x_c - s) = v - u(x_c + s)`. The solution is valid until the precursors reach the free
//! ends ([`FlyerPlate::valid_until`]).

use super::error::{positive, ExactError};
use super::root::brent;
use crate::math::real::{exp, sqrt};
use crate::math::Real;

/// Parameters of the flyer-plate problem (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FlyerPlateParams {
    /// Reference density `rho0`, kg/m³.
    pub rho0: Real,
    /// Bulk sound speed `c0` of the Hugoniot `Us = c0 + S1 up`, m/s.
    pub c0: Real,
    /// Hugoniot slope `S1` (dimensionless).
    pub s1: Real,
    /// Shear modulus `G`, Pa.
    pub shear_modulus: Real,
    /// Yield stress `Y`, Pa.
    pub yield_stress: Real,
    /// Flyer velocity `v` (the target is at rest), m/s.
    pub impact_velocity: Real,
    /// Initial interface position `x0`, m.
    pub interface_x: Real,
}

impl FlyerPlateParams {
    /// Seed 000 §4.1 in SI: `rho0 = 6100`, `c0 = 5077 m/s`, `S1 = 1.201`,
    /// `G = 48.1 GPa` (0.481 Mbar), `Y = 2.5 GPa` (0.025 Mbar), `v = 602.81 m/s`,
    /// `x0 = 0.005 m` (domain `[0, 0.01] m`, end time 0.5 us).
    pub fn seed000() -> Self {
        Self {
            rho0: 6100.0,
            c0: 5077.0,
            s1: 1.201,
            shear_modulus: 48.1e9,
            yield_stress: 2.5e9,
            impact_velocity: 602.81,
            interface_x: 0.005,
        }
    }
}

/// The exact elastic-precursor + plastic-shock solution of the symmetric impact.
#[derive(Clone, Copy, Debug)]
pub struct FlyerPlate {
    params: FlyerPlateParams,
    v_e: Real,
    sigma_e: Real,
    u_e: Real,
    d_e: Real,
    v_f: Real,
    sigma_f: Real,
    d_p: Real,
}

impl FlyerPlate {
    /// Builds the solution. Errors: a non-positive or non-finite parameter (named); an
    /// impact too weak to exceed the HEL (`v/2 <= u_e`: purely elastic, not
    /// covered) or so strong that the plastic shock overtakes the precursor
    /// (`D_p >= D_e`), both reported against `impact_velocity`.
    pub fn new(params: FlyerPlateParams) -> Result<Self, ExactError> {
        positive("rho0", params.rho0)?;
        positive("c0", params.c0)?;
        positive("s1", params.s1)?;
        positive("shear_modulus", params.shear_modulus)?;
        positive("yield_stress", params.yield_stress)?;
        positive("impact_velocity", params.impact_velocity)?;
        if !params.interface_x.is_finite() {
            return Err(ExactError::BadParameter {
                name: "interface_x",
                reason: "must be finite",
            });
        }
        let v0 = 1.0 / params.rho0;
        let y = params.yield_stress;
        let v_e = v0 * exp(-y / (2.0 * params.shear_modulus));
        let mut fp = Self {
            params,
            v_e,
            sigma_e: 0.0,
            u_e: 0.0,
            d_e: 0.0,
            v_f: v_e,
            sigma_f: 0.0,
            d_p: 0.0,
        };
        fp.sigma_e = fp.plastic_stress(v_e);
        let w_e = sqrt(fp.sigma_e / (v_e - v0));
        fp.u_e = w_e * (v0 - v_e);
        fp.d_e = w_e * v0;
        let half = 0.5 * params.impact_velocity;
        let bad = |reason| ExactError::BadParameter {
            name: "impact_velocity",
            reason,
        };
        if half <= fp.u_e {
            return Err(bad("impact below the HEL: purely elastic, not covered"));
        }
        // Plastic shock: u_e + sqrt((sigma(V) - sigma_e)(V - V_e)) = v/2 on (V_lo, V_e],
        // V_lo at x = 0.99/S1, short of the EOS singularity x = 1/S1.
        let (s_e, u_e) = (fp.sigma_e, fp.u_e);
        let g = |v: Real| u_e + sqrt((fp.plastic_stress(v) - s_e) * (v - v_e)) - half;
        let v_lo = v0 * (1.0 - 0.99 / params.s1);
        fp.v_f = brent(g, v_lo, v_e, 0.0, "plastic shock volume")?;
        fp.sigma_f = fp.plastic_stress(fp.v_f);
        let w_p = sqrt((fp.sigma_f - s_e) / (fp.v_f - v_e));
        fp.d_p = u_e + w_p * v_e;
        if fp.d_p >= fp.d_e {
            return Err(bad("plastic shock overdrives the elastic precursor"));
        }
        Ok(fp)
    }

    /// The parameters the solution was built from.
    pub fn params(&self) -> &FlyerPlateParams {
        &self.params
    }

    /// Hugoniot pressure `P(rho) = rho0 c0² x / (1 - S1 x)²`, `x = 1 - rho0/rho`, Pa.
    pub fn pressure(&self, rho: Real) -> Real {
        let p = &self.params;
        let x = 1.0 - p.rho0 / rho;
        let d = 1.0 - p.s1 * x;
        p.rho0 * p.c0 * p.c0 * x / (d * d)
    }

    /// Stress on the compressive plastic branch, `sigma = -P(V) - 2Y/3`, Pa.
    fn plastic_stress(&self, v: Real) -> Real {
        -self.pressure(1.0 / v) - 2.0 * self.params.yield_stress / 3.0
    }

    /// Longitudinal sound speed at rest, `c_l = sqrt(c0² + 4G/(3 rho0))`, m/s.
    pub fn c_long(&self) -> Real {
        let p = &self.params;
        sqrt(p.c0 * p.c0 + 4.0 * p.shear_modulus / (3.0 * p.rho0))
    }

    /// HEL stress `sigma_e = -P(V_e) - 2Y/3`, Pa.
    pub fn hel_stress(&self) -> Real {
        self.sigma_e
    }

    /// HEL state `(sigma_e, u_e, rho_e)` behind the target's precursor (Pa, m/s, kg/m³).
    pub fn hel_state(&self) -> (Real, Real, Real) {
        (self.sigma_e, self.u_e, 1.0 / self.v_e)
    }

    /// Final stress `sigma_f = -P(V_f) - 2Y/3` behind the plastic shocks, Pa.
    pub fn final_stress(&self) -> Real {
        self.sigma_f
    }

    /// Final state `(sigma_f, v/2, rho_f)` between the plastic shocks.
    pub fn final_state(&self) -> (Real, Real, Real) {
        (
            self.sigma_f,
            0.5 * self.params.impact_velocity,
            1.0 / self.v_f,
        )
    }

    /// Lab-frame speed `D_e` of the target's elastic precursor, m/s.
    pub fn precursor_speed(&self) -> Real {
        self.d_e
    }

    /// Lab-frame speed `D_p` of the target's plastic shock, m/s.
    pub fn plastic_shock_speed(&self) -> Real {
        self.d_p
    }

    /// Position of the right-going precursor in the target, `x0 + D_e t`, m.
    pub fn precursor_position(&self, t: Real) -> Real {
        self.params.interface_x + self.d_e * t
    }

    /// Position of the right-going plastic shock in the target, `x0 + D_p t`, m.
    pub fn plastic_shock_position(&self, t: Real) -> Real {
        self.params.interface_x + self.d_p * t
    }

    /// Position of the contact, `x0 + v t / 2`, m.
    pub fn contact_position(&self, t: Real) -> Real {
        self.params.interface_x + 0.5 * self.params.impact_velocity * t
    }

    /// Latest time (s) at which the solution holds for plates whose free ends start at
    /// `x_left_end < x0 < x_right_end`: the precursors reach the ends at
    /// `(x0 - x_left_end)/D_e` (the flyer's end moves at `v` towards the wave, which moves
    /// at `v - D_e`) and `(x_right_end - x0)/D_e`; after that release waves come back.
    pub fn valid_until(&self, x_left_end: Real, x_right_end: Real) -> Real {
        let x0 = self.params.interface_x;
        let (l, r) = ((x0 - x_left_end) / self.d_e, (x_right_end - x0) / self.d_e);
        if l < r {
            l
        } else {
            r
        }
    }

    /// Target state at lab position `x >= x_c(t)`, `t > 0`.
    fn target(&self, x: Real, t: Real) -> (Real, Real, Real) {
        if x >= self.precursor_position(t) {
            (0.0, 0.0, self.params.rho0)
        } else if x >= self.plastic_shock_position(t) {
            self.hel_state()
        } else {
            self.final_state()
        }
    }

    /// The exact `(sigma_xx, u, rho)` at `(x, t)` (Pa, m/s, kg/m³); for `t <= 0` the initial
    /// data. Valid for `t <= valid_until(..)` of the actual plates.
    pub fn sample(&self, x: Real, t: Real) -> (Real, Real, Real) {
        let p = &self.params;
        if t <= 0.0 {
            let u = if x < p.interface_x {
                p.impact_velocity
            } else {
                0.0
            };
            return (0.0, u, p.rho0);
        }
        let xc = self.contact_position(t);
        if x >= xc {
            self.target(x, t)
        } else {
            let (s, u, rho) = self.target(2.0 * xc - x, t);
            (s, p.impact_velocity - u, rho)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::real::abs;

    fn fp() -> FlyerPlate {
        FlyerPlate::new(FlyerPlateParams::seed000()).unwrap()
    }

    /// Relative residuals of mass and momentum jumps across a shock of speed `d` between
    /// states `a` (ahead) and `b` (behind), each `(sigma, u, rho)`.
    fn rh(a: (Real, Real, Real), b: (Real, Real, Real), d: Real) -> (Real, Real) {
        let (ma, mb) = (a.2 * (d - a.1), b.2 * (d - b.1));
        let ds = b.0 - a.0;
        (abs(ma - mb) / abs(ma), abs(ds + ma * (b.1 - a.1)) / abs(ds))
    }

    #[test]
    fn exact_flyer_jump_conditions_both_shocks_both_plates() {
        let f = fp();
        let rest = (0.0, 0.0, f.params().rho0);
        let (d_e, d_p) = (f.precursor_speed(), f.plastic_shock_speed());
        let (m1, p1) = rh(rest, f.hel_state(), d_e);
        let (m2, p2) = rh(f.hel_state(), f.final_state(), d_p);
        // Flyer: left-going shocks at lab speeds v - D, states mirrored by u -> v - u.
        let v = f.params().impact_velocity;
        let mir = |s: (Real, Real, Real)| (s.0, v - s.1, s.2);
        let (m3, p3) = rh(mir(rest), mir(f.hel_state()), v - d_e);
        let (m4, p4) = rh(mir(f.hel_state()), mir(f.final_state()), v - d_p);
        for r in [m1, p1, m2, p2, m3, p3, m4, p4] {
            assert!(r < 1e-10, "RH residual {r}");
        }
    }

    #[test]
    fn exact_flyer_key_numbers() {
        let f = fp();
        let (y, t) = (2.5e9, 0.5e-6);
        // Hand check: V_e/V0 = exp(-2.5/96.2) = 0.974346, x = 0.025654,
        // P(V_e) = 157.233 GPa * 0.025654 / (1 - 1.201 x)² = 4.2940 GPa,
        // sigma_e = -4.2940 - 1.6667 = -5.9606 GPa; D_e² = sigma_e/(rho0 (V_e/V0 - 1))
        // -> D_e = 6171.8 m/s vs c_l = sqrt(5077² + 4*48.1e9/18300) = 6024.1 m/s (+2.45 %).
        assert!(abs(f.hel_stress() + 5.9606e9) < 1e6);
        assert!(abs(f.precursor_speed() - 6171.84) < 0.01);
        let cl = f.c_long();
        assert!(abs(cl - 6024.08) < 0.01);
        assert!(f.precursor_speed() > cl && f.precursor_speed() < 1.05 * cl);
        // Final state (independent bisection): rho_f = 6429.90, sigma_f = -10.8283 GPa,
        // D_p = 5592.34 m/s; at 0.5 us the precursor is at 8.0859 mm, the shock 7.7962 mm.
        let (sf, uf, rhof) = f.final_state();
        assert!(abs(sf + 10.8283e9) < 1e6 && abs(rhof - 6429.90) < 0.01);
        assert_eq!(uf, 0.5 * 602.81);
        assert!(abs(f.final_stress() + f.pressure(rhof) + 2.0 * y / 3.0) < 1e-6 * abs(sf));
        assert!(abs(f.plastic_shock_speed() - 5592.34) < 0.01);
        assert!(abs(f.precursor_position(t) - 8.0859e-3) < 1e-7);
        assert!(abs(f.plastic_shock_position(t) - 7.7962e-3) < 1e-7);
        // HEL on the yield surface: S = sigma + P = -2Y/3.
        let (se, _, rhoe) = f.hel_state();
        assert!(abs(se + f.pressure(rhoe) + 2.0 * y / 3.0) < 1e-6);
        // Seed domain [0, 0.01] m: valid beyond the case's 0.5 us.
        let tv = f.valid_until(0.0, 0.01);
        assert!(tv > t && abs(tv - 0.005 / f.precursor_speed()) < 1e-18);
    }

    #[test]
    fn exact_flyer_symmetry_and_profile() {
        let f = fp();
        let (t, v) = (0.5e-6, 602.81);
        let xc = f.contact_position(t);
        for i in 0..=500 {
            let s = 5e-3 * (i as Real) / 500.0;
            let (r, l) = (f.sample(xc + s, t), f.sample(xc - s, t));
            assert_eq!(r.0, l.0);
            assert_eq!(r.2, l.2);
            assert!(abs(l.1 - (v - r.1)) < 1e-12);
        }
        // Far field: flyer at v, target at rest, unstressed.
        assert_eq!(f.sample(0.0001, t), (0.0, v, 6100.0));
        assert_eq!(f.sample(0.0099, t), (0.0, 0.0, 6100.0));
        assert_eq!(f.sample(xc, t), f.final_state());
        assert_eq!(f.sample(0.004, 0.0), (0.0, v, 6100.0));
        // Between the target's shocks: HEL state.
        let mid = 0.5 * (f.precursor_position(t) + f.plastic_shock_position(t));
        assert_eq!(f.sample(mid, t), f.hel_state());
    }

    #[test]
    fn exact_flyer_eos_is_the_linear_us_up_hugoniot() {
        // P = rho0 c0² zeta (1 + zeta) / (1 - (S1 - 1) zeta)², and the Rayleigh line of the
        // Hugoniot reproduces Us = c0 + S1 up from rest.
        let f = fp();
        let (r0, c0, s1) = (6100.0, 5077.0, 1.201);
        for zeta in [0.01, 0.05, 0.1, 0.3] {
            let rho = r0 * (1.0 + zeta);
            let d = 1.0 - (s1 - 1.0) * zeta;
            let p_zeta = r0 * c0 * c0 * zeta * (1.0 + zeta) / (d * d);
            let p = f.pressure(rho);
            assert!(abs(p - p_zeta) < 1e-12 * p);
            // up = sqrt(P (V0 - V)), Us = V0 sqrt(P / (V0 - V)).
            let dv = 1.0 / r0 - 1.0 / rho;
            let (up, us) = (sqrt(p * dv), sqrt(p / dv) / r0);
            assert!(abs(us - (c0 + s1 * up)) < 1e-9 * us);
        }
    }

    #[test]
    fn exact_flyer_rejects_bad_params() {
        let base = FlyerPlateParams::seed000();
        let e = FlyerPlate::new(FlyerPlateParams { c0: 0.0, ..base }).unwrap_err();
        assert!(matches!(e, ExactError::BadParameter { name: "c0", .. }));
        let slow = FlyerPlateParams {
            impact_velocity: 100.0,
            ..base
        };
        let e = FlyerPlate::new(slow).unwrap_err();
        assert!(matches!(
            e,
            ExactError::BadParameter {
                name: "impact_velocity",
                ..
            }
        ));
    }
}
