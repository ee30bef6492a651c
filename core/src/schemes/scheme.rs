//! The names a scene and the command line choose a scheme by ([`Scheme`]) and the
//! families that implement them ([`Family`]): plain names, below every scheme's code, so
//! that the options table, the messages and the families can all name them.

use crate::effects::EffectSet;

/// Scheme families. `tkc` is the `pm` family with correction and MUSCL; `ts2` is `ts`
/// with MUSCL.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    /// Standard SPH with Monaghan artificial viscosity, leap-frog.
    Av,
    /// Contact (Parshikov–Medin) Godunov SPH: full stress Riemann problem per pair.
    Pm,
    /// Time-split Godunov SPH: deviatoric step, then hydrodynamic Riemann step.
    Ts,
    /// Total-Lagrangian Godunov SPH: kernel, neighbours and correction fixed in the
    /// reference configuration; momentum and deformation gradient from pair fluxes.
    Tl,
}

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
    /// Total-Lagrangian Godunov SPH for solids.
    Tl,
}

impl Scheme {
    /// All schemes, in the order tables list them.
    pub const ALL: [Scheme; 6] = [
        Scheme::Av,
        Scheme::Pm,
        Scheme::Ts1,
        Scheme::Ts2,
        Scheme::Tkc,
        Scheme::Tl,
    ];

    /// The CLI/scene name.
    pub const fn name(self) -> &'static str {
        match self {
            Scheme::Av => "av",
            Scheme::Pm => "pm",
            Scheme::Ts1 => "ts1",
            Scheme::Ts2 => "ts2",
            Scheme::Tkc => "tkc",
            Scheme::Tl => "tl",
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
            Scheme::Tl => Family::Tl,
        }
    }
    /// The effects the scheme itself brings (on top of the scene's).
    pub const fn effects(self) -> EffectSet {
        match self {
            Scheme::Av | Scheme::Pm | Scheme::Ts1 => EffectSet::HYDRO,
            Scheme::Ts2 => EffectSet::MUSCL,
            Scheme::Tkc => EffectSet::CORRECTION.union(EffectSet::MUSCL),
            Scheme::Tl => EffectSet::REFERENCE,
        }
    }
}

/// The CLI/scene name.
impl core::fmt::Display for Scheme {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}
