//! Porous bodies: pores repeated on a periodic cell, cut out of a body's lattice
//! (seed 004 §4: copper with circular pores, porosity m = rho_solid / rho_porous).

use crate::scene::spec::PoresSpec;
use crate::scene::SceneError;

/// Validates a body's pores (`key` is `bodies[k].pores`).
pub fn validate(key: &str, p: &PoresSpec, dim: usize) -> Result<(), SceneError> {
    let fail = |k: String, msg: String| Err(SceneError(format!("{k}: {msg}")));
    if p.cell.len() != dim {
        return fail(
            format!("{key}.cell"),
            format!("must have {dim} components (got {})", p.cell.len()),
        );
    }
    for (a, &c) in p.cell.iter().enumerate() {
        if !(c.is_finite() && c > 0.0) {
            return fail(
                format!("{key}.cell[{a}]"),
                format!("must be positive and finite (got {c})"),
            );
        }
    }
    if !(p.radius.is_finite() && p.radius > 0.0) {
        return fail(
            format!("{key}.radius"),
            format!("must be positive and finite (got {})", p.radius),
        );
    }
    let half = p.cell.iter().cloned().fold(f64::INFINITY, f64::min) / 2.0;
    if p.radius >= half {
        return fail(
            format!("{key}.radius"),
            format!(
                "must be below half the smallest cell side, {half:e} m (got {:e})",
                p.radius
            ),
        );
    }
    if p.centers.is_empty() {
        return fail(
            format!("{key}.centers"),
            "at least one pore centre is required".into(),
        );
    }
    for (k, c) in p.centers.iter().enumerate() {
        if c.len() != dim || c.iter().any(|v| !v.is_finite()) {
            return fail(
                format!("{key}.centers[{k}]"),
                format!("must have {dim} finite components"),
            );
        }
    }
    if let Some(o) = &p.origin {
        if o.len() != dim || o.iter().any(|v| !v.is_finite()) {
            return fail(
                format!("{key}.origin"),
                format!("must have {dim} finite components"),
            );
        }
    }
    Ok(())
}

/// True if `x` lies inside a pore (or a periodic image of one).
pub fn inside(p: &PoresSpec, x: &[f64; 3]) -> bool {
    let dim = p.cell.len();
    p.centers.iter().any(|c| {
        let mut r2 = 0.0;
        for a in 0..dim {
            let o = p.origin.as_ref().map_or(0.0, |o| o[a]);
            let mut d = x[a] - o - c[a];
            d -= p.cell[a] * (d / p.cell[a]).round();
            r2 += d * d;
        }
        r2 < p.radius * p.radius
    })
}

/// The porosity m = V_total / V_solid the pore geometry implies when pores do not overlap
/// (2D: circles, 3D: spheres).
pub fn geometric_porosity(p: &PoresSpec) -> f64 {
    let dim = p.cell.len();
    let cell: f64 = p.cell.iter().product();
    let pore = if dim == 3 {
        4.0 / 3.0 * std::f64::consts::PI * p.radius.powi(3)
    } else {
        std::f64::consts::PI * p.radius * p.radius
    };
    cell / (cell - p.centers.len() as f64 * pore)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seed004(per_cell: usize) -> PoresSpec {
        let centers = if per_cell == 1 {
            vec![vec![10e-6, 10e-6]]
        } else {
            vec![vec![5e-6, 5e-6], vec![15e-6, 15e-6]]
        };
        PoresSpec {
            cell: vec![20e-6, 20e-6],
            centers,
            radius: 4.06e-6,
            origin: None,
        }
    }

    #[test]
    fn two_pores_per_cell_give_the_seed_porosity() {
        // seed 004 §4: m = 1.35 with r = 4.06 um; one pore per 20 um cell gives about 1.15
        let one = geometric_porosity(&seed004(1));
        let two = geometric_porosity(&seed004(2));
        assert!((one - 1.149).abs() < 1e-3, "{one}");
        assert!((two - 1.349).abs() < 1e-3, "{two}");
    }

    #[test]
    fn periodic_images_are_holes_too() {
        let p = seed004(2);
        assert!(inside(&p, &[5e-6, 5e-6, 0.0]));
        assert!(inside(&p, &[45e-6, -15e-6, 0.0])); // image of (5, 5) two cells over
        assert!(inside(&p, &[-4.9e-6, -4.9e-6, 0.0])); // image of (15, 15)
        assert!(!inside(&p, &[10e-6, 10e-6, 0.0]));
        assert!(!inside(&p, &[5e-6, 9.1e-6, 0.0]));
    }
}
