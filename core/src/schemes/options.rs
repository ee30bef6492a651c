//! A scene's `[options]`: the keys ([`OptionKey`]), their values as the scene gives them
//! ([`SceneOptions`]), which keys each scheme reads (promise 3: a key either changes the
//! result or is refused, naming the key and the scheme) and the options a scheme starts
//! from. Each family answers for its own schemes (`reads` and `defaults` in its module);
//! the reasons they give are shared here.
//!
//! | key | read by |
//! | --- | --- |
//! | `av_alpha`, `av_beta` | `av` |
//! | `limiter` | the schemes with MUSCL: `ts2`, `tkc`, `pm` with `muscl = true` |
//! | `riemann` | every Godunov scheme: `pm`, `tkc` (longitudinal wave), `ts1`, `ts2` |
//! | `dissipation` | every Godunov scheme: `pm`, `tkc`, `ts1`, `ts2` |
//! | `transverse_dissipation`, `objective` | the schemes with transverse Riemann problems: `pm`, `tkc` |
//! | `integrator` | `tkc`, `pm` with `muscl`, `ts1`, `ts2` |
//! | `corrected_slopes` | the schemes with corrected MUSCL slopes: `tkc`, `pm` with `correction` and `muscl` |
//! | `muscl_time` | `ts2` |
//! | `surface_lambda`, `det_epsilon` | `ts1`, `ts2` (free-surface divergence), `tkc`, `pm` with `correction = true` |
//! | `surface_scan` | `tkc`, `pm` with `correction = true` |
//! | `specific_volume` | `pm`, `tkc` |
//! | `correction`, `muscl` | `pm` (tkc always has both) |
//! | `artificial_stress`, `artificial_stress_exponent` | every scheme |

use super::artificial_stress::ArtificialStress;
use super::scheme::Scheme;
use crate::effects::EffectSet;
use crate::limiter::Limiter;
use crate::math::Real;
use crate::riemann::Dissipation;
use core::fmt;

/// `NAMES`, `name`, `from_name` and `Display` (the scene name) of an enum chosen by name
/// in a scene's `[options]`.
macro_rules! scene_names {
    ($t:ident { $($v:ident => $s:literal),+ $(,)? }) => {
        impl $t {
            /// The scene names, in the order messages list them.
            pub const NAMES: [&'static str; [$($s),+].len()] = [$($s),+];

            /// The scene name.
            pub const fn name(self) -> &'static str {
                match self {
                    $($t::$v => $s),+
                }
            }

            /// The choice of a scene name.
            pub fn from_name(name: &str) -> Option<$t> {
                match name {
                    $($s => Some($t::$v),)+
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

/// Scheme options (with the defaults of the seeds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SchemeOptions {
    /// Monaghan viscosity alpha (`av`).
    pub av_alpha: Real,
    /// Monaghan viscosity beta (`av`).
    pub av_beta: Real,
    /// Slope limiter of `ts2`.
    pub limiter: Limiter,
    /// Riemann solver of `ts`.
    pub riemann: RiemannSolver,
    /// Where the Riemann solver's dissipation acts (every Godunov scheme;
    /// [`crate::riemann::low_dissipation`]).
    pub dissipation: crate::riemann::Dissipation,
    /// Where the transverse Riemann problems' dissipation acts (`pm`, `tkc`), on top of
    /// `dissipation`.
    pub transverse_dissipation: crate::riemann::Dissipation,
    /// The transverse Riemann problems of `pm` and `tkc` see the velocity jump of a pair
    /// less its rigid rotation (the pair's mean spin times its separation): a rigid
    /// rotation is not dissipated (`schemes::pm`).
    pub objective: bool,
    /// The MUSCL slopes of a free-surface particle (`L = I` there) corrected with its full
    /// `L^-1` where `L` is invertible, so that they are exact for linear fields at the
    /// surface as inside (`tkc`, `pm` with correction and MUSCL); the forces keep the
    /// surface rule. Off: seed 004's `L = I` for the slopes too.
    pub corrected_slopes: bool,
    /// The time integration of `pm` and `tkc`.
    pub integrator: Integrator,
    /// How `ts2` accounts for the time step when it reconstructs the contact states (seed
    /// 000 eq 23; one choice for continuity, momentum and energy, see `schemes::ts`).
    pub muscl_time: MusclTime,
    /// Threshold on the smallest eigenvalue of L below which a particle is a free-surface
    /// particle (`tkc`: L = I there; `ts`: consistent divergence there).
    pub surface_lambda: Real,
    /// A particle below `surface_lambda` is a free-surface particle only if its
    /// neighbourhood is open by the umbrella scan (`tkc`, `pm` with correction; see
    /// `open_neighbourhood` in the schemes' common module); `false` (default): seed 004's
    /// eigenvalue test alone. Off by default: the particles it keeps corrected at
    /// compacting pore surfaces break momentum conservation (docs/elastic.md).
    pub surface_scan: bool,
    /// L is not inverted where det L is below this (`tkc`, `ts`).
    pub det_epsilon: Real,
    /// The specific volumes of the contact family's pair force (`pm`, `tkc`).
    pub specific_volume: SpecificVolume,
    /// Artificial stress (read with the effect `artificial_stress`).
    pub artificial_stress: ArtificialStress,
    /// Keep every particle's smoothing length as it starts (the peers' colliding rings,
    /// and codes with a fixed h); otherwise `h = h_factor (m/rho)^(1/D)` after each step.
    pub constant_h: bool,
}

impl Default for SchemeOptions {
    fn default() -> Self {
        SchemeOptions {
            av_alpha: 1.0,
            av_beta: 1.0,
            limiter: Limiter::Superbee,
            riemann: RiemannSolver::Acoustic,
            dissipation: crate::riemann::Dissipation::Full,
            transverse_dissipation: crate::riemann::Dissipation::Full,
            objective: true,
            corrected_slopes: false,
            integrator: Integrator::Euler,
            muscl_time: MusclTime::None,
            specific_volume: SpecificVolume::Product,
            surface_lambda: 0.75,
            surface_scan: false,
            det_epsilon: 0.05,
            artificial_stress: ArtificialStress::default(),
            constant_h: false,
        }
    }
}

/// A key of a scene's `[options]` table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum OptionKey {
    /// `av_alpha`.
    AvAlpha,
    /// `av_beta`.
    AvBeta,
    /// `limiter`.
    Limiter,
    /// `riemann`.
    Riemann,
    /// `dissipation`.
    Dissipation,
    /// `transverse_dissipation`.
    TransverseDissipation,
    /// `objective`.
    Objective,
    /// `corrected_slopes`.
    CorrectedSlopes,
    /// `integrator`.
    Integrator,
    /// `muscl_time`.
    MusclTime,
    /// `surface_lambda`.
    SurfaceLambda,
    /// `surface_scan`.
    SurfaceScan,
    /// `specific_volume`.
    SpecificVolume,
    /// `det_epsilon`.
    DetEpsilon,
    /// `correction`.
    Correction,
    /// `muscl`.
    Muscl,
    /// `artificial_stress`.
    ArtificialStress,
    /// `artificial_stress_exponent`.
    ArtificialStressExponent,
}

impl OptionKey {
    /// Every key, in the order a scene's keys are checked.
    pub const ALL: [OptionKey; 18] = [
        OptionKey::AvAlpha,
        OptionKey::AvBeta,
        OptionKey::Limiter,
        OptionKey::Riemann,
        OptionKey::Dissipation,
        OptionKey::TransverseDissipation,
        OptionKey::Objective,
        OptionKey::CorrectedSlopes,
        OptionKey::Integrator,
        OptionKey::MusclTime,
        OptionKey::SurfaceLambda,
        OptionKey::SurfaceScan,
        OptionKey::SpecificVolume,
        OptionKey::DetEpsilon,
        OptionKey::Correction,
        OptionKey::Muscl,
        OptionKey::ArtificialStress,
        OptionKey::ArtificialStressExponent,
    ];

    /// The key's path in a scene (`options.limiter`).
    pub const fn path(self) -> &'static str {
        match self {
            OptionKey::AvAlpha => "options.av_alpha",
            OptionKey::AvBeta => "options.av_beta",
            OptionKey::Limiter => "options.limiter",
            OptionKey::Riemann => "options.riemann",
            OptionKey::Dissipation => "options.dissipation",
            OptionKey::TransverseDissipation => "options.transverse_dissipation",
            OptionKey::Objective => "options.objective",
            OptionKey::CorrectedSlopes => "options.corrected_slopes",
            OptionKey::Integrator => "options.integrator",
            OptionKey::MusclTime => "options.muscl_time",
            OptionKey::SurfaceLambda => "options.surface_lambda",
            OptionKey::SurfaceScan => "options.surface_scan",
            OptionKey::SpecificVolume => "options.specific_volume",
            OptionKey::DetEpsilon => "options.det_epsilon",
            OptionKey::Correction => "options.correction",
            OptionKey::Muscl => "options.muscl",
            OptionKey::ArtificialStress => "options.artificial_stress",
            OptionKey::ArtificialStressExponent => "options.artificial_stress_exponent",
        }
    }
}

/// Why a scheme does not read a key; its `Display` is the one-line reason.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum NotRead {
    /// The scheme has no use for the key: `not read by scheme S (why)`.
    Because {
        /// The scheme.
        scheme: Scheme,
        /// Why.
        why: &'static str,
    },
    /// `tkc` always has what `correction` or `muscl` would choose.
    Always {
        /// `correction` or `MUSCL`.
        what: &'static str,
    },
    /// `correction` and `muscl` choose for scheme `pm` only.
    OnlyPm {
        /// The scheme.
        scheme: Scheme,
    },
}

impl fmt::Display for NotRead {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            NotRead::Because { scheme, why } => {
                write!(f, "not read by scheme {} ({why})", scheme.name())
            }
            NotRead::Always { what } => {
                write!(f, "scheme tkc always has {what}; choose it for scheme pm")
            }
            NotRead::OnlyPm { scheme } => {
                write!(f, "only with scheme pm (scheme is {})", scheme.name())
            }
        }
    }
}

/// The reasons the families give.
pub(crate) mod why {
    pub const AV_ONLY: &str = "artificial viscosity is scheme av's";
    pub const NO_MUSCL: &str =
        "it has no MUSCL reconstruction; ts2, tkc and pm with options.muscl have";
    pub const NO_RIEMANN: &str = "it solves no Riemann problem";
    pub const NO_TRANSVERSE: &str =
        "it solves no transverse Riemann problem; pm and tkc do (its deviatoric step has no dissipation)";
    pub const NO_CORRECTED_SLOPES: &str =
        "it has no kernel-corrected MUSCL slopes; tkc and pm with options.correction and options.muscl have";
    pub const OWN_INTEGRATOR: &str =
        "its time integration is its own leap-frog; pm, tkc, ts1 and ts2 choose";
    pub const FIRST_ORDER_EULER: &str =
        "its first-order Riemann states step with explicit Euler only (with the leap-frog pm's Verney cylinder went unstable); tkc, ts1, ts2 and pm with options.muscl choose";
    pub const NO_MUSCL_TIME: &str = "only ts2's reconstruction has a time treatment";
    pub const NO_SCAN: &str =
        "its kernel is not corrected, so no particle is switched to L = I; tkc and pm with options.correction scan";
    pub const NO_SPECIFIC_VOLUME: &str =
        "its pair force's specific volumes are not interpolated; pm and tkc interpolate them";
    pub const NO_SURFACE: &str =
        "it has no free-surface rule; ts1, ts2, tkc and pm with options.correction have";
}

/// `Err(NotRead::Because { scheme, why })` unless `read`.
pub(crate) fn read_if(read: bool, scheme: Scheme, why: &'static str) -> Result<(), NotRead> {
    if read {
        Ok(())
    } else {
        Err(NotRead::Because { scheme, why })
    }
}

/// A scene's `[options]` as given: `None` for a key it does not set. With the feature
/// `serde` it reads from the scene's `[options]` table (the names of the limiter, the
/// Riemann solver and the time treatment parsed there, an unknown one refused with the
/// known ones).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Deserialize, serde::Serialize),
    serde(default, deny_unknown_fields)
)]
pub struct SceneOptions {
    /// Monaghan alpha.
    pub av_alpha: Option<Real>,
    /// Monaghan beta.
    pub av_beta: Option<Real>,
    /// Slope limiter of the MUSCL reconstruction.
    pub limiter: Option<Limiter>,
    /// Riemann solver.
    pub riemann: Option<RiemannSolver>,
    /// Where the Riemann solver's dissipation acts.
    pub dissipation: Option<Dissipation>,
    /// Where the transverse Riemann problems' dissipation acts (pm, tkc).
    pub transverse_dissipation: Option<Dissipation>,
    /// The transverse Riemann problems leave out the pairs' rigid rotation (pm, tkc).
    pub objective: Option<bool>,
    /// MUSCL slopes corrected at free surfaces too (tkc, pm with correction and MUSCL).
    pub corrected_slopes: Option<bool>,
    /// Time integration of pm and tkc.
    pub integrator: Option<Integrator>,
    /// Time treatment of the ts2 reconstruction.
    pub muscl_time: Option<MusclTime>,
    /// Free-surface eigenvalue threshold.
    pub surface_lambda: Option<Real>,
    /// The umbrella scan confirms each free-surface particle (tkc, pm with correction).
    pub surface_scan: Option<bool>,
    /// The specific volumes of the pair force (pm, tkc).
    pub specific_volume: Option<SpecificVolume>,
    /// det L threshold below which L is not inverted.
    pub det_epsilon: Option<Real>,
    /// Kernel gradient correction for scheme pm.
    pub correction: Option<bool>,
    /// MUSCL reconstruction for scheme pm.
    pub muscl: Option<bool>,
    /// Artificial stress epsilon.
    pub artificial_stress: Option<Real>,
    /// Artificial stress exponent n.
    pub artificial_stress_exponent: Option<u32>,
}

impl SceneOptions {
    /// Whether the scene sets `key`.
    pub const fn is_set(&self, key: OptionKey) -> bool {
        match key {
            OptionKey::AvAlpha => self.av_alpha.is_some(),
            OptionKey::AvBeta => self.av_beta.is_some(),
            OptionKey::Limiter => self.limiter.is_some(),
            OptionKey::Riemann => self.riemann.is_some(),
            OptionKey::Dissipation => self.dissipation.is_some(),
            OptionKey::TransverseDissipation => self.transverse_dissipation.is_some(),
            OptionKey::Objective => self.objective.is_some(),
            OptionKey::CorrectedSlopes => self.corrected_slopes.is_some(),
            OptionKey::Integrator => self.integrator.is_some(),
            OptionKey::MusclTime => self.muscl_time.is_some(),
            OptionKey::SurfaceLambda => self.surface_lambda.is_some(),
            OptionKey::SurfaceScan => self.surface_scan.is_some(),
            OptionKey::SpecificVolume => self.specific_volume.is_some(),
            OptionKey::DetEpsilon => self.det_epsilon.is_some(),
            OptionKey::Correction => self.correction.is_some(),
            OptionKey::Muscl => self.muscl.is_some(),
            OptionKey::ArtificialStress => self.artificial_stress.is_some(),
            OptionKey::ArtificialStressExponent => self.artificial_stress_exponent.is_some(),
        }
    }

    /// Removes `key` from the scene's options.
    pub fn unset(&mut self, key: OptionKey) {
        match key {
            OptionKey::AvAlpha => self.av_alpha = None,
            OptionKey::AvBeta => self.av_beta = None,
            OptionKey::Limiter => self.limiter = None,
            OptionKey::Riemann => self.riemann = None,
            OptionKey::Dissipation => self.dissipation = None,
            OptionKey::TransverseDissipation => self.transverse_dissipation = None,
            OptionKey::Objective => self.objective = None,
            OptionKey::CorrectedSlopes => self.corrected_slopes = None,
            OptionKey::Integrator => self.integrator = None,
            OptionKey::MusclTime => self.muscl_time = None,
            OptionKey::SurfaceLambda => self.surface_lambda = None,
            OptionKey::SurfaceScan => self.surface_scan = None,
            OptionKey::SpecificVolume => self.specific_volume = None,
            OptionKey::DetEpsilon => self.det_epsilon = None,
            OptionKey::Correction => self.correction = None,
            OptionKey::Muscl => self.muscl = None,
            OptionKey::ArtificialStress => self.artificial_stress = None,
            OptionKey::ArtificialStressExponent => self.artificial_stress_exponent = None,
        }
    }

    /// The effects the scene's `correction` and `muscl` ask for.
    pub const fn asked(&self) -> EffectSet {
        let mut e = EffectSet::HYDRO;
        if matches!(self.correction, Some(true)) {
            e = e.union(EffectSet::CORRECTION);
        }
        if matches!(self.muscl, Some(true)) {
            e = e.union(EffectSet::MUSCL);
        }
        e
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::effects::EffectSet;

    #[test]
    fn every_scheme_reads_its_keys_and_refuses_the_others_with_a_reason() {
        let none = EffectSet::HYDRO;
        let read = |s: Scheme, k: OptionKey| s.reads(k, none).is_ok();
        use OptionKey::*;
        assert!(read(Scheme::Av, AvAlpha) && !read(Scheme::Ts2, AvBeta));
        assert!(read(Scheme::Ts2, Limiter) && read(Scheme::Tkc, Limiter));
        assert!(!read(Scheme::Ts1, Limiter) && !read(Scheme::Pm, Limiter));
        assert!(Scheme::Pm.reads(Limiter, EffectSet::MUSCL).is_ok());
        assert!(!read(Scheme::Av, Riemann) && read(Scheme::Pm, Riemann));
        assert!(read(Scheme::Ts2, MusclTime) && !read(Scheme::Ts1, MusclTime));
        assert!(read(Scheme::Ts1, SurfaceLambda) && read(Scheme::Tkc, DetEpsilon));
        assert!(!read(Scheme::Pm, SurfaceLambda));
        assert!(Scheme::Pm
            .reads(SurfaceLambda, EffectSet::CORRECTION)
            .is_ok());
        assert!(read(Scheme::Pm, Correction) && !read(Scheme::Tkc, Muscl));
        for s in Scheme::ALL {
            assert!(read(s, ArtificialStress) && read(s, ArtificialStressExponent));
        }
        let mut buf = [0u8; 128];
        let msg = |e: NotRead, buf: &mut [u8; 128]| {
            use core::fmt::Write;
            struct W<'a>(&'a mut [u8], usize);
            impl Write for W<'_> {
                fn write_str(&mut self, s: &str) -> fmt::Result {
                    self.0[self.1..self.1 + s.len()].copy_from_slice(s.as_bytes());
                    self.1 += s.len();
                    Ok(())
                }
            }
            let mut w = W(buf, 0);
            write!(w, "{e}").unwrap();
            let n = w.1;
            core::str::from_utf8(&buf[..n]).unwrap() == "not read by scheme ts1 (it has no MUSCL reconstruction; ts2, tkc and pm with options.muscl have)"
        };
        assert!(msg(Scheme::Ts1.reads(Limiter, none).unwrap_err(), &mut buf));
    }

    #[test]
    fn tkc_defaults_to_minmod_and_a_scene_key_overrides_it() {
        let none = SceneOptions::default();
        assert_eq!(none.resolve(Scheme::Tkc, false).limiter, Limiter::Minmod);
        assert_eq!(none.resolve(Scheme::Ts2, false).limiter, Limiter::Superbee);
        let vl = SceneOptions {
            limiter: Some(Limiter::VanLeer),
            ..none
        };
        assert_eq!(vl.resolve(Scheme::Tkc, true).limiter, Limiter::VanLeer);
        assert!(vl.resolve(Scheme::Tkc, true).constant_h);
    }
}
