//! Collapse of a cylindrical shell of incompressible, rigid–perfectly-plastic (von Mises)
//! material in plane strain: the analytic reference of the collapsing beryllium ring
//! (Howell & Ball 2002; seed 000 §4.2) and of the Verney cylinder (seed 004 §2.1.3).
//!
//! With inner and outer radii `r1 < r2` and `r2² - r1² = R2² - R1²` (incompressible), the
//! velocity is radial, `v = A(t)/r`. The kinetic energy per unit length is
//! `K = pi rho A² ln(r2/r1)`; plane-strain flow at yield (`sigma_vm = Y`, equivalent strain
//! rate `2|A|/(sqrt(3) r²)`) dissipates `dW = (4 pi Y / sqrt 3) |A| ln(r2/r1) dt`. As
//! `A dt = r1 dr1`, the work done while the inner radius moves from `R1` to `r1` is
//!
//! ```text
//! W(r1) = (4 pi Y / sqrt 3) int_{r1}^{R1} r ln( sqrt(r² + R2² - R1²) / r ) dr
//! ```
//!
//! and the shell stops where `W(r1) = K0 = pi rho (v0 R1)² ln(R2/R1)` (initial velocity
//! `v0 R1 / r`, inward). With `x = r/R1`, `alpha = (R2 - R1)/R1`, this is seed 004's
//! `U0² = 2 Y F(alpha, lambda) / (sqrt 3 rho ln(R2/R1))`,
//! `F = int_lambda^1 x ln(1 + (2 alpha + alpha²)/x²) dx`, `lambda = r1_stop/R1`.
//! The radius history follows from `K(r1) = K0 - W(r1)`, `dr1/dt = -A/r1`.

use super::error::ExactError;
use super::root::brent;
use crate::math::{real, Real, PI};

/// Parameters (SI).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShellParams {
    /// Density, kg/m³.
    pub rho: Real,
    /// Yield stress Y (von Mises), Pa.
    pub yield_stress: Real,
    /// Initial inner radius R1, m.
    pub r_inner: Real,
    /// Initial outer radius R2, m.
    pub r_outer: Real,
    /// Initial inward speed at the inner radius, m/s (velocity `-v0 R1/r`).
    pub v0: Real,
}

/// The analytic collapse.
#[derive(Clone, Copy, Debug)]
pub struct ShellCollapse {
    p: ShellParams,
    k0: Real,
    stop_inner: Real,
}

/// `int_{a}^{b} r ln( sqrt(r² + d)/r ) dr` in closed form:
/// `F(r) = ((r² + d) ln(r² + d) - r² ln r²) / 4`.
fn integral(a: Real, b: Real, d: Real) -> Real {
    let f = |r: Real| {
        let r2 = r * r;
        let s = r2 + d;
        0.25 * (s * real::ln(s) - if r2 > 0.0 { r2 * real::ln(r2) } else { 0.0 })
    };
    f(b) - f(a)
}

impl ShellCollapse {
    /// Builds the solution (solves for the stopping radius).
    pub fn new(p: ShellParams) -> Result<Self, ExactError> {
        let bad = |name, reason| Err(ExactError::BadParameter { name, reason });
        if !(p.rho > 0.0 && p.rho.is_finite()) {
            return bad("rho", "must be positive");
        }
        if !(p.yield_stress > 0.0 && p.yield_stress.is_finite()) {
            return bad("yield_stress", "must be positive");
        }
        if !(p.r_inner > 0.0 && p.r_outer > p.r_inner && p.r_outer.is_finite()) {
            return bad("r_outer", "need 0 < r_inner < r_outer");
        }
        if !(p.v0 >= 0.0 && p.v0.is_finite()) {
            return bad("v0", "must be a non-negative inward speed");
        }
        let k0 =
            PI * p.rho * (p.v0 * p.r_inner) * (p.v0 * p.r_inner) * real::ln(p.r_outer / p.r_inner);
        let s = ShellCollapse {
            p,
            k0,
            stop_inner: p.r_inner,
        };
        if k0 == 0.0 {
            return Ok(s);
        }
        if s.work(0.0) <= k0 {
            return bad("v0", "the shell closes completely before it stops");
        }
        let stop = brent(
            |r1| s.work(r1) - k0,
            0.0,
            p.r_inner,
            1e-15 * p.r_inner,
            "shell stopping radius",
        )?;
        Ok(ShellCollapse {
            stop_inner: stop,
            ..s
        })
    }

    /// The ring of seed 000 §4.2: beryllium, rho 1845, Y 330 MPa, R 0.08–0.1 m, v0 417.1 m/s.
    pub fn beryllium_ring() -> Self {
        Self::new(ShellParams {
            rho: 1845.0,
            yield_stress: 330.0e6,
            r_inner: 0.08,
            r_outer: 0.1,
            v0: 417.1,
        })
        .expect("valid parameters")
    }

    /// Parameters.
    pub fn params(&self) -> &ShellParams {
        &self.p
    }

    /// Plastic work per unit length done while the inner radius moves from R1 to `r1`, J/m.
    pub fn work(&self, r1: Real) -> Real {
        let d = self.p.r_outer * self.p.r_outer - self.p.r_inner * self.p.r_inner;
        4.0 * PI * self.p.yield_stress / real::sqrt(3.0) * integral(r1, self.p.r_inner, d)
    }

    /// Initial kinetic energy per unit length, J/m.
    pub fn kinetic_energy(&self) -> Real {
        self.k0
    }

    /// Outer radius belonging to inner radius `r1` (incompressibility).
    pub fn outer_of(&self, r1: Real) -> Real {
        real::sqrt(r1 * r1 + self.p.r_outer * self.p.r_outer - self.p.r_inner * self.p.r_inner)
    }

    /// Stopping radii (inner, outer), m.
    pub fn stopping_radii(&self) -> (Real, Real) {
        (self.stop_inner, self.outer_of(self.stop_inner))
    }

    /// Inward speed of the inner surface when it is at `r1`, m/s (0 once stopped).
    pub fn inner_speed(&self, r1: Real) -> Real {
        if r1 <= self.stop_inner {
            return 0.0;
        }
        let k = real::max(0.0, self.k0 - self.work(r1));
        let a = real::sqrt(k / (PI * self.p.rho * real::ln(self.outer_of(r1) / r1)));
        a / r1
    }

    /// Radii (inner, outer) at time `t` by integrating `dr1/dt = -A/r1` with classical
    /// Runge–Kutta in `steps` steps (the solution stops at the stopping radius).
    pub fn radii_at(&self, t: Real, steps: u32) -> (Real, Real) {
        let n = steps.max(1);
        let h = t / n as Real;
        let mut r = self.p.r_inner;
        let f = |r: Real| -self.inner_speed(r);
        for _ in 0..n {
            let k1 = f(r);
            let k2 = f(r + 0.5 * h * k1);
            let k3 = f(r + 0.5 * h * k2);
            let k4 = f(r + h * k3);
            r = real::max(
                self.stop_inner,
                r + h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4),
            );
        }
        (r, self.outer_of(r))
    }

    /// Seed 004's F(alpha, lambda) at the stopping radius (for the cross-check with its
    /// closed form of U0).
    pub fn verney_f(&self) -> Real {
        let alpha = (self.p.r_outer - self.p.r_inner) / self.p.r_inner;
        let lambda = self.stop_inner / self.p.r_inner;
        // int_lambda^1 x ln(1 + c/x²) dx with c = 2 alpha + alpha², in closed form
        let c = 2.0 * alpha + alpha * alpha;
        let g = |x: Real| 0.5 * ((x * x + c) * real::ln(x * x + c) - x * x * real::ln(x * x));
        g(1.0) - g(lambda)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn beryllium_ring_stops_at_the_published_radii() {
        // Howell & Ball / seed 000 §4.2: 0.05 m and 0.0781 m
        let (r1, r2) = ShellCollapse::beryllium_ring().stopping_radii();
        assert!((r1 - 0.0500).abs() < 5e-5, "inner {r1}");
        assert!((r2 - 0.0781).abs() < 5e-5, "outer {r2}");
    }

    #[test]
    fn verney_cylinder_stops_at_the_published_radius_and_matches_seed_004s_formula() {
        // seed 004 §2.1.3: aluminium rho 2785, Y 0.3 GPa, R 0.08-0.1 m, U0 208.55 m/s -> 0.0667 m
        let s = ShellCollapse::new(ShellParams {
            rho: 2785.0,
            yield_stress: 0.3e9,
            r_inner: 0.08,
            r_outer: 0.1,
            v0: 208.55,
        })
        .unwrap();
        let (r1, _) = s.stopping_radii();
        assert!((r1 - 0.0667).abs() < 1e-4, "inner {r1}");
        // U0² = 2 Y F / (sqrt3 rho ln(R1/R0))
        let u0 = real::sqrt(
            2.0 * 0.3e9 * s.verney_f() / (real::sqrt(3.0) * 2785.0 * real::ln(0.1 / 0.08)),
        );
        assert!((u0 - 208.55).abs() < 1e-6 * 208.55, "U0 {u0}");
    }

    #[test]
    fn closed_form_integral_matches_quadrature() {
        let d = 0.0036;
        let n = 20000;
        let (a, b) = (0.05, 0.08);
        let h = (b - a) / n as Real;
        let mut q = 0.0;
        for k in 0..n {
            let r = a + (k as Real + 0.5) * h;
            q += r * real::ln(real::sqrt(r * r + d) / r) * h;
        }
        assert!((integral(a, b, d) - q).abs() < 1e-9 * q.abs());
    }

    #[test]
    fn radius_history_decelerates_and_stops() {
        let s = ShellCollapse::beryllium_ring();
        let (r10, _) = s.radii_at(10e-6, 2000);
        let (r50, _) = s.radii_at(50e-6, 2000);
        let (r200, r2) = s.radii_at(200e-6, 4000);
        assert!(r10 < 0.08 && r50 < r10);
        // stops near 129 us at the stopping radius
        assert!(
            (r200 - s.stopping_radii().0).abs() < 1e-9 && (r2 - s.stopping_radii().1).abs() < 1e-9
        );
        // early on the surface moves at about v0
        assert!((0.08 - r10) / 10e-6 > 380.0 && (0.08 - r10) / 10e-6 < 417.2);
        // incompressible: area conserved
        assert!((r2 * r2 - r200 * r200 - 0.0036).abs() < 1e-15);
    }
}
