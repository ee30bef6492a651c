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

/// The summary of a finished run (summary.json).
pub(super) fn summary<const D: usize>(x: Summed<'_, D>) -> Map<String, Value> {
    let sim = x.sim;
    let (k1, i1) = sim.energy();
    let energy1 = k1 + i1;
    let mom1 = sim.momentum();
    let mut s = Map::new();
    s.insert("scene".into(), json!(x.scene_name));
    s.insert("gsph_version".into(), json!(env!("CARGO_PKG_VERSION")));
    s.insert("run_id".into(), json!(x.run_id));
    if let Some(src) = x.source {
        s.insert(
            "scene_sha256".into(),
            json!(crate::runlog::sha256_hex(&src.text)),
        );
        s.insert("overrides".into(), json!(src.overrides));
    }
    s.insert("dim".into(), json!(D));
    s.insert("scheme".into(), json!(sim.scheme.name()));
    s.insert(
        "effects".into(),
        json!(sim.effects.names().collect::<Vec<_>>()),
    );
    s.insert("particles".into(), json!(sim.global_len()));
    s.insert("steps".into(), json!(sim.step));
    s.insert("t_end".into(), json!(sim.t));
    s.insert("ended".into(), json!(x.ended));
    s.insert("wall_s".into(), json!(x.wall));
    s.insert("wall_total_s".into(), json!(x.wall_total));
    s.insert("threads".into(), json!(rayon::current_num_threads()));
    s.insert("ranks".into(), json!(x.ranks));
    #[cfg(feature = "mpi")]
    let pairs = match &sim.dist {
        Some(d) => {
            s.insert("mpi".into(), crate::dist::report::summary(d, sim.step));
            crate::dist::all_sum_u64(sim.pair_interactions)
        }
        None => sim.pair_interactions,
    };
    #[cfg(not(feature = "mpi"))]
    let pairs = sim.pair_interactions;
    s.insert("pair_interactions".into(), json!(pairs));
    if !sim.mirrors.is_empty() {
        let (crossings, friction_work) = sim.wall_totals();
        s.insert("wall_crossings".into(), json!(crossings));
        s.insert("wall_friction_work".into(), json!(friction_work));
    }
    s.insert("neighbor_rebuilds".into(), json!(sim.rebuilds));
    s.insert("bytes_per_particle".into(), json!(sim.bytes_per_particle()));
    s.insert("energy_initial".into(), json!(x.energy0));
    s.insert("energy_final".into(), json!(energy1));
    // relative to the initial energy, or to the final kinetic plus |internal| energy when
    // the initial energy is zero (a case that starts at rest with e = 0)
    let scale = x.energy0.abs().max(k1 + i1.abs()).max(f64::MIN_POSITIVE);
    s.insert(
        "energy_rel_error".into(),
        json!((energy1 - x.energy0) / scale),
    );
    s.insert("kinetic_final".into(), json!(k1));
    s.insert("kinetic_max".into(), json!(x.kinetic_max.max(k1)));
    s.insert("internal_final".into(), json!(i1));
    s.insert("momentum_initial".into(), json!(x.mom0[..D].to_vec()));
    s.insert("momentum_final".into(), json!(mom1[..D].to_vec()));
    if let Some(r) = x.reference {
        for (k, v) in r.measures(x.table, sim.t) {
            s.insert(k.into(), json!(v));
        }
    }
    for (k, v) in x.monitor.measures(x.table) {
        s.insert(k, json!(v));
    }
    if let Some(w) = x.window {
        for (k, v) in Window::<D>::series_names().iter().zip(w.series_values(sim)) {
            s.insert((*k).into(), json!(v));
        }
        s.insert("window_u_in".into(), json!(w.u_in));
        s.insert("window_u_out".into(), json!(w.u_out()));
    }
    s
}
