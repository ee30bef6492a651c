//! Effects: the physics a scene calls for (DESIGN §5).
//!
//! A run's effect set is resolved once from the scene (materials and options). Two kinds:
//!
//! - **Compiled** ([`EffectSet::COMPILED`]: strength, kernel correction, MUSCL) change the
//!   arithmetic of every pair, the passes a step makes and what it reads of neighbours.
//!   Each compiled specialisation of a scheme is monomorphised over one such set
//!   `E: Effects`, whose associated constants are compile-time booleans: branches such as
//!   `if E::STRENGTH { .. }` are folded away, so a hydro-only run contains no strength code.
//! - **Run-time** (plasticity, damage, heat, periodic boundaries, artificial stress,
//!   hourglass stiffness) act per
//!   particle or as one predictable term of a pair; the step reads them as flags where it
//!   needs them: periodic boundaries and artificial stress from
//!   [`crate::schemes::workspace::StepParams::effects`], plasticity, damage and heat from the storage
//!   their fields have (a run without an effect stores nothing for it:
//!   [`crate::state::System::has_plasticity`] and siblings). `cargo bench -p gsph --bench
//!   effects` measures what each flag costs when it is off.
//!
//! [`EffectSet`] is the run-time value of a set: the whole set sizes the per-particle
//! storage (absent effects get none) and reaches the step in its parameters; its
//! [`EffectSet::kernel_part`] picks the specialisation.

/// A compile-time effect set. Implemented by the marker types that `gsph-macros`
/// generates (see [`crate::dispatch`]); never implemented by hand.
pub trait Effects: Copy + Send + Sync + 'static {
    /// Deviatoric stress (some material has a shear modulus).
    const STRENGTH: bool;
    /// Kernel gradient correction (Randles–Libersky L matrix, `tkc`).
    const CORRECTION: bool;
    /// MUSCL reconstruction of the Riemann states (`ts2`, `tkc`).
    const MUSCL: bool;
    /// The set as a run-time value (compiled effects only).
    const SET: EffectSet;
    /// The run-time effects whose flags this instantiation reads; the others are compiled
    /// out (always off). Every step of the dispatch table reads all of them
    /// ([`EffectSet::RUNTIME`]); the effects benchmark instantiates steps without some, to
    /// measure what reading a flag costs when it is off.
    const RUNTIME: EffectSet = EffectSet::RUNTIME;
}

/// A run-time effect set (bit set). The `Display` form is the list of names joined by `+`,
/// or `hydro` for the empty set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EffectSet(pub u16);

impl EffectSet {
    /// No effects: hydrodynamics only.
    pub const HYDRO: EffectSet = EffectSet(0);
    /// Deviatoric stress (some material has a shear modulus); compiled.
    pub const STRENGTH: EffectSet = EffectSet(1 << 0);
    /// Plastic flow (some material has a finite yield stress); implies strength.
    pub const PLASTICITY: EffectSet = EffectSet(1 << 1);
    /// Scalar damage (JH1 ceramic); implies plasticity.
    pub const DAMAGE: EffectSet = EffectSet(1 << 2);
    /// Temperature and thermal softening (Johnson–Cook); implies plasticity.
    pub const HEAT: EffectSet = EffectSet(1 << 3);
    /// Kernel gradient correction (`tkc`); compiled.
    pub const CORRECTION: EffectSet = EffectSet(1 << 4);
    /// MUSCL reconstruction (`ts2`, `tkc`); compiled.
    pub const MUSCL: EffectSet = EffectSet(1 << 5);
    /// Periodic boundaries along at least one axis.
    pub const PERIODIC: EffectSet = EffectSet(1 << 6);
    /// Moving window (handled by the host driver; no pair-kernel code depends on it).
    pub const MOVING_WINDOW: EffectSet = EffectSet(1 << 7);
    /// Monaghan's artificial stress against the tensile instability (Gray, Monaghan &
    /// Swift 2001), in every scheme's pair forces.
    pub const ARTIFICIAL_STRESS: EffectSet = EffectSet(1 << 8);
    /// The hourglass stiffness of solids (`crate::schemes::hourglass`): a stored,
    /// non-dissipative restoring force on each particle's displacement away from the
    /// affine motion of its neighbours (only with strength; a scene without is refused).
    pub const HOURGLASS: EffectSet = EffectSet(1 << 9);
    /// The reference configuration of the total-Lagrangian scheme `tl` (brought by the
    /// scheme, like `tkc`'s correction): each particle's reference position and volume,
    /// where its kernel, neighbours and gradient correction stay fixed, and the energy its
    /// hourglass stiffness stores (`crate::schemes::tl`).
    pub const REFERENCE: EffectSet = EffectSet(1 << 10);
    /// The run-time effects: flags of every step ([`Effects::RUNTIME`]).
    pub const RUNTIME: EffectSet = EffectSet(
        Self::PLASTICITY.0
            | Self::DAMAGE.0
            | Self::HEAT.0
            | Self::PERIODIC.0
            | Self::ARTIFICIAL_STRESS.0
            | Self::HOURGLASS.0,
    );
    /// The effects compiled into a specialisation (the rest are run-time flags).
    pub const COMPILED: EffectSet =
        EffectSet(Self::STRENGTH.0 | Self::CORRECTION.0 | Self::MUSCL.0);

    /// Every named effect with its bit, in display order.
    pub const NAMED: [(&'static str, EffectSet); 11] = [
        ("strength", Self::STRENGTH),
        ("plasticity", Self::PLASTICITY),
        ("damage", Self::DAMAGE),
        ("heat", Self::HEAT),
        ("correction", Self::CORRECTION),
        ("muscl", Self::MUSCL),
        ("periodic", Self::PERIODIC),
        ("artificial_stress", Self::ARTIFICIAL_STRESS),
        ("hourglass", Self::HOURGLASS),
        ("reference", Self::REFERENCE),
        ("moving_window", Self::MOVING_WINDOW),
    ];

    /// Union.
    #[inline]
    pub const fn union(self, o: EffectSet) -> EffectSet {
        EffectSet(self.0 | o.0)
    }
    /// Set difference.
    #[inline]
    pub const fn without(self, o: EffectSet) -> EffectSet {
        EffectSet(self.0 & !o.0)
    }
    /// True if every effect of `o` is in `self`.
    #[inline]
    pub const fn contains(self, o: EffectSet) -> bool {
        self.0 & o.0 == o.0
    }
    /// The effects that select a compiled specialisation ([`Self::COMPILED`]).
    #[inline]
    pub const fn kernel_part(self) -> EffectSet {
        EffectSet(self.0 & Self::COMPILED.0)
    }
    /// Adds the effects implied by the ones present (plasticity needs strength, damage and
    /// heat need plasticity).
    pub const fn closed(self) -> EffectSet {
        let mut s = self;
        if s.contains(Self::DAMAGE) || s.contains(Self::HEAT) {
            s = s.union(Self::PLASTICITY);
        }
        if s.contains(Self::PLASTICITY) {
            s = s.union(Self::STRENGTH);
        }
        s
    }
    /// Looks an effect up by name.
    pub fn from_name(name: &str) -> Option<EffectSet> {
        Self::NAMED
            .iter()
            .find(|(n, _)| *n == name)
            .map(|(_, e)| *e)
    }
    /// Iterates over the names of the effects present.
    pub fn names(self) -> impl Iterator<Item = &'static str> {
        Self::NAMED
            .into_iter()
            .filter(move |(_, e)| self.contains(*e))
            .map(|(n, _)| n)
    }
}

impl core::fmt::Display for EffectSet {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        if self.0 == 0 {
            return f.write_str("hydro");
        }
        let mut first = true;
        for n in self.names() {
            if !first {
                f.write_str("+")?;
            }
            f.write_str(n)?;
            first = false;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closure_adds_implied_effects() {
        let s = EffectSet::DAMAGE.closed();
        assert!(s.contains(EffectSet::PLASTICITY) && s.contains(EffectSet::STRENGTH));
        assert_eq!(EffectSet::HYDRO.closed(), EffectSet::HYDRO);
    }

    #[test]
    fn names_round_trip() {
        for (n, e) in EffectSet::NAMED {
            assert_eq!(EffectSet::from_name(n), Some(e));
        }
        assert_eq!(EffectSet::from_name("magic"), None);
    }
}
