//! A simulation in one dimension: Vec-backed particle state, workspace and neighbour lists
//! around the core's slice-based step.

use crate::exec::{Rayon, Simd, SimdLevel};
use crate::neighbors::{morton_order, Lists};
use crate::output::{ParticleRow, ParticleTable};
use crate::scene::{InitialParticles, Scene};
use gsph_core::effects::EffectSet;
use gsph_core::kernel::Kernel;
use gsph_core::material::Material;
use gsph_core::math::{Matrix, Real, Sym3, Vector};
use gsph_core::neighbors::{NeighborError, Periodic};
use gsph_core::schemes::*;
use gsph_core::schemes::{Scheme, StepFn};
use gsph_core::state::*;
use rayon::prelude::*;
use std::any::Any;

pub use error::SimError;

/// A CFL step below this fraction of the first one stops the run ([`SimError::Collapsed`]).
/// Measured over the first 3,000 steps of the bundled Taylor rod, 2D impact (tkc), ring
/// collapse, colliding rings, Verney cylinder and flyer plate, the step falls by at most
/// 7.2 % (the impact); a run that went unstable fell by 1e10 (ts2's Verney cylinder with
/// the leap-frog at CFL 0.5, before this check) and stepped on at 1e-19 s.
pub const DT_COLLAPSE: Real = 1e-6;

#[macro_use]
mod fields;
mod by_id;
mod derived;
#[cfg(feature = "mpi")]
mod dist;
mod edit;
mod error;
mod lists;
mod measure;
mod reference;
mod state_io;
pub mod values;
pub mod walls;
use by_id::{cause_by_id, overflow_by_id};
pub use edit::HeldState;
pub use fields::Particle;

/// The step function for dimension `D` (looked up once per run; the specialisations are
/// compiled in `gsph-steps`).
fn select<const D: usize>(scheme: Scheme, effects: EffectSet) -> Option<StepFn<D, Rayon>> {
    use gsph_steps::{select_1d, select_2d, select_3d};
    let family = scheme.family();
    let effects = effects.kernel_part();
    let cast = |f: &dyn Any| f.downcast_ref::<StepFn<D, Rayon>>().copied();
    match D {
        1 => select_1d(family, effects).and_then(|f| cast(&f)),
        2 => select_2d(family, effects).and_then(|f| cast(&f)),
        3 => select_3d(family, effects).and_then(|f| cast(&f)),
        _ => None,
    }
}

/// The effects a material calls for: hydrodynamics, and strength, plasticity, heat and
/// damage as its strength model has them.
pub fn material_effects(m: &Material) -> EffectSet {
    let mut e = EffectSet::HYDRO;
    for (has, effect) in [
        (m.has_strength(), EffectSet::STRENGTH),
        (m.has_plasticity(), EffectSet::PLASTICITY),
        (m.has_heat(), EffectSet::HEAT),
        (m.has_damage(), EffectSet::DAMAGE),
    ] {
        if has {
            e = e.union(effect);
        }
    }
    e
}

/// The effects a scene calls for (DESIGN §5): from its materials, options and scheme.
pub fn resolve_effects(scene: &Scene, materials: &[Material]) -> EffectSet {
    let mut e = scene.scheme.effects();
    for m in materials {
        e = e.union(material_effects(m));
    }
    if scene.periodic.is_some() {
        e = e.union(EffectSet::PERIODIC);
    }
    // pm-family options (validated: only with pm or tkc).
    if scene.options.correction == Some(true) {
        e = e.union(EffectSet::CORRECTION);
    }
    if scene.options.muscl == Some(true) {
        e = e.union(EffectSet::MUSCL);
    }
    if scene.options.artificial_stress.is_some() {
        e = e.union(EffectSet::ARTIFICIAL_STRESS);
    }
    // tl reads options.hourglass as the xi of its own stiffness (always on)
    if scene.options.hourglass.is_some() && scene.scheme.family() != Family::Tl {
        e = e.union(EffectSet::HOURGLASS);
    }
    e.closed()
}

use crate::neighbors::default_capacity;

gsph_core::particle_fields!(define_sim {
/// A running simulation in dimension `D`: one array per field of the core's particle
/// table ([`gsph_core::particle_fields!`]; a field whose effect the run lacks is empty),
/// then the workspace, lists and run parameters. Cloning it saves the whole state (the
/// moving window restarts its trials from a clone).
#[derive(Clone)]
pub struct Sim {
    /// Particle ids.
    pub ids: Vec<u32>,
    /// Driven particles (bodies with `driven = true`) and the velocity they keep: each step
    /// moves them by exactly `v dt` (their material state evolves as computed).
    pub driven: Vec<(usize, Vector<D>)>,
    sums: Vec<PairSums<D>>,
    grad: Vec<Gradients<D>>,
    grad_stress: Vec<[Vector<D>; 6]>,
    corr: Vec<Correction<D>>,
    /// The hourglass stiffness's records (scratch: written before they are read in every step).
    hg_rec: Vec<Hourglass<D>>,
    av: Vec<AvRates<D>>,
    /// The first CFL step this simulation took (or was restarted with): the reference of
    /// the collapse check in [`Sim::checked_dt`].
    dt_first: Option<Real>,
    art: Vec<Matrix<D>>,
    /// Neighbour records (scratch of the vectorised pair loops; sized at each step).
    rec: Vec<Real>,
    aux: Vec<Aux>,
    geom: Vec<PairGeom<D>>,
    fac: Vec<Real>,
    ts_star: Vec<TsStar>,
    pm_star: Vec<PmStar<D>>,
    primed: bool,
    /// Times the particles were renumbered in memory (a caller that maps ids to memory
    /// indices renews its map when this changes).
    pub renumbered: u64,
    lists: Lists,
    capacity: usize,
    /// Renumber particles in Morton order at every neighbour-list rebuild (results do not
    /// depend on it: sums run in id order).
    pub reorder: bool,
    build_x: Vec<Vector<D>>,
    build_h: Vec<Real>,
    /// Materials.
    pub materials: Vec<Material>,
    /// Kernel.
    pub kernel: Kernel,
    /// Smoothing length factor.
    pub h_factor: Real,
    /// Periodic box.
    pub periodic: Periodic<D>,
    /// Scheme options.
    pub options: SchemeOptions,
    skin: Real,
    /// Resolved effects.
    pub effects: EffectSet,
    /// Scheme.
    pub scheme: Scheme,
    step_fn: StepFn<D, Rayon>,
    exec: Rayon,
    simd: SimdLevel,
    /// Time, s.
    pub t: Real,
    /// Steps taken.
    pub step: u64,
    /// Pair interactions evaluated so far (directed pairs in the lists, per step).
    pub pair_interactions: u64,
    /// Neighbour-list rebuilds so far.
    pub rebuilds: u64,
    /// tl's reference updates so far (`options.reference_update`, `sim/reference.rs`).
    pub reference_updates: u64,
    /// The particles this process owns: the first `owned` of the arrays. The rest are
    /// ghost copies of other ranks' particles (feature `mpi`) or the mirrors of walls.
    pub owned: usize,
    /// Rigid walls and symmetry planes and their mirror ghosts ([`walls`]).
    pub mirrors: walls::Mirrors<D>,
    /// The domain decomposition ([`Sim::distribute`]); `None` in one process.
    #[cfg(feature = "mpi")]
    pub dist: Option<Box<crate::dist::Dist<D>>>,
}
});

fn vec_of<const D: usize>(a: &[f64; 3]) -> Vector<D> {
    Vector::<D>::from_fn(|k, _| a[k])
}

impl<const D: usize> Sim<D> {
    /// Builds a simulation from a validated scene and its particles.
    pub fn new(scene: &Scene, parts: &InitialParticles) -> Result<Self, SimError> {
        Self::with_reorder(scene, parts, true)
    }

    /// [`Sim::new`], with or without renumbering the particles in Morton order at
    /// neighbour-list rebuilds ([`Sim::reorder`]; results are the same either way).
    pub fn with_reorder(
        scene: &Scene,
        parts: &InitialParticles,
        reorder: bool,
    ) -> Result<Self, SimError> {
        let materials: Vec<Material> = scene
            .materials
            .iter()
            .map(crate::scene::materials::material_of)
            .collect();
        let scheme = scene.scheme;
        let effects = resolve_effects(scene, &materials);
        let unsupported = effects.kernel_part().without(scheme.family().supported());
        if unsupported != EffectSet::HYDRO {
            return Err(SimError::Unsupported {
                scheme,
                effects: unsupported,
            });
        }
        let step_fn = select::<D>(scheme, effects).ok_or(SimError::NotCompiled {
            dim: D,
            scheme,
            effects,
        })?;
        let simd = crate::exec::simd().map_err(SimError::Simd)?;
        let n = parts.len();
        let kernel = scene.kernel;
        let options = scene.options.resolve(scheme, scene.constant_h);
        let periodic = match &scene.periodic {
            None => Periodic::none(),
            Some(p) => {
                let mut axes = [false; D];
                for &a in &p.axes {
                    axes[a] = true;
                }
                Periodic {
                    lo: Vector::<D>::from_fn(|k, _| p.lo[k]),
                    len: Vector::<D>::from_fn(|k, _| p.hi[k] - p.lo[k]),
                    axes,
                }
            }
        };
        let capacity = scene
            .neighbor_capacity
            .unwrap_or_else(|| default_capacity(D, kernel, scene.h_factor));
        let mut sim = gsph_core::particle_fields!(each_state_field { literal Sim {
            ids: Vec::with_capacity(n),
            driven: (0..n)
                .filter(|&i| {
                    // caller-given particles (the library) belong to no body
                    scene
                        .bodies
                        .get(parts.body[i] as usize)
                        .is_some_and(|b| b.driven)
                })
                .map(|i| (i, vec_of::<D>(&parts.v[i])))
                .collect(),
            sums: Vec::with_capacity(n),
            grad: Vec::new(),
            grad_stress: Vec::new(),
            corr: Vec::new(),
            hg_rec: Vec::new(),
            dt_first: None,
            av: Vec::new(),
            art: Vec::new(),
            rec: Vec::new(),
            aux: Vec::new(),
            geom: Vec::new(),
            fac: Vec::new(),
            ts_star: Vec::new(),
            pm_star: Vec::new(),
            primed: false,
            renumbered: 0,
            lists: Lists::default(),
            capacity,
            reorder,
            build_x: Vec::new(),
            build_h: Vec::new(),
            materials,
            kernel,
            h_factor: scene.h_factor,
            periodic,
            options,
            skin: scene.skin,
            effects,
            scheme,
            step_fn,
            exec: Rayon::default(),
            simd,
            t: 0.0,
            step: 0,
            pair_interactions: 0,
            rebuilds: 0,
            reference_updates: 0,
            owned: 0,
            mirrors: walls::Mirrors::new(&scene.walls).map_err(SimError::Walls)?,
            #[cfg(feature = "mpi")]
            dist: None,
        } });
        // the per-particle state, effect storage and workspace: one code path with the
        // particles a moving window feeds in later
        sim.append(parts);
        sim.check_walls().map_err(SimError::Walls)?;
        sim.first_rebuild(&parts.spacing)?;
        sim.check_bodies_bonded(&parts.body)?;
        Ok(sim)
    }

    /// Replaces the compiled step by `step`, which must be an instantiation of the same
    /// scheme family and compiled effects (the effects benchmark swaps in steps that
    /// compile run-time flags out, [`gsph_core::effects::Effects::RUNTIME`]).
    #[doc(hidden)]
    pub fn replace_step(&mut self, step: StepFn<D, Rayon>) {
        self.step_fn = step;
    }

    /// The instruction-set level of the vectorised loops ([`crate::exec::simd`] when built).
    pub fn simd(&self) -> Simd {
        self.simd.get()
    }

    /// Runs the vectorised loops at `simd` from now on (results are bitwise the same at
    /// every level, [`gsph_core::simd`]); an error if this CPU lacks it.
    pub fn set_simd(&mut self, simd: Simd) -> Result<(), SimError> {
        self.simd = crate::exec::level(simd).map_err(SimError::Simd)?;
        Ok(())
    }

    /// Number of particles.
    pub fn len(&self) -> usize {
        self.x.len()
    }

    /// True if there are no particles.
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }

    /// Length of the neighbour records where a vectorised loop may read them (scratch: a
    /// step sizes `rec` to this and writes it whole before it reads it).
    fn records_len(&self) -> usize {
        if self.simd.get() == gsph_core::simd::Simd::Baseline {
            0
        } else {
            self.aux.len() * gsph_core::schemes::record_len(self.scheme.family(), D)
        }
    }

    /// Bytes of per-particle storage (state, workspace and neighbour lists) per particle,
    /// the scratch records counted at the size a step gives them (so the figure does not
    /// depend on whether a step ran since a restart): the sum of [`Sim::memory`].
    pub fn bytes_per_particle(&self) -> usize {
        self.memory().iter().map(|m| m.1).sum::<usize>() / self.len().max(1)
    }

    /// Every array the run holds, by name, with its bytes: the state fields of the
    /// particle table (each a row of `gsph_core::particle_fields!`), the ids, each
    /// workspace array (`gsph_core::schemes::Workspace`; per particle or, `geom`, `fac`
    /// and the stars, per pair) and the neighbour lists. Arrays a run does not use hold 0.
    pub fn memory(&self) -> Vec<(&'static str, usize)> {
        use std::mem::size_of_val;
        let mut out: Vec<(&'static str, usize)> = vec![("ids", size_of_val(&self.ids[..]))];
        macro_rules! state_bytes {
            (($s:expr, $out:expr) $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
                $( $out.push((stringify!($name), size_of_val(&$s.$name[..]))); )*
            };
        }
        gsph_core::particle_fields!(state_bytes { self, out });
        out.extend([
            ("ws.sums", size_of_val(&self.sums[..])),
            ("ws.grad", size_of_val(&self.grad[..])),
            ("ws.grad_stress", size_of_val(&self.grad_stress[..])),
            ("ws.corr", size_of_val(&self.corr[..])),
            ("ws.hg", size_of_val(&self.hg_rec[..])),
            ("ws.av", size_of_val(&self.av[..])),
            ("ws.art", size_of_val(&self.art[..])),
            ("ws.rec", self.records_len() * std::mem::size_of::<Real>()),
            ("ws.aux", size_of_val(&self.aux[..])),
            ("ws.fac", size_of_val(&self.fac[..])),
            ("ws.geom", size_of_val(&self.geom[..])),
            ("ws.ts_star", size_of_val(&self.ts_star[..])),
            ("ws.pm_star", size_of_val(&self.pm_star[..])),
        ]);
        out.extend(self.lists.memory());
        out
    }

    /// Largest stable time step for the CFL number.
    pub fn stable_dt(&mut self, cfl: Real) -> Real {
        let dt = (0..self.owned)
            .into_par_iter()
            .with_min_len(1024)
            .map(|i| {
                let speed = self.cl[i] + self.v[i].norm();
                if speed > 0.0 {
                    self.h[i] / speed
                } else {
                    f64::INFINITY
                }
            })
            .reduce(|| f64::INFINITY, f64::min);
        #[cfg(feature = "mpi")]
        let dt = if self.dist.is_some() {
            crate::dist::all_min(dt)
        } else {
            dt
        };
        cfl * dt
    }

    /// The time step for the CFL number, or the error naming the first particle whose
    /// signal speed or smoothing length is not finite (or when no particle moves and no
    /// wave can travel).
    ///
    /// A step that has fallen below [`DT_COLLAPSE`] times the first step is refused
    /// ([`SimError::Collapsed`], naming the particle that sets it): a run whose particles
    /// have blown up or crushed together would otherwise step on for ever.
    pub fn checked_dt(&mut self, cfl: Real) -> Result<Real, SimError> {
        let dt = self.stable_dt(cfl);
        if dt.is_finite() && dt > 0.0 {
            // per unit CFL, so that a fixed step's CFL-1 check and the CFL step compare
            let first = *self.dt_first.get_or_insert(dt / cfl);
            if dt / cfl < first * DT_COLLAPSE {
                let particle = (0..self.owned)
                    .min_by(|&a, &b| {
                        let s = |i: usize| self.h[i] / (self.cl[i] + self.v[i].norm());
                        s(a).total_cmp(&s(b))
                    })
                    .map_or(0, |i| self.ids[i]);
                return Err(SimError::Collapsed {
                    step: self.step + 1,
                    t: self.t,
                    dt,
                    first: first * cfl,
                    particle,
                });
            }
            return Ok(dt);
        }
        let particle = (0..self.owned)
            .find(|&i| {
                let ok = (self.cl[i] + self.v[i].norm()).is_finite()
                    && self.h[i] > 0.0
                    && self.h[i].is_finite();
                !ok
            })
            .unwrap_or(0);
        Err(SimError::Step {
            step: self.step + 1,
            t: self.t,
            cause: StepError::NonFinite {
                particle,
                field: "time step (signal speed or smoothing length)",
            },
        })
    }

    /// The next time step of a run: `fixed` if given (an error if it exceeds the CFL-1
    /// limit `min h / (c_l + |v|)`, which would blow the run up), else the CFL step.
    pub fn next_dt(&mut self, cfl: Real, fixed: Option<Real>) -> Result<Real, SimError> {
        let Some(dt) = fixed else {
            return self.checked_dt(cfl);
        };
        let limit = self.checked_dt(1.0)?;
        if dt > limit {
            let particle = (0..self.owned)
                .filter(|&i| self.h[i] / (self.cl[i] + self.v[i].norm()) <= limit)
                .map(|i| self.ids[i])
                .min()
                .unwrap_or(0);
            return Err(SimError::TimeStep {
                step: self.step + 1,
                t: self.t,
                dt,
                limit,
                particle,
            });
        }
        Ok(dt)
    }

    /// Forgets what a scheme carries from one step into the next (av's rates, computed at
    /// the end of a step from its state): the next step recomputes it from the state, which
    /// the caller has changed (the library's field writes and external kicks).
    pub fn state_changed(&mut self) {
        self.primed = false;
    }

    /// Advances by `dt`.
    pub fn step(&mut self, dt: Real) -> Result<(), SimError> {
        let t0 = self.t;
        self.maintain()?;
        let nbrs = self.lists.view();
        // the pairs of the owned particles' rows (all rows in one process)
        let pairs = nbrs.start.get(self.owned).map_or(0, |&s| s as u64);
        let params = StepParams {
            dt,
            materials: &self.materials,
            kernel: self.kernel,
            h_factor: self.h_factor,
            periodic: self.periodic,
            nbrs,
            options: self.options,
            effects: self.effects,
            simd: self.simd,
        };
        self.rec.resize(self.records_len(), 0.0);
        let mut sys = gsph_core::particle_fields!(step each_state_field { system self });
        let mut ws = Workspace {
            sums: &mut self.sums,
            grad: &mut self.grad,
            grad_stress: &mut self.grad_stress,
            corr: &mut self.corr,
            hg: &mut self.hg_rec,
            av: &mut self.av,
            art: &mut self.art,
            rec: &mut self.rec,
            geom: &mut self.geom,
            fac: &mut self.fac,
            aux: &mut self.aux,
            ts_star: &mut self.ts_star,
            pm_star: &mut self.pm_star,
            primed: self.primed,
        };
        let step = self.step + 1;
        let fail = |cause| SimError::Step { step, t: t0, cause };
        // driven particles move at exactly their prescribed velocity: x0 + v0 dt from
        // where the step started, whatever the step computed for them
        let x_start: Vec<Vector<D>> = self.driven.iter().map(|&(i, _)| sys.x[i]).collect();
        // the ranks' ghosts (feature `mpi`), then the walls' mirrors
        #[cfg(feature = "mpi")]
        let mut both;
        #[cfg(feature = "mpi")]
        let halo: &mut dyn gsph_core::halo::Halo<D> =
            match (self.dist.as_deref_mut(), self.mirrors.is_empty()) {
                (Some(d), true) => d,
                (Some(dist), false) => {
                    both = walls::Both {
                        dist,
                        mirrors: &mut self.mirrors,
                    };
                    &mut both
                }
                (None, true) => &mut gsph_core::halo::NoHalo,
                (None, false) => &mut self.mirrors,
            };
        #[cfg(not(feature = "mpi"))]
        let halo: &mut dyn gsph_core::halo::Halo<D> = if self.mirrors.is_empty() {
            &mut gsph_core::halo::NoHalo
        } else {
            &mut self.mirrors
        };
        // ghosts (after the owned particles) hold values no one reads until the next
        // exchange refreshes them: only owned particles are checked
        let owned = self.owned;
        // the finite check, in parallel on more than one thread (serially it was 3 % of
        // av's two-thread step); whichever bad particle it meets, `cause_by_id` below
        // names the one with the lowest id, whatever the thread count
        let r = (self.step_fn)(&mut sys, &mut ws, &params, &self.exec, halo).and_then(|_| {
            let sys = &sys;
            if rayon::current_num_threads() == 1 {
                (0..owned).try_for_each(|i| check_finite_one(sys, i))
            } else {
                (0..owned)
                    .into_par_iter()
                    .with_min_len(4096)
                    .try_for_each(|i| check_finite_one(sys, i))
            }
        });
        #[cfg(feature = "mpi")]
        if self.dist.is_some() {
            let msg = r
                .err()
                .map(|c| fail(cause_by_id(c, &self.ids, &sys)).to_string());
            crate::dist::agree(msg.map_or(Ok(()), Err)).map_err(SimError::Distributed)?;
        }
        if let Err(cause) = r {
            return Err(fail(cause_by_id(cause, &self.ids, &sys)));
        }
        for (&(i, v0), &x0) in self.driven.iter().zip(&x_start) {
            self.v[i] = v0;
            self.x[i] = self.periodic.wrap(x0 + v0 * dt);
        }
        self.primed = ws.primed;
        // tl's velocity Verlet carries the acceleration into the next step's first half
        // kick: a driven particle's is zero, so it moves at its velocity within the step
        // too (F and the stresses of its neighbours see it where it is prescribed)
        if self.effects.contains(EffectSet::REFERENCE) {
            for &(i, _) in &self.driven {
                self.av[i].acc = Vector::<D>::zeros();
            }
        }
        self.enforce_walls(dt);
        self.t += dt;
        self.step = step;
        self.pair_interactions += pairs;
        self.update_reference()
    }
}
