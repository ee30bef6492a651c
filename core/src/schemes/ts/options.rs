//! The `[options]` keys `ts1` and `ts2` answer for themselves
//! ([`crate::schemes::options`]; the table answers the rest).

use crate::effects::EffectSet;
use crate::schemes::options::{read_if, why, NotRead, OptionKey};
use crate::schemes::scheme::Scheme;

/// The time-split family's own answer for `key` where the table's is not its (`None`:
/// the table's).
pub(crate) fn reads(scheme: Scheme, key: OptionKey) -> Option<Result<(), NotRead>> {
    use OptionKey::*;
    let muscl = scheme.effects().contains(EffectSet::MUSCL);
    match key {
        Limiter => Some(read_if(muscl, scheme, why::NO_MUSCL)),
        MusclTime => Some(read_if(muscl, scheme, why::NO_MUSCL_TIME)),
        _ => None,
    }
}
