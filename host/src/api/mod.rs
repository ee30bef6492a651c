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
//! final state to the last bit. Every step is recorded as `gsph run` records it (the same
//! [`Recorder`]): the series (`series.csv`, with the scene's `[monitor]` and reference
//! columns) and the summary's measures; snapshots go to CSV or to the HDF5/XDMF pair of
//! `gsph run` ([`output`]).
//!
//! Overrides are the strings of `gsph run`: `KEY=VALUE` (`--set`) and `unset:KEY`
//! (`--unset KEY`, [`unset`]).

pub mod builder;
pub mod fields;
pub mod output;
mod particles;

use crate::checkpoint::SceneSource;
use crate::driver::record::Recorder;
use crate::monitor::Monitor;
use crate::reference::Reference;
use crate::scene::{self, InitialParticles, Scene};
use crate::sim::{Sim, SimError};
use gsph_core::effects::EffectSet;
use gsph_core::schemes::Scheme;
use std::path::Path;

pub use builder::{Effect, Riemann, SceneBuilder};
pub use fields::{Field, Info, Range, FIELDS};
pub use output::Series;
pub use particles::Particles;

/// The override that removes `key` from a scene (`gsph run --unset KEY`): `unset:KEY`,
/// given among the `KEY=VALUE` overrides (applied in order).
pub fn unset(key: &str) -> String {
    format!("{}{key}", scene::UNSET)
}

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
    /// A long call ([`Simulation::run_with`], [`Simulation::advance_to_with`]) was stopped
    /// between two steps by its caller; the state is whole and can step on.
    Stopped(String),
}

impl std::fmt::Display for ApiError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            ApiError::Scene(m)
            | ApiError::Simulation(m)
            | ApiError::Argument(m)
            | ApiError::Io(m)
            | ApiError::Stopped(m) => write!(f, "{m}"),
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

/// A simulation of any dimension with the controls a coupling code needs. A clone has
/// the state and the series so far, but no open snapshot file.
pub struct Simulation {
    scene: Scene,
    source: Option<SceneSource>,
    sim: AnySim,
    /// The series, monitor and reference, as `gsph run` records them.
    rec: Recorder,
    /// Index of the next series sample (`t_end k / series`).
    next_series: usize,
    /// The HDF5/XDMF snapshots being written, if open ([`Self::open_snapshots`]).
    snapshots: Option<output::Snapshots>,
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

impl Clone for Simulation {
    fn clone(&self) -> Self {
        Simulation {
            scene: self.scene.clone(),
            source: self.source.clone(),
            sim: self.sim.clone(),
            rec: self.rec.clone(),
            next_series: self.next_series,
            snapshots: None,
            energy0: self.energy0,
            momentum0: self.momentum0,
            external: self.external.clone(),
            impulse: self.impulse,
            external_work: self.external_work,
            order: self.order.clone(),
            failed: self.failed.clone(),
        }
    }
}

impl Simulation {
    /// Reads, validates and builds a scene file, applying `overrides` in order (`KEY=VALUE`
    /// as `gsph run --set`, `unset:KEY` as `--unset KEY`: [`unset`]).
    pub fn from_file(path: &Path, overrides: &[String]) -> ApiResult<Self> {
        // a regular file of bounded size, as `gsph run` reads it
        let text = scene::read_scene(path)?;
        let stem = path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default();
        Self::from_source(&text, &path.display().to_string(), &stem, overrides)
    }

    /// Validates and builds scene text (`origin` names it in messages) with overrides.
    pub fn from_text(text: &str, origin: &str, overrides: &[String]) -> ApiResult<Self> {
        Self::from_source(text, origin, origin, overrides)
    }

    fn from_source(text: &str, origin: &str, stem: &str, overrides: &[String]) -> ApiResult<Self> {
        let scene = scene::parse(text, origin, overrides)?;
        let name = scene.name.clone().unwrap_or_else(|| stem.to_string());
        refuse_driver_only(&scene, origin)?;
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
        refuse_driver_only(&scene, "SCENE.toml")?;
        let reference = Reference::from_scene(&scene, &parts.x, &parts.spacing)?;
        let sim = match scene.dim {
            1 => AnySim::One(Box::new(Sim::new(&scene, &parts)?)),
            2 => AnySim::Two(Box::new(Sim::new(&scene, &parts)?)),
            _ => AnySim::Three(Box::new(Sim::new(&scene, &parts)?)),
        };
        let materials = with_sim!(&sim, s => s.materials.clone());
        let monitor = Monitor::new(&scene, &parts, &materials)?;
        let mut rec = Recorder::new(reference, monitor, &[]);
        with_sim!(&sim, s => rec.push(s.as_ref(), &None, 0.0));
        let mut s = Simulation {
            scene,
            source: None,
            sim,
            rec,
            next_series: 1,
            snapshots: None,
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

    /// Number of particles (the walls' mirror images, which the simulation keeps after
    /// them, are not particles of the scene).
    pub fn len(&self) -> usize {
        with_sim!(&self.sim, s => s.owned)
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
        self.record(dt);
        Ok(())
    }

    /// Samples the series after a step of `dt` when the step passed the next series time
    /// (`t_end k / series`, `series` 200 unless the scene's `output.series` says), as
    /// `gsph run` does.
    fn record(&mut self, dt: f64) {
        let t_end = self.scene.t_end;
        let n = self.scene.output.series.unwrap_or(200) as f64;
        let t = self.time();
        if t >= t_end * self.next_series as f64 / n {
            let rec = &mut self.rec;
            with_sim!(&self.sim, s => rec.push(s.as_ref(), &None, dt));
            while t >= t_end * self.next_series as f64 / n {
                self.next_series += 1;
            }
        }
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
        self.advance_to_with(t, || Ok(()))
    }

    /// [`Self::advance_to`], calling `between` after every step: an error from it stops
    /// the call there (the state is whole and can step on) and is returned. The C ABI
    /// stops a call whose handle another thread destroys, Python on Ctrl-C.
    pub fn advance_to_with(
        &mut self,
        t: f64,
        mut between: impl FnMut() -> ApiResult<()>,
    ) -> ApiResult<u64> {
        if !t.is_finite() {
            return Err(ApiError::Argument(format!("t: must be finite (got {t:e})")));
        }
        // a time already passed is a caller's mistake, not zero steps to take
        if t < self.time() * (1.0 - 1e-12) {
            return Err(ApiError::Argument(format!(
                "t: {t:e} s lies before the simulation's time {:e} s (advance runs forward to t)",
                self.time()
            )));
        }
        let first = self.steps();
        while self.time() < t * (1.0 - 1e-12) {
            let mut dt = self.stable_dt()?;
            if self.time() + dt >= t {
                dt = t - self.time();
            }
            self.step_exact(dt)?;
            between()?;
        }
        Ok(self.steps() - first)
    }

    /// Runs to the scene's `t_end` (or `max_steps`) through its snapshot times, taking the
    /// same steps as `gsph run` on the same scene (and, with a snapshot file open, writing
    /// a snapshot at each of those times, as `gsph run` does). Returns the steps taken.
    pub fn run(&mut self) -> ApiResult<u64> {
        self.run_with(|| Ok(()))
    }

    /// [`Self::run`], calling `between` after every step (see [`Self::advance_to_with`]).
    pub fn run_with(&mut self, mut between: impl FnMut() -> ApiResult<()>) -> ApiResult<u64> {
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
            if self.time() >= t_out * (1.0 - 1e-12) {
                self.snapshot_at_output_time()?;
            }
            between()?;
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
}

/// Refuses what only the run driver does, rather than ignoring it: the moving window
/// (named with the command that runs it) and the checkpoint schedule.
fn refuse_driver_only(scene: &Scene, origin: &str) -> ApiResult<()> {
    if scene.window.is_some() {
        let file = if Path::new(origin).is_file() {
            origin
        } else {
            "SCENE.toml"
        };
        return Err(ApiError::Scene(format!(
            "window: the moving window ([window]) is not run by the library; run this scene with `gsph run {file}` (its Hugoniot with `gsph hugoniot {file}`)"
        )));
    }
    let keys = [
        (
            scene.output.checkpoint_steps.is_some(),
            "output.checkpoint_steps",
        ),
        (
            scene.output.checkpoint_seconds.is_some(),
            "output.checkpoint_seconds",
        ),
    ];
    if let Some((_, key)) = keys.iter().find(|k| k.0) {
        return Err(ApiError::Scene(format!(
            "{key}: not used by the library (call write_checkpoint instead)"
        )));
    }
    Ok(())
}
