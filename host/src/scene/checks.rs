//! The one-line checks a scene's values go through (each failure names the key): a leaf
//! that the scene's checks (`validate.rs`) and the checks of its parts
//! (`validate_parts.rs`) both use.

use super::SceneError;
use gsph_core::material::params::{self, Num, Rule};

pub(super) type R = Result<(), SceneError>;

pub(super) fn fail(key: &str, msg: impl std::fmt::Display) -> R {
    Err(SceneError(format!("{key}: {msg}")))
}

/// A number for a message: plain where short (`0.5`, `-1`), else in `e` notation (`1e-300`)
/// (the core's [`Num`], as the models' own checks print it).
pub(crate) fn num(v: f64) -> String {
    Num(v).to_string()
}

/// `v` of `key` checked against `rule` by the core's rule (the message the models give).
fn rule(key: &str, v: f64, rule: Rule) -> R {
    params::check("", v, rule).or_else(|e| fail(key, e))
}

pub(super) fn positive(key: &str, v: f64) -> R {
    rule(key, v, Rule::Positive)
}

pub(super) fn non_negative(key: &str, v: f64) -> R {
    rule(key, v, Rule::NonNegative)
}

pub(super) fn finite(key: &str, v: f64) -> R {
    rule(key, v, Rule::Finite)
}

pub(super) fn dims(key: &str, v: &[f64], dim: usize) -> R {
    if v.len() != dim {
        return fail(
            key,
            format!(
                "must have {dim} component{} for a {dim}D scene (got {})",
                if dim == 1 { "" } else { "s" },
                v.len()
            ),
        );
    }
    for (k, x) in v.iter().enumerate() {
        finite(&format!("{key}[{k}]"), *x)?;
    }
    Ok(())
}
