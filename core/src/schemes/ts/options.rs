//! The `[options]` keys `ts1` and `ts2` read ([`crate::schemes::options`]).

use crate::effects::EffectSet;
use crate::schemes::options::{read_if, why, NotRead, OptionKey};
use crate::schemes::scheme::Scheme;

/// Whether a scheme of the time-split family (`ts1`, `ts2`) reads `key`, or why not
/// ([`crate::schemes::options`]).
pub(crate) fn reads(scheme: Scheme, key: OptionKey) -> Result<(), NotRead> {
    use OptionKey::*;
    let muscl = scheme.effects().contains(EffectSet::MUSCL);
    match key {
        AvAlpha | AvBeta => read_if(false, scheme, why::AV_ONLY),
        TransverseDissipation | Objective => read_if(false, scheme, why::NO_TRANSVERSE),
        Limiter => read_if(muscl, scheme, why::NO_MUSCL),
        MusclTime => read_if(muscl, scheme, why::NO_MUSCL_TIME),
        CorrectedSlopes => read_if(false, scheme, why::NO_CORRECTED_SLOPES),
        SurfaceScan => read_if(false, scheme, why::NO_SCAN),
        SpecificVolume => read_if(false, scheme, why::NO_SPECIFIC_VOLUME),
        Integrator
        | Riemann
        | Dissipation
        | SurfaceLambda
        | DetEpsilon
        | ArtificialStress
        | ArtificialStressExponent => Ok(()),
        Correction | Muscl => Err(NotRead::OnlyPm { scheme }),
    }
}
