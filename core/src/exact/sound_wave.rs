//! Linear longitudinal sound pulse in an elastic solid (seed 004 §2.1.2).
//!
//! Initial data: `U_x(x, 0) = U0(x) = A exp(-k x²)`, zero stress, density `rho0`. The seed
//! writes `5 exp(-2 x²)` with `x` in millimetres (DESIGN §8), i.e. `A = 5 m/s`,
//! `k = 2 mm⁻² = 2e6 m⁻²` in SI.
//!
//! Material: `p = c0² (rho - rho0)` (bulk modulus `B = rho0 c0²`), shear modulus from the
//! fixed Poisson ratio `nu = (3B - 2G)/(2(3B + G))`, i.e. `G = 3B(1 - 2 nu)/(2(1 + nu))`.
//! In uniaxial strain the longitudinal modulus is `B + 4G/3`, so the linear wave speed is
//! `c = c_l = sqrt(c0² + 4G/(3 rho0))`.
//!
//! Exact linear (acoustic) solution, d'Alembert with zero initial stress:
//! `U(x, t) = ½ [U0(x - c t) + U0(x + c t)]`,
//! `sigma_xx(x, t) = -½ rho0 c [U0(x - c t) - U0(x + c t)]` (tension positive: a
//! right-going wave has `sigma = -rho0 c u`, a left-going one `sigma = +rho0 c u`), and
//! `rho = rho0 (1 - sigma_xx / (rho0 c²))` to first order.

use super::error::{positive, ExactError};
use crate::math::real::{exp, sqrt};
use crate::math::Real;

/// Parameters of the sound pulse (SI units).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SoundPulseParams {
    /// Reference density `rho0`, kg/m³.
    pub rho0: Real,
    /// Bulk sound speed `c0` (`B = rho0 c0²`), m/s.
    pub c0: Real,
    /// Poisson ratio `nu`, in `(-1, 1/2)`.
    pub poisson: Real,
    /// Pulse amplitude `A`, m/s.
    pub amplitude: Real,
    /// Pulse width parameter `k` of `exp(-k x²)`, 1/m².
    pub k: Real,
}

impl SoundPulseParams {
    /// Seed 004's copper: `rho0 = 8960 kg/m³`, `c0 = 4148 m/s`, `nu = 0.33`,
    /// `A = 5 m/s`, `k = 2e6 m⁻²` (`2 mm⁻²`).
    pub fn copper() -> Self {
        Self {
            rho0: 8960.0,
            c0: 4148.0,
            poisson: 0.33,
            amplitude: 5.0,
            k: 2e6,
        }
    }
}

/// The exact linear solution of the Gaussian sound pulse centred at `x = 0`.
#[derive(Clone, Copy, Debug)]
pub struct SoundPulse {
    params: SoundPulseParams,
    g: Real,
    c: Real,
}

impl SoundPulse {
    /// Builds the pulse; rejects non-positive `rho0`, `c0`, `k`, a non-finite amplitude and
    /// a Poisson ratio outside `(-1, 1/2)`.
    pub fn new(params: SoundPulseParams) -> Result<Self, ExactError> {
        positive("rho0", params.rho0)?;
        positive("c0", params.c0)?;
        positive("k", params.k)?;
        if !params.amplitude.is_finite() {
            return Err(ExactError::BadParameter {
                name: "amplitude",
                reason: "must be finite",
            });
        }
        let nu = params.poisson;
        if !(nu > -1.0 && nu < 0.5) {
            return Err(ExactError::BadParameter {
                name: "poisson",
                reason: "must lie in (-1, 1/2)",
            });
        }
        let b = params.rho0 * params.c0 * params.c0;
        let g = 3.0 * b * (1.0 - 2.0 * nu) / (2.0 * (1.0 + nu));
        let c = sqrt(params.c0 * params.c0 + 4.0 * g / (3.0 * params.rho0));
        Ok(Self { params, g, c })
    }

    /// Seed 004's copper pulse ([`SoundPulseParams::copper`]).
    pub fn copper() -> Self {
        match Self::new(SoundPulseParams::copper()) {
            Ok(s) => s,
            Err(_) => unreachable!("the copper parameters are valid"),
        }
    }

    /// The parameters the pulse was built from.
    pub fn params(&self) -> &SoundPulseParams {
        &self.params
    }

    /// Shear modulus `G = 3B(1 - 2 nu)/(2(1 + nu))`, `B = rho0 c0²`, Pa.
    pub fn shear_modulus(&self) -> Real {
        self.g
    }

    /// Bulk modulus `B = rho0 c0²`, Pa.
    pub fn bulk_modulus(&self) -> Real {
        self.params.rho0 * self.params.c0 * self.params.c0
    }

    /// Longitudinal sound speed `c_l = sqrt(c0² + 4G/(3 rho0))`, m/s.
    pub fn c_long(&self) -> Real {
        self.c
    }

    /// Initial velocity profile `U0(x) = A exp(-k x²)`, m/s.
    pub fn initial_velocity(&self, x: Real) -> Real {
        self.params.amplitude * exp(-self.params.k * x * x)
    }

    /// Velocity `U(x, t) = ½ [U0(x - c t) + U0(x + c t)]`, m/s.
    pub fn velocity(&self, x: Real, t: Real) -> Real {
        let ct = self.c * t;
        0.5 * (self.initial_velocity(x - ct) + self.initial_velocity(x + ct))
    }

    /// Axial stress `sigma_xx(x, t) = -½ rho0 c [U0(x - c t) - U0(x + c t)]`, Pa.
    pub fn stress(&self, x: Real, t: Real) -> Real {
        let ct = self.c * t;
        let z = self.params.rho0 * self.c;
        -0.5 * z * (self.initial_velocity(x - ct) - self.initial_velocity(x + ct))
    }

    /// Density to first order, `rho0 (1 - sigma_xx/(rho0 c²))`, kg/m³.
    pub fn density(&self, x: Real, t: Real) -> Real {
        let r0 = self.params.rho0;
        r0 - self.stress(x, t) / (self.c * self.c)
    }

    /// Centres `(-c t, +c t)` of the left- and right-going half-amplitude pulses, m.
    pub fn pulse_centres(&self, t: Real) -> (Real, Real) {
        (-self.c * t, self.c * t)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::real::abs;

    #[test]
    fn exact_sound_shear_modulus_and_speed_by_hand() {
        let s = SoundPulse::copper();
        // B = 8960 * 4148² = 154.16489984e9 Pa; G = 3B(1 - 0.66)/(2 * 1.33) = 0.383459 B
        // = 59.115864e9 Pa; c_l = sqrt(4148² + 4G/(3 * 8960)) = 5099.30 m/s.
        assert!(abs(s.bulk_modulus() - 154.164_899_84e9) < 1.0);
        assert!(abs(s.shear_modulus() - 59.115_864e9) < 1e3);
        let (b, g) = (s.bulk_modulus(), s.shear_modulus());
        let nu = (3.0 * b - 2.0 * g) / (2.0 * (3.0 * b + g));
        assert!(abs(nu - 0.33) < 1e-14);
        assert!(abs(s.c_long() - 5099.30) < 0.01, "{}", s.c_long());
    }

    #[test]
    fn exact_sound_initial_pulse_recovered() {
        let s = SoundPulse::copper();
        for i in -100..=100 {
            let x = 2e-3 * (i as Real) / 100.0;
            let u0 = 5.0 * exp(-2e6 * x * x);
            assert!(abs(s.velocity(x, 0.0) - u0) < 1e-15);
            assert_eq!(s.stress(x, 0.0), 0.0);
            assert_eq!(s.density(x, 0.0), 8960.0);
        }
        assert_eq!(s.velocity(0.0, 0.0), 5.0);
    }

    #[test]
    fn exact_sound_two_half_pulses_separate() {
        let s = SoundPulse::copper();
        let t = 2e-6; // 2 us: centres at -+10.199 mm, width ~0.7 mm
        let (l, r) = s.pulse_centres(t);
        assert!(abs(r - s.c_long() * t) < 1e-15 && l == -r);
        assert!(abs(s.velocity(r, t) - 2.5) < 1e-12);
        assert!(abs(s.velocity(l, t) - 2.5) < 1e-12);
        assert!(s.velocity(0.0, t) < 1e-12);
        // Right-going: compressive, sigma = -rho0 c u; left-going: sigma = +rho0 c u.
        let z = 8960.0 * s.c_long();
        assert!(abs(s.stress(r, t) + z * 2.5) < 1e-6 * z);
        assert!(abs(s.stress(l, t) - z * 2.5) < 1e-6 * z);
        assert!(s.density(r, t) > 8960.0 && s.density(l, t) < 8960.0);
        // Each pulse is the initial one halved and shifted.
        for i in -50..=50 {
            let d = 1e-3 * (i as Real) / 50.0;
            assert!(abs(s.velocity(r + d, t) - 0.5 * s.initial_velocity(d)) < 1e-12);
        }
        let bad = SoundPulseParams {
            poisson: 0.5,
            ..SoundPulseParams::copper()
        };
        assert!(SoundPulse::new(bad).is_err());
    }
}
