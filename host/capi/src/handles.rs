//! Handles: the simulations live in a process-wide table, and a `gsph_sim *` is a key into
//! it, never a pointer gsph dereferences. So a destroyed, forged or foreign handle is
//! refused rather than read, a handle value is never reused, and a simulation is freed
//! only when no call is inside it:
//! - every call takes the handle's lock without waiting: a call while another is inside
//!   (on another thread) fails with `GSPH_ERR_BUSY`;
//! - `gsph_destroy` removes the handle from the table at once (later calls: "not a live
//!   gsph handle"), asks a `gsph_run`/`gsph_advance` inside to stop after its step, waits
//!   for the call inside to return, then frees the simulation.

use super::GsphSim;
use crate::guard::Failure;
use gsph_rs::api::Simulation;
use std::collections::HashMap;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, LazyLock, Mutex, MutexGuard, TryLockError};

/// One simulation of the table.
pub struct Entry {
    /// `None` once destroyed.
    sim: Mutex<Option<Simulation>>,
    /// Set by `gsph_destroy`: a long call inside stops after its step.
    destroyed: AtomicBool,
}

impl Entry {
    /// True once `gsph_destroy` was called on the handle.
    pub fn destroyed(&self) -> bool {
        self.destroyed.load(Ordering::SeqCst)
    }
}

/// Handle values are multiples of this (so that they look like aligned pointers).
const STRIDE: usize = 16;

static TABLE: LazyLock<Mutex<HashMap<usize, Arc<Entry>>>> =
    LazyLock::new(|| Mutex::new(HashMap::new()));
static NEXT: AtomicUsize = AtomicUsize::new(1);

/// The table, also after a panic elsewhere held its lock (it is never left half-changed).
fn table() -> MutexGuard<'static, HashMap<usize, Arc<Entry>>> {
    TABLE.lock().unwrap_or_else(|e| e.into_inner())
}

/// Adds `sim` to the table; its new handle.
pub fn register(sim: Simulation) -> Result<*mut GsphSim, Failure> {
    let key = NEXT
        .fetch_add(1, Ordering::Relaxed)
        .checked_mul(STRIDE)
        .ok_or_else(|| Failure::internal("sim: handle values exhausted"))?;
    let entry = Entry {
        sim: Mutex::new(Some(sim)),
        destroyed: AtomicBool::new(false),
    };
    table().insert(key, Arc::new(entry));
    Ok(std::ptr::without_provenance_mut(key))
}

/// Runs `f` on the simulation of handle `p`, holding its lock; refused for a null or
/// unknown handle and (`GSPH_ERR_BUSY`) while another call is inside.
pub fn with<T>(
    p: *mut GsphSim,
    f: impl FnOnce(&mut Simulation, &Entry) -> Result<T, Failure>,
) -> Result<T, Failure> {
    if p.is_null() {
        return Err(Failure::pointer("sim: null handle"));
    }
    let entry = table().get(&p.addr()).cloned().ok_or_else(|| {
        Failure::pointer("sim: not a live gsph handle (destroyed, or not from gsph_create_*)")
    })?;
    let mut sim = match entry.sim.try_lock() {
        Ok(g) => g,
        Err(TryLockError::WouldBlock) => {
            return Err(Failure::busy(
                "sim: in use by a call on another thread (one call at a time per handle)",
            ))
        }
        Err(TryLockError::Poisoned(_)) => {
            return Err(Failure::internal(
                "sim: an earlier call on this handle failed with an internal error; destroy it",
            ))
        }
    };
    match sim.as_mut() {
        Some(s) => f(s, &entry),
        None => Err(Failure::pointer(
            "sim: not a live gsph handle (destroyed, or not from gsph_create_*)",
        )),
    }
}

/// Destroys handle `p`: unknown handles (null, destroyed before, foreign) are ignored.
pub fn destroy(p: *mut GsphSim) {
    let Some(entry) = table().remove(&p.addr()) else {
        return;
    };
    entry.destroyed.store(true, Ordering::SeqCst);
    // waits for a call inside (a run stops after its step), then frees
    let mut sim = entry.sim.lock().unwrap_or_else(|e| e.into_inner());
    drop(sim.take());
}
