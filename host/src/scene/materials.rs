//! Scene materials to core materials.

use super::{EosSpec, MaterialSpec, StrengthSpec};
use gsph_core::material::eos::{
    Eos, Hugoniot, Linear, Logarithmic, MieGruneisen, Polynomial, Tillotson, TwoCurve,
};
use gsph_core::material::strength::{Jh1, JohnsonCook};
use gsph_core::material::{Material, Strength};

/// The core material of a (validated) scene material.
pub fn material_of(m: &MaterialSpec) -> Material {
    let rho0 = m.rho0;
    let eos: Eos = match m.eos {
        EosSpec::Linear { c0, gamma } => Linear { rho0, c0, gamma }.into(),
        EosSpec::Logarithmic { bulk_modulus } => Logarithmic { rho0, bulk_modulus }.into(),
        EosSpec::MieGruneisen { c0, s1, gamma0 } => MieGruneisen {
            rho0,
            c0,
            s1,
            gamma0,
        }
        .into(),
        EosSpec::Hugoniot { c0, s1 } => Hugoniot { rho0, c0, s1 }.into(),
        EosSpec::TwoCurve { c_a, s_a, gamma } => TwoCurve {
            rho0,
            c_a,
            s_a,
            gamma,
        }
        .into(),
        EosSpec::Polynomial { k1, k2, k3 } => Polynomial { rho0, k1, k2, k3 }.into(),
        EosSpec::Tillotson {
            a,
            b,
            big_a,
            big_b,
            alpha,
            beta,
            e0,
            e_iv,
            e_cv,
        } => Tillotson {
            rho0,
            a,
            b,
            big_a,
            big_b,
            alpha,
            beta,
            e0,
            e_iv,
            e_cv,
        }
        .into(),
    };
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
