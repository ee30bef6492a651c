//! The `[options]` keys `av` answers for itself ([`crate::schemes::options`]; the table
//! answers the rest).

use crate::schemes::options::{read_if, why, NotRead, OptionKey};
use crate::schemes::scheme::Scheme;

/// Scheme `av`'s own answer for `key` where the table's is not its (`None`: the table's).
pub(crate) fn reads(scheme: Scheme, key: OptionKey) -> Option<Result<(), NotRead>> {
    use OptionKey::*;
    match key {
        // it solves no Riemann problem at all, transverse or not
        TransverseDissipation | Objective => Some(read_if(false, scheme, why::NO_RIEMANN)),
        // no free-surface rule at all, scanned or not
        SurfaceScan => Some(read_if(false, scheme, why::NO_SURFACE)),
        _ => None,
    }
}
