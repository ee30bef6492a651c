//! What a scheme family is to the rest of the code ([`SchemeFamily`]): its effects, its
//! exchanges, its workspace and its step. Each family's module implements it; the
//! dispatch by [`Family`] at run time is in [`super`].

use super::options::SchemeOptions;
use super::scheme::Family;
use super::workspace::{Layout, StepParams, Workspace};
use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::halo::{Exchange, Halo};
use crate::state::{StepError, System};

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
