//! Strength models (STUB: to be implemented; API fixed).
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

/// Von Mises radial return of a trial deviator onto the yield surface `sigma_vm = yield_stress`.
pub fn radial_return(s_trial: Sym3, yield_stress: Real, shear_modulus: Real) -> ReturnMap {
    let _ = (s_trial, yield_stress, shear_modulus);
    todo!()
}
