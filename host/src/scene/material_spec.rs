//! The materials of a scene (`[[materials]]`): the EOS (the core's models, which read and
//! check themselves) and strength models with their parameters and units. Converted to the core's materials by [`super::materials`].

use super::spec::one;
pub use gsph_core::material::Eos;
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
    /// Strength model (default: elastic if shear_modulus > 0, else fluid).
    #[serde(default)]
    pub strength: Option<StrengthSpec>,
    /// Tensile strength T, Pa: the pressure never falls below -T (pressure cut-off; seed
    /// 004 table 1: copper 0.35 GPa). Not with JH1, which has its own `tensile_limit`.
    #[serde(default)]
    pub tensile_strength: Option<f64>,
}

/// Strength models.
#[derive(Debug, Clone, Deserialize, Serialize)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum StrengthSpec {
    /// No deviatoric stress.
    Fluid {},
    /// Elastic, no yield.
    Elastic {},
    /// Von Mises, constant yield stress.
    VonMises {
        /// Yield stress, Pa.
        yield_stress: f64,
    },
    /// Johnson–Cook flow stress with strain hardening, strain-rate and thermal softening;
    /// temperature from plastic work (adds the `heat` effect). Seed 000 eq 40.
    JohnsonCook {
        /// Initial yield stress A, Pa.
        a: f64,
        /// Hardening modulus B, Pa.
        b: f64,
        /// Hardening exponent n.
        n: f64,
        /// Strain-rate coefficient C.
        c: f64,
        /// Thermal softening exponent m.
        m: f64,
        /// Reference plastic strain rate, 1/s (default 1).
        #[serde(default = "one")]
        eps_dot0: f64,
        /// Room (reference and initial) temperature T0, K.
        t_room: f64,
        /// Melting temperature Tm, K.
        t_melt: f64,
        /// Specific heat c_p, J/(kg K).
        specific_heat: f64,
        /// Taylor–Quinney factor chi (fraction of plastic work turned into heat, 0..1).
        taylor_quinney: f64,
    },
    /// JH1 ceramic (Johnson–Holmquist 1992): piecewise-linear intact and failed strength,
    /// damage from plastic strain over a pressure-dependent failure strain (adds the
    /// `damage` effect). Seed 000 §5.
    Jh1 {
        /// Intact strength at `p1`, Pa.
        sigma_i1: f64,
        /// First pressure of the intact curve, Pa.
        p1: f64,
        /// Intact strength at `p2`, Pa.
        sigma_i2: f64,
        /// Second pressure of the intact curve, Pa (> p1).
        p2: f64,
        /// Maximum strength of the failed material, Pa.
        sigma_f_max: f64,
        /// Slope of the failed strength against pressure.
        c_f: f64,
        /// Hydrostatic tensile limit T, Pa (negative).
        tensile_limit: f64,
        /// Failure strain at and above `p_max`.
        eps_f_max: f64,
        /// Pressure where the failure strain reaches `eps_f_max`, Pa.
        p_max: f64,
        /// Strain-rate coefficient C.
        c: f64,
        /// Reference strain rate, 1/s (default 1).
        #[serde(default = "one")]
        eps_dot0: f64,
    },
}
