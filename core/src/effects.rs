//! Effects: the physics a scene calls for (DESIGN §5).
//!
//! A run's effect set is resolved once from the scene (materials and options). Each
//! compiled specialisation of a scheme is monomorphised over one effect set `E: Effects`,
//! whose associated constants are compile-time booleans: branches such as
//! `if E::STRENGTH { .. }` are folded away by the compiler, so a hydro-only run contains no
//! strength code at all. [`EffectSet`] is the run-time value of the same set, used to pick
//! the specialisation and to size per-particle storage (absent effects get no storage).

/// A compile-time effect set. Implemented by the marker types that `gsph-macros`
/// generates (see [`crate::dispatch`]); never implemented by hand.
pub trait Effects: Copy + Send + Sync + 'static {
    /// Deviatoric stress (some material has a shear modulus).
    const STRENGTH: bool;
    /// Plastic flow (some material has a finite yield stress). Implies `STRENGTH`.
    const PLASTICITY: bool;
    /// Scalar damage (JH1 ceramic). Implies `PLASTICITY`.
    const DAMAGE: bool;
    /// Temperature and thermal softening (Johnson–Cook). Implies `PLASTICITY`.
    const HEAT: bool;
    /// Kernel gradient correction (Randles–Libersky L matrix, `tkc`).
    const CORRECTION: bool;
    /// MUSCL reconstruction of the Riemann states (`ts2`, `tkc`).
    const MUSCL: bool;
    /// Periodic boundaries along at least one axis.
    const PERIODIC: bool;
    /// Monaghan's artificial stress against the tensile instability (Gray, Monaghan &
    /// Swift 2001), in every scheme's pair forces.
    const ARTIFICIAL_STRESS: bool;
    /// The set as a run-time value.
    const SET: EffectSet;
}

/// A run-time effect set (bit set). The `Display` form is the list of names joined by `+`,
/// or `hydro` for the empty set.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct EffectSet(pub u16);

impl EffectSet {
    /// No effects: hydrodynamics only.
    pub const HYDRO: EffectSet = EffectSet(0);
    /// See [`Effects::STRENGTH`].
    pub const STRENGTH: EffectSet = EffectSet(1 << 0);
    /// See [`Effects::PLASTICITY`].
    pub const PLASTICITY: EffectSet = EffectSet(1 << 1);
    /// See [`Effects::DAMAGE`].
    pub const DAMAGE: EffectSet = EffectSet(1 << 2);
    /// See [`Effects::HEAT`].
    pub const HEAT: EffectSet = EffectSet(1 << 3);
    /// See [`Effects::CORRECTION`].
    pub const CORRECTION: EffectSet = EffectSet(1 << 4);
    /// See [`Effects::MUSCL`].
    pub const MUSCL: EffectSet = EffectSet(1 << 5);
    /// See [`Effects::PERIODIC`].
    pub const PERIODIC: EffectSet = EffectSet(1 << 6);
    /// Moving window (handled by the host driver; no pair-kernel code depends on it).
    pub const MOVING_WINDOW: EffectSet = EffectSet(1 << 7);
    /// See [`Effects::ARTIFICIAL_STRESS`].
    pub const ARTIFICIAL_STRESS: EffectSet = EffectSet(1 << 8);

    /// Every named effect with its bit, in display order.
    pub const NAMED: [(&'static str, EffectSet); 9] = [
        ("strength", Self::STRENGTH),
        ("plasticity", Self::PLASTICITY),
        ("damage", Self::DAMAGE),
        ("heat", Self::HEAT),
        ("correction", Self::CORRECTION),
        ("muscl", Self::MUSCL),
        ("periodic", Self::PERIODIC),
        ("artificial_stress", Self::ARTIFICIAL_STRESS),
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
    /// The effects that select a compiled specialisation (everything but the host-only
    /// moving window).
    #[inline]
    pub const fn kernel_part(self) -> EffectSet {
        self.without(Self::MOVING_WINDOW)
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
