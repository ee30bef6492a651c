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

use super::{av, pm, ts, Scheme};
use crate::effects::EffectSet;
use crate::limiter::Limiter;
use crate::math::Real;
use crate::riemann::Dissipation;
use crate::state::{Family, MusclTime, RiemannSolver, SchemeOptions};
use core::fmt;

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
    pub integrator: Option<crate::state::Integrator>,
    /// Time treatment of the ts2 reconstruction.
    pub muscl_time: Option<MusclTime>,
    /// Free-surface eigenvalue threshold.
    pub surface_lambda: Option<Real>,
    /// The umbrella scan confirms each free-surface particle (tkc, pm with correction).
    pub surface_scan: Option<bool>,
    /// The specific volumes of the pair force (pm, tkc).
    pub specific_volume: Option<crate::state::SpecificVolume>,
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

    /// The first key the scene sets that `scheme` does not read, with the reason.
    pub fn first_not_read(&self, scheme: Scheme) -> Option<(OptionKey, NotRead)> {
        OptionKey::ALL.into_iter().find_map(|k| {
            if self.is_set(k) {
                scheme.reads(k, self.asked()).err().map(|why| (k, why))
            } else {
                None
            }
        })
    }

    /// The options a run of `scheme` steps with: the scheme's defaults
    /// ([`Scheme::default_options`]), then every key the scene sets.
    pub fn resolve(&self, scheme: Scheme, constant_h: bool) -> SchemeOptions {
        let mut o = scheme.default_options();
        let d = o;
        o.av_alpha = self.av_alpha.unwrap_or(d.av_alpha);
        o.av_beta = self.av_beta.unwrap_or(d.av_beta);
        o.limiter = self.limiter.unwrap_or(d.limiter);
        o.riemann = self.riemann.unwrap_or(d.riemann);
        o.dissipation = self.dissipation.unwrap_or(d.dissipation);
        o.transverse_dissipation = self
            .transverse_dissipation
            .unwrap_or(d.transverse_dissipation);
        o.objective = self.objective.unwrap_or(d.objective);
        o.corrected_slopes = self.corrected_slopes.unwrap_or(d.corrected_slopes);
        o.integrator = self.integrator.unwrap_or(d.integrator);
        o.muscl_time = self.muscl_time.unwrap_or(d.muscl_time);
        o.surface_lambda = self.surface_lambda.unwrap_or(d.surface_lambda);
        o.surface_scan = self.surface_scan.unwrap_or(d.surface_scan);
        o.specific_volume = self.specific_volume.unwrap_or(d.specific_volume);
        o.det_epsilon = self.det_epsilon.unwrap_or(d.det_epsilon);
        if let Some(eps) = self.artificial_stress {
            o.artificial_stress.epsilon = eps;
        }
        if let Some(n) = self.artificial_stress_exponent {
            o.artificial_stress.exponent = n;
        }
        o.constant_h = constant_h;
        o
    }
}

impl Scheme {
    /// Whether the scheme reads `key` when the scene's `correction`/`muscl` ask for
    /// `asked`, or why not (its family answers).
    pub fn reads(self, key: OptionKey, asked: EffectSet) -> Result<(), NotRead> {
        match self.family() {
            Family::Av => av::reads(self, key),
            Family::Pm => pm::reads(self, key, self.effects().union(asked)),
            Family::Ts => ts::reads(self, key),
        }
    }

    /// The options before a scene's keys: the seeds' defaults, with the family's choices
    /// per scheme name (tkc's minmod limiter).
    pub fn default_options(self) -> SchemeOptions {
        match self.family() {
            Family::Av => SchemeOptions::default(),
            Family::Pm => pm::defaults(self),
            Family::Ts => SchemeOptions::default(),
        }
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
