//! The shape of a rod after impact on a wall (the Taylor test): its length along its axis
//! and the diameter of its impact face (`[monitor] rod`).

use crate::output::ParticleTable;
use crate::scene::SceneError;

/// A rod standing on the plane `x[axis] = base[axis]`, its axis through `base`.
#[derive(Debug, Clone)]
pub struct Rod {
    base: [f64; 3],
    axis: usize,
}

impl Rod {
    /// From the scene's `monitor.rod` (3D only).
    pub fn new(spec: &crate::scene::RodSpec, dim: usize) -> Result<Rod, SceneError> {
        let fail = |k: &str, m: String| Err(SceneError(format!("monitor.rod.{k}: {m}")));
        if dim != 3 {
            return fail(
                "axis",
                format!("the rod measures are 3D (the scene is {dim}D)"),
            );
        }
        if spec.axis > 2 {
            return fail("axis", format!("must be 0, 1 or 2 (got {})", spec.axis));
        }
        if spec.base.len() != 3 || spec.base.iter().any(|x| !x.is_finite()) {
            return fail("base", "must be 3 finite coordinates".into());
        }
        Ok(Rod {
            base: [spec.base[0], spec.base[1], spec.base[2]],
            axis: spec.axis,
        })
    }

    /// (length, impact-face diameter), m: the far end of the particle farthest along the
    /// axis from the base plane (its position plus half its spacing `(m/rho)^(1/3)`), and
    /// twice the largest distance from the axis, plus half a spacing, of the particles
    /// within one spacing of the base plane.
    pub fn measure(&self, t: &ParticleTable) -> (f64, f64) {
        let (a, b, c) = (self.axis, (self.axis + 1) % 3, (self.axis + 2) % 3);
        let (mut length, mut radius) = (0.0f64, 0.0f64);
        for i in 0..t.len() {
            let x = [t.x[i], t.y[i], t.z[i]];
            let half = 0.5 * (t.m[i] / t.rho[i]).cbrt();
            let along = x[a] - self.base[a];
            length = length.max(along + half);
            if along < 2.0 * half {
                let r = ((x[b] - self.base[b]).powi(2) + (x[c] - self.base[c]).powi(2)).sqrt();
                radius = radius.max(r + half);
            }
        }
        (length, 2.0 * radius)
    }
}
