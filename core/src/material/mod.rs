//! Materials: an equation of state, elastic moduli and a strength model.
//!
//! Wave speeds (seed 004 eq 8): `c_l = sqrt(c_b² + 4G/(3 rho))`, `c_t = sqrt(G/rho)`, with
//! `c_b` the bulk sound speed of the EOS.

pub mod eos;
pub mod strength;

use crate::math::{real, Real};
pub use eos::{Eos, EosState};

/// How a material resists shear.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Strength {
    /// No deviatoric stress (fluid). The shear modulus must be zero.
    Fluid,
    /// Elastic deviator without a yield limit.
    Elastic,
    /// Elastic–perfectly plastic, von Mises with constant yield stress (Pa).
    VonMises {
        /// Yield stress Y, Pa.
        yield_stress: Real,
    },
    /// Johnson–Cook flow stress with strain-rate and thermal softening (heat effect).
    JohnsonCook(strength::JohnsonCook),
    /// Johnson–Holmquist JH1 ceramic with scalar damage (damage effect).
    Jh1(strength::Jh1),
}

/// One material of a scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    /// Reference density rho0, kg/m³.
    pub rho0: Real,
    /// Equation of state.
    pub eos: Eos,
    /// Shear modulus G, Pa (zero for fluids).
    pub shear_modulus: Real,
    /// Strength model.
    pub strength: Strength,
}

impl Material {
    /// Pressure and bulk sound speed at (rho, e).
    #[inline]
    pub fn eos(&self, rho: Real, e: Real) -> EosState {
        self.eos.eval(rho, e)
    }
    /// Longitudinal wave speed from the bulk sound speed squared.
    #[inline]
    pub fn c_long(&self, rho: Real, c2_bulk: Real) -> Real {
        real::sqrt(real::max(c2_bulk, 0.0) + 4.0 * self.shear_modulus / (3.0 * rho))
    }
    /// Transverse wave speed.
    #[inline]
    pub fn c_trans(&self, rho: Real) -> Real {
        real::sqrt(self.shear_modulus / rho)
    }
    /// True if the material carries deviatoric stress.
    pub fn has_strength(&self) -> bool {
        !matches!(self.strength, Strength::Fluid)
    }
    /// True if the material can yield.
    pub fn has_plasticity(&self) -> bool {
        matches!(
            self.strength,
            Strength::VonMises { .. } | Strength::JohnsonCook(_) | Strength::Jh1(_)
        )
    }
    /// True if the material tracks temperature (Johnson–Cook thermal softening).
    pub fn has_heat(&self) -> bool {
        matches!(self.strength, Strength::JohnsonCook(_))
    }
    /// True if the material accumulates damage (JH1).
    pub fn has_damage(&self) -> bool {
        matches!(self.strength, Strength::Jh1(_))
    }
    /// Initial temperature of the material, K (Johnson–Cook room temperature; 0 otherwise).
    pub fn initial_temperature(&self) -> Real {
        match self.strength {
            Strength::JohnsonCook(jc) => jc.t_room,
            _ => 0.0,
        }
    }
}
