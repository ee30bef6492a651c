//! The `[options]` keys `pm` and `tkc` answer for themselves and the options they start
//! from ([`crate::schemes::options`]; the table answers the rest).

use crate::effects::EffectSet;
use crate::limiter::Limiter;
use crate::schemes::options::SchemeOptions;
use crate::schemes::options::{read_if, why, NotRead, OptionKey};
use crate::schemes::scheme::Scheme;

/// The contact family's own answer for `key` with `effects` (its own and those the
/// scene's `correction` and `muscl` ask for) where the table's is not its (`None`: the
/// table's).
pub(crate) fn reads(
    scheme: Scheme,
    key: OptionKey,
    effects: EffectSet,
) -> Option<Result<(), NotRead>> {
    use OptionKey::*;
    let (muscl, correction) = (
        effects.contains(EffectSet::MUSCL),
        effects.contains(EffectSet::CORRECTION),
    );
    Some(match key {
        Limiter => read_if(muscl, scheme, why::NO_MUSCL),
        Integrator => read_if(muscl, scheme, why::FIRST_ORDER_EULER),
        CorrectedSlopes => read_if(correction && muscl, scheme, why::NO_CORRECTED_SLOPES),
        SurfaceLambda | SurfaceScan | DetEpsilon => read_if(correction, scheme, why::NO_SURFACE),
        EnergyEquation => read_if(!correction, scheme, why::TOTAL_WITH_CORRECTION),
        Correction if scheme == Scheme::Tkc => Err(NotRead::Always { what: "correction" }),
        Muscl if scheme == Scheme::Tkc => Err(NotRead::Always { what: "MUSCL" }),
        _ => return None,
    })
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
