//! Materials: an equation of state, elastic moduli and a strength model.
//!
//! Wave speeds (seed 004 eq 8): `c_l = sqrt(c_b² + 4G/(3 rho))`, `c_t = sqrt(G/rho)`, with
//! `c_b` the bulk sound speed of the EOS.

pub mod eos;
pub mod params;
pub mod strength;

use crate::math::{real, Real};
pub use eos::{Eos, EosState};

/// How a material resists shear. With the feature `serde` it reads from a scene's
/// `strength` table: `type` names the variant (`fluid`, `elastic`, `von_mises`,
/// `johnson_cook`, `jh1`), the other keys are the model's parameters, and a key the model
/// does not read is refused.
#[derive(Clone, Copy, Debug, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(from = "serde_repr::Tagged", into = "serde_repr::Tagged")
)]
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

impl Strength {
    /// The model's name in a scene (its `type`).
    pub fn name(&self) -> &'static str {
        match self {
            Strength::Fluid => "fluid",
            Strength::Elastic => "elastic",
            Strength::VonMises { .. } => "von_mises",
            Strength::JohnsonCook(_) => "johnson_cook",
            Strength::Jh1(_) => "jh1",
        }
    }

    /// Checks the model's parameters (each model's `check`).
    pub fn check(&self) -> Result<(), params::ParamError> {
        match self {
            Strength::Fluid | Strength::Elastic => Ok(()),
            Strength::VonMises { yield_stress } => {
                params::positive("yield_stress", *yield_stress)?;
                params::physical("yield_stress", *yield_stress, params::ranges::STRESS, "Pa")
            }
            Strength::JohnsonCook(m) => m.check(),
            Strength::Jh1(m) => m.check(),
        }
    }
}

/// The scene form of [`Strength`]: the same variants with the parameterless ones as empty
/// structs, because serde's internally tagged unit variants would ignore keys they do not
/// read (a scene key must change the result or be refused).
#[cfg(feature = "serde")]
mod serde_repr {
    use super::{strength, Real, Strength};

    #[derive(serde::Deserialize, serde::Serialize)]
    #[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
    pub enum Tagged {
        Fluid {},
        Elastic {},
        VonMises { yield_stress: Real },
        JohnsonCook(strength::JohnsonCook),
        Jh1(strength::Jh1),
    }

    impl From<Tagged> for Strength {
        fn from(t: Tagged) -> Strength {
            match t {
                Tagged::Fluid {} => Strength::Fluid,
                Tagged::Elastic {} => Strength::Elastic,
                Tagged::VonMises { yield_stress } => Strength::VonMises { yield_stress },
                Tagged::JohnsonCook(m) => Strength::JohnsonCook(m),
                Tagged::Jh1(m) => Strength::Jh1(m),
            }
        }
    }

    impl From<Strength> for Tagged {
        fn from(s: Strength) -> Tagged {
            match s {
                Strength::Fluid => Tagged::Fluid {},
                Strength::Elastic => Tagged::Elastic {},
                Strength::VonMises { yield_stress } => Tagged::VonMises { yield_stress },
                Strength::JohnsonCook(m) => Tagged::JohnsonCook(m),
                Strength::Jh1(m) => Tagged::Jh1(m),
            }
        }
    }
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
