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
        if unit(&w.normal).is_none() {
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
            let n = unit(&w.normal).expect("checked above");
            if let Some(&a) = p.axes.iter().find(|&&a| n[a].abs() > 1e-12) {
                return fail(
                    &format!("{key}.normal"),
                    format!("has a component along the periodic axis {a}"),
                );
            }
        }
    }
    if let Some((a, b)) = coincident(&s.walls) {
        return fail(
            "walls",
            format!(
                "walls[{a}] and walls[{b}] are the same plane with the same normal: each would push the particles, twice the wall's force; remove one"
            ),
        );
    }
    if !s.walls.is_empty() && s.window.is_some() {
        return fail(
            "walls",
            "not with a moving window (the window has its own entry and exit conditions)",
        );
    }
    Ok(())
}

/// The unit vector `v / |v|`, computed without overflow or underflow (the components
/// are first divided by the largest magnitude among them, so `[1e300]`, `[1e-300]` and
/// `[1e200, 1e200]` have their true directions); `None` for a zero or non-finite vector.
/// Every use of a wall's normal (validation, the periodic-axis test, the mirrors, the
/// particles-behind-the-plane check) goes through this one function.
pub fn unit(v: &[f64]) -> Option<Vec<f64>> {
    let big = v.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    if !(big.is_finite() && big > 0.0) {
        return None;
    }
    let scaled: Vec<f64> = v.iter().map(|x| x / big).collect();
    let n = scaled.iter().map(|x| x * x).sum::<f64>().sqrt();
    let u: Vec<f64> = scaled.iter().map(|x| x / n).collect();
    u.iter().all(|x| x.is_finite()).then_some(u)
}

/// The first two walls (by index) that lie in the same plane with the same unit normal:
/// normals equal to 1e-9 and the second point within 1e-9 of the scale of the points
/// from the first plane (walls further apart but within the kernel's reach of each
/// other are refused when the particles are placed, `crate::sim::walls`).
fn coincident(walls: &[WallSpec]) -> Option<(usize, usize)> {
    let planes: Vec<Option<Vec<f64>>> = walls.iter().map(|w| unit(&w.normal)).collect();
    for b in 1..walls.len() {
        for a in 0..b {
            let (Some(na), Some(nb)) = (&planes[a], &planes[b]) else {
                continue;
            };
            if na.iter().zip(nb).any(|(x, y)| (x - y).abs() > 1e-9) {
                continue;
            }
            let (pa, pb) = (&walls[a].point, &walls[b].point);
            let offset: f64 = pa
                .iter()
                .zip(pb)
                .zip(na)
                .map(|((x, y), n)| (y - x) * n)
                .sum();
            let scale = pa.iter().chain(pb).fold(0.0f64, |m, x| m.max(x.abs()));
            if offset.abs() <= 1e-9 * scale {
                return Some((a, b));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unit_normals_survive_extreme_magnitudes() {
        assert_eq!(unit(&[1e300]), Some(vec![1.0]));
        assert_eq!(unit(&[-1e-300]), Some(vec![-1.0]));
        assert_eq!(unit(&[5e-324]), Some(vec![1.0]));
        let u = unit(&[1e200, 1e200]).unwrap();
        assert!((u[0] - 0.5f64.sqrt()).abs() < 1e-15 && (u[1] - u[0]).abs() == 0.0);
        let u = unit(&[3e-310, -4e-310, 0.0]).unwrap();
        assert!((u[0] - 0.6).abs() < 1e-15 && (u[1] + 0.8).abs() < 1e-15 && u[2] == 0.0);
        assert_eq!(unit(&[0.0, 0.0]), None);
        assert_eq!(unit(&[f64::INFINITY]), None);
        assert_eq!(unit(&[f64::NAN, 1.0]), None);
    }

    fn wall(point: &[f64], normal: &[f64]) -> WallSpec {
        WallSpec {
            point: point.to_vec(),
            normal: normal.to_vec(),
            kind: "rigid".into(),
            friction: 0.0,
        }
    }

    #[test]
    fn coincident_walls_are_found_whatever_the_length_of_their_normals() {
        let same = [wall(&[0.0], &[1.0]), wall(&[0.0], &[1e300])];
        assert_eq!(coincident(&same), Some((0, 1)));
        let shifted_in_plane = [
            wall(&[0.0, 0.0], &[0.0, 2.0]),
            wall(&[0.3, 1.0], &[1.0, 0.0]),
            wall(&[5.0, 0.0], &[0.0, 1.0]),
        ];
        assert_eq!(coincident(&shifted_in_plane), Some((0, 2)));
        // opposite normals, or a plane a little further along: not the same plane
        assert_eq!(
            coincident(&[wall(&[0.0], &[1.0]), wall(&[0.0], &[-1.0])]),
            None
        );
        assert_eq!(
            coincident(&[wall(&[0.0], &[1.0]), wall(&[-1e-6], &[1.0])]),
            None
        );
    }
}
