//! Slope limiters (STUB: to be implemented; API fixed).
use crate::math::Real;

/// Slope limiter phi(r).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Limiter {
    /// minmod
    Minmod,
    /// superbee
    Superbee,
}

impl Limiter {
    /// phi(r).
    pub fn phi(self, r: Real) -> Real {
        let _ = r;
        todo!()
    }
}

/// minmod(a, b).
pub fn minmod(a: Real, b: Real) -> Real {
    let _ = (a, b);
    todo!()
}
