//! Semantic checks of the parts of a scene: materials (EOS, strength), shapes, and the
//! Poisson-ratio resolution ([`super::validate`] checks the scene as a whole with them).

use super::checks::{dims, fail, finite, non_negative, num, positive, R};
use super::spec::*;
use gsph_core::material::params::ParamError;

pub(super) fn material_known(s: &Scene, key: &str, name: &str) -> R {
    if s.materials.iter().any(|m| m.name == name) {
        Ok(())
    } else {
        let known: Vec<&str> = s.materials.iter().map(|m| m.name.as_str()).collect();
        let close = super::library::close_names(name);
        let library = if close.is_empty() {
            String::new()
        } else {
            format!("; in the material library: {}", close.join(", "))
        };
        fail(
            key,
            format!(
                "unknown material `{name}` (known: {}){library}",
                known.join(", ")
            ),
        )
    }
}

/// A model's own check of its parameters, the key prefixed with the model's path
/// (`materials[0].eos`).
pub(super) fn validate_model(key: &str, checked: Result<(), ParamError>) -> R {
    checked.or_else(|p| fail(&format!("{key}.{}", p.key), p))
}

pub(super) fn validate_shape(key: &str, sh: &ShapeSpec, dim: usize) -> R {
    match sh {
        ShapeSpec::Segment { min, max } => {
            if dim != 1 {
                return fail(key, format!("a segment is a 1D shape; use a box in {dim}D"));
            }
            finite(&format!("{key}.min"), *min)?;
            finite(&format!("{key}.max"), *max)?;
            if max <= min {
                return fail(
                    &format!("{key}.max"),
                    format!("must exceed min ({} <= {})", num(*max), num(*min)),
                );
            }
        }
        ShapeSpec::Box { min, max } => {
            if dim == 1 {
                return fail(key, "use a segment in 1D");
            }
            dims(&format!("{key}.min"), min, dim)?;
            dims(&format!("{key}.max"), max, dim)?;
            for a in 0..dim {
                if max[a] <= min[a] {
                    return fail(&format!("{key}.max[{a}]"), format!("must exceed min[{a}]"));
                }
            }
        }
        ShapeSpec::Cylinder {
            base,
            axis,
            radius,
            length,
            ..
        } => {
            if dim != 3 {
                return fail(
                    key,
                    format!("a cylinder is a 3D shape; the scene is {dim}D"),
                );
            }
            dims(&format!("{key}.base"), base, dim)?;
            if *axis > 2 {
                return fail(
                    &format!("{key}.axis"),
                    format!("must be 0, 1 or 2 (got {axis})"),
                );
            }
            positive(&format!("{key}.radius"), *radius)?;
            positive(&format!("{key}.length"), *length)?;
        }
        ShapeSpec::Disc { center, radius } => {
            if dim == 1 {
                return fail(key, "a disc needs 2 or 3 dimensions");
            }
            dims(&format!("{key}.center"), center, dim)?;
            positive(&format!("{key}.radius"), *radius)?;
        }
        ShapeSpec::Annulus {
            center,
            r_inner,
            r_outer,
        } => {
            if dim != 2 {
                return fail(key, "an annulus is a 2D shape");
            }
            dims(&format!("{key}.center"), center, dim)?;
            non_negative(&format!("{key}.r_inner"), *r_inner)?;
            positive(&format!("{key}.r_outer"), *r_outer)?;
            if r_outer <= r_inner {
                return fail(&format!("{key}.r_outer"), "must exceed r_inner");
            }
        }
        ShapeSpec::Particles { file, .. } => {
            if file.trim().is_empty() {
                return fail(&format!("{key}.file"), "must name a file");
            }
        }
        ShapeSpec::Stl {
            file,
            scale,
            offset,
        } => {
            if dim != 3 {
                return fail(
                    key,
                    format!("an `stl` shape is a closed surface in 3D; the scene is {dim}D"),
                );
            }
            if file.trim().is_empty() {
                return fail(&format!("{key}.file"), "must name a file");
            }
            positive(&format!("{key}.scale"), *scale)?;
            if let Some(o) = offset {
                dims(&format!("{key}.offset"), o, 3)?;
            }
        }
    }
    Ok(())
}

/// Replaces `poisson_ratio` by the shear modulus it implies with the EOS's bulk modulus
/// at the reference state, `G = 3K(1 - 2 nu)/(2(1 + nu))`, `K = rho0 c²(rho0)`.
pub fn resolve_poisson(s: &mut Scene) -> R {
    for (k, m) in s.materials.iter_mut().enumerate() {
        let Some(nu) = m.poisson_ratio else { continue };
        let key = format!("materials[{k}].poisson_ratio");
        if matches!(m.strength, Some(Strength::Fluid)) {
            return fail(&key, "a fluid (strength = fluid) has no shear modulus");
        }
        if m.shear_modulus != 0.0 {
            return fail(&key, "give either shear_modulus or poisson_ratio, not both");
        }
        if !(nu > -1.0 && nu < 0.5) {
            return fail(&key, format!("must lie in (-1, 0.5) (got {nu})"));
        }
        let mat = super::materials::material_of(m);
        let bulk = m.rho0 * mat.eos(m.rho0, 0.0).c2;
        m.shear_modulus = 3.0 * bulk * (1.0 - 2.0 * nu) / (2.0 * (1.0 + nu));
        m.poisson_ratio = None;
        if m.strength.is_none() {
            m.strength = Some(Strength::Elastic);
        }
    }
    Ok(())
}

/// Most steps a run without `max_steps` may be expected to take: beyond it the run would
/// not end in any useful time (a year of steps at 30 µs each).
pub const MAX_ESTIMATED_STEPS: f64 = 1e9;

/// Refuses a `t_end` that no run could reach: the steps it needs at the fixed `dt`, or at
/// the time step of the scene's materials at rest on its finest lattice (`cfl` ×
/// `h_factor` × spacing over the largest longitudinal sound speed at the reference
/// density, an overestimate of the step a run takes), above [`MAX_ESTIMATED_STEPS`],
/// unless `max_steps` bounds the run. The reference state, not the initial one, sets the
/// estimate, so a scene whose initial state blows up in its first step is not refused here
/// (it fails at that step, naming the particle). Bodies from particle files (no spacing)
/// are left out; a scene of file bodies only is not checked. Called once the particles are
/// counted (`build_particles`), so that a spacing too fine for memory is refused as such.
pub(super) fn check_step_count(s: &Scene) -> R {
    if s.max_steps.is_some() {
        return Ok(());
    }
    let dt = match s.dt {
        Some(dt) => dt,
        None => {
            let c = s
                .materials
                .iter()
                .map(|m| {
                    let mat = super::materials::material_of(m);
                    let c2 = mat.eos.eval(m.rho0, 0.0).c2;
                    (c2 + 4.0 * mat.shear_modulus / (3.0 * m.rho0)).sqrt()
                })
                .fold(0.0f64, f64::max);
            let dx = s
                .bodies
                .iter()
                .map(|b| b.spacing / s.resolution_scale)
                .filter(|d| d.is_finite() && *d > 0.0)
                .fold(f64::INFINITY, f64::min);
            if !(c.is_finite() && c > 0.0 && dx.is_finite()) {
                return Ok(());
            }
            s.cfl() * s.h_factor * dx / c
        }
    };
    let steps = s.t_end / dt;
    if steps > MAX_ESTIMATED_STEPS {
        return fail(
            "t_end",
            format!(
                "{} s would take about {steps:.1e} steps of about {dt:.1e} s (the materials' sound speed at rest on the finest spacing), more than {MAX_ESTIMATED_STEPS:.0e}; shorten t_end, or set max_steps to run it anyway",
                num(s.t_end)
            ),
        );
    }
    Ok(())
}
