//! The result of a return mapping, shared by every strength model (a leaf of the folder,
//! so that the models and their parent both import it without a cycle).

use crate::math::{Real, Sym3};

/// Result of the plastic return mapping.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ReturnMap {
    /// Deviator after the return.
    pub s: Sym3,
    /// Equivalent plastic strain increment (>= 0).
    pub d_eps_p: Real,
    /// Plastic work per unit volume dissipated in this increment, J/m³ (>= 0).
    pub plastic_work: Real,
}

impl ReturnMap {
    /// The unchanged (elastic) result: deviator `s`, no plastic strain, no plastic work.
    #[inline]
    pub const fn elastic(s: Sym3) -> Self {
        ReturnMap {
            s,
            d_eps_p: 0.0,
            plastic_work: 0.0,
        }
    }
}
