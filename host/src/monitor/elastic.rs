//! Diagnostics of elastic bodies (`[monitor]` keys `bodies`, `strain_energy`,
//! `close_pairs`): what the colliding rings of Gray, Monaghan & Swift (2001) are judged by
//! (`cases/rings.toml`, `scripts/peers.sh`). Each is computed from a particle table (rows
//! in id order), so it does not depend on how particles sit in memory.

use crate::neighbors::nearest_distances;
use crate::output::table::ParticleTable;
use crate::scene::{InitialParticles, MonitorSpec};
use gsph_core::material::Material;
use gsph_core::math::{Sym3, Vector};
use gsph_core::schemes::hourglass;

/// The diagnostics a scene asks for, with what they need from the initial particles.
#[derive(Debug, Clone)]
pub struct Elastic {
    dim: usize,
    /// Body of each particle id (`bodies`).
    body_of: Option<Vec<u16>>,
    /// Number of bodies.
    bodies: usize,
    /// Reference bulk and shear moduli of each material (`strain_energy`,
    /// `mechanical_energy`).
    moduli: Vec<(f64, f64)>,
    /// Record the strain energy (`strain_energy`).
    strain: bool,
    /// The hourglass stiffness's xi (effect `hourglass`): its stored energy counts with
    /// the strain energy.
    hourglass: Option<f64>,
    /// The initial kinetic plus strain energy, J (`mechanical_energy`).
    mechanical: Option<f64>,
    /// The initial angular momentum about the z axis through the origin, kg m²/s
    /// (`angular_momentum`).
    angular: Option<f64>,
    /// Lattice spacing of each particle id and the fraction (`close_pairs`).
    close: Option<(Vec<f64>, f64)>,
    /// Largest close fraction and smallest distance over the samples so far.
    worst: (f64, f64),
}

const AXES: [&str; 3] = ["vx", "vy", "vz"];

impl Elastic {
    /// The diagnostics of `spec` (`None` if it asks for none).
    pub fn new(
        spec: &MonitorSpec,
        dim: usize,
        parts: &InitialParticles,
        materials: &[Material],
        hourglass: Option<f64>,
    ) -> Option<Elastic> {
        if !spec.bodies
            && !spec.strain_energy
            && !spec.mechanical_energy
            && !spec.angular_momentum
            && spec.close_pairs.is_none()
        {
            return None;
        }
        let moduli: Vec<(f64, f64)> = materials
            .iter()
            .map(|m| {
                let k = m.rho0 * m.eos(m.rho0, 0.0).c2.max(0.0);
                (k, m.shear_modulus)
            })
            .collect();
        let mechanical = spec.mechanical_energy.then(|| {
            let mut e0 = 0.0;
            for i in 0..parts.x.len() {
                let mat = &materials[parts.mat[i] as usize];
                let p = mat.eos(parts.rho[i], parts.e[i]).p;
                let v = parts.v[i];
                e0 += 0.5 * parts.m[i] * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
                let (k, g) = moduli[parts.mat[i] as usize];
                e0 += parts.m[i] / parts.rho[i] * strain_density(p, &parts.s[i], k, g);
            }
            e0
        });
        let bodies = parts
            .body
            .iter()
            .map(|&b| b as usize + 1)
            .max()
            .unwrap_or(0);
        Some(Elastic {
            dim,
            body_of: spec.bodies.then(|| parts.body.clone()),
            bodies,
            moduli,
            strain: spec.strain_energy,
            hourglass,
            mechanical,
            angular: spec.angular_momentum.then(|| {
                (0..parts.x.len())
                    .map(|i| {
                        parts.m[i] * (parts.x[i][0] * parts.v[i][1] - parts.x[i][1] * parts.v[i][0])
                    })
                    .sum()
            }),
            close: spec.close_pairs.map(|f| (parts.spacing.clone(), f)),
            worst: (0.0, f64::INFINITY),
        })
    }

    /// Names of the series columns (and of the summary keys).
    pub fn names(&self) -> Vec<String> {
        let mut out = Vec::new();
        if self.body_of.is_some() {
            for k in 0..self.bodies {
                for a in AXES.iter().take(self.dim) {
                    out.push(format!("body{k}_{a}"));
                }
            }
        }
        if self.strain {
            out.push("strain_energy".into());
        }
        if self.mechanical.is_some() {
            out.push("mechanical_energy".into());
            out.push("mechanical_energy_ratio".into());
        }
        if self.angular.is_some() {
            out.push("angular_momentum_z".into());
            out.push("angular_momentum_change".into());
        }
        if self.close.is_some() {
            out.push("close_fraction".into());
            out.push("min_distance".into());
        }
        out
    }

    /// The values of [`Elastic::names`] for a table (updates the extremes over the run).
    pub fn sample(&mut self, t: &ParticleTable) -> Vec<f64> {
        let mut out = Vec::new();
        if let Some(body_of) = &self.body_of {
            let mut mom = vec![[0.0; 3]; self.bodies];
            let mut mass = vec![0.0; self.bodies];
            for i in 0..t.len() {
                let b = body_of[t.id[i] as usize] as usize;
                mass[b] += t.m[i];
                for (a, v) in [&t.vx, &t.vy, &t.vz].iter().enumerate() {
                    mom[b][a] += t.m[i] * v[i];
                }
            }
            for (m, mass) in mom.iter().zip(&mass) {
                out.extend(m.iter().take(self.dim).map(|p| p / mass));
            }
        }
        if self.strain || self.mechanical.is_some() {
            let se = self.strain_energy(t);
            if self.strain {
                out.push(se);
            }
            if let Some(e0) = self.mechanical {
                let mut ke = 0.0;
                for i in 0..t.len() {
                    ke +=
                        0.5 * t.m[i] * (t.vx[i] * t.vx[i] + t.vy[i] * t.vy[i] + t.vz[i] * t.vz[i]);
                }
                out.push(ke + se);
                out.push((ke + se) / e0);
            }
        }
        if let Some(l0) = self.angular {
            let mut l = 0.0;
            for i in 0..t.len() {
                l += t.m[i] * (t.x[i] * t.vy[i] - t.y[i] * t.vx[i]);
            }
            out.push(l);
            out.push((l - l0) / l0.abs());
        }
        if let Some((spacing, f)) = &self.close {
            let x: Vec<Vector<3>> = (0..t.len())
                .map(|i| Vector::<3>::new(t.x[i], t.y[i], t.z[i]))
                .collect();
            let reach = spacing.iter().copied().fold(0.0, f64::max);
            let near = nearest_distances(&x, reach);
            let (mut close, mut min) = (0usize, f64::INFINITY);
            for (i, d) in near.iter().enumerate() {
                let dx = spacing[t.id[i] as usize];
                close += (*d < f * dx) as usize;
                min = min.min(d / dx);
            }
            let frac = close as f64 / t.len().max(1) as f64;
            self.worst = (self.worst.0.max(frac), self.worst.1.min(min));
            out.push(frac);
            out.push(min);
        }
        out
    }

    /// The elastic strain energy `sum V (p²/(2K) + S:S/(4G))`, J, with the energy the
    /// hourglass stiffness stores (`gsph_core::schemes::hourglass::stored_energy`) where
    /// the run has it, and the energy tl's stiffness stores (the particle field `phi`).
    fn strain_energy(&self, t: &ParticleTable) -> f64 {
        let mut se = 0.0;
        for i in 0..t.len() {
            let (k, g) = self.moduli[t.material[i] as usize];
            let s = Sym3::new(t.sxx[i], t.syy[i], t.szz[i], t.sxy[i], t.sxz[i], t.syz[i]);
            let vol = t.m[i] / t.rho[i];
            se += vol * strain_density(t.p[i], &s, k, g);
            if let Some(xi) = self.hourglass {
                let kh = hourglass::stiffness(xi, g, vol, t.h[i], t.damage[i]);
                let d = Vector::<3>::new(t.hgx[i], t.hgy[i], t.hgz[i]);
                se += hourglass::stored_energy(kh, &d);
            }
            // tl's stiffness keeps its energy per particle (0 in other schemes)
            se += t.phi[i];
        }
        se
    }

    /// Summary keys: the values at the end, and the extremes of the close pairs over the
    /// samples (including the end).
    pub fn measures(&mut self, t: &ParticleTable) -> Vec<(String, f64)> {
        let values = self.sample(t);
        let mut out: Vec<(String, f64)> = self.names().into_iter().zip(values).collect();
        if self.close.is_some() {
            out.push(("close_fraction_max".into(), self.worst.0));
            out.push(("min_distance_min".into(), self.worst.1));
        }
        out
    }

    /// What must survive a restart: the extremes so far.
    pub fn accumulated(&self) -> Vec<f64> {
        if self.close.is_some() {
            vec![self.worst.0, self.worst.1]
        } else {
            Vec::new()
        }
    }

    /// Restores [`Elastic::accumulated`]; returns how many values it took.
    pub fn restore(&mut self, values: &[f64]) -> Result<usize, String> {
        if self.close.is_none() {
            return Ok(0);
        }
        match values {
            [a, b, ..] => {
                self.worst = (*a, *b);
                Ok(2)
            }
            _ => Err("monitor state: the close-pair extremes are missing".into()),
        }
    }
}

/// Strain energy per unit volume, J/m³: `p²/(2K) + S:S/(4G)` (the shear part only where
/// `G > 0`).
fn strain_density(p: f64, s: &Sym3, k: f64, g: f64) -> f64 {
    let mut w = p * p / (2.0 * k);
    if g > 0.0 {
        w += s.ddot(s) / (4.0 * g);
    }
    w
}
