//! Why an exact solution could not be constructed, and the parameter check every solution
//! shares (a leaf of the folder, so that the solutions and their parent both import it
//! without a cycle).

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
