//! The whole evolving state of a [`Sim`] as checkpoint bytes, and back.
//!
//! Saved: ids, every per-particle array (effect storage included), the scheme workspace
//! (pair sums, MUSCL and stress gradients, kernel corrections, the `av` leap-frog rates
//! and the `primed` flag), the positions and smoothing lengths the neighbour lists were
//! built at (the lists are rebuilt from them on restore, without renumbering, so the
//! rebuild schedule and the particle order continue unchanged), time, step and counters. Not saved: what the scene determines (materials, kernel,
//! options, effects, the step function, driven particles), which a restart rebuilds from
//! the scene text stored in the checkpoint.
//!
//! Of the workspace, only `av` and `primed` carry information from one step to the next
//! (`av` steps reuse the rates of the end of the previous step); the other arrays are
//! recomputed before they are read in every step. They are saved anyway: the cost is small
//! and a restart then does not depend on that property of the schemes.

use super::values::{first_outside, Range, Values};
use super::Sim;
use crate::codec::{Codec, Dec, DecodeError, Enc};
use crate::words::Words;
use gsph_core::effects::EffectSet;

/// Most steps a checkpoint may claim (2^53: counted exactly in an f64 too); a forged
/// `u64::MAX` would overflow on the next step.
pub const MAX_STEP: u64 = 1 << 53;

/// The names of the per-particle fields in the order a checkpoint stores them.
fn field_names() -> String {
    gsph_core::particles::FIELD_NAMES.join(",")
}

impl<const D: usize> Sim<D> {
    /// Appends the state to `e`.
    pub fn save_checkpoint(&self, e: &mut Enc) {
        // owned particles only: a restart recreates the wall mirrors from them
        if !self.mirrors.map.is_empty() {
            let mut owned = self.clone();
            owned.drop_mirrors();
            return owned.save_checkpoint(e);
        }
        e.put(&self.t);
        e.put(&self.step);
        e.put(&self.pair_interactions);
        e.put(&self.rebuilds);
        e.put(&self.reference_updates);
        e.put(&self.primed);
        e.put(&(self.capacity as u64));
        e.put(&self.ids);
        // the particle state in the order of the core's table (gsph_core::particle_fields!),
        // after the table's field names: a checkpoint of another table is refused by name
        e.put(&field_names());
        fn put<T: Codec>(v: &Vec<T>, e: &mut Enc) {
            e.put(v);
        }
        gsph_core::particle_fields!(each_state_field { ref self, put, e });
        e.put(&self.sums);
        e.put(&self.grad);
        e.put(&self.grad_stress);
        e.put(&self.corr);
        e.put(&self.av);
        e.put(&self.build_x);
        e.put(&self.build_h);
        e.put(&self.mirrors.crossings);
        e.put(&self.mirrors.friction_work);
    }

    /// Replaces the state of this simulation (built from the same scene) with the state
    /// read from `d`. Every array must have the length the scene gives it (the workspace
    /// arrays may also be empty or full where the scheme fills them on its first step) and
    /// ids must be unique; on error `self` is left unusable.
    pub fn restore_checkpoint(&mut self, d: &mut Dec<'_>) -> Result<(), DecodeError> {
        self.drop_mirrors();
        let n = self.len();
        self.t = d.get()?;
        self.step = d.get()?;
        self.pair_interactions = d.get()?;
        self.rebuilds = d.get()?;
        self.reference_updates = d.get()?;
        self.primed = d.get()?;
        let capacity: u64 = d.get()?;
        if capacity != self.capacity as u64 {
            return Err(DecodeError(format!(
                "neighbour capacity {capacity}, the scene gives {}",
                self.capacity
            )));
        }
        // `exact`: the length the scene gives (n or 0); `free`: n or 0 either way
        fn field<T: Codec>(
            d: &mut Dec<'_>,
            name: &str,
            have: &mut Vec<T>,
            n: usize,
            exact: bool,
        ) -> Result<(), DecodeError> {
            let v: Vec<T> = d.get()?;
            let ok = if exact {
                v.len() == have.len()
            } else {
                v.is_empty() || v.len() == n
            };
            if !ok {
                return Err(DecodeError(format!(
                    "`{name}` holds {} values for {n} particles",
                    v.len()
                )));
            }
            *have = v;
            Ok(())
        }
        field(d, "ids", &mut self.ids, n, true)?;
        let names: String = d.get()?;
        if names != field_names() {
            return Err(DecodeError(format!(
                "particle fields `{names}`, this gsph has `{}`",
                field_names()
            )));
        }
        // the particle state: stored exactly as the scene sizes it
        fn state<T: Codec>(
            name: &str,
            have: &mut Vec<T>,
            (d, n): (&mut Dec<'_>, usize),
        ) -> Result<(), DecodeError> {
            field(d, name, have, n, true)
        }
        gsph_core::particle_fields!(each_state_field { named self, state, (&mut *d, n) });
        field(d, "sums", &mut self.sums, n, false)?;
        field(d, "grad", &mut self.grad, n, false)?;
        field(d, "grad_stress", &mut self.grad_stress, n, false)?;
        field(d, "corr", &mut self.corr, n, false)?;
        field(d, "av", &mut self.av, n, false)?;
        field(d, "build_x", &mut self.build_x, n, true)?;
        field(d, "build_h", &mut self.build_h, n, true)?;
        self.mirrors.crossings = d.get()?;
        self.mirrors.friction_work = d.get()?;
        let mut ids = self.ids.clone();
        ids.sort_unstable();
        if ids.windows(2).any(|w| w[0] == w[1]) {
            return Err(DecodeError("two particles have the same id".into()));
        }
        if self.materials.len() <= self.mat.iter().copied().max().unwrap_or(0) as usize {
            return Err(DecodeError("a material index names no material".into()));
        }
        // a checksum proves the bytes are as written, not that they were written by gsph:
        // the decoded values must be a state a run can reach
        if !(self.t.is_finite() && self.t >= 0.0) {
            return Err(DecodeError(format!("time t = {:e} s", self.t)));
        }
        if (self.step == 0) != (self.t == 0.0) || self.step > MAX_STEP {
            return Err(DecodeError(format!(
                "step {} at t = {:e} s",
                self.step, self.t
            )));
        }
        // before anything is built from them (the lists from `build_x`, `build_h`)
        self.check_values()?;
        if !self.build_x.is_empty() {
            self.owned = self.len();
            self.add_mirrors()
                .map_err(|e| DecodeError(format!("walls: {e}")))?;
            self.build_lists()
                .map_err(|e| DecodeError(format!("neighbour lists: {e}")))?;
        }
        Ok(())
    }

    /// The first particle whose value in `v` (a field stored with `effect`) lies outside
    /// `range` where the particle's material calls for `effect`, or is not finite where it
    /// does not (a steel particle's temperature, 0 K, in a run where another material heats).
    pub(super) fn outside<T: Values>(
        &self,
        v: &[T],
        range: Range,
        effect: EffectSet,
    ) -> Option<(usize, f64, &'static str)> {
        let acts: Vec<bool> = (self.materials.iter())
            .map(|m| super::material_effects(m).contains(effect))
            .collect();
        let mat = &self.mat;
        first_outside(v, |i| match acts.get(mat[i] as usize) {
            Some(true) => range,
            _ => Range::Any,
        })
    }

    /// Every value of the particle state within the range the core's table gives its field
    /// (`api(…, range)`: finite everywhere, positive masses, densities and smoothing
    /// lengths, damage in [0, 1], …: derived from the table, so a field added later is
    /// checked too), every value of the workspace finite, and the smoothing lengths the
    /// lists were built with positive.
    fn check_values(&self) -> Result<(), DecodeError> {
        let ids = &self.ids;
        let state = |name: &str, bad: Option<(usize, f64, &str)>| match bad {
            Some((i, y, why)) => Err(DecodeError(format!(
                "particle {}: `{name}` {why} (got {y:e})",
                ids[i]
            ))),
            None => Ok(()),
        };
        gsph_core::particle_fields!(each_state_field { ranged self, state });
        fn finite<T: Words>(name: &str, v: &[T], ids: &[u32]) -> Result<(), DecodeError> {
            let mut w = Vec::with_capacity(T::words());
            for (i, x) in v.iter().enumerate() {
                w.clear();
                x.put_words(&mut w);
                if let Some(y) = w.iter().find(|y| !y.is_finite()) {
                    return Err(DecodeError(format!(
                        "particle {}: the workspace's `{name}` holds {y}",
                        ids.get(i).copied().unwrap_or(u32::MAX)
                    )));
                }
            }
            Ok(())
        }
        finite("sums", &self.sums, ids)?;
        finite("grad", &self.grad, ids)?;
        finite("grad_stress", &self.grad_stress, ids)?;
        finite("corr", &self.corr, ids)?;
        finite("av", &self.av, ids)?;
        state("build_x", first_outside(&self.build_x, |_| Range::Any))?;
        state("build_h", first_outside(&self.build_h, |_| Range::Positive))?;
        match Range::Nonnegative.refuses(self.mirrors.friction_work) {
            Some(why) => Err(DecodeError(format!(
                "the walls' friction work {why} (got {:e} J)",
                self.mirrors.friction_work
            ))),
            None => Ok(()),
        }
    }
}
