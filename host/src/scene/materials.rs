//! Scene materials to core materials.

use super::MaterialSpec;
use gsph_core::material::{Material, Strength};

/// The core material of a (validated) scene material.
pub fn material_of(m: &MaterialSpec) -> Material {
    let rho0 = m.rho0;
    let eos = m.eos.with_rho0(rho0);
    let strength = match m.strength {
        Some(strength) => strength,
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
