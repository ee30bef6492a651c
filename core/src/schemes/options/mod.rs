//! A scene's `[options]`, declared once: the table [`scheme_options!`](crate::scheme_options)
//! gives each option's key, type, default, unit, range, the families that read it, the
//! reason the others give, and its doc line. Generated from it: the keys
//! ([`OptionKey`], their paths, docs, units, ranges and values), the options as a scene
//! gives them ([`SceneOptions`]: its fields and serde reading, `is_set`, `unset`, `number`,
//! `apply`), the options a step runs with ([`SchemeOptions`] and its defaults), and in the
//! host the range checks of a scene and the scene-key reference (`docs/scene-keys.md`).
//! Promise 3 (a key either changes the result or is refused, naming the key and the
//! scheme): the table says which families read a key; a family that reads it only with
//! some effects, or refuses it with a reason of its own, says so in its `options.rs`
//! ([`crate::schemes::Scheme::reads`]).
//!
//! # Adding an option
//!
//! A row in the table; an arm in the `options.rs` of a family that reads it only under a
//! condition; its physics; and wherever the lanes of a family that reads it must
//! implement or decline it (each `lanes.rs`' `covers` names every option, so the build
//! says where).

mod values;

pub use values::{
    EnergyEquation, Integrator, MusclTime, OptionType, Range, RiemannSolver, SpecificVolume,
};

use super::scheme::{Family, Scheme};
use crate::effects::EffectSet;
use crate::limiter::Limiter;
use crate::math::Real;
use crate::riemann::Dissipation;
use core::fmt;

/// Calls `$cb! { ROWS }` with the table of scheme options, one row each:
///
/// ```text
/// key: Type = default, Variant, "unit", range, [families], why, "doc";
/// ```
///
/// - `key`: the scene key (`options.key`) and the field of [`SceneOptions`] and
///   [`SchemeOptions`]; `Variant`: its [`OptionKey`];
/// - `Type`: an [`OptionType`] (a number, an integer, a flag or a named choice); `default`:
///   the value a run starts from (a family may start some schemes elsewhere:
///   [`crate::schemes::Scheme::default_options`]);
/// - `unit`: the SI unit (`"1"`: dimensionless, `""`: not a quantity); `range`: a
///   [`Range`] for numbers (`Any` otherwise);
/// - `families`: the scheme families that read the key ([`Family`]); a family's
///   `options.rs` may narrow that (read only with some effects) or give its own reason;
/// - `why`: the reason the other families give (a constant of the module `why`, or `ONLY_PM`);
/// - `doc`: one line for the docs and the reference.
///
/// The table's order is the order in which a scene's keys are checked.
#[macro_export]
macro_rules! scheme_options {
    ($cb:ident) => {
        $cb! {
            av_alpha: Real = 1.0, AvAlpha, "1", NonNegative, [Av], AV_ONLY,
                "Monaghan's artificial viscosity alpha (the linear, bulk term)";
            av_beta: Real = 1.0, AvBeta, "1", NonNegative, [Av], AV_ONLY,
                "Monaghan's artificial viscosity beta (the quadratic, shock term)";
            limiter: Limiter = Limiter::Superbee, Limiter, "", Any, [Pm, Ts], NO_MUSCL,
                "Slope limiter of the MUSCL reconstruction (tkc starts from minmod, Rublev & Murzov's)";
            riemann: RiemannSolver = RiemannSolver::Acoustic, Riemann, "", Any, [Pm, Ts], NO_RIEMANN,
                "Riemann solver of the pairs: linearised acoustic, or Dukowicz's two-shock solver (pm, tkc: the longitudinal wave)";
            dissipation: Dissipation = Dissipation::Full, Dissipation, "", Any, [Pm, Ts, Tl], NO_RIEMANN,
                "Where the Riemann solver's dissipation acts: on every pair, or only where a pair compresses";
            transverse_dissipation: Dissipation = Dissipation::Full, TransverseDissipation, "", Any, [Pm], NO_TRANSVERSE,
                "Where the transverse Riemann problems' dissipation acts, on top of `dissipation`";
            objective: bool = true, Objective, "", Any, [Pm], NO_TRANSVERSE,
                "The transverse Riemann problems see a pair's velocity jump less its rigid rotation, so a rigid rotation is not dissipated";
            corrected_slopes: bool = false, CorrectedSlopes, "", Any, [Pm], NO_CORRECTED_SLOPES,
                "The MUSCL slopes of a free-surface particle corrected with its full L^-1 where L is invertible (the forces keep L = I there)";
            integrator: Integrator = Integrator::Euler, Integrator, "", Any, [Pm, Ts], OWN_INTEGRATOR,
                "Time integration: the seeds' (first order), or av's predictor-corrector leap-frog (second order)";
            muscl_time: MusclTime = MusclTime::None, MusclTime, "", Any, [Ts], NO_MUSCL_TIME,
                "How ts2's reconstruction accounts for the time step (Connolly et al. 2013, eq 23): none, a MUSCL-Hancock predictor, or a Courant factor";
            surface_lambda: Real = 0.75, SurfaceLambda, "1", Positive, [Pm, Ts], NO_SURFACE,
                "Smallest eigenvalue of the correction matrix L below which a particle is a free-surface particle";
            surface_scan: bool = false, SurfaceScan, "", Any, [Pm], NO_SCAN,
                "A particle below `surface_lambda` is a free-surface particle only if the umbrella scan finds its neighbourhood open";
            specific_volume: SpecificVolume = SpecificVolume::Product, SpecificVolume, "", Any, [Pm], NO_SPECIFIC_VOLUME,
                "The specific volumes of the pair force: the seeds' 1/(rho_i rho_j), or Sugiura & Inutsuka's interpolation";
            det_epsilon: Real = 0.05, DetEpsilon, "1", NonNegative, [Pm, Ts, Tl], NO_SURFACE,
                "L is not inverted where det L is below this";
            energy_equation: EnergyEquation = EnergyEquation::Internal, EnergyEquation, "", Any, [Pm], NO_ENERGY_EQUATION,
                "pm's energy equation: the seed's internal-energy rate at the start-of-step velocity, or the total-energy rate (exact total energy; tkc's)";
            correction: bool = false, Correction, "", Any, [Pm], ONLY_PM,
                "Kernel gradient correction for scheme pm (tkc always has it)";
            muscl: bool = false, Muscl, "", Any, [Pm], ONLY_PM,
                "MUSCL reconstruction for scheme pm (tkc always has it)";
            artificial_stress: Real = 0.3, ArtificialStress, "1", Positive, [Av, Pm, Ts], EVERY_SCHEME,
                "Monaghan's artificial stress against the tensile instability: its epsilon (at most 1; setting it turns the effect on)";
            hourglass: Real = 1.0, Hourglass, "1", Positive, [Pm, Ts, Tl], NO_HOURGLASS,
                "The hourglass stiffness of solids, non-dissipative and stored: its xi (stiffness xi G V/h^2 on each particle's displacement from its neighbours' affine motion; setting it turns the effect on; tl always has its own, on each pair's error of the F-predicted separation)";
            reference_update: Real = 0.0, ReferenceUpdate, "1", NonNegative, [Tl], NO_REFERENCE,
                "tl's updated reference: the reference configuration is re-based on the current one after a step in which some pair's stretch |r/R - 1| exceeds this (0: never)";
            artificial_stress_exponent: u32 = 4, ArtificialStressExponent, "", Any, [Av, Pm, Ts], EVERY_SCHEME,
                "The exponent n of the artificial stress's factor f_ij^n (1 to 16)";
        }
    };
}

/// The refusal of a family outside a row's families.
macro_rules! refusal {
    ($scheme:expr, ONLY_PM) => {
        NotRead::OnlyPm { scheme: $scheme }
    };
    ($scheme:expr, $why:ident) => {
        NotRead::Because {
            scheme: $scheme,
            why: why::$why,
        }
    };
}

/// Everything the table gives (module docs).
macro_rules! options_from_table {
    ($($key:ident: $ty:ty = $default:expr, $variant:ident, $unit:literal, $range:ident,
        [$($fam:ident),*], $why:ident, $doc:literal;)*) => {
        /// A key of a scene's `[options]` table (a row of [`scheme_options!`](crate::scheme_options)).
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
        pub enum OptionKey {
            $(
                #[doc = concat!("`options.", stringify!($key), "`: ", $doc, ".")]
                $variant,
            )*
        }

        impl OptionKey {
            /// Every key, in the table's order (the order a scene's keys are checked).
            pub const ALL: [OptionKey; [$(stringify!($key)),*].len()] = [$(OptionKey::$variant),*];

            /// The key's name in `[options]` (`limiter`).
            pub const fn name(self) -> &'static str {
                match self {
                    $(OptionKey::$variant => stringify!($key),)*
                }
            }

            /// The key's path in a scene (`options.limiter`).
            pub const fn path(self) -> &'static str {
                match self {
                    $(OptionKey::$variant => concat!("options.", stringify!($key)),)*
                }
            }

            /// The key of a name in `[options]`.
            pub fn from_name(name: &str) -> Option<OptionKey> {
                OptionKey::ALL.into_iter().find(|k| k.name() == name)
            }

            /// The table's doc line.
            pub const fn doc(self) -> &'static str {
                match self {
                    $(OptionKey::$variant => $doc,)*
                }
            }

            /// The SI unit (`"1"`: dimensionless, `""`: not a quantity).
            pub const fn unit(self) -> &'static str {
                match self {
                    $(OptionKey::$variant => $unit,)*
                }
            }

            /// Where a number must lie.
            pub const fn range(self) -> Range {
                match self {
                    $(OptionKey::$variant => Range::$range,)*
                }
            }

            /// The values a scene may give.
            pub const fn values(self) -> &'static str {
                match self {
                    $(OptionKey::$variant => <$ty as OptionType>::VALUES,)*
                }
            }

            /// The families that read the key (a family may narrow it by effects).
            pub const fn families(self) -> &'static [Family] {
                match self {
                    $(OptionKey::$variant => &[$(Family::$fam),*],)*
                }
            }

            /// The table's answer for `scheme`: read if its family is in the row, otherwise
            /// refused with the row's reason.
            pub(crate) fn table_reads(self, scheme: Scheme) -> Result<(), NotRead> {
                if self.families().contains(&scheme.family()) {
                    return Ok(());
                }
                Err(match self {
                    $(OptionKey::$variant => refusal!(scheme, $why),)*
                })
            }
        }

        /// A scene's `[options]` as given: `None` for a key it does not set. With the
        /// feature `serde` it reads from the scene's `[options]` table (the named choices
        /// parsed there, an unknown one refused with the known ones).
        #[derive(Clone, Copy, Debug, Default, PartialEq)]
        #[cfg_attr(
            feature = "serde",
            derive(serde::Deserialize, serde::Serialize),
            serde(default, deny_unknown_fields)
        )]
        pub struct SceneOptions {
            $(
                #[doc = concat!($doc, ".")]
                pub $key: Option<$ty>,
            )*
        }

        impl SceneOptions {
            /// Whether the scene sets `key`.
            pub const fn is_set(&self, key: OptionKey) -> bool {
                match key {
                    $(OptionKey::$variant => self.$key.is_some(),)*
                }
            }

            /// Removes `key` from the scene's options.
            pub fn unset(&mut self, key: OptionKey) {
                match key {
                    $(OptionKey::$variant => self.$key = None,)*
                }
            }

            /// The value the scene gives `key` as a number, where it sets it and it is one.
            pub fn number(&self, key: OptionKey) -> Option<Real> {
                match key {
                    $(OptionKey::$variant => self.$key.and_then(OptionType::number),)*
                }
            }

            /// Every key the scene sets, written over `o`.
            pub fn apply(&self, o: &mut SchemeOptions) {
                $(
                    if let Some(v) = self.$key {
                        o.$key = v;
                    }
                )*
            }
        }

        /// The options a step runs with: the table's defaults ([`Default`]), a scheme's
        /// own choices ([`crate::schemes::Scheme::default_options`]) and the scene's keys
        /// ([`SceneOptions::apply`]).
        #[derive(Clone, Copy, Debug, PartialEq)]
        pub struct SchemeOptions {
            $(
                #[doc = concat!($doc, " (`options.", stringify!($key), "`).")]
                pub $key: $ty,
            )*
            /// Keep every particle's smoothing length as it starts (the scene's top-level
            /// `constant_h`: the peers' colliding rings, codes with a fixed h); otherwise
            /// `h = h_factor (m/rho)^(1/D)` after each step.
            pub constant_h: bool,
        }

        impl Default for SchemeOptions {
            fn default() -> Self {
                SchemeOptions {
                    $($key: $default,)*
                    constant_h: false,
                }
            }
        }

        impl SchemeOptions {
            /// The value of `key`, in the scene's form.
            pub fn value(&self, key: OptionKey) -> impl fmt::Display + '_ {
                struct V<'a>(&'a SchemeOptions, OptionKey);
                impl fmt::Display for V<'_> {
                    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                        match self.1 {
                            $(OptionKey::$variant => fmt::Display::fmt(&self.0.$key, f),)*
                        }
                    }
                }
                V(self, key)
            }
        }
    };
}

crate::scheme_options!(options_from_table);

impl SceneOptions {
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
    pub const NO_ENERGY_EQUATION: &str =
        "its energy equation is fixed; pm chooses (tkc and pm with correction book the total energy)";
    pub const TOTAL_WITH_CORRECTION: &str =
        "with kernel correction it always books the total energy (Rublev & Murzov eq 11)";
    pub const NO_SPECIFIC_VOLUME: &str =
        "its pair force's specific volumes are not interpolated; pm and tkc interpolate them";
    pub const NO_SURFACE: &str =
        "it has no free-surface rule; ts1, ts2, tkc and pm with options.correction have";
    pub const NO_HOURGLASS: &str = "it has no hourglass stiffness; pm, tkc, ts1, ts2 and tl have";
    pub const NO_REFERENCE: &str =
        "its kernel and neighbours follow the particles: it has no reference configuration to update; tl has";
    /// The reason of a key every family reads (never given).
    pub const EVERY_SCHEME: &str = "every scheme reads it";
}

/// `Err(NotRead::Because { scheme, why })` unless `read`.
pub(crate) fn read_if(read: bool, scheme: Scheme, why: &'static str) -> Result<(), NotRead> {
    if read {
        Ok(())
    } else {
        Err(NotRead::Because { scheme, why })
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
            // every scheme but tl, which has no tensile instability to delay
            let reads = read(s, ArtificialStress) && read(s, ArtificialStressExponent);
            assert_eq!(reads, s != Scheme::Tl, "{}", s.name());
            // the updated reference is tl's alone
            assert_eq!(read(s, ReferenceUpdate), s == Scheme::Tl, "{}", s.name());
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
