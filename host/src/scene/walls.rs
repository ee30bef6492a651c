//! `[[walls]]`: rigid walls and symmetry planes (see `crate::sim::walls` for how the
//! schemes see them).
//!
//! ```toml
//! [[walls]]
//! point = [0.0, 0.0, 0.0]   # a point of the plane, m
//! normal = [1.0, 0.0, 0.0]  # towards the side the particles are on (normalised)
//! type = "rigid"            # or "symmetry"
//! friction = 0.3            # Coulomb coefficient (rigid walls only; default 0)
//! ```

use super::{Scene, SceneError};
use serde::{Deserialize, Serialize};

/// A plane particles cannot cross.
#[derive(Debug, Clone, Deserialize, Serialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct WallSpec {
    /// A point of the plane, m (one component per dimension).
    pub point: Vec<f64>,
    /// The plane's normal, pointing to the particles' side (need not be unit length).
    pub normal: Vec<f64>,
    /// `rigid` (default) or `symmetry`.
    #[serde(default = "rigid", rename = "type")]
    pub kind: String,
    /// Coulomb friction coefficient of a rigid wall (default 0: frictionless).
    #[serde(default)]
    pub friction: f64,
}

fn rigid() -> String {
    "rigid".into()
}

fn fail(key: &str, msg: impl std::fmt::Display) -> Result<(), SceneError> {
    Err(SceneError(format!("{key}: {msg}")))
}

/// Checks the walls of a scene.
pub fn validate(s: &Scene) -> Result<(), SceneError> {
    for (k, w) in s.walls.iter().enumerate() {
        let key = format!("walls[{k}]");
        for (name, v) in [("point", &w.point), ("normal", &w.normal)] {
            if v.len() != s.dim {
                return fail(
                    &format!("{key}.{name}"),
                    format!(
                        "must have {} component{} for a {}D scene (got {})",
                        s.dim,
                        if s.dim == 1 { "" } else { "s" },
                        s.dim,
                        v.len()
                    ),
                );
            }
            if let Some(x) = v.iter().find(|x| !x.is_finite()) {
                return fail(
                    &format!("{key}.{name}"),
                    format!("must be finite (got {x})"),
                );
            }
        }
        if w.normal.iter().all(|&x| x == 0.0) {
            return fail(&format!("{key}.normal"), "must not be zero");
        }
        match w.kind.as_str() {
            "rigid" | "symmetry" => {}
            other => {
                return fail(
                    &format!("{key}.type"),
                    format!("unknown type `{other}` (known: rigid, symmetry)"),
                )
            }
        }
        if !(w.friction.is_finite() && w.friction >= 0.0) {
            return fail(
                &format!("{key}.friction"),
                format!("must be non-negative and finite (got {})", w.friction),
            );
        }
        if w.kind == "symmetry" && w.friction != 0.0 {
            return fail(
                &format!("{key}.friction"),
                "a symmetry plane has no friction (its mirror is the other half of the body)",
            );
        }
        if let Some(p) = &s.periodic {
            let n = unit(&w.normal);
            if let Some(&a) = p.axes.iter().find(|&&a| n[a].abs() > 1e-12) {
                return fail(
                    &format!("{key}.normal"),
                    format!("has a component along the periodic axis {a}"),
                );
            }
        }
    }
    if !s.walls.is_empty() && s.window.is_some() {
        return fail(
            "walls",
            "not with a moving window (the window has its own entry and exit conditions)",
        );
    }
    Ok(())
}

/// `v / |v|`.
pub fn unit(v: &[f64]) -> Vec<f64> {
    let n = v.iter().map(|x| x * x).sum::<f64>().sqrt();
    v.iter().map(|x| x / n).collect()
}
