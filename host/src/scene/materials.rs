//! Scene materials to core materials.

use super::{MaterialSpec, StrengthSpec};
use gsph_core::material::strength::{Jh1, JohnsonCook};
use gsph_core::material::{Material, Strength};

/// The core material of a (validated) scene material.
pub fn material_of(m: &MaterialSpec) -> Material {
    let rho0 = m.rho0;
    let eos = m.eos.with_rho0(rho0);
    let strength = match &m.strength {
        Some(spec) => strength_of(spec),
        None if m.shear_modulus > 0.0 => Strength::Elastic,
        None => Strength::Fluid,
    };
    Material {
        rho0,
        eos,
        shear_modulus: m.shear_modulus,
        strength,
        tensile_strength: m.tensile_strength.unwrap_or(f64::INFINITY),
    }
}

/// The core strength model of a scene strength model.
pub fn strength_of(spec: &StrengthSpec) -> Strength {
    match *spec {
        StrengthSpec::Fluid {} => Strength::Fluid,
        StrengthSpec::Elastic {} => Strength::Elastic,
        StrengthSpec::VonMises { yield_stress } => Strength::VonMises { yield_stress },
        StrengthSpec::JohnsonCook {
            a,
            b,
            n,
            c,
            m: exponent,
            eps_dot0,
            t_room,
            t_melt,
            specific_heat,
            taylor_quinney,
        } => Strength::JohnsonCook(JohnsonCook {
            a,
            b,
            n,
            c,
            m: exponent,
            eps_dot0,
            t_room,
            t_melt,
            specific_heat,
            taylor_quinney,
        }),
        StrengthSpec::Jh1 {
            sigma_i1,
            p1,
            sigma_i2,
            p2,
            sigma_f_max,
            c_f,
            tensile_limit,
            eps_f_max,
            p_max,
            c,
            eps_dot0,
        } => Strength::Jh1(Jh1 {
            sigma_i1,
            p1,
            sigma_i2,
            p2,
            sigma_f_max,
            c_f,
            tensile_limit,
            eps_f_max,
            p_max,
            c,
            eps_dot0,
        }),
    }
}
