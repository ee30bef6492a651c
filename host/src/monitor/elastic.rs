//! Diagnostics of elastic bodies (`[monitor]` keys `bodies`, `strain_energy`,
//! `close_pairs`): what the colliding rings of Gray, Monaghan & Swift (2001) are judged by
//! (`cases/rings.toml`, `scripts/peers.sh`). Each is computed from a particle table (rows
//! in id order), so it does not depend on how particles sit in memory.

use crate::neighbors::nearest_distances;
use crate::output::table::ParticleTable;
use crate::scene::{InitialParticles, MonitorSpec};
use gsph_core::material::Material;
use gsph_core::math::{Sym3, Vector};

/// The diagnostics a scene asks for, with what they need from the initial particles.
#[derive(Debug, Clone)]
pub struct Elastic {
    dim: usize,
    /// Body of each particle id (`bodies`).
    body_of: Option<Vec<u16>>,
    /// Number of bodies.
    bodies: usize,
    /// Reference bulk and shear moduli of each material (`strain_energy`).
    moduli: Option<Vec<(f64, f64)>>,
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
    ) -> Option<Elastic> {
        if !spec.bodies && !spec.strain_energy && spec.close_pairs.is_none() {
            return None;
        }
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
            moduli: spec.strain_energy.then(|| {
                materials
                    .iter()
                    .map(|m| {
                        let k = m.rho0 * m.eos(m.rho0, 0.0).c2.max(0.0);
                        (k, m.shear_modulus)
                    })
                    .collect()
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
        if self.moduli.is_some() {
            out.push("strain_energy".into());
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
        if let Some(moduli) = &self.moduli {
            let mut se = 0.0;
            for i in 0..t.len() {
                let (k, g) = moduli[t.material[i] as usize];
                let s = Sym3::new(t.sxx[i], t.syy[i], t.szz[i], t.sxy[i], t.sxz[i], t.syz[i]);
                let mut w = t.p[i] * t.p[i] / (2.0 * k);
                if g > 0.0 {
                    w += s.ddot(&s) / (4.0 * g);
                }
                se += t.m[i] / t.rho[i] * w;
            }
            out.push(se);
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
