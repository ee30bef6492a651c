//! The numerical schemes. Each family lives in its own module with the same shape
//! (passes over pairs, then per-particle updates) and implements [`SchemeFamily`]; the
//! driver and the generated dispatch table (`crate::dispatch`) know only the trait.
//!
//! | CLI name | family | effects added by the name | seed |
//! | --- | --- | --- | --- |
//! | `av`  | [`av::Av`] | – | 000 §4 |
//! | `pm`  | [`pm::Pm`] | – | 000 §3.2 |
//! | `tkc` | [`pm::Pm`] | correction + MUSCL (minmod) | 004 §1–2 |
//! | `ts1` | [`ts::Ts`] | – | 000 §3.3–3.4 |
//! | `ts2` | [`ts::Ts`] | MUSCL (limiter selectable) | 000 §3.3.1 |

// Per-particle updates index several structure-of-arrays slices with one index.
#![allow(clippy::needless_range_loop)]

pub mod artificial_stress;
pub mod av;
pub(crate) mod common;
pub(crate) mod leapfrog;
pub mod options;
pub mod pm;
pub mod ts;

use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::halo::{Exchange, Halo};
use crate::state::{Family, Layout, SchemeOptions, StepError, StepParams, System, Workspace};

/// One scheme family: advances the particles by one step of `params.dt`. What the rest
/// of the code needs to know of a family is here, declared by the family's module: the
/// effects it runs with, the exchanges its step makes, the workspace it needs; [`Family`]
/// hands them out at run time.
pub trait SchemeFamily {
    /// The family.
    const FAMILY: Family;
    /// The effects this family can run with (others are rejected before stepping).
    const SUPPORTED: EffectSet;
    /// The halo exchanges a step makes, in order (see [`crate::halo`]).
    const EXCHANGES: &'static [Exchange];
    /// The workspace arrays a step with `effects` and `options` reads and writes.
    fn layout(effects: EffectSet, options: &SchemeOptions) -> Layout;
    /// [`SchemeFamily::step`] after checking the particle and workspace arrays have the
    /// lengths `params.effects` and [`SchemeFamily::layout`] give them (the one storage
    /// check of every family).
    #[inline]
    fn checked_step<const D: usize, E: Effects, X: Executor>(
        sys: &mut System<'_, D>,
        ws: &mut Workspace<'_, D>,
        params: &StepParams<'_, D>,
        exec: &X,
        halo: &mut dyn Halo<D>,
    ) -> Result<(), StepError> {
        sys.check_storage(params.effects)?;
        let layout = Self::layout(params.effects, &params.options);
        ws.check(&layout, sys.len(), params.nbrs.unordered_pairs())?;
        Self::step::<D, E, X>(sys, ws, params, exec, halo)
    }
    /// Advances `sys` by one time step, calling `halo` before each pass that reads a
    /// neighbour field an earlier pass changed (see [`crate::halo`]; serial: [`NoHalo`]).
    ///
    /// [`NoHalo`]: crate::halo::NoHalo
    fn step<const D: usize, E: Effects, X: Executor>(
        sys: &mut System<'_, D>,
        ws: &mut Workspace<'_, D>,
        params: &StepParams<'_, D>,
        exec: &X,
        halo: &mut dyn Halo<D>,
    ) -> Result<(), StepError>;
}

/// A compiled step function (one specialisation).
pub type StepFn<const D: usize, X> = fn(
    &mut System<'_, D>,
    &mut Workspace<'_, D>,
    &StepParams<'_, D>,
    &X,
    &mut dyn Halo<D>,
) -> Result<(), StepError>;

/// The scheme names of the CLI and scenes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Scheme {
    /// Artificial-viscosity SPH.
    Av,
    /// Parshikov–Medin contact SPH (first order).
    Pm,
    /// Time-split Godunov SPH, first order.
    Ts1,
    /// Time-split Godunov SPH with MUSCL.
    Ts2,
    /// TKC-MUSCL-SPH: contact SPH with kernel correction and MUSCL.
    Tkc,
}

impl Scheme {
    /// All schemes, in the order tables list them.
    pub const ALL: [Scheme; 5] = [
        Scheme::Av,
        Scheme::Pm,
        Scheme::Ts1,
        Scheme::Ts2,
        Scheme::Tkc,
    ];

    /// The CLI/scene name.
    pub const fn name(self) -> &'static str {
        match self {
            Scheme::Av => "av",
            Scheme::Pm => "pm",
            Scheme::Ts1 => "ts1",
            Scheme::Ts2 => "ts2",
            Scheme::Tkc => "tkc",
        }
    }
    /// Parses a CLI/scene name.
    pub fn from_name(s: &str) -> Option<Scheme> {
        Scheme::ALL.into_iter().find(|x| x.name() == s)
    }
    /// The family that implements it.
    pub const fn family(self) -> Family {
        match self {
            Scheme::Av => Family::Av,
            Scheme::Pm | Scheme::Tkc => Family::Pm,
            Scheme::Ts1 | Scheme::Ts2 => Family::Ts,
        }
    }
    /// The effects the scheme itself brings (on top of the scene's).
    pub const fn effects(self) -> EffectSet {
        match self {
            Scheme::Av | Scheme::Pm | Scheme::Ts1 => EffectSet::HYDRO,
            Scheme::Ts2 => EffectSet::MUSCL,
            Scheme::Tkc => EffectSet::CORRECTION.union(EffectSet::MUSCL),
        }
    }
}

/// The CLI/scene name.
impl core::fmt::Display for Scheme {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

impl Family {
    /// The effects the family supports ([`SchemeFamily::SUPPORTED`]).
    pub const fn supported(self) -> EffectSet {
        match self {
            Family::Av => av::Av::SUPPORTED,
            Family::Pm => pm::Pm::SUPPORTED,
            Family::Ts => ts::Ts::SUPPORTED,
        }
    }

    /// The exchanges a step of the family makes, in order ([`SchemeFamily::EXCHANGES`]).
    pub const fn exchanges(self) -> &'static [Exchange] {
        match self {
            Family::Av => av::Av::EXCHANGES,
            Family::Pm => pm::Pm::EXCHANGES,
            Family::Ts => ts::Ts::EXCHANGES,
        }
    }

    /// The workspace arrays a step with `effects` and `options` needs
    /// ([`SchemeFamily::layout`]).
    pub fn layout(self, effects: EffectSet, options: &SchemeOptions) -> Layout {
        match self {
            Family::Av => av::Av::layout(effects, options),
            Family::Pm => pm::Pm::layout(effects, options),
            Family::Ts => ts::Ts::layout(effects, options),
        }
    }
}

#[cfg(test)]
mod tests;
