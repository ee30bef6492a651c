//! Caller-given particles: arrays of positions, velocities and states, and the material
//! of each particle from the settings' `[[materials]]`.

use super::{ApiError, ApiResult};
use crate::scene::materials::material_of;
use crate::scene::{self, InitialParticles, Scene};
use gsph_core::math::Sym3;

/// Particles from the caller's arrays (`n` particles; vectors `dim` values per particle).
/// Mass is `density * spacing^dim` unless given.
#[derive(Debug, Clone, Copy, Default)]
pub struct Particles<'a> {
    /// Positions, m (`n * dim`).
    pub position: &'a [f64],
    /// Velocities, m/s (`n * dim`; empty: at rest).
    pub velocity: &'a [f64],
    /// Densities, kg/m³ (`n`; empty: each material's `rho0`).
    pub density: &'a [f64],
    /// Specific internal energies, J/kg (`n`; empty: 0).
    pub energy: &'a [f64],
    /// Masses, kg (`n`; empty: `density * spacing^dim`).
    pub mass: &'a [f64],
    /// Material index of each particle, into the settings' `[[materials]]` (`n`).
    pub material: &'a [u32],
    /// Lattice spacing, m (`n`, or one value for all): sets the smoothing length
    /// (`h_factor * spacing` at the initial density) and the overlap check.
    pub spacing: &'a [f64],
}

fn arg<T>(msg: String) -> ApiResult<T> {
    Err(ApiError::Argument(msg))
}

impl Particles<'_> {
    /// Number of particles (the length of `material`).
    pub fn len(&self) -> usize {
        self.material.len()
    }

    /// True without particles.
    pub fn is_empty(&self) -> bool {
        self.material.is_empty()
    }

    /// Checks every array and builds the particles of `scene` (validated settings).
    pub(super) fn build(&self, scene: &Scene) -> ApiResult<InitialParticles> {
        let (n, d) = (self.len(), scene.dim);
        if n == 0 {
            return arg("particles: none given (`material` is empty)".into());
        }
        let lengths: [(&str, usize, &[f64], bool); 6] = [
            ("position", n * d, self.position, true),
            ("velocity", n * d, self.velocity, false),
            ("density", n, self.density, false),
            ("energy", n, self.energy, false),
            ("mass", n, self.mass, false),
            ("spacing", n, self.spacing, true),
        ];
        for (name, want, a, required) in lengths {
            let ok = a.len() == want
                || (!required && a.is_empty())
                || (name == "spacing" && a.len() == 1);
            if !ok {
                let also = if name == "spacing" {
                    " or 1"
                } else if required {
                    ""
                } else {
                    " or 0"
                };
                return arg(format!(
                    "particles.{name}: {} values given, {want}{also} needed ({n} particles, dim {d})",
                    a.len()
                ));
            }
            if let Some(k) = a.iter().position(|v| !v.is_finite()) {
                return arg(format!("particles.{name}: value {k} is not finite"));
            }
            let positive = matches!(name, "density" | "mass" | "spacing");
            if let Some(k) = a.iter().position(|&v| positive && v <= 0.0) {
                return arg(format!(
                    "particles.{name}: value {k} must be positive (got {:e})",
                    a[k]
                ));
            }
        }
        let mats = &scene.materials;
        if let Some(k) = self.material.iter().position(|&m| m as usize >= mats.len()) {
            return arg(format!(
                "particles.material: particle {k} has material {}, but the settings define {} material(s)",
                self.material[k],
                mats.len()
            ));
        }
        let materials: Vec<_> = mats.iter().map(material_of).collect();
        let pick = |a: &[f64], k: usize, default: f64| if a.is_empty() { default } else { a[k] };
        let mut out = InitialParticles {
            dim: d,
            porosity: vec![1.0; mats.len()],
            ..Default::default()
        };
        for k in 0..n {
            let mi = self.material[k] as usize;
            let mut x = [0.0; 3];
            x[..d].copy_from_slice(&self.position[k * d..(k + 1) * d]);
            let mut v = [0.0; 3];
            if !self.velocity.is_empty() {
                v[..d].copy_from_slice(&self.velocity[k * d..(k + 1) * d]);
            }
            let dx = if self.spacing.len() == 1 {
                self.spacing[0]
            } else {
                self.spacing[k]
            };
            let rho = pick(self.density, k, materials[mi].rho0);
            let e = pick(self.energy, k, 0.0);
            let st = materials[mi].eos(rho, e);
            if !(st.p.is_finite() && st.c2.is_finite()) {
                return arg(format!(
                    "particles: particle {k}: the EOS of material `{}` has no state at density {rho:e} kg/m³, energy {e:e} J/kg",
                    mats[mi].name
                ));
            }
            out.x.push(x);
            out.v.push(v);
            out.m.push(pick(self.mass, k, rho * dx.powi(d as i32)));
            out.rho.push(rho);
            out.e.push(e);
            out.s.push(Sym3::ZERO);
            out.mat.push(mi as u16);
            out.body.push(mi as u16);
            out.spacing.push(dx);
        }
        if let Some(p) = &scene.periodic {
            // as scene::periodic::check_length, with the caller's coarsest spacing
            let dx = out.spacing.iter().cloned().fold(0.0, f64::max);
            let support = scene.kernel.support();
            let min = 2.0 * support * scene.h_factor * dx;
            if let Some(&a) = p
                .axes
                .iter()
                .find(|&&a| p.hi[a] - p.lo[a] < min * (1.0 - 1e-9))
            {
                return arg(format!(
                    "periodic.hi: the periodic length along axis {a} is {:e} m, below twice the kernel support, {min:e} m at the particles' largest spacing {dx:e} m",
                    p.hi[a] - p.lo[a]
                ));
            }
        }
        scene::check_particles(scene, &out)?;
        Ok(out)
    }
}
