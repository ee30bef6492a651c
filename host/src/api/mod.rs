//! The library interface: a [`Simulation`] whatever its dimension, built from a scene file,
//! scene text, a [`SceneBuilder`] or caller-given particle arrays,
//! stepped by the caller, its per-particle fields read and written by name in particle-id
//! order, external accelerations applied for coupling. The C ABI (`host/capi`) and
//! the Python package (`host/python`) are thin layers over this module.
//!
//! ```no_run
//! use gsph::api::Simulation;
//! let mut sim = Simulation::from_file("cases/flyer_plate.toml".as_ref(), &[]).unwrap();
//! sim.advance_to(0.25e-6).unwrap();
//! let mut p = vec![0.0; sim.len()];
//! sim.read("pressure", &mut p).unwrap();
//! ```
//!
//! Steps are the [`Sim::step`] of the `gsph` command: [`Simulation::run`] takes the same
//! time steps as `gsph run` (it lands on the same snapshot times) and gives the same
//! final state to the last bit.

pub mod builder;
pub mod fields;
mod particles;

use crate::checkpoint::SceneSource;
use crate::reference::Reference;
use crate::scene::{self, InitialParticles, Scene};
use crate::sim::{Sim, SimError};
use gsph_core::effects::EffectSet;
use gsph_core::schemes::Scheme;
use serde_json::{json, Map, Value};
use std::path::Path;

pub use builder::{Effect, Riemann, SceneBuilder};
pub use fields::{Field, FIELDS};
pub use particles::Particles;

/// What went wrong in a library call; `Display` is one line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ApiError {
    /// The scene (file, text, overrides) is invalid: the message names the key.
    Scene(String),
    /// The simulation failed (a step, a neighbour overflow): the message names the step
    /// and particle.
    Simulation(String),
    /// A bad argument: unknown field, wrong buffer length, non-finite value.
    Argument(String),
    /// A file could not be written.
    Io(String),
}

impl std::fmt::Display for ApiError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ApiError::Scene(m) | ApiError::Simulation(m) | ApiError::Argument(m) => {
                write!(f, "{m}")
            }
            ApiError::Io(m) => write!(f, "{m}"),
        }
    }
}

impl std::error::Error for ApiError {}

impl From<scene::SceneError> for ApiError {
    fn from(e: scene::SceneError) -> Self {
        ApiError::Scene(e.to_string())
    }
}

impl From<SimError> for ApiError {
    fn from(e: SimError) -> Self {
        ApiError::Simulation(e.to_string())
    }
}

/// Result of a library call.
pub type ApiResult<T> = Result<T, ApiError>;

/// The simulation of one dimension.
#[derive(Clone)]
pub(crate) enum AnySim {
    One(Box<Sim<1>>),
    Two(Box<Sim<2>>),
    Three(Box<Sim<3>>),
}

/// Runs `$body` with `$s` bound to the `Sim<D>` inside an [`AnySim`].
macro_rules! with_sim {
    ($any:expr, $s:ident => $body:expr) => {
        match $any {
            $crate::api::AnySim::One($s) => $body,
            $crate::api::AnySim::Two($s) => $body,
            $crate::api::AnySim::Three($s) => $body,
        }
    };
}
pub(crate) use with_sim;

/// A simulation of any dimension with the controls a coupling code needs.
#[derive(Clone)]
pub struct Simulation {
    scene: Scene,
    source: Option<SceneSource>,
    sim: AnySim,
    reference: Option<Reference>,
    energy0: f64,
    momentum0: [f64; 3],
    /// External accelerations in id order (`dim` per particle), empty for none.
    external: Vec<f64>,
    impulse: [f64; 3],
    external_work: f64,
    /// Indices in memory of the particles in id order, and the renumbering they hold for
    /// ([`Self::refresh_order`]).
    order: (u64, Vec<usize>),
    /// Why the simulation can no longer step (a step failed part-way).
    failed: Option<String>,
}

impl Simulation {
    /// Reads, validates and builds a scene file, applying `overrides` (`KEY=VALUE`, as
    /// `gsph run --set`).
    pub fn from_file(path: &Path, overrides: &[String]) -> ApiResult<Self> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| ApiError::Scene(format!("{}: cannot read scene: {e}", path.display())))?;
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        Self::from_source(&text, &path.display().to_string(), &stem, overrides)
    }

    /// Validates and builds scene text (`origin` names it in messages).
    pub fn from_text(text: &str, origin: &str, overrides: &[String]) -> ApiResult<Self> {
        Self::from_source(text, origin, origin, overrides)
    }

    fn from_source(text: &str, origin: &str, stem: &str, overrides: &[String]) -> ApiResult<Self> {
        let scene = scene::parse(text, origin, overrides)?;
        let name = scene.name.clone().unwrap_or_else(|| stem.to_string());
        let mut sim = Self::from_scene(scene)?;
        sim.source = Some(SceneSource {
            origin: origin.to_string(),
            text: text.to_string(),
            overrides: overrides.to_vec(),
            name,
        });
        Ok(sim)
    }

    /// Builds a validated scene (from [`scene::parse`] or a [`SceneBuilder`]).
    pub fn from_scene(scene: Scene) -> ApiResult<Self> {
        let parts = scene::build_particles(&scene)?;
        Self::with_particles(scene, parts)
    }

    /// Builds a simulation of the caller's particles: `settings` is scene text without
    /// bodies (dimension, scheme, t_end, materials, options); see [`Particles`].
    pub fn from_particles(
        settings: &str,
        origin: &str,
        overrides: &[String],
        particles: &Particles<'_>,
    ) -> ApiResult<Self> {
        let scene = scene::parse_settings(settings, origin, overrides)?;
        let parts = particles.build(&scene)?;
        Self::with_particles(scene, parts)
    }

    fn with_particles(scene: Scene, parts: InitialParticles) -> ApiResult<Self> {
        // what only the run driver does is refused, not ignored
        let driver_only = [
            (
                scene.window.is_some(),
                "window",
                "the moving window runs under `gsph run` and `gsph hugoniot`",
            ),
            (
                scene.monitor.is_some(),
                "monitor",
                "the monitors run under `gsph run`; read the fields instead",
            ),
            (
                scene.output.series.is_some(),
                "output.series",
                "series.csv is written by `gsph run`",
            ),
            (
                scene.output.checkpoint_steps.is_some(),
                "output.checkpoint_steps",
                "call write_checkpoint instead",
            ),
            (
                scene.output.checkpoint_seconds.is_some(),
                "output.checkpoint_seconds",
                "call write_checkpoint instead",
            ),
        ];
        if let Some((_, key, why)) = driver_only.iter().find(|d| d.0) {
            return Err(ApiError::Scene(format!(
                "{key}: not used by the library ({why})"
            )));
        }
        let reference = Reference::from_scene(&scene, &parts.x, &parts.spacing)?;
        let sim = match scene.dim {
            1 => AnySim::One(Box::new(Sim::new(&scene, &parts)?)),
            2 => AnySim::Two(Box::new(Sim::new(&scene, &parts)?)),
            _ => AnySim::Three(Box::new(Sim::new(&scene, &parts)?)),
        };
        let mut s = Simulation {
            scene,
            source: None,
            sim,
            reference,
            energy0: 0.0,
            momentum0: [0.0; 3],
            external: Vec::new(),
            impulse: [0.0; 3],
            external_work: 0.0,
            order: (u64::MAX, Vec::new()),
            failed: None,
        };
        let (k, i) = s.energy();
        s.energy0 = k + i;
        s.momentum0 = s.momentum();
        Ok(s)
    }

    /// The validated scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// Dimension (1, 2 or 3).
    pub fn dim(&self) -> usize {
        self.scene.dim
    }

    /// Number of particles.
    pub fn len(&self) -> usize {
        with_sim!(&self.sim, s => s.len())
    }

    /// True without particles (never, for a simulation that was built).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Simulated time, s.
    pub fn time(&self) -> f64 {
        with_sim!(&self.sim, s => s.t)
    }

    /// Steps taken.
    pub fn steps(&self) -> u64 {
        with_sim!(&self.sim, s => s.step)
    }

    /// The scheme.
    pub fn scheme(&self) -> Scheme {
        with_sim!(&self.sim, s => s.scheme)
    }

    /// The effects simulated (from the materials and options of the scene).
    pub fn effects(&self) -> EffectSet {
        with_sim!(&self.sim, s => s.effects)
    }

    /// The step the scene's rule gives now: its fixed `dt` if it has one (an error if that
    /// exceeds the stability limit), else the CFL step `cfl min h / (c_l + |v|)`.
    pub fn stable_dt(&mut self) -> ApiResult<f64> {
        self.check_usable()?;
        let (cfl, fixed) = (self.scene.cfl(), self.scene.dt);
        Ok(with_sim!(&mut self.sim, s => s.next_dt(cfl, fixed))?)
    }

    /// Takes one step of `dt` (`None`: [`Self::stable_dt`]); a given `dt` longer than the
    /// CFL-1 limit is refused. Returns the step taken.
    pub fn step(&mut self, dt: Option<f64>) -> ApiResult<f64> {
        let dt = match dt {
            None => self.stable_dt()?,
            Some(dt) if !(dt.is_finite() && dt > 0.0) => {
                return Err(ApiError::Argument(format!(
                    "dt: must be positive and finite (got {dt:e})"
                )));
            }
            Some(dt) => {
                let cfl = self.scene.cfl();
                with_sim!(&mut self.sim, s => s.next_dt(cfl, Some(dt)))?
            }
        };
        self.step_exact(dt)?;
        Ok(dt)
    }

    /// One step of exactly `dt` with the external accelerations applied as a half kick
    /// before and after it (second order, and the momentum they add is `m a dt` exactly).
    fn step_exact(&mut self, dt: f64) -> ApiResult<()> {
        self.check_usable()?;
        self.kick(0.5 * dt);
        if let Err(e) = with_sim!(&mut self.sim, s => s.step(dt)) {
            // the step changed the state in place before it failed: stepping on would
            // start from a half-step (and count the half kick twice)
            let e = ApiError::from(e);
            self.failed = Some(e.to_string());
            return Err(e);
        }
        self.kick(0.5 * dt);
        Ok(())
    }

    /// An error if a step failed before: the state is half a step and cannot go on.
    fn check_usable(&self) -> ApiResult<()> {
        match &self.failed {
            Some(why) => Err(ApiError::Simulation(format!(
                "this simulation failed ({why}); build it again or continue from a checkpoint"
            ))),
            None => Ok(()),
        }
    }

    /// Steps with the scene's rule until time `t`, the last step shortened to land on it
    /// (as `gsph run` lands on its snapshot times). Returns the steps taken.
    pub fn advance_to(&mut self, t: f64) -> ApiResult<u64> {
        if !t.is_finite() {
            return Err(ApiError::Argument(format!("t: must be finite (got {t:e})")));
        }
        let first = self.steps();
        while self.time() < t * (1.0 - 1e-12) {
            let mut dt = self.stable_dt()?;
            if self.time() + dt >= t {
                dt = t - self.time();
            }
            self.step_exact(dt)?;
        }
        Ok(self.steps() - first)
    }

    /// Runs to the scene's `t_end` (or `max_steps`) through its snapshot times, taking the
    /// same steps as `gsph run` on the same scene. Returns the steps taken.
    pub fn run(&mut self) -> ApiResult<u64> {
        let first = self.steps();
        let (t_end, n_out) = (self.scene.t_end, self.scene.output.snapshots.max(1));
        let max_steps = self.scene.max_steps.unwrap_or(u64::MAX);
        let mut k = 1;
        while self.time() < t_end * (1.0 - 1e-12) && self.steps() < max_steps {
            let t_out = t_end * k as f64 / n_out as f64;
            if self.time() >= t_out * (1.0 - 1e-12) {
                k += 1;
                continue;
            }
            let mut dt = self.stable_dt()?;
            if self.time() + dt >= t_out {
                dt = t_out - self.time();
            }
            self.step_exact(dt)?;
        }
        Ok(self.steps() - first)
    }

    /// Kinetic and internal energy, J (summed in id order).
    pub fn energy(&self) -> (f64, f64) {
        with_sim!(&self.sim, s => s.energy())
    }

    /// Total momentum, padded to 3 components (summed in id order).
    pub fn momentum(&self) -> [f64; 3] {
        with_sim!(&self.sim, s => s.momentum())
    }

    /// Momentum the external accelerations have added so far, `sum m a dt`.
    pub fn external_impulse(&self) -> [f64; 3] {
        self.impulse
    }

    /// Kinetic energy the external accelerations have added so far, J.
    pub fn external_work(&self) -> f64 {
        self.external_work
    }

    /// Sets the external acceleration of every particle (m/s², `dim` components per
    /// particle in id order), applied in every following step until it is set again;
    /// an empty slice removes it. Driven particles keep their prescribed velocity.
    pub fn set_external_acceleration(&mut self, a: &[f64]) -> ApiResult<()> {
        self.check_usable()?;
        if a.is_empty() {
            self.external.clear();
            return Ok(());
        }
        let want = self.len() * self.dim();
        if a.len() != want {
            return Err(ApiError::Argument(format!(
                "acceleration: {} values given, {want} needed ({} particles x {} components)",
                a.len(),
                self.len(),
                self.dim()
            )));
        }
        if let Some(k) = a.iter().position(|v| !v.is_finite()) {
            return Err(ApiError::Argument(format!(
                "acceleration: value {k} (particle {}) is not finite",
                k / self.dim()
            )));
        }
        self.external = a.to_vec();
        Ok(())
    }

    /// Adds `a dt` to the velocities (id order), accumulating impulse and work.
    fn kick(&mut self, dt: f64) {
        if self.external.is_empty() {
            return;
        }
        self.refresh_order();
        let (order, a) = (&self.order.1, &self.external);
        let (impulse, work) = with_sim!(&mut self.sim, s => {
            let d = s.x.first().map_or(0, |x| x.len());
            let driven: std::collections::HashSet<usize> = s.driven.iter().map(|p| p.0).collect();
            let mut impulse = [0.0; 3];
            let mut work = 0.0;
            for (k, &i) in order.iter().enumerate() {
                if driven.contains(&i) {
                    continue;
                }
                let before = s.v[i].norm_squared();
                for c in 0..d {
                    let dv = a[k * d + c] * dt;
                    s.v[i][c] += dv;
                    impulse[c] += s.m[i] * dv;
                }
                work += 0.5 * s.m[i] * (s.v[i].norm_squared() - before);
            }
            (impulse, work)
        });
        for (acc, add) in self.impulse.iter_mut().zip(impulse) {
            *acc += add;
        }
        self.external_work += work;
        with_sim!(&mut self.sim, s => s.state_changed());
    }

    /// Renews [`Self::order`] (memory indices in id order) after a renumbering.
    fn refresh_order(&mut self) {
        let renumbered = with_sim!(&self.sim, s => s.renumbered);
        if self.order.0 != renumbered {
            let order: Vec<usize> = with_sim!(&self.sim, s => s.by_id().collect());
            self.order = (renumbered, order);
        }
    }

    /// Particle ids in id order (0..n for a scene as built).
    pub fn ids(&mut self) -> Vec<u32> {
        self.refresh_order();
        let order = &self.order.1;
        with_sim!(&self.sim, s => order.iter().map(|&i| s.ids[i]).collect())
    }

    /// The summary of the state now: the keys of `gsph run`'s summary.json that do not
    /// need the run's history (scene, scheme, effects, particles, steps, t, energies and
    /// momenta, the reference's measures), plus the external impulse and work.
    pub fn summary(&self) -> Map<String, Value> {
        let mut s = Map::new();
        let name = self
            .source
            .as_ref()
            .map(|s| s.name.clone())
            .or_else(|| self.scene.name.clone())
            .unwrap_or_default();
        let (k, i) = self.energy();
        let e1 = k + i;
        let scale = self.energy0.abs().max(k + i.abs()).max(f64::MIN_POSITIVE);
        let d = self.dim();
        s.insert("scene".into(), json!(name));
        s.insert("dim".into(), json!(d));
        s.insert("scheme".into(), json!(self.scheme().name()));
        s.insert(
            "effects".into(),
            json!(self.effects().names().collect::<Vec<_>>()),
        );
        s.insert("particles".into(), json!(self.len()));
        s.insert("steps".into(), json!(self.steps()));
        s.insert("t".into(), json!(self.time()));
        s.insert("energy_initial".into(), json!(self.energy0));
        s.insert("energy_final".into(), json!(e1));
        s.insert(
            "energy_rel_error".into(),
            json!((e1 - self.energy0 - self.external_work) / scale),
        );
        s.insert("kinetic_final".into(), json!(k));
        s.insert("internal_final".into(), json!(i));
        s.insert(
            "momentum_initial".into(),
            json!(self.momentum0[..d].to_vec()),
        );
        s.insert(
            "momentum_final".into(),
            json!(self.momentum()[..d].to_vec()),
        );
        s.insert("external_impulse".into(), json!(self.impulse[..d].to_vec()));
        s.insert("external_work".into(), json!(self.external_work));
        if let Some(r) = &self.reference {
            let table = with_sim!(&self.sim, s => s.table());
            for (key, v) in r.measures(&table, self.time()) {
                s.insert(key.into(), json!(v));
            }
        }
        s
    }

    /// `[x, sigma_xx, exact sigma_xx]` of every particle sorted by x (the exact value NaN
    /// where it does not hold), for scenes whose reference is a stress profile (the flyer
    /// plate, the elastic-plastic Riemann problem): `gsph run`'s profile.csv.
    pub fn profile(&self) -> ApiResult<Vec<[f64; 3]>> {
        let r = match &self.reference {
            Some(r) if r.is_profile() => r,
            _ => {
                return Err(ApiError::Argument(
                    "profile: the scene's [reference] is not a stress profile (flyer_plate or elastic_plastic_riemann)".into(),
                ))
            }
        };
        let rows = r.profile(&self.table(), self.time()).unwrap_or_default();
        Ok(rows
            .into_iter()
            .map(|(x, s, ex)| [x, s, ex.unwrap_or(f64::NAN)])
            .collect())
    }

    /// The particle table (the columns of `final.csv`), rows in id order.
    pub fn table(&self) -> crate::output::ParticleTable {
        with_sim!(&self.sim, s => s.table())
    }

    /// Writes the state as `final.csv` does (a CSV file at `path`, written atomically).
    pub fn write_snapshot(&self, path: &Path) -> ApiResult<()> {
        crate::output::write_csv(path, &self.table())
            .map_err(|e| ApiError::Io(format!("{}: {e}", path.display())))
    }

    /// Writes a checkpoint into `dir` (`dir/checkpoint.bin`) from which the library
    /// ([`Self::from_checkpoint`]) continues bitwise identically. Only for simulations
    /// built from a scene file or text.
    pub fn write_checkpoint(&self, dir: &Path) -> ApiResult<()> {
        self.check_usable()?;
        if !self.external.is_empty() || self.external_work != 0.0 {
            return Err(ApiError::Argument(
                "checkpoint: external accelerations have acted on this simulation, and a checkpoint does not hold them nor the impulse and work they added".into(),
            ));
        }
        let Some(source) = &self.source else {
            return Err(ApiError::Argument(
                "checkpoint: only a simulation built from scene text or a file can be checkpointed"
                    .into(),
            ));
        };
        std::fs::create_dir_all(dir)
            .map_err(|e| ApiError::Io(format!("{}: {e}", dir.display())))?;
        let state = crate::checkpoint::DriverState {
            energy0: self.energy0,
            mom0: self.momentum0,
            ..Default::default()
        };
        let run_id = crate::outdir::new_run_id();
        let mut control =
            crate::checkpoint::Control::new(Default::default(), source.clone(), dir, &run_id);
        with_sim!(&self.sim, s => control.write(s.as_ref(), &state, None))
            .map_err(|e| ApiError::Io(format!("{}: checkpoint: {e}", dir.display())))
    }

    /// Continues from a checkpoint written by [`Self::write_checkpoint`] (or by `gsph run
    /// --checkpoint-every` for a scene the library accepts: no monitor, no series or
    /// checkpoint keys).
    pub fn from_checkpoint(dir: &Path) -> ApiResult<Self> {
        let ck =
            crate::checkpoint::Checkpoint::read(dir).map_err(|e| ApiError::Io(e.to_string()))?;
        let src = ck.source.clone();
        let mut sim = Self::from_source(&src.text, &src.origin, &src.name, &src.overrides)?;
        with_sim!(&mut sim.sim, s => ck.restore_sim(s.as_mut()))
            .map_err(|e| ApiError::Io(e.to_string()))?;
        sim.energy0 = ck.driver.energy0;
        sim.momentum0 = ck.driver.mom0;
        sim.order = (u64::MAX, Vec::new());
        Ok(sim)
    }
}
