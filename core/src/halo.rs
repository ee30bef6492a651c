//! The step as a fixed sequence of passes with a halo exchange between them.
//!
//! A step of every family is a fixed sequence of passes over the particles (see each
//! scheme's module): *pair passes* read per-particle fields of neighbours, *local passes*
//! read and write only the particle itself. A domain-decomposed caller (the host's MPI
//! build) holds, after its `owned` particles, read-only *ghost* copies of the particles of
//! other ranks that lie within the neighbour-list reach, in the same slices. Every pass
//! runs over owned and ghost particles alike, so the rows of a ghost (which see only part
//! of its neighbourhood) produce values that are not used; what an owned particle reads of
//! a ghost must be an exact copy of what its owner computed. So before each pair pass that
//! reads a neighbour field some earlier pass of the step changed, the step calls
//! [`Halo::refresh`] with that pass's [`Exchange`]: the fields it reads, nothing else. The
//! caller copies those fields from the owners into the ghost slots.
//!
//! A serial caller passes [`NoHalo`] (no ghosts; every call is a no-op). The exchanges of
//! each family are a constant of its step
//! ([`SchemeFamily::EXCHANGES`](crate::schemes::SchemeFamily::EXCHANGES)), handed out at
//! run time by [`Family::exchanges`](crate::schemes::scheme::Family::exchanges), so a caller can print
//! and account for them.

use crate::effects::EffectSet;
use crate::math::Vector;
use crate::state::{Correction, Gradients, Hourglass, System};

/// A set of per-particle fields that neighbours read.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Fields(pub u32);

impl Fields {
    /// Positions.
    pub const X: Fields = Fields(1);
    /// Smoothing lengths.
    pub const H: Fields = Fields(1 << 1);
    /// Velocities.
    pub const V: Fields = Fields(1 << 2);
    /// Densities.
    pub const RHO: Fields = Fields(1 << 3);
    /// Pressures.
    pub const P: Fields = Fields(1 << 4);
    /// Bulk sound speeds.
    pub const C: Fields = Fields(1 << 5);
    /// Longitudinal sound speeds.
    pub const CL: Fields = Fields(1 << 6);
    /// Stress deviators (empty without strength: nothing is sent).
    pub const S: Fields = Fields(1 << 7);
    /// Damage (empty without damage).
    pub const DAMAGE: Fields = Fields(1 << 8);
    /// MUSCL gradients ([`crate::schemes::workspace::Workspace::grad`]).
    pub const GRAD: Fields = Fields(1 << 9);
    /// Stress gradients ([`crate::schemes::workspace::Workspace::grad_stress`]).
    pub const GRAD_STRESS: Fields = Fields(1 << 10);
    /// Kernel corrections ([`crate::schemes::workspace::Workspace::corr`]).
    pub const CORR: Fields = Fields(1 << 11);
    /// Hourglass records ([`crate::schemes::workspace::Workspace::hg`]).
    pub const HOURGLASS: Fields = Fields(1 << 12);
    /// The state a stress-based pair pass reads at the start of a step: geometry (x, h)
    /// and the Cauchy stress, velocity and wave speed of the other side (`av`'s rates,
    /// `pm`/`tkc`'s correction, gradients and Riemann problems).
    pub const STRESS_STATE: Fields = Fields(
        Fields::X.0
            | Fields::H.0
            | Fields::V.0
            | Fields::RHO.0
            | Fields::P.0
            | Fields::CL.0
            | Fields::S.0
            | Fields::DAMAGE.0,
    );
    /// Every field, in the order [`Fields::names`] gives.
    pub const ALL: [(Fields, &'static str); 13] = [
        (Fields::X, "x"),
        (Fields::H, "h"),
        (Fields::V, "v"),
        (Fields::RHO, "rho"),
        (Fields::P, "p"),
        (Fields::C, "c"),
        (Fields::CL, "cl"),
        (Fields::S, "s"),
        (Fields::DAMAGE, "damage"),
        (Fields::GRAD, "grad"),
        (Fields::GRAD_STRESS, "grad_stress"),
        (Fields::CORR, "corr"),
        (Fields::HOURGLASS, "hourglass"),
    ];

    /// The union.
    pub const fn with(self, o: Fields) -> Fields {
        Fields(self.0 | o.0)
    }
    /// True if every field of `o` is in `self`.
    pub const fn contains(self, o: Fields) -> bool {
        self.0 & o.0 == o.0
    }
    /// True if no field is set.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }
    /// The names of the fields, in a fixed order.
    pub fn names(self) -> impl Iterator<Item = &'static str> {
        Fields::ALL
            .into_iter()
            .filter(move |(f, _)| self.contains(*f))
            .map(|(_, n)| n)
    }
}

/// One halo exchange of a step: before the pass `before`, ghosts need fresh `fields`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Exchange {
    /// The pass that follows (for accounting: time and bytes per pass).
    pub before: &'static str,
    /// The neighbour fields it reads that changed since the previous exchange.
    pub fields: Fields,
    /// Only with these effects (all of them); `EffectSet::HYDRO`: always.
    pub needs: EffectSet,
    /// Only with at least one of these effects; `EffectSet::HYDRO`: always.
    pub needs_any: EffectSet,
}

impl Exchange {
    /// True when the step of a family with `effects` makes this exchange.
    pub const fn applies(&self, effects: EffectSet) -> bool {
        effects.contains(self.needs) && (self.needs_any.0 == 0 || self.needs_any.0 & effects.0 != 0)
    }
}

/// The workspace arrays that pair passes read from neighbours (the rest of the workspace
/// is per pair or only read for the particle itself).
#[derive(Debug)]
pub struct GhostWorkspace<'a, const D: usize> {
    /// MUSCL gradients (empty without MUSCL).
    pub grad: &'a mut [Gradients<D>],
    /// Stress gradients (empty unless `tkc` with strength).
    pub grad_stress: &'a mut [[Vector<D>; 6]],
    /// Kernel corrections (empty without correction).
    pub corr: &'a mut [Correction<D>],
    /// Hourglass records (empty without the hourglass stiffness).
    pub hg: &'a mut [Hourglass<D>],
}

/// The caller's hook between passes (module docs).
pub trait Halo<const D: usize> {
    /// Makes `exchange.fields` of every ghost an exact copy of its owner's.
    fn refresh(&mut self, exchange: &Exchange, sys: &mut System<'_, D>, ws: GhostWorkspace<'_, D>);
}

/// No ghosts: the serial step.
#[derive(Clone, Copy, Debug, Default)]
pub struct NoHalo;

impl<const D: usize> Halo<D> for NoHalo {
    #[inline(always)]
    fn refresh(&mut self, _: &Exchange, _: &mut System<'_, D>, _: GhostWorkspace<'_, D>) {}
}
