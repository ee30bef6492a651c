//! The values of the scheme options: the enums a scene chooses by name, and how every
//! option's type reads in a scene and in the reference ([`OptionType`]).

use crate::limiter::Limiter;
use crate::math::Real;
use crate::riemann::Dissipation;
use core::fmt;

/// The type of a scheme option: how its values read in a scene (`Display` gives the scene
/// form) and in the scene-key reference.
pub trait OptionType: Copy + fmt::Display {
    /// The values a scene may give (the reference's "values" column).
    const VALUES: &'static str;
    /// The value as a number, where it is one (for the range check of the table).
    fn number(self) -> Option<Real> {
        None
    }
}

impl OptionType for Real {
    const VALUES: &'static str = "a number";
    fn number(self) -> Option<Real> {
        Some(self)
    }
}

impl OptionType for u32 {
    const VALUES: &'static str = "an integer";
    fn number(self) -> Option<Real> {
        Some(self as Real)
    }
}

impl OptionType for bool {
    const VALUES: &'static str = "`true`, `false`";
}

impl OptionType for Limiter {
    const VALUES: &'static str = "`minmod`, `superbee`, `mc`, `vanleer`, `sweby:BETA`";
}

impl OptionType for Dissipation {
    const VALUES: &'static str = "`full`, `compression`";
}

impl OptionType for MusclTime {
    const VALUES: &'static str = "`none`, `predictor`, `courant`";
}

/// Where a number-valued option must lie (checked when a scene is read).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Range {
    /// Any finite value (or not a number).
    Any,
    /// `> 0`.
    Positive,
    /// `>= 0`.
    NonNegative,
}

/// `NAMES`, `KNOWN`, `name`, `from_name`, `Display` (the scene name) and the
/// [`OptionType`] of an enum chosen by name in a scene's `[options]`: its names are
/// written here once (the serde impl's message reads `KNOWN`, `crate::named`).
macro_rules! scene_names {
    ($t:ident { $v0:ident => $s0:literal $(, $v:ident => $s:literal)* $(,)? }) => {
        impl $t {
            /// The scene names, in the order messages list them.
            pub const NAMES: [&'static str; [$s0 $(, $s)*].len()] = [$s0 $(, $s)*];

            /// The scene names as a message lists them (`a, b`).
            pub const KNOWN: &'static str = concat!($s0 $(, ", ", $s)*);

            /// The scene name.
            pub const fn name(self) -> &'static str {
                match self {
                    $t::$v0 => $s0,
                    $($t::$v => $s),*
                }
            }

            /// The choice of a scene name.
            pub fn from_name(name: &str) -> Option<$t> {
                match name {
                    $s0 => Some($t::$v0),
                    $($s => Some($t::$v),)*
                    _ => None,
                }
            }
        }

        /// The scene name.
        impl core::fmt::Display for $t {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.write_str(self.name())
            }
        }

        impl OptionType for $t {
            const VALUES: &'static str = concat!("`", $s0, "`" $(, ", `", $s, "`")*);
        }
    };
}

/// Riemann solver of the hydrodynamic step of `ts`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RiemannSolver {
    /// Linearised acoustic solver.
    Acoustic,
    /// Two-shock approximate solver (Dukowicz 1985).
    TwoShock,
}

/// The time dimension of the MUSCL reconstruction of `ts2`. Seed 000 eq 23 multiplies the
/// slope by `[1 - c_i dt]`, which has units of length: see `schemes::ts` for the choice.
/// Whatever is chosen applies to every use of the pair's star state (continuity, momentum
/// and energy), as seed 000 eqs 22 and 34 use the same contact velocity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MusclTime {
    /// MUSCL–Hancock predictor: the particle's state is advanced half a step with the
    /// Lagrangian acoustic equations before the spatial reconstruction.
    Predictor,
    /// The seed's factor made dimensionless: slopes scaled by `max(0, 1 - c_i dt / r_ij)`.
    CourantFactor,
    /// Spatial reconstruction only (default).
    None,
}

/// The scene name.
impl core::fmt::Display for MusclTime {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            MusclTime::Predictor => "predictor",
            MusclTime::CourantFactor => "courant",
            MusclTime::None => "none",
        })
    }
}

impl MusclTime {
    /// The scene names, in the order messages list them.
    pub const NAMES: [&'static str; 3] = ["predictor", "courant", "none"];

    /// The time treatment of a scene name.
    pub fn from_name(name: &str) -> Option<MusclTime> {
        match name {
            "predictor" => Some(MusclTime::Predictor),
            "courant" => Some(MusclTime::CourantFactor),
            "none" => Some(MusclTime::None),
            _ => None,
        }
    }
}

scene_names!(RiemannSolver { Acoustic => "acoustic", TwoShock => "two_shock" });

/// How the contact family (`pm`, `tkc`) advances in time (`options.integrator`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integrator {
    /// The seeds': every rate from the state at the start of the step (pm, explicit
    /// Euler), or with MUSCL density and deviator first and the forces from the new
    /// stresses (tkc, symplectic Euler). First order in time.
    Euler,
    /// The predictor–corrector leap-frog of `av` (kick, drift, predict, one rate
    /// evaluation at the predicted end state, kick): second order in time, one pair
    /// pass per step; with tkc's total-energy equation, energy stays exact.
    Leapfrog,
}

scene_names!(Integrator { Euler => "euler", Leapfrog => "leapfrog" });

/// The specific volumes a pair force of the contact family (`pm`, `tkc`) carries
/// (`options.specific_volume`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecificVolume {
    /// The seeds': `1/(rho_i rho_j)`.
    Product,
    /// Sugiura & Inutsuka (2016, 2017): `1/rho` interpolated along the pair, linear
    /// through both values where the pair is compressed and cubic through the values and
    /// the slopes of the plain kernel sum where it is stretched, and its square averaged
    /// over the pair's kernel product (Inutsuka 2002; `schemes::pm::volume`).
    Interpolated,
}

scene_names!(SpecificVolume { Product => "product", Interpolated => "interpolated" });

/// The energy equation of scheme `pm` (`options.energy_equation`; `tkc` and `pm` with
/// correction always book the total energy, Rublev & Murzov eq 11).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum EnergyEquation {
    /// The seed's (Connolly et al. 2013 eq 16): the internal-energy rate
    /// `sum f t*.(v* - v_i)` at the start-of-step velocity. Its total energy is not the
    /// work of the stepped momentum: each step adds `m |a|² dt²/2` per particle.
    Internal,
    /// The total-energy rate `sum f t*.v*`, booked as `de = dt (power - a.(v + dv/2))`:
    /// total energy exact to round-off (tkc's).
    Total,
}

scene_names!(EnergyEquation { Internal => "internal", Total => "total" });
