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
    /// At most `hi` (in `unit`): beyond it the value is no real material's.
    AtMost {
        /// The largest value of the range of real materials.
        hi: Real,
        /// The unit (for the message).
        unit: &'static str,
    },
    /// At least `lo` (in `unit`): below it the value is no real material's.
    AtLeast {
        /// The smallest value of the range of real materials.
        lo: Real,
        /// The unit (for the message).
        unit: &'static str,
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
            Rule::AtMost { hi, unit } => write!(
                f,
                "must be at most {}{}{unit}, beyond every real material (got {got})",
                Num(hi),
                if unit.is_empty() { "" } else { " " }
            ),
            Rule::AtLeast { lo, unit } => write!(
                f,
                "must be at least {}{}{unit}, below every real material (got {got})",
                Num(lo),
                if unit.is_empty() { "" } else { " " }
            ),
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
            Rule::AtMost { hi, .. } => value <= hi,
            Rule::AtLeast { lo, .. } => value >= lo,
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

/// `value` of `key` (in `unit`) within the range of real materials: `[lo, hi]`, either
/// end `None` where another rule bounds it (positivity, a ratio to another parameter).
/// docs/materials.md lists every model's ranges and why.
pub fn physical(
    key: &'static str,
    value: Real,
    (lo, hi): (Option<Real>, Option<Real>),
    unit: &'static str,
) -> Result<(), ParamError> {
    if let Some(lo) = lo {
        check(key, value, Rule::AtLeast { lo, unit })?;
    }
    if let Some(hi) = hi {
        check(key, value, Rule::AtMost { hi, unit })?;
    }
    Ok(())
}

/// The ranges of real materials that [`physical`] checks, shared by the models.
pub mod ranges {
    use crate::math::Real;
    /// Reference densities, kg/m³: a gas at a thousandth of an atmosphere (1e-3) to
    /// four times osmium (22,590).
    pub const DENSITY: (Option<Real>, Option<Real>) = (Some(1e-3), Some(1e5));
    /// Sound speeds, m/s: from 1 (below the slowest foams and gels, tens of m/s) to
    /// 1e5 (five times diamond's 18 km/s).
    pub const SOUND_SPEED: (Option<Real>, Option<Real>) = (Some(1.0), Some(1e5));
    /// Elastic moduli (bulk, shear and the EOS's pressure coefficients), Pa: at most 1e13,
    /// twenty times diamond's bulk modulus (4.4e11).
    pub const MODULUS: (Option<Real>, Option<Real>) = (None, Some(1e13));
    /// Pressure coefficients of either sign (a polynomial EOS's `k2`, `k3`, Tillotson's
    /// B), Pa: magnitude at most [`MODULUS`]'s bound.
    pub const SIGNED_MODULUS: (Option<Real>, Option<Real>) = (Some(-1e13), Some(1e13));
    /// Bulk moduli, Pa, from below: 1e3 (a thousandth of the softest foams').
    pub const BULK_MODULUS: (Option<Real>, Option<Real>) = (Some(1e3), Some(1e13));
    /// Strengths and pressures of a strength model, Pa: at most 1e12, ten times the
    /// ideal strength of diamond.
    pub const STRESS: (Option<Real>, Option<Real>) = (None, Some(1e12));
    /// Tensions (a negative tensile limit), Pa: magnitude at most [`STRESS`]'s bound.
    pub const TENSION: (Option<Real>, Option<Real>) = (Some(-1e12), None);
    /// Dimensionless slopes and exponents (Hugoniot slope s, Grüneisen Γ, the exponents
    /// and coefficients of the strength models): magnitudes up to 20 (real materials: up
    /// to about 5; K' of porous media up to about 15).
    pub const COEFFICIENT: (Option<Real>, Option<Real>) = (Some(-20.0), Some(20.0));
    /// Temperatures, K: at most 1e5 (the models describe solids; tungsten melts at 3,695).
    pub const TEMPERATURE: (Option<Real>, Option<Real>) = (None, Some(1e5));
    /// Specific energies, J/kg: at most 1e10 (twenty times the vaporisation energy of
    /// any metal).
    pub const SPECIFIC_ENERGY: (Option<Real>, Option<Real>) = (None, Some(1e10));
    /// Specific heats, J/(kg K): at most 1e5 (hydrogen's is 14,300).
    pub const SPECIFIC_HEAT: (Option<Real>, Option<Real>) = (None, Some(1e5));
    /// Reference strain rates, 1/s: at most 1e12 (shock rise times of a picosecond).
    pub const STRAIN_RATE: (Option<Real>, Option<Real>) = (None, Some(1e12));
}

/// 1 (a serde default).
#[cfg(feature = "serde")]
pub(crate) fn one() -> Real {
    1.0
}
