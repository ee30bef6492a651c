//! The shape of a rod after impact on a wall (the Taylor test): its length along its axis
//! and the diameter of its impact face (`[monitor] rod`).

use crate::output::ParticleTable;
use crate::scene::SceneError;
use std::path::Path;

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

    /// A rod on the plane through `base` normal to `axis` (for `gsph plot rod`).
    pub fn at(base: [f64; 3], axis: usize) -> Rod {
        Rod { base, axis }
    }

    /// Particle `i`'s height above the base plane, its distance from the axis, and half its
    /// spacing `(m/rho)^(1/3)`, m.
    fn place(&self, t: &ParticleTable, i: usize) -> (f64, f64, f64) {
        let (a, b, c) = (self.axis, (self.axis + 1) % 3, (self.axis + 2) % 3);
        let x = [t.x[i], t.y[i], t.z[i]];
        let r = ((x[b] - self.base[b]).powi(2) + (x[c] - self.base[c]).powi(2)).sqrt();
        (x[a] - self.base[a], r, 0.5 * (t.m[i] / t.rho[i]).cbrt())
    }

    /// The outline of the rod: for each slab `bin` m thick along the axis, counted from the
    /// rod's near end (as in [`Rod::measure`], so a rod that has bounced off the wall is
    /// drawn standing on it), the height of the slab's middle above that end and the
    /// largest distance from the axis of its particles plus half a spacing, both m; slabs
    /// without particles are left out.
    pub fn profile(&self, t: &ParticleTable, bin: f64) -> Vec<(f64, f64)> {
        let places: Vec<(f64, f64, f64)> = (0..t.len()).map(|i| self.place(t, i)).collect();
        let lo = places
            .iter()
            .map(|&(along, _, half)| along - half)
            .filter(|v| v.is_finite())
            .fold(f64::INFINITY, f64::min);
        let mut slabs: Vec<Option<f64>> = Vec::new();
        for &(along, r, half) in &places {
            let h = along - lo;
            if !(h.is_finite() && bin > 0.0) {
                continue;
            }
            let k = (h / bin) as usize;
            if k >= slabs.len() {
                slabs.resize(k + 1, None);
            }
            let r = r + half;
            slabs[k] = Some(slabs[k].map_or(r, |s: f64| s.max(r)));
        }
        let mid = |k: usize| (k as f64 + 0.5) * bin;
        (0..slabs.len())
            .filter_map(|k| slabs[k].map(|r| (mid(k), r)))
            .collect()
    }

    /// (length, impact-face diameter), m. The length is the rod's extent along the axis:
    /// from the near end of the particle nearest the wall to the far end of the farthest
    /// (each particle's ends half its spacing `(m/rho)^(1/3)` either side of it), so that a
    /// rod that has bounced off the wall is not measured with the gap. The diameter is
    /// twice the largest distance from the axis, plus half a spacing, of the particles
    /// within one spacing of the nearest one. Both are estimates of a surface from particles
    /// and carry the lattice's error: on the undeformed rod of cases/taylor_copper.toml the
    /// length is exact and the diameter reads 8.30 mm at D0/10 and 7.94 mm at D0/20 for
    /// D0 = 7.62 mm (the outermost sites lie almost on the circle).
    pub fn measure(&self, t: &ParticleTable) -> (f64, f64) {
        let places: Vec<(f64, f64, f64)> = (0..t.len()).map(|i| self.place(t, i)).collect();
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut near = (f64::INFINITY, 0.0);
        for &(along, _, half) in &places {
            lo = lo.min(along - half);
            hi = hi.max(along + half);
            if along < near.0 {
                near = (along, half);
            }
        }
        let radius = places
            .iter()
            .filter(|&&(along, _, _)| along < near.0 + 2.0 * near.1)
            .map(|&(_, r, half)| r + half)
            .fold(0.0f64, f64::max);
        ((hi - lo).max(0.0), 2.0 * radius)
    }
}

/// Reads a measured rod outline: a CSV of `r_mm,z_mm` (after `#` comment lines and the
/// header), each row one point of the half profile (r from the axis, z from the impact
/// face), in millimetres. Errors name the file and line.
pub fn read_outline(path: &Path) -> Result<Vec<(f64, f64)>, String> {
    let text = crate::output::safe::read_text(path, crate::output::safe::MAX_TABLE)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let mut rows = text
        .lines()
        .enumerate()
        .filter(|(_, l)| !l.trim_start().starts_with('#') && !l.trim().is_empty());
    match rows.next() {
        Some((_, h)) if h.replace(' ', "") == "r_mm,z_mm" => {}
        Some((k, h)) => {
            return Err(format!(
                "{} line {}: the header must be `r_mm,z_mm` (got `{}`)",
                path.display(),
                k + 1,
                crate::output::safe::excerpt(h)
            ))
        }
        None => return Err(format!("{}: no header `r_mm,z_mm`", path.display())),
    }
    let rows: Vec<(f64, f64)> = rows
        .map(|(k, l)| {
            let v: Vec<f64> = l
                .split(',')
                .map(|x| x.trim().parse().unwrap_or(f64::NAN))
                .collect();
            if v.len() != 2 || v.iter().any(|x| !x.is_finite()) {
                return Err(format!(
                    "{} line {}: expected two finite numbers r_mm,z_mm (got `{}`)",
                    path.display(),
                    k + 1,
                    crate::output::safe::excerpt(l)
                ));
            }
            Ok((v[0], v[1]))
        })
        .collect::<Result<_, _>>()?;
    if rows.len() < 2 {
        return Err(format!("{}: fewer than two outline points", path.display()));
    }
    Ok(rows)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::ParticleRow;

    /// Unit cubes (spacing 1 mm, density 1) of a 2 x 2 x 5 mm rod on the plane z = lift.
    fn rod(lift: f64) -> ParticleTable {
        let mut t = ParticleTable::default();
        for k in 0..5 {
            for j in 0..2 {
                for i in 0..2 {
                    t.push(&ParticleRow {
                        x: (i as f64 - 0.5) * 1e-3,
                        y: (j as f64 - 0.5) * 1e-3,
                        z: lift + (k as f64 + 0.5) * 1e-3,
                        m: 1e-9,
                        rho: 1.0,
                        ..ParticleRow::default()
                    });
                }
            }
        }
        t
    }

    #[test]
    fn a_rod_that_has_left_the_wall_keeps_its_length_and_face() {
        let r = Rod::at([0.0; 3], 2);
        let (l0, d0) = r.measure(&rod(0.0));
        let (l1, d1) = r.measure(&rod(3e-3));
        assert!((l0 - 5e-3).abs() < 1e-12, "{l0}");
        assert!((l1 - 5e-3).abs() < 1e-12, "{l1}");
        let face = 2.0 * (0.5f64.hypot(0.5) + 0.5) * 1e-3;
        assert!(
            (d0 - face).abs() < 1e-12 && (d1 - face).abs() < 1e-12,
            "{d0} {d1}"
        );
    }

    #[test]
    fn the_profile_has_one_point_per_occupied_slab() {
        let p = Rod::at([0.0; 3], 2).profile(&rod(0.0), 1e-3);
        assert_eq!(p, Rod::at([0.0; 3], 2).profile(&rod(2e-3), 1e-3));
        assert_eq!(p.len(), 5);
        for (k, (z, r)) in p.iter().enumerate() {
            assert!((z - (k as f64 + 0.5) * 1e-3).abs() < 1e-12);
            assert!((r - (0.5f64.hypot(0.5) + 0.5) * 1e-3).abs() < 1e-12);
        }
    }
}
