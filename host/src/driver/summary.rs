//! summary.json of a run.

use super::*;

/// What [`summary`] reads.
pub(super) struct Summed<'a, const D: usize> {
    pub sim: &'a Sim<D>,
    pub scene_name: &'a str,
    pub run_id: &'a str,
    pub source: Option<&'a SceneSource>,
    pub wall: f64,
    pub wall_total: f64,
    pub ranks: usize,
    pub energy0: f64,
    pub mom0: [f64; 3],
    pub kinetic_max: f64,
    pub reference: &'a Option<Reference>,
    pub monitor: &'a mut Monitor,
    pub window: &'a Option<Window<D>>,
    pub table: &'a crate::output::ParticleTable,
    /// How the run ended: `t_end`, or `max_steps` when that bound stopped it first.
    pub ended: &'static str,
}

/// summary.json of a finished run: one field per key, in file order, each with its unit.
/// Energies and momenta are per unit length in 2D and per unit area in 1D (the masses'
/// convention). Non-finite numbers are written as `null`.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Summary {
    /// The scene's name.
    pub scene: String,
    /// The version of gsph that ran it.
    pub gsph_version: String,
    /// The run's identifier (a checkpoint resumes only the run that wrote it).
    pub run_id: String,
    /// SHA-256 of the scene file's text (runs from a file).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub scene_sha256: Option<String>,
    /// The `--set`/`--unset` overrides, in order (runs from a file).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub overrides: Option<Vec<String>>,
    /// Dimension, 1–3.
    pub dim: usize,
    /// Scheme name.
    pub scheme: String,
    /// The effects the run simulated.
    pub effects: Vec<String>,
    /// Particles at the end (all ranks).
    pub particles: usize,
    /// Steps taken.
    pub steps: u64,
    /// Time reached, s.
    pub t_end: f64,
    /// What ended the run: `t_end`, or `max_steps` when that bound stopped it first.
    pub ended: &'static str,
    /// Wall time of the stepping, s.
    pub wall_s: f64,
    /// Wall time of the whole run (set-up and output included), s.
    pub wall_total_s: f64,
    /// Worker threads per rank.
    pub threads: usize,
    /// Instruction-set level of the vectorised loops (`gsph run --simd`; results are
    /// bitwise the same at every level).
    pub simd: &'static str,
    /// MPI ranks.
    pub ranks: usize,
    /// What the decomposition cost (several ranks): `crate::dist::report::summary`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mpi: Option<Value>,
    /// Pair interactions evaluated (directed pairs in the lists, summed over the steps).
    pub pair_interactions: u64,
    /// Particles pushed back across a wall (runs with walls).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wall_crossings: Option<u64>,
    /// Kinetic energy turned into heat by wall friction, J (runs with walls).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub wall_friction_work: Option<f64>,
    /// Neighbour-list rebuilds.
    pub neighbor_rebuilds: u64,
    /// tl's reference updates (`options.reference_update`; scheme tl only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference_updates: Option<u64>,
    /// Memory of the particle state and workspace per particle, bytes.
    pub bytes_per_particle: usize,
    /// The same by array (`Sim::memory`), bytes per particle; arrays the run does not
    /// use are left out.
    pub bytes_per_particle_by_array: std::collections::BTreeMap<String, f64>,
    /// Total energy at the start, J.
    pub energy_initial: f64,
    /// Total energy at the end, J.
    pub energy_final: f64,
    /// `(energy_final - energy_initial) / scale`, the scale the initial energy, or the
    /// final kinetic plus |internal| energy when that is zero (a body at rest with e = 0).
    pub energy_rel_error: f64,
    /// Kinetic energy at the end, J.
    pub kinetic_final: f64,
    /// Largest kinetic energy sampled (series rows and the end), J.
    pub kinetic_max: f64,
    /// Internal energy at the end, J.
    pub internal_final: f64,
    /// Momentum at the start, kg m/s per component.
    pub momentum_initial: Vec<f64>,
    /// Momentum at the end, kg m/s per component.
    pub momentum_final: Vec<f64>,
    /// The reference's measures (e.g. `l1_error`, `radius_error`), the monitor's
    /// (`density_min`, the scene's probes) and the moving window's series, by name; the
    /// units are in docs/output.md.
    #[serde(flatten)]
    pub measures: Map<String, Value>,
}

impl Summary {
    /// A measure by name (`l1_error`, `density_min` …), if the run has it as a number.
    pub fn measure(&self, key: &str) -> Option<f64> {
        self.measures.get(key).and_then(Value::as_f64)
    }

    /// Any number of the summary by its key in summary.json (a field or a measure).
    pub fn number(&self, key: &str) -> Option<f64> {
        self.to_map().get(key).and_then(Value::as_f64)
    }

    /// The keys of summary.json whose value is a number or `null` (a non-finite number).
    pub fn number_keys(&self) -> Vec<String> {
        self.to_map()
            .into_iter()
            .filter(|(_, v)| v.is_number() || v.is_null())
            .map(|(k, _)| k)
            .collect()
    }

    /// The summary as summary.json's object.
    pub fn to_map(&self) -> Map<String, Value> {
        match serde_json::to_value(self).expect("a summary serialises") {
            Value::Object(m) => m,
            _ => unreachable!("a struct serialises to an object"),
        }
    }
}

/// The summary of a finished run (summary.json).
pub(super) fn summary<const D: usize>(x: Summed<'_, D>) -> Summary {
    let sim = x.sim;
    let (k1, i1) = sim.energy();
    let energy1 = k1 + i1;
    let mom1 = sim.momentum();
    #[cfg(feature = "mpi")]
    let (mpi, pairs) = match &sim.dist {
        Some(d) => (
            Some(crate::dist::report::summary(d, sim.step)),
            crate::dist::all_sum_u64(sim.pair_interactions),
        ),
        None => (None, sim.pair_interactions),
    };
    #[cfg(not(feature = "mpi"))]
    let (mpi, pairs) = (None, sim.pair_interactions);
    let walls = (!sim.mirrors.is_empty()).then(|| sim.wall_totals());
    // relative to the initial energy, or to the final kinetic plus |internal| energy when
    // the initial energy is zero (a case that starts at rest with e = 0)
    let scale = x.energy0.abs().max(k1 + i1.abs()).max(f64::MIN_POSITIVE);
    let mut measures = Map::new();
    if let Some(r) = x.reference {
        for (k, v) in r.measures(x.table, sim.t) {
            measures.insert(k.into(), json!(v));
        }
    }
    for (k, v) in x.monitor.measures(x.table) {
        measures.insert(k, json!(v));
    }
    if let Some(w) = x.window {
        for (k, v) in Window::<D>::series_names().iter().zip(w.series_values(sim)) {
            measures.insert((*k).into(), json!(v));
        }
        measures.insert("window_u_in".into(), json!(w.u_in));
        measures.insert("window_u_out".into(), json!(w.u_out()));
    }
    Summary {
        scene: x.scene_name.into(),
        gsph_version: env!("CARGO_PKG_VERSION").into(),
        run_id: x.run_id.into(),
        scene_sha256: x.source.map(|src| crate::runlog::sha256_hex(&src.text)),
        overrides: x.source.map(|src| src.overrides.clone()),
        dim: D,
        scheme: sim.scheme.name().into(),
        effects: sim.effects.names().map(String::from).collect(),
        particles: sim.global_len(),
        steps: sim.step,
        t_end: sim.t,
        ended: x.ended,
        wall_s: x.wall,
        wall_total_s: x.wall_total,
        threads: rayon::current_num_threads(),
        simd: sim.simd().name(),
        ranks: x.ranks,
        mpi,
        pair_interactions: pairs,
        wall_crossings: walls.map(|w| w.0),
        wall_friction_work: walls.map(|w| w.1),
        neighbor_rebuilds: sim.rebuilds,
        reference_updates: (sim.scheme == gsph_core::schemes::Scheme::Tl)
            .then_some(sim.reference_updates),
        bytes_per_particle: sim.bytes_per_particle(),
        bytes_per_particle_by_array: sim
            .memory()
            .into_iter()
            .filter(|m| m.1 > 0)
            .map(|(name, bytes)| (name.to_string(), bytes as f64 / sim.len().max(1) as f64))
            .collect(),
        energy_initial: x.energy0,
        energy_final: energy1,
        energy_rel_error: (energy1 - x.energy0) / scale,
        kinetic_final: k1,
        kinetic_max: x.kinetic_max.max(k1),
        internal_final: i1,
        momentum_initial: x.mom0[..D].to_vec(),
        momentum_final: mom1[..D].to_vec(),
        measures,
    }
}
