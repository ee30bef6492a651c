//! The step specialisations compiled into this build ([`gsph_core::dispatch::CATALOGUE`])
//! and the Cargo features that select one, for the message that refuses a scene a narrowed
//! build cannot run (docs/performance.md "Compile-time-selected builds").

use gsph_core::dispatch::{Specialisation, CATALOGUE};
use gsph_core::effects::EffectSet;
use gsph_core::schemes::Family;

/// The feature that compiles the specialisations containing each compiled effect, as
/// declared to `specialise!` in `core/src/dispatch.rs` (a unit test checks the two agree).
/// The run-time effects (plasticity, damage, heat, periodic, artificial stress) need none.
const EFFECT_FEATURES: [(EffectSet, &str); 3] = [
    (EffectSet::STRENGTH, "effects-strength"),
    (EffectSet::CORRECTION, "effects-correction"),
    (EffectSet::MUSCL, "effects-muscl"),
];

/// The name of a scheme family as in its `scheme-*` feature and step names.
pub fn family_name(family: Family) -> &'static str {
    match family {
        Family::Av => "av",
        Family::Pm => "pm",
        Family::Ts => "ts",
        Family::Tl => "tl",
    }
}

/// The Cargo features (of `gsph` and of `gsph-core`) that compile the specialisation of
/// `dim`, `family` and `effects` (moving window, a host-only effect, needs none).
pub fn features(dim: usize, family: Family, effects: EffectSet) -> Vec<&'static str> {
    let dim = match dim {
        1 => "dim1",
        2 => "dim2",
        _ => "dim3",
    };
    let family = match family {
        Family::Av => "scheme-av",
        Family::Pm => "scheme-pm",
        Family::Ts => "scheme-ts",
        Family::Tl => "scheme-tl",
    };
    let mut f = vec![dim, family];
    for (e, name) in EFFECT_FEATURES {
        if effects.contains(e) && !f.contains(&name) {
            f.push(name);
        }
    }
    f
}

/// The catalogue entry of `dim`, `family` and the kernel part of `effects`, if the family
/// supports those effects.
pub fn find(dim: usize, family: Family, effects: EffectSet) -> Option<&'static Specialisation> {
    let effects = effects.kernel_part();
    CATALOGUE
        .iter()
        .find(|s| s.dim == dim && s.family == family && s.effects == effects)
}

/// How many specialisations this build contains, and how many exist.
pub fn compiled() -> (usize, usize) {
    let n = CATALOGUE.iter().filter(|s| s.compiled).count();
    (n, CATALOGUE.len())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The effect → feature table above against the `specialise!` declaration.
    #[test]
    fn effect_features_match_the_dispatch_declaration() {
        let src = include_str!("../../core/src/dispatch.rs");
        for (e, feature) in EFFECT_FEATURES {
            let name = e.names().next().unwrap();
            let line = src
                .lines()
                .map(str::trim)
                .find(|l| l.starts_with(&format!("{name}:")))
                .unwrap_or_else(|| panic!("effect {name} not declared in dispatch.rs"));
            assert!(
                line.contains(&format!("feature \"{feature}\"")),
                "{name}: dispatch.rs says `{line}`, specs.rs says {feature}"
            );
        }
        // every declared effect is in the table
        let declared = src.lines().filter(|l| l.contains(" feature \"")).count();
        assert_eq!(declared, EFFECT_FEATURES.len());
    }

    /// A specialisation is compiled exactly when this crate's features include all of
    /// the ones [`features`] names for it (the host features forward to gsph-core's).
    #[test]
    fn compiled_matches_features() {
        let on = |f: &str| match f {
            "dim1" => cfg!(feature = "dim1"),
            "dim2" => cfg!(feature = "dim2"),
            "dim3" => cfg!(feature = "dim3"),
            "scheme-av" => cfg!(feature = "scheme-av"),
            "scheme-pm" => cfg!(feature = "scheme-pm"),
            "scheme-ts" => cfg!(feature = "scheme-ts"),
            "scheme-tl" => cfg!(feature = "scheme-tl"),
            "effects-strength" => cfg!(feature = "effects-strength"),
            "effects-muscl" => cfg!(feature = "effects-muscl"),
            "effects-correction" => cfg!(feature = "effects-correction"),
            _ => panic!("unknown feature {f}"),
        };
        for s in CATALOGUE {
            let f = features(s.dim, s.family, s.effects);
            assert_eq!(s.compiled, f.iter().all(|f| on(f)), "{} {f:?}", s.name);
            let prefix = format!("step_{}d_{}_", s.dim, family_name(s.family));
            assert!(s.name.starts_with(&prefix), "{}", s.name);
        }
    }

    /// Periodic boundaries and plasticity are run-time flags: the 2D periodic tkc run is
    /// the compiled `step_2d_pm_strength_correction_muscl`, five features.
    #[test]
    fn tkc_2d_periodic_needs_five_features() {
        let e = EffectSet::STRENGTH
            .union(EffectSet::PLASTICITY)
            .union(EffectSet::CORRECTION)
            .union(EffectSet::MUSCL)
            .union(EffectSet::PERIODIC);
        assert_eq!(
            features(2, Family::Pm, e),
            [
                "dim2",
                "scheme-pm",
                "effects-strength",
                "effects-correction",
                "effects-muscl"
            ]
        );
        let s = find(2, Family::Pm, e).expect("in the catalogue");
        assert_eq!(s.name, "step_2d_pm_strength_correction_muscl");
    }

    /// 3 dimensions × (av and tl: hydro, strength; ts: × MUSCL; pm: × MUSCL × correction).
    #[test]
    fn the_catalogue_holds_48_steps() {
        assert_eq!(CATALOGUE.len(), 3 * (2 + 4 + 8 + 2));
    }
}
