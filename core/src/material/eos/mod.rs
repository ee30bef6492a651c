//! Equations of state (STUB: to be implemented; API fixed).
use crate::math::Real;

/// Pressure and squared bulk sound speed at one state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EosState {
    /// Pressure, Pa, positive in compression.
    pub p: Real,
    /// Squared isentropic bulk sound speed dP/drho|_s, m²/s².
    pub c2: Real,
}

/// An equation of state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Eos {
    /// p = c0² (rho - rho0) + (gamma - 1) rho e
    Linear {
        /// reference density
        rho0: Real,
        /// sound speed
        c0: Real,
        /// gamma (1 for none)
        gamma: Real,
    },
}

impl Eos {
    /// Evaluates P and c² at density `rho` and specific internal energy `e`.
    pub fn eval(&self, rho: Real, e: Real) -> EosState {
        let _ = (rho, e);
        todo!()
    }
    /// Reference density.
    pub fn rho0(&self) -> Real {
        match *self {
            Eos::Linear { rho0, .. } => rho0,
        }
    }
}
