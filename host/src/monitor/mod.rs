//! Quantities recorded during a run that do not need an exact reference: the peak velocity
//! of a target's free back face (spall), the damaged area, the temperature and the
//! smallest density. Series columns are sampled on the series schedule; summary keys are
//! computed from the final state (peaks: over the sampled series).

pub mod elastic;
pub mod rod;

use crate::output::table::ParticleTable;
use crate::scene::{InitialParticles, Scene, SceneError};
use elastic::Elastic;
use gsph_core::material::Material;

/// The particles of a back face and the running peak of their velocity.
#[derive(Debug, Clone)]
struct BackFace {
    /// `member[id]`: the particle with this id belongs to the face.
    member: Vec<bool>,
    axis: usize,
    normal: f64,
    peak: f64,
    peak_time: f64,
}

/// A wave front tracked along an axis.
#[derive(Debug, Clone)]
struct Front {
    axis: usize,
    velocity: f64,
    bin: f64,
    fit_from: f64,
    behind: f64,
    /// (t, position) samples.
    samples: Vec<(f64, f64)>,
}

impl Front {
    /// Mean velocity along the axis per bin: (bin index -> (sum v, count)), from `lo`.
    fn bins(&self, table: &ParticleTable) -> (f64, Vec<(f64, usize)>) {
        let x = [&table.x, &table.y, &table.z][self.axis];
        let v = [&table.vx, &table.vy, &table.vz][self.axis];
        let lo = x.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = x.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let n = (((hi - lo) / self.bin).floor() as usize + 1).min(1 << 24);
        let mut bins = vec![(0.0, 0usize); n];
        for i in 0..table.len() {
            let k = (((x[i] - lo) / self.bin) as usize).min(n - 1);
            bins[k].0 += v[i];
            bins[k].1 += 1;
        }
        (lo, bins)
    }

    /// Front position: far end of the last bin of the first run of bins (from the low end
    /// of the axis) whose mean velocity reaches the threshold (NaN if none does), and the
    /// index of that bin.
    fn locate(&self, table: &ParticleTable) -> (f64, Option<usize>, Vec<(f64, usize)>) {
        let (lo, bins) = self.bins(table);
        // the end of the first run of bins (from the low end) at or above the threshold:
        // the driven side is at the low end, and disturbances far ahead of the front (a free
        // rear surface) do not count
        let above = |&(sum, c): &(f64, usize)| c > 0 && sum / c as f64 >= self.velocity;
        let k = bins.iter().position(above).map(|first| {
            first
                + bins[first..]
                    .iter()
                    .position(|b| b.1 > 0 && !above(b))
                    .unwrap_or(bins.len() - first)
                - 1
        });
        let pos = k.map_or(f64::NAN, |k| lo + (k + 1) as f64 * self.bin);
        (pos, k, bins)
    }

    /// Least-squares slope of position against time over the samples after `t0`.
    fn speed(&self, t0: f64) -> f64 {
        let pts: Vec<(f64, f64)> = self
            .samples
            .iter()
            .copied()
            .filter(|&(t, x)| t >= t0 && x.is_finite())
            .collect();
        slope(&pts)
    }
}

/// Least-squares slope dy/dx of the points `(x, y)` (NaN for fewer than three points).
pub fn slope(pts: &[(f64, f64)]) -> f64 {
    let n = pts.len() as f64;
    if pts.len() < 3 {
        return f64::NAN;
    }
    let (mt, mx) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let cov: f64 = pts.iter().map(|p| (p.0 - mt) * (p.1 - mx)).sum();
    let var: f64 = pts.iter().map(|p| (p.0 - mt).powi(2)).sum();
    cov / var
}

/// What a scene asks to record (see [`crate::scene::MonitorSpec`]) plus the measures every
/// damage or heat run reports.
#[derive(Debug, Clone)]
pub struct Monitor {
    back_face: Option<BackFace>,
    front: Option<Front>,
    t_end: f64,
    /// `damaging[k]`: material k accumulates damage.
    damaging: Vec<bool>,
    heat: bool,
    elastic: Option<Elastic>,
    rod: Option<rod::Rod>,
}

impl Monitor {
    /// The monitor of a (validated) scene.
    pub fn new(
        scene: &Scene,
        parts: &InitialParticles,
        materials: &[Material],
    ) -> Result<Monitor, SceneError> {
        let back_face = scene
            .monitor
            .as_ref()
            .and_then(|m| m.back_face.as_ref())
            .map(|bf| {
                let mat = scene
                    .materials
                    .iter()
                    .position(|m| m.name == bf.material)
                    .unwrap_or(usize::MAX);
                let member: Vec<bool> = (0..parts.x.len())
                    .map(|i| {
                        parts.mat[i] as usize == mat
                            && (parts.x[i][bf.axis] - bf.position).abs() < parts.spacing[i]
                    })
                    .collect();
                if !member.contains(&true) {
                    return Err(SceneError(format!(
                        "monitor.back_face: no particle of `{}` starts within one spacing of x[{}] = {:e} m",
                        bf.material, bf.axis, bf.position
                    )));
                }
                Ok(BackFace {
                    member,
                    axis: bf.axis,
                    normal: bf.normal,
                    peak: f64::NEG_INFINITY,
                    peak_time: 0.0,
                })
            })
            .transpose()?;
        let finest = parts.spacing.iter().copied().fold(f64::INFINITY, f64::min);
        let front = scene
            .monitor
            .as_ref()
            .and_then(|m| m.front.as_ref())
            .map(|f| {
                let bin = f.bin.unwrap_or(2.0 * finest);
                Front {
                    axis: f.axis,
                    velocity: f.velocity,
                    bin,
                    fit_from: f.fit_from.unwrap_or(0.5),
                    behind: f.behind.unwrap_or(10.0 * bin),
                    samples: Vec::new(),
                }
            });
        Ok(Monitor {
            back_face,
            front,
            t_end: scene.t_end,
            damaging: materials.iter().map(Material::has_damage).collect(),
            heat: materials.iter().any(Material::has_heat),
            elastic: scene.monitor.as_ref().and_then(|m| {
                Elastic::new(m, scene.dim, parts, materials, scene.options.hourglass)
            }),
            rod: scene
                .monitor
                .as_ref()
                .and_then(|m| m.rod.as_ref())
                .map(|r| rod::Rod::new(r, scene.dim))
                .transpose()?,
        })
    }

    /// True if the series needs a particle table at each sample.
    pub fn samples(&self) -> bool {
        self.back_face.is_some()
            || self.front.is_some()
            || self.elastic.is_some()
            || self.rod.is_some()
    }

    /// Names of the series columns.
    pub fn series_names(&self) -> Vec<String> {
        let mut names = Vec::new();
        if self.back_face.is_some() {
            names.push("back_face_velocity".to_string());
        }
        if self.front.is_some() {
            names.push("front_position".to_string());
        }
        if let Some(el) = &self.elastic {
            names.extend(el.names());
        }
        if self.rod.is_some() {
            names.extend(["rod_length".to_string(), "rod_impact_diameter".to_string()]);
        }
        names
    }

    /// Samples the series columns at time `t` (and updates the peaks).
    pub fn sample(&mut self, table: &ParticleTable, t: f64) -> Vec<f64> {
        let mut out = Vec::new();
        if let Some(bf) = self.back_face.as_mut() {
            let v = [&table.vx, &table.vy, &table.vz][bf.axis];
            let fastest = (0..table.len())
                .filter(|&i| bf.member.get(table.id[i] as usize) == Some(&true))
                .map(|i| bf.normal * v[i])
                .fold(f64::NEG_INFINITY, f64::max);
            if fastest > bf.peak {
                bf.peak = fastest;
                bf.peak_time = t;
            }
            out.push(fastest);
        }
        if let Some(fr) = self.front.as_mut() {
            let (pos, _, _) = fr.locate(table);
            fr.samples.push((t, pos));
            out.push(pos);
        }
        if let Some(el) = self.elastic.as_mut() {
            out.extend(el.sample(table));
        }
        if let Some(rod) = &self.rod {
            let (l, d) = rod.measure(table);
            out.extend([l, d]);
        }
        out
    }

    /// What the monitor has accumulated so far, as numbers (for checkpoints): the back-face
    /// peak and its time, then the front samples `(t, position)` in order.
    pub fn accumulated(&self) -> Vec<f64> {
        let mut out = Vec::new();
        if let Some(bf) = &self.back_face {
            out.extend([bf.peak, bf.peak_time]);
        }
        if let Some(el) = &self.elastic {
            out.extend(el.accumulated());
        }
        if let Some(fr) = &self.front {
            out.extend(fr.samples.iter().flat_map(|&(t, x)| [t, x]));
        }
        out
    }

    /// Restores what [`Monitor::accumulated`] returned for a monitor of the same scene.
    pub fn restore_accumulated(&mut self, values: &[f64]) -> Result<(), String> {
        let mut rest = values;
        if let Some(bf) = self.back_face.as_mut() {
            let [peak, time] = rest
                .get(..2)
                .and_then(|v| v.try_into().ok())
                .ok_or("monitor state: the back-face peak is missing".to_string())?;
            (bf.peak, bf.peak_time) = (peak, time);
            rest = &rest[2..];
        }
        if let Some(el) = self.elastic.as_mut() {
            rest = &rest[el.restore(rest)?..];
        }
        match self.front.as_mut() {
            Some(fr) if rest.len().is_multiple_of(2) => {
                fr.samples = rest.chunks_exact(2).map(|p| (p[0], p[1])).collect();
                Ok(())
            }
            None if rest.is_empty() => Ok(()),
            _ => Err(format!(
                "monitor state: {} values do not fit this scene's monitor",
                values.len()
            )),
        }
    }

    /// Summary keys from the final state.
    pub fn measures(&mut self, table: &ParticleTable) -> Vec<(String, f64)> {
        let n = table.len();
        let mut out = vec![(
            "density_min".to_string(),
            table.rho.iter().copied().fold(f64::INFINITY, f64::min),
        )];
        if let Some(el) = self.elastic.as_mut() {
            out.extend(el.measures(table));
        }
        if let Some(rod) = &self.rod {
            let (l, d) = rod.measure(table);
            out.extend([
                ("rod_length".to_string(), l),
                ("rod_impact_diameter".to_string(), d),
            ]);
        }
        let mut out_static: Vec<(&'static str, f64)> = Vec::new();
        if let Some(bf) = &self.back_face {
            out_static.push(("back_face_velocity_peak", bf.peak));
            out_static.push(("back_face_velocity_peak_time", bf.peak_time));
        }
        if let Some(fr) = &self.front {
            let (pos, k, bins) = fr.locate(table);
            out_static.push(("front_position", pos));
            out_static.push(("front_speed", fr.speed(fr.fit_from * self.t_end)));
            // mean velocity of the particles in the bins behind the front
            let behind = (fr.behind / fr.bin).round().max(1.0) as usize;
            let (sum, count) = k.map_or((f64::NAN, 1), |k| {
                bins[k.saturating_sub(behind)..k]
                    .iter()
                    .fold((0.0, 0usize), |(s, c), &(bs, bc)| (s + bs, c + bc))
            });
            out_static.push(("behind_front_velocity", sum / count.max(1) as f64));
            // and ahead of it (the state the front runs into)
            let (sum, count) = k.map_or((f64::NAN, 1), |k| {
                bins[(k + 1).min(bins.len())..(k + 1 + behind).min(bins.len())]
                    .iter()
                    .fold((0.0, 0usize), |(s, c), &(bs, bc)| (s + bs, c + bc))
            });
            out_static.push(("ahead_front_velocity", sum / count.max(1) as f64));
        }
        if self.damaging.iter().any(|&d| d) {
            // areas (volumes in 3D) m/rho of the particles of damage-bearing materials
            let (mut all, mut failed, mut weighted) = (0.0, 0.0, 0.0);
            for i in 0..n {
                if self.damaging.get(table.material[i] as usize) != Some(&true) {
                    continue;
                }
                let a = table.m[i] / table.rho[i];
                all += a;
                weighted += a * table.damage[i];
                if table.damage[i] >= 1.0 {
                    failed += a;
                }
            }
            let all = all.max(f64::MIN_POSITIVE);
            out_static.push(("damaged_area_fraction", failed / all));
            out_static.push(("damage_mean", weighted / all));
        }
        if self.heat {
            out_static.push((
                "temperature_max",
                table
                    .temperature
                    .iter()
                    .copied()
                    .fold(f64::NEG_INFINITY, f64::max),
            ));
        }
        out.extend(out_static.into_iter().map(|(k, v)| (k.to_string(), v)));
        out
    }
}
