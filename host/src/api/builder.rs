//! Scenes built in code with typed values: the scheme, kernel, Riemann solver and effects
//! as enums, materials and bodies as the scene schema's own types. The builder writes the
//! scene's TOML and validates it exactly as a scene file is validated, so an error names
//! the same key a file would, and the simulation can be checkpointed.

use super::{ApiResult, Simulation};
use crate::scene::{BodySpec, MaterialSpec};
use gsph_core::effects::EffectSet;
use gsph_core::kernel::Kernel;
use gsph_core::schemes::Scheme;

/// An effect a scene can simulate. Strength, plasticity, damage and heat follow from the
/// materials' models, periodicity from the `periodic` box; kernel correction, MUSCL and
/// artificial stress are options ([`SceneBuilder::with`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Effect {
    /// Deviatoric stress (a material with shear modulus).
    Strength,
    /// A yield model.
    Plasticity,
    /// A damage model.
    Damage,
    /// A thermal model (temperature).
    Heat,
    /// Kernel gradient correction (pm family).
    Correction,
    /// MUSCL reconstruction.
    Muscl,
    /// Periodic boundaries.
    Periodic,
    /// Artificial stress against the tensile instability.
    ArtificialStress,
}

impl Effect {
    /// Every effect.
    pub const ALL: [Effect; 8] = [
        Effect::Strength,
        Effect::Plasticity,
        Effect::Damage,
        Effect::Heat,
        Effect::Correction,
        Effect::Muscl,
        Effect::Periodic,
        Effect::ArtificialStress,
    ];

    /// The core's effect flag.
    pub const fn set(self) -> EffectSet {
        match self {
            Effect::Strength => EffectSet::STRENGTH,
            Effect::Plasticity => EffectSet::PLASTICITY,
            Effect::Damage => EffectSet::DAMAGE,
            Effect::Heat => EffectSet::HEAT,
            Effect::Correction => EffectSet::CORRECTION,
            Effect::Muscl => EffectSet::MUSCL,
            Effect::Periodic => EffectSet::PERIODIC,
            Effect::ArtificialStress => EffectSet::ARTIFICIAL_STRESS,
        }
    }
}

/// The Riemann solver of the Godunov schemes (`[options] riemann`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Riemann {
    /// The linearised (acoustic) solver.
    Acoustic,
    /// The iterative two-shock solver.
    TwoShock,
}

/// A scene under construction; [`SceneBuilder::build`] validates it.
#[derive(Debug, Clone)]
pub struct SceneBuilder {
    table: toml::Table,
    options: toml::Table,
    materials: Vec<MaterialSpec>,
    bodies: Vec<BodySpec>,
    artificial_stress: Option<f64>,
}

fn kernel_name(k: Kernel) -> &'static str {
    match k {
        Kernel::CubicSpline => "cubic_spline",
        Kernel::WendlandC2 => "wendland_c2",
        Kernel::Gaussian => "gaussian",
    }
}

impl SceneBuilder {
    /// A scene in `dim` dimensions run with `scheme` to `t_end` seconds.
    pub fn new(dim: usize, scheme: Scheme, t_end: f64) -> Self {
        let mut table = toml::Table::new();
        table.insert("dim".into(), (dim as i64).into());
        table.insert("scheme".into(), scheme.name().into());
        table.insert("t_end".into(), t_end.into());
        SceneBuilder {
            table,
            options: toml::Table::new(),
            materials: Vec::new(),
            bodies: Vec::new(),
            artificial_stress: None,
        }
    }

    fn set(mut self, key: &str, v: impl Into<toml::Value>) -> Self {
        self.table.insert(key.into(), v.into());
        self
    }

    /// The scene's name (in summaries).
    pub fn name(self, name: &str) -> Self {
        self.set("name", name)
    }

    /// CFL number.
    pub fn cfl(self, cfl: f64) -> Self {
        self.set("cfl", cfl)
    }

    /// A fixed time step, s (instead of the CFL step).
    pub fn dt(self, dt: f64) -> Self {
        self.set("dt", dt)
    }

    /// The kernel.
    pub fn kernel(self, k: Kernel) -> Self {
        self.set("kernel", kernel_name(k))
    }

    /// Smoothing length over spacing.
    pub fn h_factor(self, f: f64) -> Self {
        self.set("h_factor", f)
    }

    /// Stop after this many steps.
    pub fn max_steps(self, n: u64) -> Self {
        self.set("max_steps", n as i64)
    }

    /// Snapshot count of a run (the times [`Simulation::run`] lands on).
    pub fn snapshots(mut self, n: usize) -> Self {
        let mut out = toml::Table::new();
        out.insert("snapshots".into(), (n as i64).into());
        self.table.insert("output".into(), out.into());
        self
    }

    /// The Riemann solver.
    pub fn riemann(mut self, r: Riemann) -> Self {
        let name = match r {
            Riemann::Acoustic => "acoustic",
            Riemann::TwoShock => "two_shock",
        };
        self.options.insert("riemann".into(), name.into());
        self
    }

    /// Turns on an optional effect: [`Effect::Correction`] or [`Effect::Muscl`] (the
    /// others follow from materials and boundaries; asking for them here is refused by
    /// [`Self::build`]).
    pub fn with(mut self, e: Effect) -> Self {
        let key = match e {
            Effect::Correction => "correction",
            Effect::Muscl => "muscl",
            other => {
                self.options
                    .insert(format!("{other:?}").to_lowercase(), true.into());
                return self;
            }
        };
        self.options.insert(key.into(), true.into());
        self
    }

    /// Artificial stress with coefficient `eps` (Monaghan 2000; typically 0.2-0.3).
    pub fn artificial_stress(mut self, eps: f64) -> Self {
        self.artificial_stress = Some(eps);
        self
    }

    /// Adds a material (bodies name it).
    pub fn material(mut self, m: MaterialSpec) -> Self {
        self.materials.push(m);
        self
    }

    /// Adds a body.
    pub fn body(mut self, b: BodySpec) -> Self {
        self.bodies.push(b);
        self
    }

    /// The scene as TOML text (what [`Self::build`] validates).
    pub fn to_toml(&self) -> String {
        let mut t = self.table.clone();
        let mut options = self.options.clone();
        if let Some(eps) = self.artificial_stress {
            options.insert("artificial_stress".into(), eps.into());
        }
        if !options.is_empty() {
            t.insert("options".into(), options.into());
        }
        let value = |v: Result<toml::Value, toml::ser::Error>| {
            v.expect("the scene schema serialises to TOML")
        };
        let materials = self
            .materials
            .iter()
            .map(|m| value(toml::Value::try_from(m)));
        t.insert("materials".into(), toml::Value::Array(materials.collect()));
        let bodies = self.bodies.iter().map(|b| value(toml::Value::try_from(b)));
        t.insert("bodies".into(), toml::Value::Array(bodies.collect()));
        toml::to_string(&t).expect("a TOML table serialises")
    }

    /// Validates the scene (as a file is validated) and builds the simulation.
    pub fn build(&self) -> ApiResult<Simulation> {
        Simulation::from_text(&self.to_toml(), "builder", &[])
    }
}

impl Simulation {
    /// True if the simulation has effect `e`.
    pub fn simulates(&self, e: Effect) -> bool {
        self.effects().contains(e.set())
    }
}
