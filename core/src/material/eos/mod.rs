//! Equations of state `P(rho, e)` and the isentropic bulk sound speed (DESIGN §4).
//!
//! Units: density `rho` in kg/m³, specific internal energy `e` in J/kg, pressure `P` in Pa
//! (positive in compression, DESIGN §2), `c²` in m²/s².
//!
//! Every model returns the squared isentropic bulk sound speed
//! `c² = dP/drho|_s = dP/drho|_e + P/rho² dP/de|_rho` (from `de = P/rho² drho` along an
//! isentrope), computed analytically; unit tests check it against a finite difference of
//! `P` along `de = P/rho² drho`.
//!
//! One file per model: [`linear`], [`logarithmic`], [`mie_gruneisen`], [`hugoniot`],
//! [`two_curve`], [`polynomial`], [`tillotson`], [`murnaghan`].
//!
//! ## Sound-speed floor
//! Where a model can reach `c² <= 0` (the linear EOS with `gamma != 1`, Mie–Grüneisen,
//! two-curve Mie–Grüneisen, polynomial, Tillotson) the state is mechanically unstable: it
//! lies past the spinodal in deep tension (or, for the polynomial, at compressions where a
//! negative `k3` makes the fit meaningless), where a real solid would already have spalled. The
//! Riemann solvers need a real, positive impedance `rho c`, so there, and only there,
//! `c²` is floored at [`C2_FLOOR_FRACTION`] times the model's reference `c0²`. The
//! logarithmic and Hugoniot models have `c² > 0` everywhere and are not floored.
//!
//! ## Compression guard
//! The linear `Us = c0 + s up` Hugoniot, `P_H = rho0 c0² y / (1 - s y)²` with
//! `y = 1 - rho0/rho = up/Us`, diverges at `y = 1/s` (`rho/rho0 = s/(s-1)`), and on the
//! Hugoniot `1 - s y = c0/Us`. Models built on it (Mie–Grüneisen, Hugoniot, two-curve)
//! evaluate their reference curves only up to the guard density [`guard_density`], where
//! `1 - s y = `[`HUGONIOT_GUARD`] (shock speed `Us = 10 c0`, far beyond the validity of
//! any linear `Us`–`up` fit), and continue them beyond it by their tangent lines in
//! `rho` (value and slope continuous). Outputs stay finite for every finite positive
//! `rho`.

pub mod hugoniot;
pub mod linear;
pub mod logarithmic;
pub mod mie_gruneisen;
pub mod murnaghan;
pub mod polynomial;
mod state;
pub mod tillotson;
pub mod two_curve;

pub use hugoniot::Hugoniot;
pub use linear::Linear;
pub use logarithmic::Logarithmic;
pub use mie_gruneisen::MieGruneisen;
pub use murnaghan::Murnaghan;
pub use polynomial::Polynomial;
pub use tillotson::Tillotson;
pub use two_curve::TwoCurve;

pub use state::{guard_density, EosState, C2_FLOOR_FRACTION, HUGONIOT_GUARD};

use crate::material::params::ParamError;
use crate::math::Real;

/// An equation of state. Each variant holds the parameters of one model. With the
/// feature `serde` it reads from a scene's `eos` table: `type` names the variant in
/// snake_case (`mie_gruneisen`), the other keys are the model's fields but `rho0`, which
/// the material gives ([`Eos::with_rho0`]).
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(tag = "type", rename_all = "snake_case")
)]
pub enum Eos {
    /// `P = c0² (rho - rho0) + (gamma - 1) rho e` (seed 004).
    Linear(Linear),
    /// `P = B ln(rho/rho0)` (seed 004 eq 24).
    Logarithmic(Logarithmic),
    /// Mie–Grüneisen on a linear `Us`–`up` Hugoniot with `rho Gamma = rho0 Gamma0`
    /// (seed 000 eq 37).
    MieGruneisen(MieGruneisen),
    /// The shock Hugoniot of `Us = c0 + s1 up` as a barotropic EOS ("isothermal
    /// Mie–Grüneisen", Gamma = 0; seed 000 eq 36, corrected).
    Hugoniot(Hugoniot),
    /// Mie–Grüneisen with two reference curves (seed 004 eqs 6–7, corrected).
    TwoCurve(TwoCurve),
    /// `P = k1 z + k2 z² + k3 z³`, `z = rho/rho0 - 1` (seed 000 eq 39).
    Polynomial(Polynomial),
    /// Tillotson's metallic EOS: compressed, cold and hot expanded states and an
    /// interpolation between (Tillotson 1962; Melosh 1989; Benz & Asphaug 1999).
    Tillotson(Tillotson),
    /// Murnaghan (Tait): `P = (rho0 c0²/gamma)((rho/rho0)^gamma - 1)`, the weakly
    /// compressible SPH users' liquid.
    Murnaghan(Murnaghan),
}

impl Eos {
    /// Evaluates P (Pa) and c² (m²/s²) at density `rho` (kg/m³) and specific internal
    /// energy `e` (J/kg).
    #[inline]
    pub fn eval(&self, rho: Real, e: Real) -> EosState {
        match self {
            Eos::Linear(m) => m.eval(rho, e),
            Eos::Logarithmic(m) => m.eval(rho, e),
            Eos::MieGruneisen(m) => m.eval(rho, e),
            Eos::Hugoniot(m) => m.eval(rho, e),
            Eos::TwoCurve(m) => m.eval(rho, e),
            Eos::Polynomial(m) => m.eval(rho, e),
            Eos::Tillotson(m) => m.eval(rho, e),
            Eos::Murnaghan(m) => m.eval(rho, e),
        }
    }

    /// Slope `s` of the linear shock-speed relation `Us = c0 + s up` behind this EOS; used
    /// by the two-shock Riemann solver. Models built on a Hugoniot give their `s1`. The
    /// others give the weak-shock slope `s = (1 + K')/4`, `K' = dK_S/dP` at the reference
    /// state (`K_S = rho c²` the isentropic bulk modulus; a weak shock is isentropic to
    /// second order, so `dUs/dup` at `up = 0` is fixed by `K'`):
    /// linear `(1 + gamma)/4` (`K_S' = gamma`; 1/2 for the barotropic `gamma = 1`),
    /// logarithmic 1/4 (`K_S = B`), Murnaghan `(1 + gamma)/4` (`K_S = rho0 c0² + gamma P`), polynomial `1/2 + k2/(2 k1)` (compression branch),
    /// Tillotson `1/2 + B/(2A) + (a + b)/4` (`K_S = eta (A + 2 B mu) + (a + b) P` along
    /// the isentrope from `(rho0, 0)`, where `e` is of second order: `K_S' = 1 + 2B/A + a + b`).
    /// The test `weak_shock_slope_matches_the_exact_hugoniot` checks each against the
    /// Rankine–Hugoniot shock of the EOS itself.
    pub fn hugoniot_slope(&self) -> Real {
        match self {
            Eos::MieGruneisen(m) => m.s1,
            Eos::Hugoniot(m) => m.s1,
            Eos::TwoCurve(m) => m.s_a,
            Eos::Linear(m) => 0.25 * (1.0 + m.gamma),
            Eos::Logarithmic(_) => 0.25,
            Eos::Polynomial(m) => 0.5 + 0.5 * m.k2 / m.k1,
            Eos::Tillotson(m) => 0.5 + 0.5 * m.big_b / m.big_a + 0.25 * (m.a + m.b),
            Eos::Murnaghan(m) => 0.25 * (1.0 + m.gamma),
        }
    }

    /// The model's name in a scene (`type = "..."`).
    pub const fn name(&self) -> &'static str {
        match self {
            Eos::Linear(_) => "linear",
            Eos::Logarithmic(_) => "logarithmic",
            Eos::MieGruneisen(_) => "mie_gruneisen",
            Eos::Hugoniot(_) => "hugoniot",
            Eos::TwoCurve(_) => "two_curve",
            Eos::Polynomial(_) => "polynomial",
            Eos::Tillotson(_) => "tillotson",
            Eos::Murnaghan(_) => "murnaghan",
        }
    }

    /// Checks the model's parameters (each model's `check`).
    pub fn check(&self) -> Result<(), ParamError> {
        match self {
            Eos::Linear(m) => m.check(),
            Eos::Logarithmic(m) => m.check(),
            Eos::MieGruneisen(m) => m.check(),
            Eos::Hugoniot(m) => m.check(),
            Eos::TwoCurve(m) => m.check(),
            Eos::Polynomial(m) => m.check(),
            Eos::Tillotson(m) => m.check(),
            Eos::Murnaghan(m) => m.check(),
        }
    }

    /// The same model with reference density `rho0` (kg/m³).
    pub fn with_rho0(mut self, rho0: Real) -> Eos {
        match &mut self {
            Eos::Linear(m) => m.rho0 = rho0,
            Eos::Logarithmic(m) => m.rho0 = rho0,
            Eos::MieGruneisen(m) => m.rho0 = rho0,
            Eos::Hugoniot(m) => m.rho0 = rho0,
            Eos::TwoCurve(m) => m.rho0 = rho0,
            Eos::Polynomial(m) => m.rho0 = rho0,
            Eos::Tillotson(m) => m.rho0 = rho0,
            Eos::Murnaghan(m) => m.rho0 = rho0,
        }
        self
    }

    /// Reference density, kg/m³.
    #[inline]
    pub fn rho0(&self) -> Real {
        match *self {
            Eos::Linear(m) => m.rho0,
            Eos::Logarithmic(m) => m.rho0,
            Eos::MieGruneisen(m) => m.rho0,
            Eos::Hugoniot(m) => m.rho0,
            Eos::TwoCurve(m) => m.rho0,
            Eos::Polynomial(m) => m.rho0,
            Eos::Tillotson(m) => m.rho0,
            Eos::Murnaghan(m) => m.rho0,
        }
    }
}

macro_rules! impl_from {
    ($($t:ident),*) => {$(
        impl From<$t> for Eos {
            #[inline]
            fn from(m: $t) -> Eos {
                Eos::$t(m)
            }
        }
    )*};
}
impl_from!(
    Linear,
    Logarithmic,
    MieGruneisen,
    Hugoniot,
    TwoCurve,
    Polynomial,
    Tillotson,
    Murnaghan
);

/// Helpers shared by the models' unit tests.
// Tolerances are for f64: the accuracy targets apply to f64 (DESIGN §1).
#[cfg(all(test, not(feature = "f32")))]
pub(crate) mod test_util {
    use super::{EosState, Real};

    /// `|a - b| <= tol |b|`, with a message.
    pub fn assert_rel(a: Real, b: Real, tol: Real, what: &str) {
        assert!(
            (a - b).abs() <= tol * b.abs(),
            "{what}: {a} vs {b} (rel {})",
            (a - b) / b
        );
    }

    /// Central finite difference of `P` along the isentrope `de = P/rho² drho` through
    /// `(rho, e)`; the second-order drift of `e` cancels in the central difference.
    pub fn isentrope_c2(f: impl Fn(Real, Real) -> EosState, rho: Real, e: Real) -> Real {
        let p = f(rho, e).p;
        let d = 1e-5 * rho;
        let de = p / (rho * rho) * d;
        (f(rho + d, e + de).p - f(rho - d, e - de).p) / (2.0 * d)
    }

    /// Checks `c²` against [`isentrope_c2`] to 1e-5 relative at each `(rho, e)`.
    pub fn check_c2(f: impl Fn(Real, Real) -> EosState + Copy, states: &[(Real, Real)]) {
        for &(rho, e) in states {
            let c2 = f(rho, e).c2;
            assert!(c2 > 0.0, "c2 = {c2} at rho {rho}, e {e}");
            assert_rel(isentrope_c2(f, rho, e), c2, 1e-5, "isentropic c2");
        }
    }

    /// `P` finite and `c² > 0` finite for `rho` from 1e-3 rho0 to 1e3 rho0 (covering
    /// [0.5, 2.5] rho0 finely) and a range of energies.
    pub fn check_finite(f: impl Fn(Real, Real) -> EosState, rho0: Real, e_scale: Real) {
        let mut etas = [0.0; 212];
        for (i, x) in etas.iter_mut().take(201).enumerate() {
            *x = 0.5 + 2.0 * i as Real / 200.0;
        }
        let extra = [
            1e-3, 0.01, 0.1, 0.3, 3.0, 5.0, 6.0, 10.0, 100.0, 1e3, 0.999_999,
        ];
        etas[201..].copy_from_slice(&extra);
        for eta in etas {
            for e in [0.0, 0.1 * e_scale, e_scale, -0.1 * e_scale] {
                let s = f(eta * rho0, e);
                assert!(s.p.is_finite(), "P = {} at eta {eta}, e {e}", s.p);
                assert!(
                    s.c2.is_finite() && s.c2 > 0.0,
                    "c2 = {} at eta {eta}, e {e}",
                    s.c2
                );
            }
        }
    }
}

// Tolerances are for f64: the accuracy targets apply to f64 (DESIGN §1).
#[cfg(all(test, not(feature = "f32")))]
mod tests {
    use super::*;

    #[test]
    fn enum_dispatch_and_rho0() {
        let lin = Linear {
            rho0: 8960.0,
            c0: 4148.0,
            gamma: 1.0,
        };
        let eos: Eos = lin.into();
        assert_eq!(eos.rho0(), 8960.0);
        assert_eq!(eos.eval(9000.0, 5.0), lin.eval(9000.0, 5.0));
        let pol = Eos::Polynomial(Polynomial {
            rho0: 3215.0,
            k1: 2.2e11,
            k2: 3.61e11,
            k3: 0.0,
        });
        assert_eq!(pol.rho0(), 3215.0);
        assert_eq!(pol.eval(3215.0, 0.0).p, 0.0);
    }

    #[test]
    fn guard_density_matches_shock_speed_of_ten_c0() {
        // on the Hugoniot 1 - s y = c0/Us; Us = 10 c0 -> up = 9 c0 / s
        let (rho0, c0, s) = (6100.0, 5077.0, 1.201);
        let up = 9.0 * c0 / s;
        let us = c0 + s * up;
        let rho_shock = rho0 * us / (us - up);
        test_util::assert_rel(guard_density(rho0, s), rho_shock, 1e-12, "guard");
        assert_eq!(guard_density(rho0, 0.5), Real::INFINITY);
    }
    /// The Rankine–Hugoniot shock of each EOS from rest at `(rho0, e = 0)`: for a
    /// compression `eta = 1 - rho0/rho`, `P` solves `P = P(rho, e)` with
    /// `e = P eta / (2 rho0)`, and `Us = sqrt(P/(rho0 eta))`, `up = sqrt(P eta/rho0)`.
    /// The slope `(Us(up2) - Us(up1))/(up2 - up1)` between two weak shocks equals
    /// [`Eos::hugoniot_slope`] to first order in `eta`.
    #[test]
    fn weak_shock_slope_matches_the_exact_hugoniot() {
        let cases: [Eos; 11] = [
            Murnaghan {
                rho0: 1000.0,
                c0: 1480.0,
                gamma: 7.0,
            }
            .into(),
            Linear {
                rho0: 8960.0,
                c0: 4148.0,
                gamma: 1.0,
            }
            .into(),
            Linear {
                rho0: 2785.0,
                c0: 5328.0,
                gamma: 2.0,
            }
            .into(),
            Logarithmic {
                rho0: 2688.9,
                bulk_modulus: 73e9,
            }
            .into(),
            Polynomial {
                rho0: 3215.0,
                k1: 2.2e11,
                k2: 3.61e11,
                k3: 0.0,
            }
            .into(),
            Polynomial {
                rho0: 3215.0,
                k1: 2.2e11,
                k2: -1.0e11,
                k3: 5e11,
            }
            .into(),
            MieGruneisen {
                rho0: 1845.0,
                c0: 12870.0,
                s1: 1.124,
                gamma0: 2.0,
            }
            .into(),
            Hugoniot {
                rho0: 6100.0,
                c0: 5077.0,
                s1: 1.201,
            }
            .into(),
            TwoCurve {
                rho0: 8930.0,
                c_a: 3940.0,
                s_a: 1.49,
                gamma: 2.0,
            }
            .into(),
            Tillotson {
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
            }
            .into(),
            Tillotson {
                rho0: 7860.0,
                a: 0.5,
                b: 1.5,
                big_a: 127.9e9,
                big_b: 105.0e9,
                alpha: 5.0,
                beta: 5.0,
                e0: 9.5e6,
                e_iv: 1.42e6,
                e_cv: 8.45e6,
            }
            .into(),
        ];
        for eos in cases {
            let rho0 = eos.rho0();
            let shock = |eta: Real| {
                let rho = rho0 / (1.0 - eta);
                let mut p = 0.0;
                for _ in 0..200 {
                    p = eos.eval(rho, p * eta / (2.0 * rho0)).p;
                }
                ((p / (rho0 * eta)).sqrt(), (p * eta / rho0).sqrt())
            };
            let (us1, up1) = shock(1e-5);
            let (us2, up2) = shock(2e-5);
            let slope = (us2 - us1) / (up2 - up1);
            let s = eos.hugoniot_slope();
            assert!(
                (slope - s).abs() < 2e-3 * s.max(0.25),
                "{eos:?}: exact weak-shock slope {slope}, hugoniot_slope {s}"
            );
        }
    }
}
