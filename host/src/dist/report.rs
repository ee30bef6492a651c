//! What the decomposition cost: halo bytes and time per exchange point, migration, ghost
//! counts and balance, as summary.json's `mpi` object (collective: every rank calls it).

use super::{all_gather_u64, all_max, all_sum_u64, Dist};
use serde_json::{json, Map, Value};

/// The `mpi` object of summary.json after `steps` steps. Times are the largest over the
/// ranks (an exchange waits for the slowest rank, so they include load imbalance); bytes
/// are summed over the ranks.
pub fn summary<const D: usize>(d: &Dist<D>, steps: u64) -> Value {
    let per_step = |b: u64| b as f64 / steps.max(1) as f64;
    let mut halo = Map::new();
    let (mut bytes, mut secs) = (0u64, 0.0f64);
    for (name, a) in &d.halo {
        let b = all_sum_u64(a.bytes);
        let t = all_max(a.seconds);
        bytes += b;
        secs += t;
        halo.insert(
            (*name).into(),
            json!({"calls": a.calls, "bytes_per_step": per_step(b), "seconds": t}),
        );
    }
    let owned = all_gather_u64(d.owned as u64);
    let ghosts: u64 = all_sum_u64(d.plan.recv.iter().sum::<usize>() as u64);
    let total: u64 = owned.iter().sum();
    let mean = total as f64 / owned.len().max(1) as f64;
    let max = owned.iter().copied().max().unwrap_or(0) as f64;
    json!({
        "ranks": d.size,
        "owned_per_rank": owned,
        "imbalance": if mean > 0.0 { max / mean - 1.0 } else { 0.0 },
        "ghosts": ghosts,
        "rebalances": d.rebalances,
        "halo_bytes_per_step": per_step(bytes),
        "halo_seconds": secs,
        "halo": halo,
        "rebuild_bytes": all_sum_u64(d.rebuild.bytes),
        "rebuild_seconds": all_max(d.rebuild.seconds),
        "rebuilds": d.rebuild.calls,
    })
}
