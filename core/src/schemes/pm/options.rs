//! The `[options]` keys `pm` and `tkc` read and the options they start from
//! ([`crate::schemes::options`]).

use crate::effects::EffectSet;
use crate::limiter::Limiter;
use crate::schemes::options::SchemeOptions;
use crate::schemes::options::{read_if, why, NotRead, OptionKey};
use crate::schemes::scheme::Scheme;

/// Whether a scheme of the contact family (`pm`, `tkc`) reads `key` with `effects` (its
/// own and those the scene's `correction` and `muscl` ask for), or why not
/// ([`crate::schemes::options`]).
pub(crate) fn reads(scheme: Scheme, key: OptionKey, effects: EffectSet) -> Result<(), NotRead> {
    use OptionKey::*;
    match key {
        AvAlpha | AvBeta => read_if(false, scheme, why::AV_ONLY),
        Limiter => read_if(effects.contains(EffectSet::MUSCL), scheme, why::NO_MUSCL),
        Riemann
        | Dissipation
        | TransverseDissipation
        | Objective
        | SpecificVolume
        | ArtificialStress
        | ArtificialStressExponent => Ok(()),
        MusclTime => read_if(false, scheme, why::NO_MUSCL_TIME),
        Integrator => read_if(
            effects.contains(EffectSet::MUSCL),
            scheme,
            why::FIRST_ORDER_EULER,
        ),
        CorrectedSlopes => read_if(
            effects.contains(EffectSet::CORRECTION) && effects.contains(EffectSet::MUSCL),
            scheme,
            why::NO_CORRECTED_SLOPES,
        ),
        SurfaceLambda | SurfaceScan | DetEpsilon => read_if(
            effects.contains(EffectSet::CORRECTION),
            scheme,
            why::NO_SURFACE,
        ),
        Correction if scheme == Scheme::Tkc => Err(NotRead::Always { what: "correction" }),
        Muscl if scheme == Scheme::Tkc => Err(NotRead::Always { what: "MUSCL" }),
        Correction | Muscl => Ok(()),
    }
}

/// The options a scheme of the contact family starts from: `tkc` limits with minmod
/// (Rublev & Murzov), `pm` with MUSCL keeps the seeds' superbee.
pub(crate) fn defaults(scheme: Scheme) -> SchemeOptions {
    let mut o = SchemeOptions::default();
    if scheme == Scheme::Tkc {
        o.limiter = Limiter::Minmod;
    }
    o
}
