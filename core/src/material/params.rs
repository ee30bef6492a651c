//! A model's own checks of its parameters: each model has `check(&self) -> Result<(),
//! ParamError>`, naming the parameter (its key in a scene) and the rule it breaks. The
//! scene reader prefixes the key's path (`materials[0].eos.c0: must be positive and finite
//! (got -1)`).

use crate::math::Real;
use core::fmt;

/// What a parameter must satisfy.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Rule {
    /// Finite and > 0.
    Positive,
    /// Finite and >= 0.
    NonNegative,
    /// Finite.
    Finite,
    /// Finite and < 0, with what a negative value means (`a hydrostatic tension`).
    Negative {
        /// The meaning, for the message.
        meaning: &'static str,
    },
    /// Within `[lo, hi]`.
    Within {
        /// Lower bound.
        lo: Real,
        /// Upper bound.
        hi: Real,
    },
    /// Greater than another parameter of the model.
    Exceeds {
        /// The other parameter's key.
        other: &'static str,
        /// Its value.
        bound: Real,
        /// The unit both are in (for the message).
        unit: &'static str,
    },
}

/// A parameter of a model that breaks its rule.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ParamError {
    /// The parameter's key (`c0`, `gamma`, …).
    pub key: &'static str,
    /// The rule.
    pub rule: Rule,
    /// The value given.
    pub value: Real,
}

/// A number for a message: plain where short (`0.5`, `-1`), else in `e` notation (`1e-300`).
#[derive(Clone, Copy, Debug)]
pub struct Num(pub Real);

impl fmt::Display for Num {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let v = self.0;
        let a = if v < 0.0 { -v } else { v };
        if v == 0.0 || !v.is_finite() || (1e-3..1e6).contains(&a) {
            write!(f, "{v}")
        } else {
            write!(f, "{v:e}")
        }
    }
}

/// The reason, without the key: `must be positive and finite (got -1)`.
impl fmt::Display for ParamError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let got = Num(self.value);
        match self.rule {
            Rule::Positive => write!(f, "must be positive and finite (got {got})"),
            Rule::NonNegative => write!(f, "must be non-negative and finite (got {got})"),
            Rule::Finite => write!(f, "must be finite (got {got})"),
            Rule::Negative { meaning } => write!(f, "must be negative ({meaning}; got {got})"),
            Rule::Within { lo, hi } => {
                write!(f, "must lie in [{}, {}] (got {got})", Num(lo), Num(hi))
            }
            Rule::Exceeds { other, bound, unit } => {
                write!(f, "must exceed {other} = {} {unit} (got {got})", Num(bound))
            }
        }
    }
}

/// Checks `value` of parameter `key` against `rule`.
pub fn check(key: &'static str, value: Real, rule: Rule) -> Result<(), ParamError> {
    let ok = value.is_finite()
        && match rule {
            Rule::Positive => value > 0.0,
            Rule::NonNegative => value >= 0.0,
            Rule::Finite => true,
            Rule::Negative { .. } => value < 0.0,
            Rule::Within { lo, hi } => (lo..=hi).contains(&value),
            Rule::Exceeds { bound, .. } => value > bound,
        };
    if ok {
        Ok(())
    } else {
        Err(ParamError { key, rule, value })
    }
}

/// [`check`] of `Rule::Positive`.
pub fn positive(key: &'static str, value: Real) -> Result<(), ParamError> {
    check(key, value, Rule::Positive)
}

/// [`check`] of `Rule::NonNegative`.
pub fn non_negative(key: &'static str, value: Real) -> Result<(), ParamError> {
    check(key, value, Rule::NonNegative)
}

/// [`check`] of `Rule::Finite`.
pub fn finite(key: &'static str, value: Real) -> Result<(), ParamError> {
    check(key, value, Rule::Finite)
}

/// [`check`] of `Rule::Exceeds`: `value` (in `unit`) above parameter `other`'s `bound`.
pub fn exceeds(
    key: &'static str,
    value: Real,
    other: &'static str,
    bound: Real,
    unit: &'static str,
) -> Result<(), ParamError> {
    check(key, value, Rule::Exceeds { other, bound, unit })
}

/// 1 (a serde default).
#[cfg(feature = "serde")]
pub(crate) fn one() -> Real {
    1.0
}
