//! The materials of a scene (`[[materials]]`): the EOS and the strength model are the
//! core's models, which read and check themselves. Converted to the core's materials by [`super::materials`].

pub use gsph_core::material::{Eos, Strength};
use serde::{Deserialize, Serialize};

/// A material. In a scene file a `[[materials]]` table may also say `library = "NAME"`,
/// `include = "FILE"` and `unset = [KEYS]`, which are resolved before this is read (see
/// [`super::library`]).
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
pub struct MaterialSpec {
    /// Name bodies refer to.
    pub name: String,
    /// Reference density, kg/m³.
    pub rho0: f64,
    /// Shear modulus, Pa (omit or 0 for a fluid).
    #[serde(default)]
    pub shear_modulus: f64,
    /// Poisson ratio, instead of `shear_modulus`: G = 3K(1 - 2 nu)/(2(1 + nu)) with the bulk
    /// modulus K = rho0 c² of the EOS at the reference state (seed 004's sound wave).
    #[serde(default)]
    pub poisson_ratio: Option<f64>,
    /// Equation of state: the core's [`Eos`], read from the `eos` table (`type` and the
    /// model's parameters; its `rho0` is this material's, set by [`super::materials`]).
    pub eos: Eos,
    /// Strength model: the core's [`Strength`], read from the `strength` table (`type`
    /// and the model's parameters). Default: elastic if shear_modulus > 0, else fluid.
    #[serde(default)]
    pub strength: Option<Strength>,
    /// Tensile strength T, Pa: the pressure never falls below -T (pressure cut-off; seed
    /// 004 table 1: copper 0.35 GPa). Not with JH1, which has its own `tensile_limit`.
    #[serde(default)]
    pub tensile_strength: Option<f64>,
}
