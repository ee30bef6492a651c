//! What a step needs besides the particles: its parameters ([`StepParams`]) and the
//! caller's per-step scratch ([`Workspace`]), with which arrays a family and effect set
//! need ([`Layout`]) and the length of the neighbour records ([`record_len`]). On the
//! schemes' side of the core: the particles ([`crate::state`]) know nothing of schemes.

use super::av::records::AvRates;
use super::options::SchemeOptions;
use super::pm::records::PmStar;
use super::scheme::Family;
use super::ts::records::TsStar;
use crate::effects::{EffectSet, Effects};
use crate::kernel::Kernel;
use crate::material::Material;
use crate::math::{Matrix, Real, Vector};
use crate::neighbors::{Neighbors, Periodic};
use crate::state::{Aux, Correction, Gradients, Hourglass, PairGeom, PairSums, StepError};

/// The reals per particle of [`Workspace::rec`] for a family in `d` dimensions.
pub const fn record_len(family: Family, d: usize) -> usize {
    match family {
        Family::Av => super::av::records::record_len(d),
        Family::Ts => super::ts::records::record_len(d),
        Family::Pm => super::pm::records::record_len(d),
        // no vectorised loops
        Family::Tl => 0,
    }
}

/// Per-step scratch and scheme state owned by the caller. Arrays a family or effect set
/// does not use are empty (see [`Layout`]).
#[derive(Debug)]
pub struct Workspace<'a, const D: usize> {
    /// Pair sums (all schemes).
    pub sums: &'a mut [PairSums<D>],
    /// MUSCL gradients.
    pub grad: &'a mut [Gradients<D>],
    /// Gradients of the stress components in Voigt order (`tkc` with strength; only those
    /// the pairs read: in 2D xx, yy and xy, the others zero).
    pub grad_stress: &'a mut [[Vector<D>; 6]],
    /// Kernel correction.
    pub corr: &'a mut [Correction<D>],
    /// Hourglass records (effect `hourglass`).
    pub hg: &'a mut [Hourglass<D>],
    /// Leap-frog rates (`av`); persistent between steps.
    pub av: &'a mut [AvRates<D>],
    /// Artificial stress tensors `R_i` (effect `artificial_stress`).
    pub art: &'a mut [Matrix<D>],
    /// Neighbour records of the vectorised pair loops (`crate::simd`; every family),
    /// [`record_len`]`(family, D)` reals per particle: what each particle gives its
    /// neighbours' pairs, in one place. Scratch, written by the step where a vectorised
    /// loop reads it; optional: empty (or another length), the portable loops run.
    pub rec: &'a mut [Real],
    /// Pair geometry (all schemes), one per unordered pair of the lists.
    pub geom: &'a mut [PairGeom<D>],
    /// The artificial stress factor `f_ij^n` of each pair (effect `artificial_stress`).
    pub fac: &'a mut [Real],
    /// Per-particle quantities the pair loops read from neighbours (all schemes).
    pub aux: &'a mut [Aux],
    /// Star states of the pairs (`ts` family), one per unordered pair of the lists.
    pub ts_star: &'a mut [TsStar],
    /// Star states of the pairs (`pm` family), one per unordered pair of the lists.
    pub pm_star: &'a mut [PmStar<D>],
    /// True once `av` holds the rates of the current state (set by the first `av` step).
    pub primed: bool,
}

/// Which workspace arrays a family and effect set need.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    /// [`Workspace::grad`].
    pub grad: bool,
    /// [`Workspace::grad_stress`].
    pub grad_stress: bool,
    /// [`Workspace::corr`].
    pub corr: bool,
    /// [`Workspace::hg`].
    pub hg: bool,
    /// [`Workspace::av`].
    pub av: bool,
    /// [`Workspace::geom`] (one per unordered pair), and [`Workspace::fac`] with `art`: the
    /// pair geometry stored by the geometry pass. `av` computes it in its one pair loop
    /// instead.
    pub geom: bool,
    /// [`Workspace::art`], and [`Workspace::fac`] (one per unordered pair) with `geom`.
    pub art: bool,
    /// [`Workspace::ts_star`] (one record per unordered pair).
    pub ts_star: bool,
    /// [`Workspace::pm_star`] (one record per unordered pair).
    pub pm_star: bool,
}

impl Layout {
    /// The arrays the effects ask for whatever the family: MUSCL gradients, kernel
    /// corrections, artificial stress; a family's [`layout`](crate::schemes::SchemeFamily::layout)
    /// adds its own.
    pub const fn base(effects: EffectSet) -> Layout {
        Layout {
            grad: effects.contains(EffectSet::MUSCL),
            grad_stress: false,
            corr: effects.contains(EffectSet::CORRECTION),
            hg: effects.contains(EffectSet::HOURGLASS),
            av: false,
            geom: true,
            art: effects.contains(EffectSet::ARTIFICIAL_STRESS),
            ts_star: false,
            pm_star: false,
        }
    }
}

impl<const D: usize> Workspace<'_, D> {
    /// Checks that the arrays `layout` asks for have their lengths: one per particle (`n`)
    /// or per unordered pair (`pairs`); the sums, geometry and `aux` every step uses.
    /// Arrays the layout does not ask for are not read and not checked.
    pub fn check(&self, layout: &Layout, n: usize, pairs: usize) -> Result<(), StepError> {
        let wrong = [
            ("sums", true, self.sums.len(), n),
            ("aux", true, self.aux.len(), n),
            ("geom", layout.geom, self.geom.len(), pairs),
            ("grad", layout.grad, self.grad.len(), n),
            ("grad_stress", layout.grad_stress, self.grad_stress.len(), n),
            ("corr", layout.corr, self.corr.len(), n),
            ("hg", layout.hg, self.hg.len(), n),
            ("av", layout.av, self.av.len(), n),
            ("art", layout.art, self.art.len(), n),
            ("fac", layout.art && layout.geom, self.fac.len(), pairs),
            ("ts_star", layout.ts_star, self.ts_star.len(), pairs),
            ("pm_star", layout.pm_star, self.pm_star.len(), pairs),
        ]
        .into_iter()
        .find(|&(_, needed, len, want)| needed && len != want);
        match wrong {
            Some((field, ..)) => Err(StepError::Storage { field }),
            None => Ok(()),
        }
    }
}

/// Everything a step needs besides the particles.
#[derive(Clone, Copy, Debug)]
pub struct StepParams<'a, const D: usize> {
    /// Time step, s.
    pub dt: Real,
    /// Materials, indexed by [`System::mat`](crate::state::System::mat).
    pub materials: &'a [Material],
    /// Smoothing kernel.
    pub kernel: Kernel,
    /// `h = h_factor (m/rho)^(1/D)`.
    pub h_factor: Real,
    /// Periodic boundaries.
    pub periodic: Periodic<D>,
    /// Neighbour lists (sorted; see [`crate::neighbors`]).
    pub nbrs: Neighbors<'a>,
    /// Scheme options.
    pub options: SchemeOptions,
    /// The run's whole effect set (closed). The step is compiled for its
    /// [`EffectSet::kernel_part`]; it reads the run-time effects periodic and
    /// artificial stress from here ([`Self::has`]), and plasticity, damage and heat from
    /// their storage ([`System::has_plasticity`](crate::state::System::has_plasticity) …), which the caller sizes by this set.
    pub effects: EffectSet,
    /// The instruction-set level of the vectorised loops ([`crate::simd`]; results are
    /// bitwise the same at every level).
    pub simd: crate::simd::SimdLevel,
}

impl<const D: usize> StepParams<'_, D> {
    /// True if the run has every effect of `e`: a run-time flag of a step of `E` (false
    /// where `E` compiles the flag out, [`Effects::RUNTIME`]).
    #[inline(always)]
    pub fn has<E: Effects>(&self, e: EffectSet) -> bool {
        E::RUNTIME.contains(e) && self.effects.contains(e)
    }
}
