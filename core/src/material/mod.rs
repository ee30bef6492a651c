//! Materials: an equation of state, elastic moduli and a strength model.
//!
//! Wave speeds (seed 004 eq 8): `c_l = sqrt(c_b² + 4G/(3 rho))`, `c_t = sqrt(G/rho)`, with
//! `c_b` the bulk sound speed of the EOS.

pub mod eos;
pub mod params;
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
    /// Tensile strength T, Pa (`Real::INFINITY`: none): the pressure never falls below
    /// `-T` (the pressure cut-off of hydrocodes; seed 004 table 1 gives copper
    /// T = 0.35 GPa). Applied in [`Material::eos`], so every scheme sees the cut pressure.
    pub tensile_strength: Real,
}

impl Material {
    /// Pressure and bulk sound speed at (rho, e).
    #[inline]
    pub fn eos(&self, rho: Real, e: Real) -> EosState {
        let st = self.eos.eval(rho, e);
        if st.p < -self.tensile_strength {
            // tension beyond T: the pressure stays at the cut-off, the sound speed that of
            // the EOS (the wave speeds of the Riemann solvers and the time step)
            EosState {
                p: -self.tensile_strength,
                c2: st.c2,
            }
        } else {
            st
        }
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::eos::TwoCurve;

    fn copper(tensile_strength: Real) -> Material {
        Material {
            rho0: 8960.0,
            eos: TwoCurve {
                rho0: 8960.0,
                c_a: 3930.0,
                s_a: 1.5,
                gamma: 1.7,
            }
            .into(),
            shear_modulus: 43e9,
            strength: Strength::VonMises {
                yield_stress: 0.35e9,
            },
            tensile_strength,
        }
    }

    /// Seed 004 table 1's copper: T = 0.35 GPa. Compression and moderate tension are the
    /// EOS's; beyond -T the pressure stays at -T with the EOS's sound speed.
    #[test]
    fn tensile_strength_cuts_the_pressure_at_minus_t() {
        let (cut, free) = (copper(0.35e9), copper(Real::INFINITY));
        for rho in [9500.0, 8960.0, 8950.0] {
            assert_eq!(cut.eos(rho, 0.0), free.eos(rho, 0.0), "rho {rho}");
        }
        let deep = 8000.0;
        assert!(free.eos(deep, 0.0).p < -0.35e9);
        assert_eq!(cut.eos(deep, 0.0).p, -0.35e9);
        assert_eq!(cut.eos(deep, 0.0).c2, free.eos(deep, 0.0).c2);
    }
}
