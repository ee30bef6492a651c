//! Tests of the material library, its resolution in scenes, and the refusal of arrays
//! where a table is expected.

use super::super::{parse, parse_settings, Scene};
use super::*;
use gsph_core::material::eos::{Eos, MieGruneisen, Tillotson};
use gsph_core::material::strength::JohnsonCook;
use gsph_core::material::Strength;
use std::path::PathBuf;

fn cases_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases")
}

fn read_case(rel: &str) -> String {
    let p = cases_dir().join(rel);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn parse_err(text: &str, overrides: &[&str]) -> String {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let e = parse(text, "scene.toml", &o).expect_err("scene should be rejected");
    assert!(!e.0.contains('\n'), "not one line: {e}");
    e.0
}

/// A 1D scene of one body of material `material`, with `materials` tables before it.
fn bar(materials: &str, material: &str) -> String {
    format!(
        "dim = 1\nscheme = \"ts1\"\nt_end = 1e-7\n{materials}\n[[bodies]]\nmaterial = \"{material}\"\n\
         shape = {{ type = \"segment\", min = 0.0, max = 0.01 }}\nspacing = 1e-3\n"
    )
}

#[test]
fn every_file_in_cases_materials_is_in_the_library_and_valid() {
    let mut files: Vec<String> = std::fs::read_dir(cases_dir().join("materials"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter_map(|n| n.strip_suffix(".toml").map(str::to_string))
        .collect();
    files.sort();
    let names: Vec<&str> = LIBRARY.iter().map(|e| e.name).collect();
    assert_eq!(
        files, names,
        "register every cases/materials/*.toml in LIBRARY (name order)"
    );
    for e in LIBRARY {
        assert!(
            e.name
                .bytes()
                .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_'),
            "{}: a name is lower case, digits and _",
            e.name
        );
        let t = table_of(e).unwrap();
        for k in ["name", "library", "include", "unset"] {
            assert!(
                !t.contains_key(k),
                "{}: a library file has no `{k}`",
                e.name
            );
        }
        assert_ne!(
            source_line(e),
            "(no source line)",
            "{}: `# source:` line",
            e.name
        );
        assert!(e.text.contains("Units SI"), "{}: say the units", e.name);
        // a body of it validates and builds
        let s = parse(&bar("", e.name), e.name, &[]).unwrap_or_else(|err| panic!("{err}"));
        assert_eq!(s.materials.len(), 1);
        assert_eq!(s.materials[0].name, e.name);
        assert_eq!(
            s.material_sources[0],
            format!("library {} (named by bodies[0].material)", e.name)
        );
    }
    let listing = list().unwrap();
    assert_eq!(listing.lines().count(), LIBRARY.len() + 2, "{listing}");
}

#[test]
fn a_body_takes_a_library_material_by_name() {
    let s = parse(&bar("", "steel_4340"), "scene.toml", &[]).unwrap();
    let m = &s.materials[0];
    assert_eq!(m.name, "steel_4340");
    assert_eq!(m.rho0, 7830.0);
    let Some(Strength::JohnsonCook(JohnsonCook { a, t_melt, .. })) = m.strength else {
        panic!("{m:?}")
    };
    assert_eq!((a, t_melt), (792.0e6, 1793.0));
    // a declared material of that name wins over the library
    let local =
        "[[materials]]\nname = \"steel_4340\"\nrho0 = 1.0\neos = { type = \"linear\", c0 = 1.0 }\n";
    let s = parse(&bar(local, "steel_4340"), "scene.toml", &[]).unwrap();
    assert_eq!(
        (s.materials[0].rho0, s.material_sources[0].as_str()),
        (1.0, "scene")
    );
}

#[test]
fn local_keys_override_the_library_key_by_key() {
    let t = "[[materials]]\nname = \"st\"\nlibrary = \"steel_4340\"\nrho0 = 7850.0\n\
             strength = { a = 800.0e6 }\neos = { gamma0 = 2.0 }\n";
    let s = parse(&bar(t, "st"), "scene.toml", &[]).unwrap();
    let m = &s.materials[0];
    assert_eq!(m.rho0, 7850.0);
    let Some(Strength::JohnsonCook(JohnsonCook { a, b, .. })) = m.strength else {
        panic!("{m:?}")
    };
    assert_eq!(
        (a, b),
        (800.0e6, 510.0e6),
        "a overridden, b from the library"
    );
    let Eos::MieGruneisen(MieGruneisen { c0, gamma0, .. }) = m.eos else {
        panic!("{m:?}")
    };
    assert_eq!((c0, gamma0), (4569.0, 2.0));
    assert_eq!(
        s.material_sources[0],
        "library steel_4340, with the scene's eos.gamma0, rho0, strength.a"
    );
    // a nested table of another type replaces the library's whole
    let t = "[[materials]]\nname = \"st\"\nlibrary = \"steel_4340\"\n\
             strength = { type = \"von_mises\", yield_stress = 1.0e9 }\n";
    let s = parse(&bar(t, "st"), "scene.toml", &[]).unwrap();
    assert!(matches!(
        s.materials[0].strength,
        Some(Strength::VonMises { yield_stress }) if yield_stress == 1.0e9
    ));
    // --set reaches into a library-based table the same way
    let t = "[[materials]]\nname = \"st\"\nlibrary = \"steel_4340\"\n";
    let e = parse_err(&bar(t, "st"), &["materials.0.strength.t_melt=200"]);
    assert_eq!(
        e,
        "--set materials.0.strength.t_melt=200: materials[0].strength.t_melt: must exceed t_room = 298 K (got 200)"
    );
    // the name defaults to the library's
    let s = parse(
        &bar("[[materials]]\nlibrary = \"sic\"\n", "sic"),
        "s.toml",
        &[],
    )
    .unwrap();
    assert_eq!(s.materials[0].name, "sic");
}

#[test]
fn unset_removes_library_keys() {
    let t = "[[materials]]\nname = \"cu\"\nlibrary = \"rublev_murzov_copper\"\nunset = [\"tensile_strength\"]\n";
    let s = parse(&bar(t, "cu"), "scene.toml", &[]).unwrap();
    assert_eq!(s.materials[0].tensile_strength, None);
    assert_eq!(
        s.material_sources[0],
        "library rublev_murzov_copper, without tensile_strength"
    );
    let bad = t.replace("[\"tensile_strength\"]", "[\"colour\"]");
    assert_eq!(
        parse_err(&bar(&bad, "cu"), &[]),
        "scene.toml: materials[0].unset: `colour` is not a key of the material it names"
    );
    let alone = "[[materials]]\nname = \"cu\"\nrho0 = 1.0\neos = { type = \"linear\", c0 = 1.0 }\nunset = [\"x\"]\n";
    assert!(parse_err(&bar(alone, "cu"), &[])
        .starts_with("scene.toml: materials[0].unset: removes keys"));
}

#[test]
fn unknown_library_names_are_one_line_with_close_names() {
    let t = "[[materials]]\nname = \"st\"\nlibrary = \"steel_434\"\n";
    assert_eq!(
        parse_err(&bar(t, "st"), &[]),
        format!(
            "scene.toml: materials[0].library: `steel_434` is not in the material library (close: steel_4340, connolly2013_steel; `gsph materials` lists all {})",
            LIBRARY.len()
        )
    );
    let m = "[[materials]]\nname = \"m\"\nrho0 = 1.0\neos = { type = \"linear\", c0 = 1.0 }\n";
    let e = parse_err(&bar(m, "coper"), &[]);
    assert!(
        e.starts_with("scene.toml: bodies[0].material: unknown material `coper` (known: m); in the material library: "),
        "{e}"
    );
    assert!(e.contains("ofhc_copper"), "{e}");
    assert_eq!(
        parse_err(&bar(m, "xyzzy"), &[]),
        "scene.toml: bodies[0].material: unknown material `xyzzy` (known: m)"
    );
    assert!(close_names("copper").contains(&"ofhc_copper"));
    assert!(close_names("Steel").contains(&"connolly2013_steel"));
    assert!(close_names("unobtainium").is_empty());
    let e = parse_err(&bar("[[materials]]\nlibrary = 3\n", "x"), &[]);
    assert!(
        e.starts_with("scene.toml: materials[0].library: expected the name"),
        "{e}"
    );
}

#[test]
fn unknown_keys_next_to_library_are_refused() {
    let t = "[[materials]]\nname = \"st\"\nlibrary = \"steel_4340\"\ncolour = 1\n";
    assert_eq!(
        parse_err(&bar(t, "st"), &[]),
        "scene.toml: materials[0].colour: unknown key (known: name, rho0, shear_modulus, poisson_ratio, eos, strength, tensile_strength, library, include, unset)"
    );
    let t = "[[materials]]\nname = \"st\"\nlibrary = \"steel_4340\"\nstrength = { colour = 1 }\n";
    assert!(parse_err(&bar(t, "st"), &[]).contains("materials[0].strength.colour: unknown key"));
    let both = "[[materials]]\nname = \"st\"\nlibrary = \"sic\"\ninclude = \"x.toml\"\n";
    assert!(parse_err(&bar(both, "st"), &[])
        .contains("materials[0]: give `library` or `include`, not both"));
}

#[test]
fn include_reads_a_file_beside_the_scene() {
    let dir = std::env::temp_dir().join(format!("gsph_library_{}", std::process::id()));
    std::fs::create_dir_all(dir.join("mats")).unwrap();
    std::fs::write(
        dir.join("mats/my_steel.toml"),
        "# my steel: the library's with another yield stress\nlibrary = \"steel_4340\"\nstrength = { a = 1.0e9 }\n",
    )
    .unwrap();
    std::fs::write(dir.join("mats/loop.toml"), "include = \"loop.toml\"\n").unwrap();
    let scene = dir.join("scene.toml");
    let text = bar(
        "[[materials]]\ninclude = \"mats/my_steel.toml\"\nrho0 = 7800.0\n",
        "my_steel",
    );
    std::fs::write(&scene, &text).unwrap();
    let s = crate::scene::load(&scene, &[]).unwrap();
    let m = &s.materials[0];
    assert_eq!((m.name.as_str(), m.rho0), ("my_steel", 7800.0));
    assert!(
        matches!(m.strength, Some(Strength::JohnsonCook(JohnsonCook { a, n, .. })) if a == 1.0e9 && n == 0.26)
    );
    assert_eq!(
        s.material_sources[0],
        "include mats/my_steel.toml (library steel_4340, with the scene's strength.a), with the scene's rho0"
    );
    for (inc, want) in [
        ("mats/none.toml", "materials[0].include: cannot read "),
        ("mats/loop.toml", "included files nest more than 8 deep"),
        ("/dev/zero", "cannot read /dev/zero: not a regular file"),
        ("mats", "mats: not a regular file"),
    ] {
        let t = bar(
            &format!("[[materials]]\nname = \"m\"\ninclude = \"{inc}\"\n"),
            "m",
        );
        std::fs::write(&scene, &t).unwrap();
        let e = crate::scene::load(&scene, &[]).unwrap_err().0;
        assert!(e.contains(want) && !e.contains('\n'), "{e}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn arrays_where_a_table_is_expected_are_refused() {
    let flyer = read_case("flyer_plate.toml");
    for (set, want) in [
        (
            "options=[0.0, 0.0]",
            "options: expected a table, found an array",
        ),
        ("output=[3]", "output: expected a table, found an array"),
        (
            "materials.0.eos=[\"hugoniot\", 5077.0, 1.2]",
            "materials[0].eos: expected a table, found an array",
        ),
        (
            "materials.0.strength=[\"von_mises\", 1e9]",
            "materials[0].strength: expected a table, found an array",
        ),
        (
            "bodies.0.shape=[\"segment\", 0.0, 0.005]",
            "bodies[0].shape: expected a table, found an array",
        ),
        (
            "reference=[]",
            "reference: expected a table, found an array",
        ),
        (
            "monitor=[true]",
            "monitor: expected a table, found an array",
        ),
        (
            "periodic=[[0], [0.0], [1.0]]",
            "periodic: expected a table, found an array",
        ),
        (
            "materials.0=[\"metal\", 6100.0]",
            "materials[0]: expected a table, found an array",
        ),
    ] {
        assert_eq!(parse_err(&flyer, &[set]), format!("--set {set}: {want}"));
    }
    // in the file too, and as an array of tables
    let text = flyer.replace(
        "[output]\nsnapshots = 10",
        "options = [0.0, 0.0]\n[output]\nsnapshots = 10",
    );
    assert_eq!(
        parse_err(&text, &[]),
        "scene.toml: options: expected a table, found an array"
    );
    let text = flyer.replace("[output]", "[[output]]");
    assert_eq!(
        parse_err(&text, &[]),
        "scene.toml: output: expected a table, found an array"
    );
    // arrays where arrays belong still parse
    parse(
        &flyer,
        "flyer.toml",
        &["bodies.0.velocity.value=[1.0]".into()],
    )
    .unwrap();
}

// ---- the scenes in cases/ ----

/// Scene settings without bodies, to read frozen `[[materials]]` tables as a scene would.
fn materials_of(tables: &str) -> String {
    let text = format!("dim = 1\nscheme = \"ts1\"\nt_end = 1e-7\n{tables}");
    let s = parse_settings(&text, "frozen", &[]).unwrap_or_else(|e| panic!("{e}"));
    format!("{:?}", s.materials)
}

/// The `[[materials]]` tables the converted scenes had before the library, as they were
/// written (`git show c4c9f7d:cases/...`), so that a library edit cannot silently change
/// a validated case.
const STEEL: &str = r#"[[materials]]
name = "steel"
rho0 = 7903.0
shear_modulus = 74.8e9
eos = { type = "mie_gruneisen", c0 = 4552.0, s1 = 1.4933, gamma0 = 2.2 }
strength = { type = "johnson_cook", a = 300.0e6, b = 1000.0e6, n = 0.65, c = 0.07, m = 1.0, t_room = 298.0, t_melt = 1673.0, specific_heat = 440.0, taylor_quinney = 0.9 }
"#;
const SIC: &str = r#"[[materials]]
name = "sic"
rho0 = 3215.0
shear_modulus = 193.0e9
eos = { type = "polynomial", k1 = 220.0e9, k2 = 361.0e9, k3 = 0.0 }
strength = { type = "jh1", sigma_i1 = 7.1e9, p1 = 2.5e9, sigma_i2 = 12.2e9, p2 = 10.0e9, sigma_f_max = 1.3e9, c_f = 0.4, tensile_limit = -0.75e9, eps_f_max = 0.8, p_max = 99.75e9, c = 0.009 }
"#;
const COPPER: &str = r#"[[materials]]
name = "copper"
rho0 = 8960.0
shear_modulus = 43.0e9
eos = { type = "two_curve", c_a = 3930.0, s_a = 1.5, gamma = 1.7 }
strength = { type = "von_mises", yield_stress = 0.35e9 }
"#;
const CUT_OFF: &str = "tensile_strength = 0.35e9\n";
const RIEMANN_AL: &str = r#"[[materials]]
name = "aluminium"
rho0 = 2688.9
shear_modulus = 23.0e9
eos = { type = "logarithmic", bulk_modulus = 73.0e9 }
strength = { type = "von_mises", yield_stress = 0.3e9 }
"#;
const BERYLLIUM: &str = r#"[[materials]]
name = "beryllium"
rho0 = 1845.0
shear_modulus = 15.1e9
eos = { type = "mie_gruneisen", c0 = 12870.0, s1 = 1.124, gamma0 = 2.0 }
strength = { type = "von_mises", yield_stress = 330.0e6 }
"#;
const SOUND_CU: &str = r#"[[materials]]
name = "copper"
rho0 = 8960.0
poisson_ratio = 0.33
eos = { type = "linear", c0 = 4148.0 }
strength = { type = "elastic" }
"#;
const VERNEY_AL: &str = r#"[[materials]]
name = "aluminium"
rho0 = 2785.0
shear_modulus = 27.6e9
eos = { type = "linear", c0 = 5328.0, gamma = 2.0 }
strength = { type = "von_mises", yield_stress = 0.3e9 }
"#;
const FLYER_METAL: &str = r#"[[materials]]
name = "metal"
rho0 = 6100.0
shear_modulus = 48.1e9
eos = { type = "hugoniot", c0 = 5077.0, s1 = 1.201 }
strength = { type = "von_mises", yield_stress = 2.5e9 }
"#;

/// Every scene that uses the library resolves to exactly the materials it had before
/// (names, order and every value, bit for bit; `poisson_ratio` resolved the same way), and
/// the frozen texts agree with the library entries they came from.
#[test]
fn cases_resolve_to_their_pre_library_materials() {
    let aluminium_mg = r#"[[materials]]
name = "aluminium"
rho0 = 2700.0
shear_modulus = 26.0e9
eos = { type = "mie_gruneisen", c0 = 5350.0, s1 = 1.34, gamma0 = 2.0 }
strength = { type = "von_mises", yield_stress = 0.3e9 }
"#;
    let soft = r#"[[materials]]
name = "soft"
rho0 = 1000.0
shear_modulus = 0.1e9
eos = { type = "mie_gruneisen", c0 = 1290.0, s1 = 1.5, gamma0 = 1.0 }
strength = { type = "von_mises", yield_stress = 20.0e6 }
"#;
    let copper_t = format!("{COPPER}{CUT_OFF}");
    let steel_sic = format!("{STEEL}{SIC}");
    let cases: Vec<(&str, String)> = vec![
        ("porous_cu_piston.toml", copper_t.clone()),
        ("porous_cu_window.toml", copper_t.clone()),
        ("riemann_al_2d.toml", RIEMANN_AL.into()),
        ("ring_collapse.toml", BERYLLIUM.into()),
        ("sound_cu.toml", SOUND_CU.into()),
        ("sound_cu_2d.toml", SOUND_CU.into()),
        ("steel_sic_impact_3d.toml", steel_sic.clone()),
        ("verney_al.toml", VERNEY_AL.into()),
        ("hard/impact_3d.toml", format!("{STEEL}{aluminium_mg}")),
        ("hard/impedance_mismatch.toml", format!("{STEEL}{soft}")),
        ("hard/near_pair.toml", COPPER.into()),
        ("hard/pore_collapse_500.toml", copper_t),
        ("hard/spall_plate.toml", COPPER.into()),
        ("hard/steel_sic_800.toml", steel_sic.clone()),
        ("hard/steel_sic_2000.toml", steel_sic.clone()),
        // (written out until host/tests/cli_errors.rs anchored its edits on `name = "…"`)
        ("flyer_plate.toml", FLYER_METAL.into()),
        ("riemann_al.toml", RIEMANN_AL.into()),
        ("steel_sic_impact.toml", steel_sic),
    ];
    for (case, frozen) in &cases {
        let s = parse(&read_case(case), case, &[]).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(format!("{:?}", s.materials), materials_of(frozen), "{case}");
    }
    let libs = [
        (FLYER_METAL, "connolly2013_flyer_metal"),
        (RIEMANN_AL, "rublev_murzov_riemann_aluminium"),
        (STEEL, "connolly2013_steel"),
        (SIC, "sic"),
    ];
    for (frozen, lib) in libs {
        let name = frozen.lines().nth(1).unwrap();
        let via = format!("[[materials]]\n{name}\nlibrary = \"{lib}\"\n");
        assert_eq!(materials_of(&via), materials_of(frozen), "{lib}");
    }
}

/// Every scene in cases/ and cases/hard/ against its text before the library, whole (not
/// only its materials): `GSPH_CASES_BEFORE=DIR` names a copy of the old cases/ (e.g.
/// `git archive c4c9f7d cases | tar -x -C /tmp/before`, DIR = /tmp/before/cases).
#[test]
#[ignore = "needs GSPH_CASES_BEFORE"]
fn cases_resolve_to_the_scenes_they_were() {
    let before = PathBuf::from(std::env::var("GSPH_CASES_BEFORE").expect("GSPH_CASES_BEFORE"));
    let mut n = 0;
    for sub in ["", "hard"] {
        for e in std::fs::read_dir(before.join(sub)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_none_or(|x| x != "toml") {
                continue;
            }
            let rel = Path::new(sub).join(p.file_name().unwrap());
            let rel = rel.to_str().unwrap();
            let whole = |text: &str| {
                let mut s: Scene = parse(text, rel, &[]).unwrap_or_else(|e| panic!("{e}"));
                s.material_sources.clear();
                format!("{s:?}")
            };
            let old = std::fs::read_to_string(&p).unwrap();
            assert_eq!(whole(&read_case(rel)), whole(&old), "{rel}");
            n += 1;
        }
    }
    assert_eq!(n, 21);
}

#[test]
fn al_tillotson_is_a_tillotson_fluid_and_bad_tillotson_parameters_are_refused() {
    let s = parse(&bar("", "al_tillotson"), "scene.toml", &[]).unwrap();
    let m = &s.materials[0];
    assert_eq!(model_summary(m), "tillotson + fluid");
    let Eos::Tillotson(Tillotson {
        big_a, e_iv, e_cv, ..
    }) = m.eos
    else {
        panic!("{m:?}")
    };
    assert_eq!((big_a, e_iv, e_cv), (75.2e9, 3.0e6, 13.9e6));
    // the scene EOS becomes the core one: P(rho0, 0) = 0, c0² = A/rho0
    let core = crate::scene::materials::material_of(m);
    assert!(matches!(core.eos, gsph_core::material::Eos::Tillotson(_)));
    let st = core.eos.eval(2700.0, 0.0);
    assert_eq!((st.p, st.c2), (0.0, 75.2e9 / 2700.0));
    // bad parameters: one line naming the key
    let lib = |eos: &str| {
        format!("[[materials]]\nname = \"al\"\nlibrary = \"al_tillotson\"\neos = {{ {eos} }}\n")
    };
    assert_eq!(
        parse_err(&bar(&lib("e_cv = 2.0e6"), "al"), &[]),
        "scene.toml: materials[0].eos.e_cv: must exceed e_iv = 3e6 J/kg (got 2e6)"
    );
    assert_eq!(
        parse_err(&bar(&lib("e_cv = 3.0e6"), "al"), &[]),
        "scene.toml: materials[0].eos.e_cv: must exceed e_iv = 3e6 J/kg (got 3e6)"
    );
    assert_eq!(
        parse_err(&bar(&lib("big_a = -1.0e9"), "al"), &[]),
        "scene.toml: materials[0].eos.big_a: must be positive and finite (got -1e9)"
    );
    assert_eq!(
        parse_err(&bar(&lib("e0 = 0.0"), "al"), &[]),
        "scene.toml: materials[0].eos.e0: must be positive and finite (got 0)"
    );
    assert_eq!(
        parse_err(&bar(&lib("alpha = -5.0"), "al"), &[]),
        "scene.toml: materials[0].eos.alpha: must be non-negative and finite (got -5)"
    );
}
