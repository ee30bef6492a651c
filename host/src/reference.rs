//! Exact references of the cases and the error measures reported in `summary.json` and
//! `series.csv`.

use crate::output::ParticleTable;
use crate::scene::{Eos, ReferenceSpec, Scene, SceneError, Strength};
use gsph_core::exact::{
    ElasticPlasticRiemann, EpRiemannParams, FlyerPlate, FlyerPlateParams, ShellCollapse,
    ShellParams, SoundPulse, SoundPulseParams,
};
use gsph_core::material::eos::{Hugoniot, Linear, Logarithmic};

/// A case's exact or analytic solution.
#[derive(Debug, Clone)]
pub enum Reference {
    /// Seed 000 §4.1.
    Flyer(FlyerPlate),
    /// Seed 004 §2.1.1 with a free left end.
    EpRiemann {
        /// The solution (centred at x = 0).
        sol: ElasticPlasticRiemann,
        /// Where the discontinuity starts, m.
        interface: f64,
        /// Free left end, m.
        x_left: f64,
    },
    /// Cylindrical shell collapse (ring, Verney).
    Shell(Shell),
    /// Linear sound pulse (centred at `center` along x).
    Sound {
        /// The solution (centred at x = 0).
        sol: SoundPulse,
        /// Initial centre, m.
        center: f64,
        /// Lattice spacing of the first particle, m.
        spacing: f64,
    },
}

/// The shell-collapse reference with the particle rows that mark its surfaces.
#[derive(Debug, Clone)]
pub struct Shell {
    /// The analytic solution.
    pub sol: ShellCollapse,
    /// Axis.
    pub center: [f64; 2],
    /// Particles (indices) of the inner surface row.
    pub inner: Vec<usize>,
    /// Particles of the outer surface row.
    pub outer: Vec<usize>,
}

impl Shell {
    /// Inner and outer surface radii of a state, estimated from the surface rows: the
    /// material between a row and its surface is half the rows' volume, so
    /// `pi (r_row² - r_in²) = sum V / 2` (and likewise outside). Exact for a polar lattice
    /// at rest; the `*_row_radius` measures give the plain row radii.
    pub fn radii(&self, t: &ParticleTable) -> ShellRadii {
        let r = |i: usize| {
            ((t.x[i] - self.center[0]).powi(2) + (t.y[i] - self.center[1]).powi(2)).sqrt()
        };
        let vol = |i: usize| t.m[i] / t.rho[i];
        let stats = |rows: &[usize]| {
            let n = rows.len().max(1) as f64;
            let mean = rows.iter().map(|&i| r(i)).sum::<f64>() / n;
            let min = rows.iter().map(|&i| r(i)).fold(f64::INFINITY, f64::min);
            let max = rows.iter().map(|&i| r(i)).fold(0.0, f64::max);
            let v: f64 = rows.iter().map(|&i| vol(i)).sum();
            (mean, min, max, v)
        };
        let (ri, imin, imax, vi) = stats(&self.inner);
        let (ro, _, _, vo) = stats(&self.outer);
        ShellRadii {
            inner: (ri * ri - vi / (2.0 * std::f64::consts::PI))
                .max(0.0)
                .sqrt(),
            outer: (ro * ro + vo / (2.0 * std::f64::consts::PI)).sqrt(),
            inner_row: ri,
            outer_row: ro,
            inner_spread: (imax - imin) / ri,
        }
    }
}

/// Radii of a shell state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShellRadii {
    /// Inner surface radius, m.
    pub inner: f64,
    /// Outer surface radius, m.
    pub outer: f64,
    /// Mean radius of the inner row of particles, m.
    pub inner_row: f64,
    /// Mean radius of the outer row, m.
    pub outer_row: f64,
    /// (max - min)/mean of the inner row's radii: the circumferential symmetry measure.
    pub inner_spread: f64,
}

fn yield_of(scene: &Scene, name: &str, key: &str) -> Result<(f64, f64), SceneError> {
    let m = scene
        .materials
        .iter()
        .find(|m| m.name == name)
        .expect("validated");
    match m.strength {
        Some(Strength::VonMises { yield_stress }) => Ok((m.shear_modulus, yield_stress)),
        _ => Err(SceneError(format!(
            "{key}: material `{name}` must use von_mises strength for this reference"
        ))),
    }
}

impl Reference {
    /// Builds the reference named in the scene, if any. `x0` are the initial positions
    /// and `spacing` each particle's lattice spacing (used to find surface rows).
    pub fn from_scene(
        scene: &Scene,
        x0: &[[f64; 3]],
        spacing: &[f64],
    ) -> Result<Option<Reference>, SceneError> {
        let Some(r) = &scene.reference else {
            return Ok(None);
        };
        let find = |name: &str| {
            scene
                .materials
                .iter()
                .find(|m| m.name == name)
                .expect("validated")
        };
        let bad = |e: gsph_core::exact::ExactError| SceneError(format!("reference: {e}"));
        Ok(Some(match r {
            ReferenceSpec::FlyerPlate {
                material,
                impact_velocity,
                interface,
            } => {
                let m = find(material);
                let Eos::Hugoniot(Hugoniot { c0, s1, .. }) = m.eos else {
                    return Err(SceneError(format!(
                        "reference.material: `{material}` must use the hugoniot EOS for the flyer-plate reference"
                    )));
                };
                let (g, y) = yield_of(scene, material, "reference.material")?;
                Reference::Flyer(
                    FlyerPlate::new(FlyerPlateParams {
                        rho0: m.rho0,
                        c0,
                        s1,
                        shear_modulus: g,
                        yield_stress: y,
                        impact_velocity: *impact_velocity,
                        interface_x: *interface,
                    })
                    .map_err(bad)?,
                )
            }
            ReferenceSpec::ElasticPlasticRiemann {
                material,
                sigma1,
                interface,
                x_left,
            } => {
                let m = find(material);
                let Eos::Logarithmic(Logarithmic { bulk_modulus, .. }) = m.eos else {
                    return Err(SceneError(format!(
                        "reference.material: `{material}` must use the logarithmic EOS for this reference"
                    )));
                };
                let (g, y) = yield_of(scene, material, "reference.material")?;
                let sol = ElasticPlasticRiemann::new(EpRiemannParams {
                    rho0: m.rho0,
                    bulk_modulus,
                    shear_modulus: g,
                    yield_stress: y,
                    sigma1: *sigma1,
                })
                .map_err(bad)?;
                Reference::EpRiemann {
                    sol,
                    interface: *interface,
                    x_left: *x_left,
                }
            }
            ReferenceSpec::SoundWave {
                material,
                amplitude,
                k,
                center,
            } => {
                let m = find(material);
                let Eos::Linear(Linear { c0, .. }) = m.eos else {
                    return Err(SceneError(format!(
                        "reference.material: `{material}` must use the linear EOS for the sound-wave reference"
                    )));
                };
                // Poisson ratio implied by the material's moduli (K = rho0 c0², G)
                let (kb, g) = (m.rho0 * c0 * c0, m.shear_modulus);
                let poisson = (3.0 * kb - 2.0 * g) / (2.0 * (3.0 * kb + g));
                let sol = SoundPulse::new(SoundPulseParams {
                    rho0: m.rho0,
                    c0,
                    poisson,
                    amplitude: *amplitude,
                    k: *k,
                })
                .map_err(bad)?;
                Reference::Sound {
                    sol,
                    center: *center,
                    spacing: spacing.first().copied().unwrap_or(f64::NAN),
                }
            }
            ReferenceSpec::ShellCollapse {
                material,
                center,
                r_inner,
                r_outer,
                v0,
            } => {
                let m = find(material);
                let (_, y) = yield_of(scene, material, "reference.material")?;
                let sol = ShellCollapse::new(ShellParams {
                    rho: m.rho0,
                    yield_stress: y,
                    r_inner: *r_inner,
                    r_outer: *r_outer,
                    v0: *v0,
                })
                .map_err(bad)?;
                let c = [center[0], center[1]];
                let r = |i: usize| ((x0[i][0] - c[0]).powi(2) + (x0[i][1] - c[1]).powi(2)).sqrt();
                let inner: Vec<usize> = (0..x0.len())
                    .filter(|&i| r(i) < r_inner + 0.99 * spacing[i])
                    .collect();
                let outer: Vec<usize> = (0..x0.len())
                    .filter(|&i| r(i) > r_outer - 0.99 * spacing[i])
                    .collect();
                if inner.is_empty() || outer.is_empty() {
                    return Err(SceneError(
                        "reference: no particle within one spacing of the shell's surfaces (do center and radii match the body?)"
                            .into(),
                    ));
                }
                Reference::Shell(Shell {
                    sol,
                    center: c,
                    inner,
                    outer,
                })
            }
        }))
    }

    /// Exact sigma_xx at (x, t), or `None` where the exact solution does not hold or the
    /// reference is not a stress profile.
    pub fn sigma_xx(&self, x: f64, t: f64) -> Option<f64> {
        match self {
            Reference::Flyer(sol) => Some(sol.sample(x, t).0),
            Reference::EpRiemann {
                sol,
                interface,
                x_left,
            } => (x >= sol.valid_from(*x_left, t)).then(|| sol.sample(x - interface, t).sigma_xx),
            Reference::Shell(_) | Reference::Sound { .. } => None,
        }
    }

    /// `(x, sigma_xx, exact sigma_xx)` of every particle sorted by x (the exact value
    /// `None` where it does not hold), or `None` for references that are not stress
    /// profiles.
    pub fn profile(&self, table: &ParticleTable, t: f64) -> Option<Vec<(f64, f64, Option<f64>)>> {
        if !self.is_profile() {
            return None;
        }
        let mut rows: Vec<(f64, f64, Option<f64>)> = (0..table.len())
            .map(|i| {
                let x = table.x[i];
                (x, table.sxx[i] - table.p[i], self.sigma_xx(x, t))
            })
            .collect();
        rows.sort_by(|a, b| a.0.total_cmp(&b.0));
        Some(rows)
    }

    /// True for references that are a sigma_xx profile (profile.csv, `l1_error` of stress).
    pub fn is_profile(&self) -> bool {
        matches!(self, Reference::Flyer(_) | Reference::EpRiemann { .. })
    }

    /// Names of the time-series columns this reference adds to series.csv.
    pub fn series_names(&self) -> &'static [&'static str] {
        match self {
            Reference::Shell(_) => &[
                "inner_radius",
                "outer_radius",
                "inner_radius_exact",
                "outer_radius_exact",
                "inner_spread",
            ],
            _ => &[],
        }
    }

    /// Values of the series columns for a state at time t.
    pub fn series_values(&self, table: &ParticleTable, t: f64) -> Vec<f64> {
        match self {
            Reference::Shell(s) => {
                let r = s.radii(table);
                let (ei, eo) = s.sol.radii_at(t, 2000);
                vec![r.inner, r.outer, ei, eo, r.inner_spread]
            }
            _ => Vec::new(),
        }
    }

    /// The measures of a state at time t. Stress profiles: `l1_error` (mean
    /// |sigma_xx - exact| over the particles where the exact solution holds, Pa),
    /// `l1_error_relative`, `l1_points` and, for the flyer plate, the precursor position.
    /// Shells: surface and row radii, their exact stopping values, relative errors,
    /// `radius_error` (the larger of the two) and the symmetry measure `inner_spread`.
    pub fn measures(&self, table: &ParticleTable, t: f64) -> Vec<(&'static str, f64)> {
        if let Reference::Sound {
            sol,
            center,
            spacing,
        } = self
        {
            // L1 of the velocity over all particles (seed 004 §2.1.2) and the centroid of the
            // right-going pulse, x > center, weighted by v_x
            let n = table.len().max(1) as f64;
            let l1 = (0..table.len())
                .map(|i| (table.vx[i] - sol.velocity(table.x[i] - center, t)).abs())
                .sum::<f64>()
                / n;
            let (mut w, mut wx) = (0.0, 0.0);
            for i in 0..table.len() {
                if table.x[i] > *center {
                    w += table.vx[i];
                    wx += table.vx[i] * table.x[i];
                }
            }
            let centre = wx / w;
            let exact = center + sol.pulse_centres(t).1;
            return vec![
                ("l1_error", l1),
                ("l1_error_relative", l1 / sol.params().amplitude.abs()),
                ("pulse_centre", centre),
                ("pulse_centre_exact", exact),
                ("pulse_centre_error", centre - exact),
                ("pulse_centre_error_spacings", (centre - exact) / spacing),
                ("c_long", sol.c_long()),
            ];
        }
        if let Reference::Shell(s) = self {
            let r = s.radii(table);
            let (ei, eo) = s.sol.stopping_radii();
            let (ti, to) = ((r.inner - ei) / ei, (r.outer - eo) / eo);
            return vec![
                ("inner_radius", r.inner),
                ("outer_radius", r.outer),
                ("inner_row_radius", r.inner_row),
                ("outer_row_radius", r.outer_row),
                ("inner_radius_exact", ei),
                ("outer_radius_exact", eo),
                ("inner_radius_error_relative", ti),
                ("outer_radius_error_relative", to),
                ("radius_error", ti.abs().max(to.abs())),
                ("inner_spread", r.inner_spread),
            ];
        }
        let mut sum = 0.0;
        let mut n = 0usize;
        for i in 0..table.len() {
            if let Some(ex) = self.sigma_xx(table.x[i], t) {
                let sxx = table.sxx[i] - table.p[i];
                sum += (sxx - ex).abs();
                n += 1;
            }
        }
        let l1 = if n > 0 { sum / n as f64 } else { f64::NAN };
        let scale = match self {
            Reference::Flyer(sol) => sol.final_stress().abs(),
            Reference::EpRiemann { sol, .. } => sol.params().sigma1.abs(),
            Reference::Shell(_) | Reference::Sound { .. } => 1.0,
        };
        let mut out = vec![
            ("l1_error", l1),
            ("l1_error_relative", l1 / scale),
            ("l1_points", n as f64),
        ];
        if let Reference::Flyer(sol) = self {
            let front = front_position(table, 0.5 * sol.hel_stress(), sol.params().interface_x);
            let exact = sol.precursor_position(t);
            let travel = exact - sol.params().interface_x;
            out.push(("precursor_position", front));
            out.push(("precursor_position_exact", exact));
            out.push((
                "precursor_position_error_relative",
                (front - exact).abs() / travel,
            ));
        }
        out
    }
}

/// The right-most position (beyond `x_min`) where sigma_xx crosses `level` (< 0), by
/// linear interpolation between particles sorted by x.
pub fn front_position(table: &ParticleTable, level: f64, x_min: f64) -> f64 {
    let mut pts: Vec<(f64, f64)> = (0..table.len())
        .filter(|&i| table.x[i] >= x_min)
        .map(|i| (table.x[i], table.sxx[i] - table.p[i]))
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    for k in (1..pts.len()).rev() {
        let (x0, s0) = pts[k - 1];
        let (x1, s1) = pts[k];
        if s0 <= level && s1 > level {
            return x0 + (level - s0) / (s1 - s0) * (x1 - x0);
        }
    }
    f64::NAN
}
