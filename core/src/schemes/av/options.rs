//! The `[options]` keys `av` reads ([`crate::schemes::options`]).

use crate::schemes::options::{read_if, why, NotRead, OptionKey};
use crate::schemes::scheme::Scheme;

/// Whether scheme `av` reads `key`, or why not ([`crate::schemes::options`]).
pub(crate) fn reads(scheme: Scheme, key: OptionKey) -> Result<(), NotRead> {
    use OptionKey::*;
    match key {
        AvAlpha | AvBeta | ArtificialStress | ArtificialStressExponent => Ok(()),
        Limiter => read_if(false, scheme, why::NO_MUSCL),
        Riemann | Dissipation | TransverseDissipation | Objective => {
            read_if(false, scheme, why::NO_RIEMANN)
        }
        MusclTime => read_if(false, scheme, why::NO_MUSCL_TIME),
        CorrectedSlopes => read_if(false, scheme, why::NO_CORRECTED_SLOPES),
        Integrator => read_if(false, scheme, why::OWN_INTEGRATOR),
        SpecificVolume => read_if(false, scheme, why::NO_SPECIFIC_VOLUME),
        SurfaceLambda | SurfaceScan | DetEpsilon => read_if(false, scheme, why::NO_SURFACE),
        Correction | Muscl => Err(NotRead::OnlyPm { scheme }),
    }
}
