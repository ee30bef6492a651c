//! The numerical schemes. Each family lives in its own module with the same shape
//! (passes over pairs, then per-particle updates) and implements [`SchemeFamily`]; the
//! driver and the generated dispatch table (`crate::dispatch`) know only the trait.
//!
//! | CLI name | family | effects added by the name | seed |
//! | --- | --- | --- | --- |
//! | `av`  | [`av::Av`] | – | 000 §4 |
//! | `pm`  | [`pm::Pm`] | – | 000 §3.2 |
//! | `tkc` | [`pm::Pm`] | correction + MUSCL (minmod) | 004 §1–2 |
//! | `ts1` | [`ts::Ts`] | – | 000 §3.3–3.4 |
//! | `ts2` | [`ts::Ts`] | MUSCL (limiter selectable) | 000 §3.3.1 |
//! | `tl`  | [`tl::Tl`] | reference configuration | issue 47 (Lee et al. 2019) |

// Per-particle updates index several structure-of-arrays slices with one index.
#![allow(clippy::needless_range_loop)]

pub mod artificial_stress;
pub mod av;
pub(crate) mod common;
pub mod family;
pub mod hourglass;
pub(crate) mod leapfrog;
pub mod options;
pub(crate) mod pairs;
pub mod pm;
pub mod scheme;
#[cfg(all(test, target_arch = "x86_64", not(feature = "f32")))]
mod star_tests;
pub mod tl;
pub mod ts;
pub mod workspace;

pub use av::records::AvRates;
pub use family::{SchemeFamily, StepFn};
pub use options::{
    EnergyEquation, Integrator, MusclTime, NotRead, OptionKey, RiemannSolver, SceneOptions,
    SchemeOptions, SpecificVolume,
};
pub use pm::records::PmStar;
pub use scheme::{Family, Scheme};
pub use ts::records::TsStar;
pub use workspace::{record_len, Layout, StepParams, Workspace};

use crate::effects::EffectSet;
use crate::halo::Exchange;

impl Family {
    /// The effects the family supports ([`SchemeFamily::SUPPORTED`]).
    pub const fn supported(self) -> EffectSet {
        match self {
            Family::Av => av::Av::SUPPORTED,
            Family::Pm => pm::Pm::SUPPORTED,
            Family::Ts => ts::Ts::SUPPORTED,
            Family::Tl => tl::Tl::SUPPORTED,
        }
    }

    /// The exchanges a step of the family makes, in order ([`SchemeFamily::EXCHANGES`]).
    pub const fn exchanges(self) -> &'static [Exchange] {
        match self {
            Family::Av => av::Av::EXCHANGES,
            Family::Pm => pm::Pm::EXCHANGES,
            Family::Ts => ts::Ts::EXCHANGES,
            Family::Tl => tl::Tl::EXCHANGES,
        }
    }

    /// The workspace arrays a step with `effects` and `options` needs
    /// ([`SchemeFamily::layout`]).
    pub fn layout(self, effects: EffectSet, options: &SchemeOptions) -> Layout {
        match self {
            Family::Av => av::Av::layout(effects, options),
            Family::Pm => pm::Pm::layout(effects, options),
            Family::Ts => ts::Ts::layout(effects, options),
            Family::Tl => tl::Tl::layout(effects, options),
        }
    }
}

impl SceneOptions {
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
    /// ([`Scheme::default_options`]), then every key the scene sets; `correction` and
    /// `muscl` say whether the run has the effect (the scheme's own or the scene's).
    pub fn resolve(&self, scheme: Scheme, constant_h: bool) -> SchemeOptions {
        let mut o = scheme.default_options();
        self.apply(&mut o);
        let effects = scheme.effects().union(self.asked());
        o.correction = effects.contains(EffectSet::CORRECTION);
        o.muscl = effects.contains(EffectSet::MUSCL);
        o.constant_h = constant_h;
        o
    }
}

impl Scheme {
    /// Whether the scheme reads `key` when the scene's `correction`/`muscl` ask for
    /// `asked`, or why not: its family's answer where it gives one (a key it reads only
    /// with some effects, or refuses for a reason of its own), else the options table's.
    pub fn reads(self, key: OptionKey, asked: EffectSet) -> Result<(), NotRead> {
        let family = match self.family() {
            Family::Av => av::reads(self, key),
            Family::Pm => pm::reads(self, key, self.effects().union(asked)),
            Family::Ts => ts::reads(self, key),
            Family::Tl => tl::reads(self, key),
        };
        family.unwrap_or_else(|| key.table_reads(self))
    }

    /// The options before a scene's keys: the table's defaults, with the family's choices
    /// per scheme name (tkc's minmod limiter, tl's det_epsilon).
    pub fn default_options(self) -> SchemeOptions {
        match self.family() {
            Family::Av => SchemeOptions::default(),
            Family::Pm => pm::defaults(self),
            Family::Ts => SchemeOptions::default(),
            Family::Tl => tl::defaults(),
        }
    }
}

#[cfg(test)]
mod tests;
