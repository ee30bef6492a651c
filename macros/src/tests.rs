//! Unit tests: the model's rules and counts, and the expansion snapshots in
//! `tests/expand/` (regenerate with `UPDATE_EXPAND=1 cargo test -p gsph-macros`).

use std::path::PathBuf;

use proc_macro2::TokenStream;
use quote::quote;

use crate::expand;
use crate::model::{EffectSet, Model};

/// `tests/expand/{name}`.
fn expand_dir(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("tests/expand")
        .join(name)
}

/// The tokens of the (single) `specialise!` invocation in `tests/expand/{name}.rs`.
fn invocation(name: &str) -> TokenStream {
    let src = std::fs::read_to_string(expand_dir(&format!("{name}.rs"))).unwrap();
    let file = syn::parse_file(&src).unwrap();
    file.items
        .into_iter()
        .find_map(|item| match item {
            syn::Item::Macro(m) => Some(m.mac.tokens),
            _ => None,
        })
        .expect("no macro invocation")
}

fn model(name: &str) -> Model {
    syn::parse2(invocation(name)).unwrap()
}

/// The pretty-printed expansion of `tests/expand/{name}.rs`.
fn pretty(name: &str) -> String {
    let file: syn::File = syn::parse2(expand::specialise(invocation(name))).unwrap();
    let header = format!(
        "// Expansion of tests/expand/{name}.rs, pretty-printed by prettyplease.\n\
         // Regenerate with `UPDATE_EXPAND=1 cargo test -p gsph-macros`.\n"
    );
    header + &prettyplease::unparse(&file)
}

fn check_snapshot(name: &str) {
    let path = expand_dir(&format!("{name}.expanded.rs"));
    let actual = pretty(name);
    if std::env::var_os("UPDATE_EXPAND").is_some_and(|v| v == "1") || !path.exists() {
        std::fs::write(&path, &actual).unwrap();
        return;
    }
    let expected = std::fs::read_to_string(&path).unwrap();
    if expected != actual {
        let line = expected
            .lines()
            .zip(actual.lines())
            .position(|(a, b)| a != b);
        panic!(
            "{} differs from the expansion (first difference at line {}); \
             rerun with UPDATE_EXPAND=1 and review the diff",
            path.display(),
            line.map_or_else(|| "end".into(), |l| (l + 1).to_string()),
        );
    }
}

#[test]
fn snapshot_small() {
    check_snapshot("small");
}

#[test]
fn snapshot_gsph() {
    check_snapshot("gsph");
}

/// Set of the named effects.
fn set(m: &Model, names: &[&str]) -> EffectSet {
    let mut s = 0;
    for n in names {
        s |= 1 << m.effects.iter().position(|e| e.name == n).unwrap();
    }
    EffectSet(s)
}

fn family(m: &Model, name: &str) -> usize {
    m.families.iter().position(|f| f.name == name).unwrap()
}

/// The effect list gsph compiled before issue 26 (504 steps): a chain of `requires`
/// (plasticity needs strength; damage and heat need plasticity) and family-free effects,
/// kept to exercise the model's closure rules.
fn chain_model() -> Model {
    syn::parse2(quote! {
        dims: [1, 2, 3];
        families: [av => A, pm => P, ts => T];
        effects: [
            strength: STRENGTH feature "effects-strength",
            plasticity: PLASTICITY requires strength feature "effects-strength",
            damage: DAMAGE requires plasticity feature "effects-damage",
            heat: HEAT requires plasticity feature "effects-heat",
            correction: CORRECTION only [pm] feature "effects-correction",
            muscl: MUSCL only [pm, ts] feature "effects-muscl",
            periodic: PERIODIC feature "effects-periodic",
            artificial_stress: ARTIFICIAL_STRESS feature "effects-artificial-stress",
        ];
    })
    .unwrap()
}

#[test]
fn gsph_counts() {
    // strength on/off (2); per family the extras: av none (1), pm correction x muscl (4),
    // ts muscl (2), tl none (1). Sets valid for some family: 2 * 4 = 8. Step functions per
    // dimension: 2 * (1 + 4 + 2 + 1) = 16; over three dimensions 48.
    let m = model("gsph");
    assert_eq!(m.sets().len(), 8);
    let specs = m.specialisations();
    assert_eq!(specs.len(), 48);
    for d in 1..=3 {
        assert_eq!(specs.iter().filter(|s| s.dim == d).count(), 16);
    }
    for (f, n) in [("av", 2), ("pm", 8), ("ts", 4), ("tl", 2)] {
        let f = family(&m, f);
        assert_eq!(
            specs.iter().filter(|s| s.dim == 2 && s.family == f).count(),
            n
        );
    }
}

#[test]
fn chain_counts() {
    // Closed subsets of the material chain: hydro, s, s+p, s+p+damage, s+p+heat,
    // s+p+damage+heat = 6; times periodic on/off and artificial stress on/off = 24; per
    // family the extras as above: 24 * (1 + 4 + 2) = 168 per dimension, 504 in all.
    let m = chain_model();
    assert_eq!(m.sets().len(), 96);
    assert_eq!(m.specialisations().len(), 504);
}

#[test]
fn closure_and_validity() {
    let m = chain_model();
    let (av, pm, ts) = (family(&m, "av"), family(&m, "pm"), family(&m, "ts"));
    assert!(m.is_closed(set(&m, &[])));
    assert!(m.is_closed(set(&m, &["strength", "plasticity", "damage"])));
    assert!(!m.is_closed(set(&m, &["plasticity"])));
    assert!(!m.is_closed(set(&m, &["plasticity", "damage"])));
    assert!(!m.is_closed(set(&m, &["strength", "heat"])));
    assert!(m.sets().iter().all(|&s| m.is_closed(s)));

    let corr = set(&m, &["correction", "muscl"]);
    assert!(m.is_valid_for(corr, pm) && !m.is_valid_for(corr, ts) && !m.is_valid_for(corr, av));
    let muscl = set(&m, &["muscl", "periodic"]);
    assert!(m.is_valid_for(muscl, pm) && m.is_valid_for(muscl, ts) && !m.is_valid_for(muscl, av));
    assert!(
        !m.is_valid_for(set(&m, &["damage"]), pm),
        "not closed, so not valid"
    );
    assert_eq!(m.sets()[0], EffectSet(0), "hydro comes first");
}

#[test]
fn features_are_deduplicated() {
    let m = chain_model();
    let s = set(&m, &["strength", "plasticity", "heat", "periodic"]);
    assert_eq!(
        m.features(s),
        ["effects-strength", "effects-heat", "effects-periodic"]
    );
}

#[test]
fn generated_names() {
    let out = pretty("gsph");
    for item in [
        "pub struct FxHydro;",
        "pub struct FxStrengthCorrectionMuscl;",
        "pub fn step_1d_av_hydro<",
        "pub fn step_3d_ts_strength_muscl<",
        "pub fn select_2d<",
        "pub struct FxCorrection;",
        "features `dim2`, `scheme-pm`, `effects-strength`, `effects-correction` are enabled",
    ] {
        assert!(out.contains(item), "missing `{item}`");
    }
    for absent in [
        "fn step_2d_av_muscl<",
        "fn step_2d_ts_correction<",
        "FxPlasticity;",
        "fn step_2d_pm_strength_plasticity",
    ] {
        assert!(!out.contains(absent), "unexpected `{absent}`");
    }
}

#[test]
fn every_public_item_is_documented() {
    let file: syn::File = syn::parse2(expand::specialise(invocation("gsph"))).unwrap();
    let documented = |attrs: &[syn::Attribute]| attrs.iter().any(|a| a.path().is_ident("doc"));
    for item in &file.items {
        match item {
            syn::Item::Struct(s) => {
                assert!(documented(&s.attrs), "{}", s.ident);
                assert!(s.fields.iter().all(|f| documented(&f.attrs)), "{}", s.ident);
            }
            syn::Item::Fn(f) => assert!(documented(&f.attrs), "{}", f.sig.ident),
            syn::Item::Const(c) => assert!(documented(&c.attrs), "{}", c.ident),
            syn::Item::Impl(_) => {}
            other => panic!("unexpected item {}", quote!(#other)),
        }
    }
}

/// The error message for an input.
fn error(input: TokenStream) -> String {
    match syn::parse2::<Model>(input) {
        Ok(_) => panic!("accepted"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn validation_errors() {
    let fam = quote!(families: [pm => P];);
    assert_eq!(
        error(quote!(dims: [2]; #fam effects: [a: A requires b];)),
        "unknown effect `b`"
    );
    assert_eq!(
        error(quote!(dims: [2]; #fam effects: [a: A only [ts]];)),
        "unknown family `ts`"
    );
    assert_eq!(
        error(quote!(dims: [2]; #fam effects: [a: A, a: B];)),
        "duplicate effect `a`"
    );
    assert_eq!(
        error(quote!(dims: [2]; #fam effects: [a: A, b: A];)),
        "duplicate effect constant `A`"
    );
    assert_eq!(
        error(quote!(dims: [2]; families: [pm => P, pm => Q]; effects: [a: A];)),
        "duplicate family `pm`"
    );
    assert_eq!(
        error(quote!(dims: [2, 2]; #fam effects: [a: A];)),
        "duplicate dimension 2"
    );
    assert_eq!(
        error(quote!(dims: [4]; #fam effects: [a: A];)),
        "dimension 4 is not in 1..=3"
    );
    assert_eq!(
        error(quote!(dims: [0]; #fam effects: [a: A];)),
        "dimension 0 is not in 1..=3"
    );
    assert_eq!(
        error(quote!(dims: []; #fam effects: [a: A];)),
        "`dims` must not be empty"
    );
    assert_eq!(
        error(quote!(dims: [2]; families: []; effects: [a: A];)),
        "`families` must not be empty"
    );
    assert_eq!(
        error(quote!(dims: [2]; #fam effects: [];)),
        "`effects` must not be empty"
    );
    assert_eq!(
        error(quote!(dims: [2]; #fam effects: [a: A only []];)),
        "`only` must not be empty"
    );
    assert_eq!(error(quote!(dims: [2]; #fam)), "missing section `effects`");
    assert_eq!(
        error(quote!(dims: [2]; dims: [3]; #fam effects: [a: A];)),
        "duplicate section `dims`"
    );
    assert_eq!(
        error(quote!(dims: [2]; #fam effects: [a: A optional];)),
        "expected `requires`, `only` or `feature`, found `optional`"
    );
    assert_eq!(
        error(quote!(dims: [2]; #fam effects: [a: A feature "x" feature "y"];)),
        "duplicate `feature` clause"
    );
    assert_eq!(
        error(quote!(dims: [2]; #fam effects: [hydro: H];)),
        "`hydro` names the empty effect set"
    );
}

#[test]
fn requires_cycles_are_rejected() {
    let fam = quote!(families: [pm => P];);
    assert!(
        error(quote!(dims: [2]; #fam effects: [a: A requires a];)).starts_with("`requires` cycle")
    );
    let long =
        quote!(dims: [2]; #fam effects: [a: A requires c, b: B requires a, c: C requires b];);
    assert!(error(long).starts_with("`requires` cycle"));
    // A diamond is not a cycle.
    let effects = quote!([a: A, b: B requires a, c: C requires a, d: D requires [b, c]]);
    let diamond = quote!(dims: [2]; #fam effects: #effects;);
    let m: Model = syn::parse2(diamond).unwrap();
    assert_eq!(m.sets().len(), 6, "{{}}, a, ab, ac, abc, abcd");
}

/// The `gsph` snapshot is the invocation gsph-core really makes: a change to
/// core/src/dispatch.rs must be mirrored in tests/expand/gsph.rs (and the snapshot
/// regenerated), so the checked-in expansion never drifts from the code that runs.
#[test]
fn gsph_snapshot_input_matches_core_dispatch() {
    let strip = |s: &str| -> String {
        let start = s
            .find("gsph_macros::specialise!")
            .expect("invocation present");
        let body = &s[start..];
        let end = body.find("\n}").expect("closing brace") + 2;
        body[..end].split_whitespace().collect::<Vec<_>>().join(" ")
    };
    let core = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../core/src/dispatch.rs"),
    )
    .expect("core/src/dispatch.rs");
    let snap = std::fs::read_to_string(expand_dir("gsph.rs")).expect("tests/expand/gsph.rs");
    assert_eq!(strip(&core), strip(&snap));
}
