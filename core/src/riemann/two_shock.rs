//! The two-shock approximate Riemann solver (Dukowicz 1985) for the hydrodynamic step.
//!
//! # Model
//!
//! The pair axis points from the left side `l` (particle i) to the right side `r` (particle
//! j); `u` is the velocity component along it and `p` the pressure (positive in
//! compression). Each side `K` has a linear shock-speed relation `Us = c_K + s_K up`. Across a
//! shock of particle-velocity jump `w > 0` running into state `K`, mass and momentum
//! conservation give `p* - p_K = rho_K Us up = rho_K (c_K + s_K w) w`, with the compressive
//! jump `w = u_l - u*` on the left and `w = u* - u_r` on the right. For an expansion
//! (`w < 0`) this solver uses the acoustic impedance alone, `p* - p_K = rho_K c_K w`, so that
//! rarefactions are **not** stiffened by the shock slope (Dukowicz's `rho (c + s |w|) w` on
//! both branches would make the release stiffer than the sound speed, which no real
//! rarefaction is). Both branches have the slope `rho c` at `w = 0`, so each side's curve
//!
//! ```text
//! W_K(w) = rho_K (c_K + s_K max(w, 0)) w
//! ```
//!
//! is continuously differentiable and strictly increasing (for `s_K >= 0`; a negative or
//! non-finite slope is replaced by zero).
//!
//! # Solution
//!
//! `f(u*) = p_l + W_l(u_l - u*) - p_r - W_r(u* - u_r)` is continuous and strictly decreasing,
//! and piecewise quadratic with breakpoints `u_l`, `u_r`: left side shocked for `u* < u_l`,
//! right side shocked for `u* > u_r`. The solver evaluates `f` at `lo = min(u_l, u_r)` and
//! `hi = max(u_l, u_r)`, picks the interval with the sign change, and solves its quadratic
//! exactly in closed form about the interval's end point `u0` (for two shocks, the end
//! where `-4 A f(u0) >= 0`, so the square root below never cancels): with `d = u* - u0`,
//! `k_K = rho_K s_K` on a shocked side (0 otherwise), `a_l = u_l - u0`, `a_r = u0 - u_r`,
//!
//! ```text
//! f(u0 + d) = f(u0) - B d + A d²,   B = Z_l + Z_r + 2 k_l a_l + 2 k_r a_r,   A = k_l - k_r,
//! d = 2 f(u0) / (B + sqrt(B² - 4 A f(u0)))
//! ```
//!
//! (the root on the decreasing branch, written without cancellation; `B >= Z_l + Z_r > 0`).
//! No iteration is needed, so it always terminates; if the inputs are not usable (`rho c`
//! not positive and finite) or the result is not finite, it falls back to the acoustic
//! solver [`pressure_star`]. `p*` is the mean of the two sides' Hugoniot pressures at `u*`
//! (equal at the root), which keeps the i/j swap symmetry to round-off.
use super::acoustic::{pressure_star, PressureSide};
use crate::math::real::{max, sqrt};
use crate::math::Real;

/// One side of the two-shock Riemann problem along the pair axis (from i to j).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShockSide {
    /// Velocity component along the axis, m/s.
    pub u: Real,
    /// Pressure, Pa, positive in compression.
    pub p: Real,
    /// Density, kg/m³.
    pub rho: Real,
    /// Bulk sound speed (intercept of `Us = c + s up`), m/s.
    pub c: Real,
    /// Slope `s` of the linear shock-speed relation `Us = c + s up` (dimensionless, >= 0).
    pub s: Real,
}

impl ShockSide {
    /// Pressure jump `p* - p` across this side's wave for the compressive velocity jump `w`:
    /// `rho (c + s w) w` for a shock (`w > 0`), `rho c w` for an expansion.
    #[inline]
    pub fn hugoniot(&self, w: Real) -> Real {
        self.rho * (self.c + self.slope() * max(w, 0.0)) * w
    }

    /// Acoustic impedance `rho c`.
    #[inline]
    pub fn impedance(&self) -> Real {
        self.rho * self.c
    }

    /// The slope used by the solver: `s`, or zero if `s` is negative or not finite.
    #[inline]
    fn slope(&self) -> Real {
        if self.s.is_finite() {
            max(self.s, 0.0)
        } else {
            0.0
        }
    }
}

/// Star state `(u*, p*)` of the two-shock Riemann problem between the left side `l`
/// (particle i) and the right side `r` (particle j), axis from l to r, `p*` positive in
/// compression. Exact for the piecewise model `p* - p_K = rho_K (c_K + s_K max(w, 0)) w`
/// described in the module documentation; equal to [`pressure_star`] when `s = 0`.
///
/// Lane twin: `two_shock` in `core/src/simd/riemann.rs` (held bitwise equal through the star tests,
/// `schemes/star_tests.rs`).
pub fn two_shock_star(l: ShockSide, r: ShockSide) -> (Real, Real) {
    let acoustic = || {
        pressure_star(
            PressureSide {
                u: l.u,
                p: l.p,
                z: l.impedance(),
            },
            PressureSide {
                u: r.u,
                p: r.p,
                z: r.impedance(),
            },
        )
    };
    let (zl, zr) = (l.impedance(), r.impedance());
    let usable = |z: Real| z > 0.0 && z.is_finite();
    if !(usable(zl) && usable(zr)) {
        return acoustic();
    }
    let f = |u: Real| l.p + l.hugoniot(l.u - u) - r.p - r.hugoniot(u - r.u);
    let (lo, hi) = if l.u <= r.u { (l.u, r.u) } else { (r.u, l.u) };
    let (f_lo, f_hi) = (f(lo), f(hi));
    // Interval end point and the branch of each side on the interval holding the root.
    let (u0, f0, left_shock, right_shock) = if f_lo <= 0.0 {
        (lo, f_lo, true, false) // u* <= lo: left shocked, right expanding
    } else if f_hi >= 0.0 {
        (hi, f_hi, false, true) // u* >= hi: left expanding, right shocked
    } else if r.u < l.u {
        // u_r < u* < u_l: two shocks. Expand about the end where `-4 A f0 >= 0`, so that
        // `b² - 4 A f0` cannot cancel (about lo when k_l > k_r, a stiff shocked side
        // against a very soft one kept only half the digits; found by fuzzing,
        // docs/fuzzing.md)
        if l.rho * l.slope() > r.rho * r.slope() {
            (hi, f_hi, true, true)
        } else {
            (lo, f_lo, true, true)
        }
    } else {
        (lo, f_lo, false, false) // u_l < u* < u_r: two expansions (linear)
    };
    let kl = if left_shock { l.rho * l.slope() } else { 0.0 };
    let kr = if right_shock { r.rho * r.slope() } else { 0.0 };
    let b = zl + zr + 2.0 * kl * (l.u - u0) + 2.0 * kr * (u0 - r.u);
    let a = kl - kr;
    let d = 2.0 * f0 / (b + sqrt(max(b * b - 4.0 * a * f0, 0.0)));
    let u = u0 + d;
    let p = 0.5 * (l.p + l.hugoniot(l.u - u) + r.p + r.hugoniot(u - r.u));
    if u.is_finite() && p.is_finite() {
        (u, p)
    } else {
        acoustic()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn copper(u: Real, p: Real) -> ShockSide {
        ShockSide {
            u,
            p,
            rho: 8930.0,
            c: 3940.0,
            s: 1.49,
        }
    }
    fn alu(u: Real, p: Real) -> ShockSide {
        ShockSide {
            u,
            p,
            rho: 2785.0,
            c: 5328.0,
            s: 1.338,
        }
    }
    fn rel(a: Real, b: Real) -> Real {
        (a - b).abs() / b.abs().max(1.0)
    }
    /// Residual check with a direct bisection of p_l + W_l(u_l - u) = p_r + W_r(u - u_r).
    fn bisect(l: ShockSide, r: ShockSide) -> (Real, Real) {
        let f = |u: Real| l.p + l.hugoniot(l.u - u) - r.p - r.hugoniot(u - r.u);
        let (mut a, mut b) = (-1e5, 1e5);
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if f(m) > 0.0 {
                a = m
            } else {
                b = m
            }
        }
        let u = 0.5 * (a + b);
        (u, l.p + l.hugoniot(l.u - u))
    }
    use crate::math::Lcg;
    fn random_pair(g: &mut Lcg) -> (ShockSide, ShockSide) {
        let side = |g: &mut Lcg| ShockSide {
            u: 1500.0 * g.next(),
            p: 2e10 * g.next(),
            rho: 5000.0 + 4000.0 * g.next(),
            c: 5000.0 + 2000.0 * g.next(),
            s: 1.5 + g.next(),
        };
        (side(g), side(g))
    }

    #[test]
    fn symmetric_collision_gives_the_linear_us_up_hugoniot() {
        for u in [1.0, 100.0, 417.1, 3000.0] {
            let (us, ps) = two_shock_star(copper(u, 0.0), copper(-u, 0.0));
            let exact = 8930.0 * (3940.0 + 1.49 * u) * u;
            assert!(us.abs() < 1e-12 * u, "u* = {us}");
            assert!(rel(ps, exact) < 1e-13, "{ps} vs {exact}");
        }
    }

    #[test]
    fn zero_slope_reduces_to_the_acoustic_solver() {
        let mut g = Lcg(3);
        for _ in 0..500 {
            let (mut l, mut r) = random_pair(&mut g);
            l.s = 0.0;
            r.s = 0.0;
            let (u, p) = two_shock_star(l, r);
            let (ua, pa) = pressure_star(
                PressureSide {
                    u: l.u,
                    p: l.p,
                    z: l.rho * l.c,
                },
                PressureSide {
                    u: r.u,
                    p: r.p,
                    z: r.rho * r.c,
                },
            );
            assert!((u - ua).abs() < 1e-9 && (p - pa).abs() < 1e-12 * 4e10);
        }
    }

    #[test]
    fn galilean_invariance_and_swap_symmetry() {
        let mut g = Lcg(5);
        for _ in 0..500 {
            let (l, r) = random_pair(&mut g);
            let (u, p) = two_shock_star(l, r);
            let w = 2000.0 * g.next();
            let shift = |x: ShockSide| ShockSide { u: x.u + w, ..x };
            let (uw, pw) = two_shock_star(shift(l), shift(r));
            assert!((uw - u - w).abs() < 1e-9 && (pw - p).abs() < 1e-12 * 1e11);
            let flip = |x: ShockSide| ShockSide { u: -x.u, ..x };
            let (u2, p2) = two_shock_star(flip(r), flip(l));
            assert!((u2 + u).abs() < 1e-9 && (p2 - p).abs() < 1e-12 * 1e11);
        }
    }

    /// Found by the `riemann` fuzz target: a stiff shocked side against a very soft one.
    /// Expanded about `lo`, `b² - 4 A f0` cancelled: u* came out 1.2e-3 m/s beyond u_l
    /// (outside the bracket of the two velocities) and p* = 0.95 Pa instead of 2.08 Pa.
    #[test]
    fn stiff_against_very_soft_keeps_full_precision() {
        let l = ShockSide {
            u: 99997.45088472776,
            p: 1.4542675792978867e-105,
            rho: 33207.80991025317,
            c: 0.020780069740730156,
            s: 41.79751527075673,
        };
        let r = ShockSide {
            u: 1.9104918289e-313,
            p: 5.36864935114e-312,
            rho: 0.0010000052508370887,
            c: 0.020780072518389692,
            s: 1.4260258159786313e-105,
        };
        let (u, p) = two_shock_star(l, r);
        let (ub, pb) = bisect(l, r);
        assert!(
            u <= l.u && (u - ub).abs() < 1e-9,
            "u* = {u}, bisection {ub}"
        );
        assert!(
            rel(p, pb) < 1e-6 && (p - 2.078).abs() < 1e-3,
            "p* = {p}, bisection {pb}"
        );
    }

    #[test]
    fn star_pressure_is_monotone_in_the_approach_velocity() {
        let mut last = Real::NEG_INFINITY;
        for k in -200..=200 {
            let du = 20.0 * k as Real;
            let (_, p) = two_shock_star(copper(du, 1e9), alu(0.0, -2e8));
            assert!(p > last, "p* not increasing at du = {du}");
            last = p;
        }
    }

    #[test]
    fn matches_direct_solution_of_the_two_hugoniots() {
        // copper flyer on an aluminium target, pre-stressed, with every branch combination
        for (ul, pl, ur, pr) in [
            (800.0, 0.0, 0.0, 0.0),
            (800.0, 5e9, -100.0, 3e10),
            (-300.0, 1e10, 400.0, 0.0),
            (-300.0, -1e9, 400.0, 2e10),
            (10.0, 4e10, 0.0, -1e9),
        ] {
            let (l, r) = (copper(ul, pl), alu(ur, pr));
            let (u, p) = two_shock_star(l, r);
            let (ub, pb) = bisect(l, r);
            assert!(
                (u - ub).abs() < 1e-8 && rel(p, pb) < 1e-10,
                "{u} {p} vs {ub} {pb}"
            );
        }
        let mut g = Lcg(11);
        for _ in 0..500 {
            let (l, r) = random_pair(&mut g);
            let (u, p) = two_shock_star(l, r);
            let (ub, pb) = bisect(l, r);
            assert!((u - ub).abs() < 1e-8 && (p - pb).abs() < 1e-11 * 1e11);
        }
    }

    #[test]
    fn degenerate_inputs_fall_back_and_stay_finite() {
        let bad = ShockSide {
            u: 0.0,
            p: 0.0,
            rho: 0.0,
            c: 0.0,
            s: 1.5,
        };
        let (u, p) = two_shock_star(copper(100.0, 0.0), bad);
        assert!(u.is_finite() && p.is_finite());
        // negative / NaN slopes are treated as zero
        let l = ShockSide {
            s: Real::NAN,
            ..copper(50.0, 0.0)
        };
        let r = ShockSide {
            s: -3.0,
            ..copper(-50.0, 0.0)
        };
        let (u, p) = two_shock_star(l, r);
        assert!(u.abs() < 1e-12 && rel(p, 8930.0 * 3940.0 * 50.0) < 1e-13);
        // huge approach velocities
        let (u, p) = two_shock_star(copper(1e12, 0.0), alu(-1e12, 0.0));
        assert!(u.is_finite() && p.is_finite() && p > 0.0);
    }
}
