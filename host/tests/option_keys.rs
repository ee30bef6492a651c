//! Promise 3, table-driven: every `[options]` key, set to a value other than its default,
//! either changes the final state of a run or is refused by validation with a one-line
//! error that names the key and the scheme. Each (scheme, key) pair is checked both ways
//! round: the test also requires that the keys the scheme reads do change the result, so
//! a refusal list that grew too long fails as well as a key that is silently ignored.

use gsph::driver::{run, RunOptions};
use gsph::scene::parse;

/// The flyer plate (1D, Hugoniot EOS with s1 = 1.2, von Mises, free ends), 80 steps: a
/// shock, release waves and free surfaces, so every option has something to act on.
const FLYER: &str = r#"
dim = 1
t_end = 1.0
max_steps = 80
[output]
snapshots = 1
[[materials]]
name = "metal"
rho0 = 6100.0
shear_modulus = 48.1e9
eos = { type = "hugoniot", c0 = 5077.0, s1 = 1.201 }
strength = { type = "von_mises", yield_stress = 2.5e9 }
[[bodies]]
material = "metal"
shape = { type = "segment", min = 0.0, max = 5.0e-3 }
spacing = 1.0e-4
velocity = { type = "uniform", value = [602.81] }
[[bodies]]
material = "metal"
shape = { type = "segment", min = 5.0e-3, max = 1.0e-2 }
spacing = 1.0e-4
"#;

/// Scheme configurations: the five schemes, and pm with each half of tkc.
const SCHEMES: &[(&str, &[&str])] = &[
    ("av", &[]),
    ("pm", &[]),
    ("pm+muscl", &["options.muscl=true"]),
    ("pm+correction", &["options.correction=true"]),
    ("ts1", &[]),
    ("ts2", &[]),
    ("tkc", &[]),
];

/// Every key with a non-default value, and the configurations that read it.
const KEYS: &[(&str, &[&str])] = &[
    ("options.av_alpha=2.0", &["av"]),
    ("options.av_beta=2.0", &["av"]),
    ("options.limiter=mc", &["pm+muscl", "ts2", "tkc"]),
    (
        "options.riemann=two_shock",
        &["pm", "pm+muscl", "pm+correction", "ts1", "ts2", "tkc"],
    ),
    ("options.energy_equation=total", &["pm", "pm+muscl"]),
    (
        "options.dissipation=compression",
        &["pm", "pm+muscl", "pm+correction", "ts1", "ts2", "tkc"],
    ),
    // (options.transverse_dissipation and options.objective: 1D has no transverse waves,
    // so they are refused on this scene; host/tests/elastic_monitor.rs shows them acting
    // in 2D)
    ("options.corrected_slopes=true", &["tkc"]),
    // (options.surface_scan acts only where a particle's L is small with its neighbourhood
    // closed, which this flyer never has; it is in the refusal half through
    // `surface_scan_is_refused_where_not_read` below, and host/tests/correction_flags.rs shows
    // it acting on the Taylor rod's face)
    (
        "options.integrator=leapfrog",
        &["pm+muscl", "ts1", "ts2", "tkc"],
    ),
    ("options.muscl_time=courant", &["ts2"]),
    ("options.muscl_time=predictor", &["ts2"]),
    (
        "options.surface_lambda=0.3",
        &["pm+correction", "ts1", "ts2", "tkc"],
    ),
    (
        "options.det_epsilon=1.1",
        &["pm+correction", "ts1", "ts2", "tkc"],
    ),
    ("options.correction=true", &["pm", "pm+muscl"]),
    ("options.muscl=true", &["pm", "pm+correction"]),
    (
        "options.specific_volume=interpolated",
        &["pm", "pm+muscl", "pm+correction", "tkc"],
    ),
];

fn final_state(scheme: &str, extra: &[&str], key: Option<&str>) -> Result<Vec<u64>, String> {
    let mut set: Vec<String> = vec![format!("scheme={scheme}")];
    set.extend(extra.iter().map(|s| s.to_string()));
    set.extend(key.map(str::to_string));
    let sc = parse(FLYER, "flyer", &set).map_err(|e| e.0)?;
    let r = run(
        &sc,
        "flyer",
        &RunOptions {
            out: None,
            progress: false,
        },
    )
    .map_err(|e| e.to_string())?;
    let t = &r.table;
    Ok(t.x
        .iter()
        .chain(&t.vx)
        .chain(&t.rho)
        .chain(&t.e)
        .map(|v| v.to_bits())
        .collect())
}

#[test]
fn every_option_key_changes_the_result_or_is_refused_naming_key_and_scheme() {
    let mut table = String::new();
    for &(config, extra) in SCHEMES {
        let scheme = config.split('+').next().unwrap();
        let base = final_state(scheme, extra, None).unwrap();
        for &(kv, readers) in KEYS {
            let key = kv.split('=').next().unwrap();
            if extra.iter().any(|x| x.starts_with(&format!("{key}="))) {
                continue; // the configuration itself sets this key
            }
            let reads = readers.contains(&config);
            let outcome = final_state(scheme, extra, Some(kv));
            match (&outcome, reads) {
                (Ok(state), true) => {
                    assert!(
                        state != &base,
                        "{config}: {kv} is accepted but changes nothing"
                    );
                    table.push_str(&format!("{config:14} {kv:32} changes the result\n"));
                }
                (Err(e), false) => {
                    assert!(
                        e.contains(key) && e.contains(scheme) && !e.contains('\n'),
                        "{config}: {kv} refused without naming key and scheme: {e}"
                    );
                    table.push_str(&format!("{config:14} {kv:32} refused: {e}\n"));
                }
                (Ok(_), false) => {
                    panic!("{config}: {kv} is accepted but the scheme does not read it")
                }
                (Err(e), true) => panic!("{config}: {kv} should apply but was refused: {e}"),
            }
        }
    }
    println!("{table}");
}

/// `options.surface_scan` (left out of [`KEYS`]: nothing on the flyer is stretched) is
/// refused by every scheme without a corrected kernel, naming key and scheme.
#[test]
fn surface_scan_is_refused_where_not_read() {
    for (config, extra) in [("av", &[][..]), ("pm", &[]), ("ts1", &[]), ("ts2", &[])] {
        let e = final_state(config, extra, Some("options.surface_scan=true")).unwrap_err();
        assert!(
            e.contains("options.surface_scan") && e.contains(config) && !e.contains('\n'),
            "{config}: {e}"
        );
    }
    for (config, extra) in [("tkc", &[][..]), ("pm", &["options.correction=true"][..])] {
        assert!(final_state(config, extra, Some("options.surface_scan=true")).is_ok());
    }
}

/// `options.specific_volume` is refused without strength (the halo would not carry its
/// slopes, and it stands in for artificial stress in solids), naming the key; "has
/// strength" is one rule for the refusal and the effect (issue 45 item 3): a fluid
/// written either way is refused, a material that is elastic by its shear modulus alone
/// is not, and runs with the strength effect.
#[test]
fn specific_volume_is_refused_without_strength() {
    let strength = "strength = { type = \"von_mises\", yield_stress = 2.5e9 }\n";
    let modulus = "shear_modulus = 48.1e9\n";
    let no_key = FLYER.replace(strength, "").replace(modulus, "");
    let fluid = FLYER
        .replace(strength, "strength = { type = \"fluid\" }\n")
        .replace(modulus, "");
    let elastic = FLYER.replace(strength, "");
    for s in [&no_key, &fluid, &elastic] {
        assert_ne!(s, FLYER);
    }
    for scheme in ["pm", "tkc"] {
        let set = [
            format!("scheme={scheme}"),
            "options.specific_volume=interpolated".to_string(),
        ];
        for (what, text) in [("no strength key", &no_key), ("strength = fluid", &fluid)] {
            let e = parse(text, "flyer", &set).unwrap_err().0;
            assert!(
                e.contains("options.specific_volume")
                    && e.contains("strength")
                    && !e.contains('\n'),
                "{scheme}, {what}: {e}"
            );
        }
        let sc = parse(&elastic, "flyer", &set).expect("elastic by its shear modulus");
        let mats: Vec<_> = sc
            .materials
            .iter()
            .map(gsph::scene::materials::material_of)
            .collect();
        let effects = gsph::sim::resolve_effects(&sc, &mats);
        assert!(effects.contains(gsph_core::effects::EffectSet::STRENGTH));
    }
}

/// `docs/scene-keys.md` is the reference generated from the options table
/// (`gsph::scene::applies::options_reference`); `GSPH_BLESS=1` rewrites it.
#[test]
fn the_scene_key_reference_is_generated_from_the_options_table() {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../docs/scene-keys.md");
    let want = gsph::scene::applies::options_reference();
    if std::env::var_os("GSPH_BLESS").is_some() {
        std::fs::write(&path, &want).unwrap();
    }
    let have = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        have == want,
        "docs/scene-keys.md is not the generated reference: rerun with GSPH_BLESS=1\n{want}"
    );
    // every key of the table is in it, with its doc line
    for key in gsph_core::schemes::options::OptionKey::ALL {
        assert!(want.contains(&format!("`{}`", key.path())) && want.contains(key.doc()));
    }
}

/// The readers [`KEYS`] lists are the schemes' own answers (`Scheme::reads`, from the
/// options table), and every key of the table is exercised here or, named below, by
/// another test: a new option cannot go untested.
#[test]
fn the_keys_tested_here_are_the_tables() {
    use gsph_core::effects::EffectSet;
    use gsph_core::schemes::options::OptionKey;
    use gsph_core::schemes::Scheme;
    let config = |c: &str| -> (Scheme, EffectSet) {
        let scheme = Scheme::from_name(c.split('+').next().unwrap()).unwrap();
        let mut asked = EffectSet::HYDRO;
        if c.contains("+muscl") {
            asked = asked.union(EffectSet::MUSCL);
        }
        if c.contains("+correction") {
            asked = asked.union(EffectSet::CORRECTION);
        }
        (scheme, asked)
    };
    let mut tested = std::collections::BTreeSet::new();
    for &(kv, readers) in KEYS {
        let name = kv
            .split('=')
            .next()
            .unwrap()
            .strip_prefix("options.")
            .unwrap();
        let key = OptionKey::from_name(name).unwrap();
        tested.insert(key.name());
        for &(c, extra) in SCHEMES {
            if extra
                .iter()
                .any(|x| x.starts_with(kv.split('=').next().unwrap()))
            {
                continue; // the configuration itself sets this key
            }
            let (scheme, asked) = config(c);
            assert_eq!(
                scheme.reads(key, asked).is_ok(),
                readers.contains(&c),
                "{kv} for {c}: the list here and the scheme's answer differ"
            );
        }
    }
    // the keys shown elsewhere: transverse_dissipation and objective act only in 2D/3D
    // (host/tests/elastic_monitor.rs), surface_scan above and host/tests/correction_flags.rs,
    // artificial stress tests/tests/artificial_stress.rs, the hourglass stiffness
    // tests/tests/hourglass.rs, tl's updated reference host/tests/tl.rs
    for other in [
        "transverse_dissipation",
        "objective",
        "surface_scan",
        "artificial_stress",
        "artificial_stress_exponent",
        "hourglass",
        "reference_update",
    ] {
        tested.insert(other);
    }
    let untested: Vec<&str> = OptionKey::ALL
        .into_iter()
        .map(|k| k.name())
        .filter(|k| !tested.contains(k))
        .collect();
    assert!(
        untested.is_empty(),
        "options no test exercises: {untested:?}"
    );
}
