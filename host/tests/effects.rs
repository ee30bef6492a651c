//! Effects (DESIGN §5): a scene resolves to exactly the effects it calls for, storage grows
//! only with the effects present, and an effect made inert by its parameters does not change
//! the result.

use gsph::driver::{run, RunOptions};
use gsph::output::table::{ParticleTable, FLOAT_COLUMNS};
use gsph::scene::{build_particles, parse, Scene};
use gsph::sim::Sim;

/// A small 2D block, hydro only (fluid, Mie–Grüneisen), scheme pm.
const BLOCK_2D: &str = r#"
dim = 2
scheme = "pm"
t_end = 1.0

[[materials]]
name = "aluminium"
rho0 = 2785.0
eos = { type = "mie_gruneisen", c0 = 5328.0, s1 = 1.338, gamma0 = 2.0 }

[[bodies]]
material = "aluminium"
shape = { type = "box", min = [0.0, 0.0], max = [1.2e-3, 1.2e-3] }
spacing = 1.0e-4
"#;

/// Each step adds one effect to the previous: (expected effect set, overrides added).
const STEPS: &[(&str, &[&str])] = &[
    ("hydro", &[]),
    (
        "strength",
        &[
            "materials.0.shear_modulus=27.6e9",
            "materials.0.strength={ type = \"elastic\" }",
        ],
    ),
    (
        "strength+plasticity",
        &["materials.0.strength={ type = \"von_mises\", yield_stress = 3e8 }"],
    ),
    (
        "strength+plasticity+correction",
        &["options.correction=true"],
    ),
    (
        "strength+plasticity+correction+muscl",
        &["options.muscl=true"],
    ),
    (
        "strength+plasticity+correction+muscl+periodic",
        &[
            "periodic.axes=[1]",
            "periodic.lo=[0.0, 0.0]",
            "periodic.hi=[1.2e-3, 1.2e-3]",
        ],
    ),
];

fn scene(text: &str, overrides: &[String]) -> Scene {
    parse(text, "effects", overrides).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn storage_grows_with_each_effect() {
    let mut overrides = Vec::new();
    let mut last: Option<(String, usize)> = None;
    for (expected, set) in STEPS {
        overrides.extend(set.iter().map(|s| s.to_string()));
        let scene = scene(BLOCK_2D, &overrides);
        let parts = build_particles(&scene).unwrap();
        let sim = Sim::<2>::new(&scene, &parts).unwrap_or_else(|e| panic!("{expected}: {e}"));
        assert_eq!(sim.effects.to_string(), *expected);
        let bytes = sim.bytes_per_particle();
        if let Some((prev, prev_bytes)) = &last {
            if prev == "hydro" {
                assert!(
                    bytes > *prev_bytes,
                    "strength ({bytes} B) must need more storage than hydro ({prev_bytes} B)"
                );
            }
            assert!(
                bytes >= *prev_bytes,
                "{expected} ({bytes} B) needs less storage than {prev} ({prev_bytes} B)"
            );
        }
        last = Some((expected.to_string(), bytes));
    }
}

#[test]
fn pm_family_options_match_tkc_and_are_rejected_elsewhere() {
    let both = [
        "options.correction=true".to_string(),
        "options.muscl=true".to_string(),
    ];
    let pm = scene(BLOCK_2D, &both);
    let tkc = scene(BLOCK_2D, &["scheme=tkc".to_string()]);
    for s in [&pm, &tkc] {
        let parts = build_particles(s).unwrap();
        let sim = Sim::<2>::new(s, &parts).unwrap();
        assert_eq!(sim.effects.to_string(), "correction+muscl");
    }
    for scheme in ["av", "ts1", "ts2"] {
        for opt in ["options.correction=true", "options.muscl=true"] {
            let key = opt.split('=').next().unwrap();
            let e = parse(
                BLOCK_2D,
                "effects",
                &[format!("scheme={scheme}"), opt.to_string()],
            )
            .expect_err("only pm takes the option");
            assert!(
                e.0.contains(&format!("{key}: only with scheme pm (scheme is {scheme})")),
                "{scheme} {opt}: {e}"
            );
        }
    }
}

/// The flyer plate (cases/flyer_plate.toml) elastic, stopped after `MAX_STEPS` steps.
const FLYER: &str = r#"
dim = 1
scheme = "ts2"
t_end = 1.0
max_steps = 300
cfl = 0.5

[[materials]]
name = "metal"
rho0 = 6100.0
shear_modulus = 48.1e9
eos = { type = "hugoniot", c0 = 5077.0, s1 = 1.201 }
strength = { type = "elastic" }

[[bodies]]
material = "metal"
shape = { type = "segment", min = 0.0, max = 0.005 }
spacing = 1.0e-4
velocity = { type = "uniform", value = [602.81] }

[[bodies]]
material = "metal"
shape = { type = "segment", min = 0.005, max = 0.01 }
spacing = 1.0e-4
"#;

fn final_table(text: &str, overrides: &[String]) -> (String, ParticleTable) {
    let s = scene(text, overrides);
    let parts = build_particles(&s).unwrap();
    let effects = Sim::<1>::new(&s, &parts).unwrap().effects.to_string();
    let opts = RunOptions {
        out: None,
        progress: false,
    };
    let r = run(&s, "effects", &opts).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.summary.steps, 300, "{effects}");
    (effects, r.table)
}

/// Every column of two tables is bitwise equal, except those in `skip`.
fn assert_same(a: &ParticleTable, b: &ParticleTable, skip: &[&str], what: &str) {
    assert_eq!(a.id, b.id, "{what}: id");
    assert_eq!(a.material, b.material, "{what}: material");
    for ((name, ca), cb) in FLOAT_COLUMNS
        .iter()
        .zip(a.float_columns())
        .zip(b.float_columns())
    {
        if skip.contains(name) {
            continue;
        }
        let same =
            ca.len() == cb.len() && ca.iter().zip(cb).all(|(x, y)| x.to_bits() == y.to_bits());
        assert!(same, "{what}: column {name} differs");
    }
}

#[test]
fn unreachable_yield_stress_is_elastic() {
    for scheme in ["av", "pm", "ts1", "ts2", "tkc"] {
        let set = format!("scheme={scheme}");
        let (e_el, elastic) = final_table(FLYER, std::slice::from_ref(&set));
        let (e_vm, plastic) = final_table(
            FLYER,
            &[
                set,
                "materials.0.strength={ type = \"von_mises\", yield_stress = 1e12 }".to_string(),
            ],
        );
        assert!(!e_el.contains("plasticity") && e_vm.contains("plasticity"));
        // The run did something: the plates are compressed and carry a deviator.
        assert!(elastic.sxx.iter().any(|&s| s.abs() > 1e8), "{scheme}");
        assert_same(&elastic, &plastic, &["eps_p"], scheme);
        assert!(plastic.eps_p.iter().all(|&e| e == 0.0), "{scheme}: eps_p");
    }
}

#[test]
fn periodic_box_out_of_reach_changes_nothing() {
    // Periodic along x with a box 200 times the rod: no particle sees an image.
    let periodic = [
        "periodic.axes=[0]".to_string(),
        "periodic.lo=[-1.0]".to_string(),
        "periodic.hi=[1.0]".to_string(),
    ];
    for scheme in ["pm", "tkc"] {
        let set = format!("scheme={scheme}");
        let (e_free, free) = final_table(FLYER, std::slice::from_ref(&set));
        let mut with = vec![set];
        with.extend(periodic.iter().cloned());
        let (e_per, per) = final_table(FLYER, &with);
        assert!(!e_free.contains("periodic") && e_per.contains("periodic"));
        assert_same(&free, &per, &[], scheme);
    }
}
