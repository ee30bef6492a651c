//! Exact and analytic reference solutions for the validation cases (DESIGN §7).
//!
//! * [`ElasticPlasticRiemann`]: the four-wave elastic–plastic Riemann problem of seed 004
//!   §2.1.1 (log EOS, Wilkins elastic–perfectly-plastic), with the rarefactions as centred
//!   fans (DESIGN §8).
//! * [`FlyerPlate`]: the symmetric flyer-plate impact of seed 000 §4.1 (elastic precursor
//!   and plastic shock in each plate).
//! * [`SoundPulse`]: the linear longitudinal sound pulse of seed 004 §2.1.2.
//! * [`ShellCollapse`]: the incompressible rigid-plastic collapse of a cylindrical shell,
//!   reference of the beryllium ring (seed 000 §4.2) and the Verney cylinder (seed 004 §2.1.3).
//!
//! Conventions (DESIGN §2): SI units, Cauchy stress tension positive, pressure positive in
//! compression, 1D = uniaxial strain with `S_xx = -2 S_yy = -2 S_zz`, so that
//! `|S_xx| <= 2Y/3` at yield. Every solver here is allocation-free and `no_std`.

mod elastic_plastic_riemann;
mod flyer_plate;
pub(crate) mod root;
mod shell_collapse;
mod sound_wave;

pub use elastic_plastic_riemann::{ElasticPlasticRiemann, EpRiemannParams, EpState, EpWaves};
pub use flyer_plate::{FlyerPlate, FlyerPlateParams};
pub use shell_collapse::{ShellCollapse, ShellParams};
pub use sound_wave::{SoundPulse, SoundPulseParams};

use core::fmt;

/// Why an exact solution could not be constructed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ExactError {
    /// A scalar root was requested on an interval whose end values do not bracket a sign
    /// change (or are not finite); `what` names the equation being solved.
    NoRootBracket {
        /// The equation (for example `"contact stress"`).
        what: &'static str,
    },
    /// A parameter is out of the range the solution supports.
    BadParameter {
        /// The parameter's name as spelt in the params struct.
        name: &'static str,
        /// Why it was rejected.
        reason: &'static str,
    },
}

impl fmt::Display for ExactError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ExactError::NoRootBracket { what } => {
                write!(f, "exact solution: no root bracket for the {what} equation")
            }
            ExactError::BadParameter { name, reason } => {
                write!(f, "exact solution: bad parameter `{name}`: {reason}")
            }
        }
    }
}

/// `Ok(())` when `value` is finite and strictly positive, else a [`ExactError::BadParameter`].
pub(crate) fn positive(name: &'static str, value: crate::math::Real) -> Result<(), ExactError> {
    if value.is_finite() && value > 0.0 {
        Ok(())
    } else {
        Err(ExactError::BadParameter {
            name,
            reason: "must be finite and > 0",
        })
    }
}
