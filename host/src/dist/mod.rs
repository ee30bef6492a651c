//! Domain decomposition over MPI (feature `mpi`): the communication layer, the halo
//! exchange between passes ([`gsph_core::halo::Halo`]) and the accounting of both.
//!
//! A run on `n > 1` ranks (docs/mpi.md):
//! - every rank builds the scene and the serial [`crate::sim::Sim`] (the same particles,
//!   the same checks and errors on every rank), then [`crate::sim::Sim::distribute`] keeps
//!   its block of ids and the first neighbour-list rebuild sends every particle to the
//!   rank whose sub-domain holds it;
//! - sub-domains come from recursive coordinate bisection by particle count ([`rcb`]),
//!   recomputed at a rebuild when the largest rank holds more than
//!   [`REBALANCE_THRESHOLD`] above the mean; particles migrate at every rebuild;
//! - after its owned particles each rank holds ghost copies of the particles of other
//!   ranks within `support (1 + skin) h_max` of its sub-domain (the reach of the
//!   neighbour lists), refreshed before each pass that reads a field an earlier pass
//!   changed, with exactly those fields;
//! - the time step is an all-reduce min, the rebuild decision an all-reduce of the serial
//!   criterion's max/min terms (exact operations: the same bits as one process);
//! - diagnostics and outputs are gathered in global id order, so sums run in the order
//!   of one process.
//!
//! Every collective here is called by every rank in the same order: the driver's
//! decisions depend only on reduced values.

pub mod rcb;
pub mod report;

use crate::words::Words;
use gsph_core::halo::{Exchange, Fields, GhostWorkspace, Halo};
use gsph_core::state::System;
use mpi::collective::SystemOperation;
use mpi::datatype::{Partition, PartitionMut};
use mpi::topology::SimpleCommunicator;
use mpi::traits::*;
use std::time::Instant;

/// Rebalance at a rebuild when `max owned / mean owned - 1` exceeds this.
pub const REBALANCE_THRESHOLD: f64 = 0.10;

/// True when an MPI launcher started this process (Open MPI's `mpirun`, MPICH's Hydra,
/// or PMIx, as under Slurm's `srun --mpi=pmix`), or `GSPH_MPI=1` asks for MPI anyway. The
/// `gsph` binary initialises MPI only then, so a plain run pays no MPI start-up.
pub fn launched() -> bool {
    ["OMPI_COMM_WORLD_SIZE", "PMIX_RANK", "PMI_RANK", "PMI_SIZE"]
        .iter()
        .any(|v| std::env::var_os(v).is_some())
        || std::env::var("GSPH_MPI").is_ok_and(|v| v == "1")
}

/// The world communicator (MPI must be initialised: the `gsph` binary does it).
pub fn world() -> SimpleCommunicator {
    SimpleCommunicator::world()
}

/// The number of ranks (1 when MPI was not initialised, as in library use and tests).
pub fn size() -> usize {
    if mpi::environment::is_initialized() && !mpi::environment::is_finalized() {
        world().size() as usize
    } else {
        1
    }
}

/// This rank (0 when MPI was not initialised).
pub fn rank() -> usize {
    if size() > 1 {
        world().rank() as usize
    } else {
        0
    }
}

/// The global minimum (exact: the same bits as a serial minimum).
pub fn all_min(v: f64) -> f64 {
    let mut out = v;
    world().all_reduce_into(&v, &mut out, SystemOperation::min());
    out
}

/// The global maximum.
pub fn all_max(v: f64) -> f64 {
    let mut out = v;
    world().all_reduce_into(&v, &mut out, SystemOperation::max());
    out
}

/// The global sum of integers.
pub fn all_sum_u64(v: u64) -> u64 {
    let mut out = v;
    world().all_reduce_into(&v, &mut out, SystemOperation::sum());
    out
}

/// The global sum (in rank order of the reduction: not the bits of a serial sum).
pub fn all_sum_f64(v: f64) -> f64 {
    let mut out = v;
    world().all_reduce_into(&v, &mut out, SystemOperation::sum());
    out
}

/// Element-wise global sums of integer vectors.
pub fn all_sum_vec(v: &[u64]) -> Vec<u64> {
    let mut out = vec![0u64; v.len()];
    world().all_reduce_into(v, &mut out[..], SystemOperation::sum());
    out
}

/// Element-wise global minima.
pub fn all_min_vec(v: &[f64]) -> Vec<f64> {
    let mut out = vec![0.0; v.len()];
    world().all_reduce_into(v, &mut out[..], SystemOperation::min());
    out
}

/// True on every rank if `flag` is true on some rank.
pub fn any(flag: bool) -> bool {
    all_sum_u64(flag as u64) > 0
}

/// One value from every rank, in rank order.
pub fn all_gather_u64(v: u64) -> Vec<u64> {
    let mut out = vec![0u64; size()];
    world().all_gather_into(&v, &mut out[..]);
    out
}

fn displs(counts: &[i32]) -> Vec<i32> {
    counts
        .iter()
        .scan(0i32, |acc, &c| {
            let d = *acc;
            *acc += c;
            Some(d)
        })
        .collect()
}

fn count_i32(n: usize) -> i32 {
    i32::try_from(n).expect("an MPI message of more than 2^31 values")
}

/// Sends `parts[r]` to rank `r` (all ranks call it); returns what each rank sent here, in
/// rank order.
pub fn all_to_all(parts: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let send_counts: Vec<i32> = parts.iter().map(|p| count_i32(p.len())).collect();
    let mut recv_counts = vec![0i32; parts.len()];
    world().all_to_all_into(&send_counts[..], &mut recv_counts[..]);
    all_to_all_known(parts, &recv_counts)
}

/// [`all_to_all`] when each rank's message length is known here (`recv_counts`, words).
pub fn all_to_all_known(parts: &[Vec<f64>], recv_counts: &[i32]) -> Vec<Vec<f64>> {
    let n = parts.len();
    let send_counts: Vec<i32> = parts.iter().map(|p| count_i32(p.len())).collect();
    let flat: Vec<f64> = parts.concat();
    let sd = displs(&send_counts);
    let rd = displs(recv_counts);
    let total: usize = recv_counts.iter().map(|&c| c as usize).sum();
    let mut recv = vec![0.0f64; total];
    {
        let s = Partition::new(&flat[..], &send_counts[..], &sd[..]);
        let mut r = PartitionMut::new(&mut recv[..], recv_counts, &rd[..]);
        world().all_to_all_varcount_into(&s, &mut r);
    }
    let mut out = Vec::with_capacity(n);
    let mut at = 0;
    for &c in recv_counts {
        out.push(recv[at..at + c as usize].to_vec());
        at += c as usize;
    }
    out
}

/// Every rank's `mine`, concatenated in rank order, on every rank.
pub fn all_gather(mine: &[f64]) -> Vec<f64> {
    let counts: Vec<i32> = all_gather_u64(mine.len() as u64)
        .into_iter()
        .map(|c| count_i32(c as usize))
        .collect();
    let d = displs(&counts);
    let total: usize = counts.iter().map(|&c| c as usize).sum();
    let mut out = vec![0.0f64; total];
    {
        let mut r = PartitionMut::new(&mut out[..], &counts[..], &d[..]);
        world().all_gather_varcount_into(mine, &mut r);
    }
    out
}

/// The bytes of a UTF-8 message from rank `root`, on every rank.
pub fn broadcast_text(root: usize, text: &str) -> String {
    let w = world();
    let p = w.process_at_rank(root as i32);
    let mut len = text.len() as u64;
    p.broadcast_into(&mut len);
    let mut buf = if rank() == root {
        text.as_bytes().to_vec()
    } else {
        vec![0u8; len as usize]
    };
    p.broadcast_into(&mut buf[..]);
    String::from_utf8_lossy(&buf).into_owned()
}

/// Makes a local failure collective: every rank learns whether some rank failed, and the
/// ranks that did not fail get the first failing rank's message.
pub fn agree(local: Result<(), String>) -> Result<(), String> {
    let me = rank() as u64;
    let code = if local.is_err() { me } else { u64::MAX };
    let mut first = code;
    world().all_reduce_into(&code, &mut first, SystemOperation::min());
    if first == u64::MAX {
        return Ok(());
    }
    let text = match &local {
        Err(e) if first == me => e.clone(),
        _ => String::new(),
    };
    let msg = broadcast_text(first as usize, &text);
    match local {
        Err(e) => Err(e),
        Ok(()) => Err(format!("rank {first}: {msg}")),
    }
}

/// Refuses, on every rank and in one line, a run whose ranks built different things:
/// rank 0 broadcasts its `digest` (of the scene, the overrides, the particles and any
/// restored state) and every rank compares it with its own. Without this check, ranks
/// that read different scenes (a `t_end` edited while the job started) take different
/// steps and wait for ever in mismatched collectives.
pub fn same_everywhere(digest: &str) -> Result<(), String> {
    let root = broadcast_text(0, digest);
    let mine = if root == digest {
        Ok(())
    } else {
        Err(format!(
            "its run differs from rank 0's (scene, overrides, particle files or checkpoint: sha256 {} there, {} on rank 0); every rank must read the same files and options (was one changed while the job started?)",
            &digest[..digest.len().min(16)],
            &root[..root.len().min(16)]
        ))
    };
    agree(mine)
}

/// Which owned particles each rank receives as ghosts, and how many ghosts come from each
/// rank (they sit after the owned particles, in rank order).
#[derive(Clone, Debug, Default)]
pub struct Plan {
    /// Local indices of the owned particles sent to each rank (indexed by rank).
    pub send: Vec<Vec<u32>>,
    /// Ghosts received from each rank.
    pub recv: Vec<usize>,
}

/// Time, bytes and calls of one exchange point.
#[derive(Clone, Debug, Default)]
pub struct Account {
    /// Seconds in the exchange (packing, waiting for the slowest rank, transfer).
    pub seconds: f64,
    /// Bytes this rank sent.
    pub bytes: u64,
    /// Number of exchanges.
    pub calls: u64,
}

/// The state of the decomposition on this rank.
#[derive(Clone, Debug)]
pub struct Dist<const D: usize> {
    /// This rank.
    pub rank: usize,
    /// Number of ranks.
    pub size: usize,
    /// Owned particles (the first `owned` of the local arrays); the rest are ghosts.
    pub owned: usize,
    /// The ghost exchange plan of the current neighbour lists.
    pub plan: Plan,
    /// The sub-domains.
    pub rcb: Option<rcb::Rcb<D>>,
    /// Per exchange point (named after the pass that follows), in first-use order.
    pub halo: Vec<(&'static str, Account)>,
    /// Particle migration and ghost set-up at rebuilds.
    pub rebuild: Account,
    /// Times the sub-domains were recomputed.
    pub rebalances: u64,
}

impl<const D: usize> Dist<D> {
    /// A decomposition over the world communicator.
    pub fn new() -> Self {
        let (rank, size) = (rank(), size());
        Dist {
            rank,
            size,
            owned: 0,
            plan: Plan::default(),
            rcb: None,
            halo: Vec::new(),
            rebuild: Account::default(),
            rebalances: 0,
        }
    }

    fn account(&mut self, name: &'static str) -> &mut Account {
        if let Some(k) = self.halo.iter().position(|(n, _)| *n == name) {
            return &mut self.halo[k].1;
        }
        self.halo.push((name, Account::default()));
        &mut self.halo.last_mut().expect("pushed").1
    }
}

impl<const D: usize> Default for Dist<D> {
    fn default() -> Self {
        Self::new()
    }
}

/// Appends the `fields` of particle `i` to `out` (fields with empty storage are skipped:
/// their effect is absent).
fn put_fields<const D: usize>(
    fields: Fields,
    sys: &System<'_, D>,
    ws: &GhostWorkspace<'_, D>,
    i: usize,
    out: &mut Vec<f64>,
) {
    fn put<T: Words>(on: bool, v: &[T], i: usize, out: &mut Vec<f64>) {
        if on && !v.is_empty() {
            v[i].put_words(out);
        }
    }
    put(fields.contains(Fields::X), sys.x, i, out);
    put(fields.contains(Fields::H), sys.h, i, out);
    put(fields.contains(Fields::V), sys.v, i, out);
    put(fields.contains(Fields::RHO), sys.rho, i, out);
    put(fields.contains(Fields::P), sys.p, i, out);
    put(fields.contains(Fields::C), sys.c, i, out);
    put(fields.contains(Fields::CL), sys.cl, i, out);
    put(fields.contains(Fields::S), sys.s, i, out);
    put(fields.contains(Fields::DAMAGE), sys.damage, i, out);
    put(fields.contains(Fields::GRAD), ws.grad, i, out);
    put(fields.contains(Fields::GRAD_STRESS), ws.grad_stress, i, out);
    put(fields.contains(Fields::CORR), ws.corr, i, out);
    put(fields.contains(Fields::HOURGLASS), ws.hg, i, out);
}

/// Reads what [`put_fields`] wrote into particle `i`; returns the words read.
fn get_fields<const D: usize>(
    fields: Fields,
    sys: &mut System<'_, D>,
    ws: &mut GhostWorkspace<'_, D>,
    i: usize,
    src: &[f64],
) -> usize {
    fn get<T: Words>(on: bool, v: &mut [T], i: usize, src: &[f64], at: &mut usize) {
        if on && !v.is_empty() {
            v[i] = T::from_words(&src[*at..]);
            *at += T::words();
        }
    }
    let mut at = 0;
    get(fields.contains(Fields::X), sys.x, i, src, &mut at);
    get(fields.contains(Fields::H), sys.h, i, src, &mut at);
    get(fields.contains(Fields::V), sys.v, i, src, &mut at);
    get(fields.contains(Fields::RHO), sys.rho, i, src, &mut at);
    get(fields.contains(Fields::P), sys.p, i, src, &mut at);
    get(fields.contains(Fields::C), sys.c, i, src, &mut at);
    get(fields.contains(Fields::CL), sys.cl, i, src, &mut at);
    get(fields.contains(Fields::S), sys.s, i, src, &mut at);
    get(fields.contains(Fields::DAMAGE), sys.damage, i, src, &mut at);
    get(fields.contains(Fields::GRAD), ws.grad, i, src, &mut at);
    get(
        fields.contains(Fields::GRAD_STRESS),
        ws.grad_stress,
        i,
        src,
        &mut at,
    );
    get(fields.contains(Fields::CORR), ws.corr, i, src, &mut at);
    get(fields.contains(Fields::HOURGLASS), ws.hg, i, src, &mut at);
    at
}

impl<const D: usize> Halo<D> for Dist<D> {
    fn refresh(
        &mut self,
        exchange: &Exchange,
        sys: &mut System<'_, D>,
        mut ws: GhostWorkspace<'_, D>,
    ) {
        let t0 = Instant::now();
        let parts: Vec<Vec<f64>> = self
            .plan
            .send
            .iter()
            .map(|idx| {
                let mut out = Vec::new();
                for &i in idx {
                    put_fields(exchange.fields, sys, &ws, i as usize, &mut out);
                }
                out
            })
            .collect();
        let bytes = 8 * parts.iter().map(Vec::len).sum::<usize>() as u64;
        // every particle sends the same fields: the message lengths are known here (a
        // rank without particles receives nothing)
        let width = {
            let mut one = Vec::new();
            if !sys.is_empty() {
                put_fields(exchange.fields, sys, &ws, 0, &mut one);
            }
            one.len()
        };
        let counts: Vec<i32> = self
            .plan
            .recv
            .iter()
            .map(|&n| count_i32(n * width))
            .collect();
        let recv = all_to_all_known(&parts, &counts);
        let mut slot = self.owned;
        for (r, buf) in recv.iter().enumerate() {
            let n = self.plan.recv[r];
            let mut at = 0;
            for _ in 0..n {
                at += get_fields(exchange.fields, sys, &mut ws, slot, &buf[at..]);
                slot += 1;
            }
            debug_assert_eq!(at, buf.len(), "halo message from rank {r}");
        }
        let a = self.account(exchange.before);
        a.seconds += t0.elapsed().as_secs_f64();
        a.bytes += bytes;
        a.calls += 1;
    }
}
