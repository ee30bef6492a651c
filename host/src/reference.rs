//! Exact references of the cases and the error measures reported in `summary.json`.

use crate::output::ParticleTable;
use crate::scene::{EosSpec, ReferenceSpec, Scene, SceneError, StrengthSpec};
use gsph_core::exact::{ElasticPlasticRiemann, EpRiemannParams, FlyerPlate, FlyerPlateParams};

/// A case's exact solution.
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
}

fn yield_of(scene: &Scene, name: &str, key: &str) -> Result<(f64, f64), SceneError> {
    let m = scene
        .materials
        .iter()
        .find(|m| m.name == name)
        .expect("validated");
    match m.strength {
        Some(StrengthSpec::VonMises { yield_stress }) => Ok((m.shear_modulus, yield_stress)),
        _ => Err(SceneError(format!(
            "{key}: material `{name}` must use von_mises strength for this reference"
        ))),
    }
}

impl Reference {
    /// Builds the reference named in the scene, if any.
    pub fn from_scene(scene: &Scene) -> Result<Option<Reference>, SceneError> {
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
        Ok(Some(match r {
            ReferenceSpec::FlyerPlate {
                material,
                impact_velocity,
                interface,
            } => {
                let m = find(material);
                let EosSpec::Hugoniot { c0, s1 } = m.eos else {
                    return Err(SceneError(format!("reference.material: `{material}` must use the hugoniot EOS for the flyer-plate reference")));
                };
                let (g, y) = yield_of(scene, material, "reference.material")?;
                let sol = FlyerPlate::new(FlyerPlateParams {
                    rho0: m.rho0,
                    c0,
                    s1,
                    shear_modulus: g,
                    yield_stress: y,
                    impact_velocity: *impact_velocity,
                    interface_x: *interface,
                })
                .map_err(|e| SceneError(format!("reference: {e}")))?;
                Reference::Flyer(sol)
            }
            ReferenceSpec::ElasticPlasticRiemann {
                material,
                sigma1,
                interface,
                x_left,
            } => {
                let m = find(material);
                let EosSpec::Logarithmic { bulk_modulus } = m.eos else {
                    return Err(SceneError(format!("reference.material: `{material}` must use the logarithmic EOS for this reference")));
                };
                let (g, y) = yield_of(scene, material, "reference.material")?;
                let sol = ElasticPlasticRiemann::new(EpRiemannParams {
                    rho0: m.rho0,
                    bulk_modulus,
                    shear_modulus: g,
                    yield_stress: y,
                    sigma1: *sigma1,
                })
                .map_err(|e| SceneError(format!("reference: {e}")))?;
                Reference::EpRiemann {
                    sol,
                    interface: *interface,
                    x_left: *x_left,
                }
            }
        }))
    }

    /// Exact sigma_xx at (x, t), or `None` where the exact solution does not hold.
    pub fn sigma_xx(&self, x: f64, t: f64) -> Option<f64> {
        match self {
            Reference::Flyer(sol) => Some(sol.sample(x, t).0),
            Reference::EpRiemann {
                sol,
                interface,
                x_left,
            } => (x >= sol.valid_from(*x_left, t)).then(|| sol.sample(x - interface, t).sigma_xx),
        }
    }

    /// A stress scale for relative errors, Pa.
    pub fn stress_scale(&self) -> f64 {
        match self {
            Reference::Flyer(sol) => sol.final_stress().abs(),
            Reference::EpRiemann { sol, .. } => sol.params().sigma1.abs(),
        }
    }

    /// The measures of a state at time t: `l1_error` (mean |sigma_xx - exact| over the
    /// particles where the exact solution holds, Pa), `l1_error_relative` (divided by the
    /// stress scale), `l1_points`, and case-specific positions.
    pub fn measures(&self, table: &ParticleTable, t: f64) -> Vec<(&'static str, f64)> {
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
        let mut out = vec![
            ("l1_error", l1),
            ("l1_error_relative", l1 / self.stress_scale()),
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
