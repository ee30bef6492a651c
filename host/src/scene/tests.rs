//! Unit tests of `--set` overrides and of the scene error messages (each names its key).

use super::*;

const FLYER: &str = include_str!("../../../cases/flyer_plate.toml");

fn table(text: &str) -> toml::Table {
    text.parse().expect("valid TOML")
}

fn set(t: &mut toml::Table, kv: &str) -> Result<(), SceneError> {
    apply_override(t, kv)
}

/// The error of parsing `text` with `overrides`; asserts it is one line.
fn parse_err(text: &str, overrides: &[&str]) -> String {
    let o: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let e = parse(text, "scene.toml", &o).expect_err("scene should be rejected");
    assert!(!e.0.contains('\n'), "not one line: {e}");
    e.0
}

#[test]
fn flyer_plate_parses() {
    let s = parse(FLYER, "flyer.toml", &[]).unwrap();
    assert_eq!(s.dim, 1);
    assert_eq!(s.bodies.len(), 2);
    let parts = build_particles(&s).unwrap();
    assert_eq!(parts.len(), 100);
}

#[test]
fn override_sets_top_level_and_nested_keys() {
    let mut t = table(FLYER);
    set(&mut t, "scheme=pm").unwrap();
    assert_eq!(t["scheme"].as_str(), Some("pm"));
    set(&mut t, "output.snapshots=3").unwrap();
    assert_eq!(t["output"]["snapshots"].as_integer(), Some(3));
    set(&mut t, "materials.0.eos.c0=4000.5").unwrap();
    assert_eq!(t["materials"][0]["eos"]["c0"].as_float(), Some(4000.5));
}

#[test]
fn override_addresses_array_elements_by_index() {
    let mut t = table(FLYER);
    set(&mut t, "bodies.1.spacing=2e-4").unwrap();
    assert_eq!(t["bodies"][1]["spacing"].as_float(), Some(2e-4));
    assert_eq!(t["bodies"][0]["spacing"].as_float(), Some(1e-4));
    set(&mut t, "bodies.0.velocity.value.0=10.0").unwrap();
    assert_eq!(
        t["bodies"][0]["velocity"]["value"][0].as_float(),
        Some(10.0)
    );
    set(&mut t, "bodies.0=1").unwrap();
    assert_eq!(t["bodies"][0].as_integer(), Some(1));
}

#[test]
fn override_creates_missing_tables() {
    let mut t = table(FLYER);
    set(&mut t, "options.limiter=minmod").unwrap();
    assert_eq!(t["options"]["limiter"].as_str(), Some("minmod"));
    set(&mut t, "bodies.1.velocity.type=uniform").unwrap();
    assert_eq!(t["bodies"][1]["velocity"]["type"].as_str(), Some("uniform"));
    set(&mut t, "a.b.c=1").unwrap();
    assert_eq!(t["a"]["b"]["c"].as_integer(), Some(1));
}

#[test]
fn override_rejects_bad_paths() {
    let mut t = table(FLYER);
    let e = set(&mut t, "bodies.5.spacing=1").unwrap_err().0;
    assert_eq!(e, "`bodies` has 2 elements, index 5 is out of range");
    let e = set(&mut t, "bodies.x.spacing=1").unwrap_err().0;
    assert_eq!(e, "`bodies` is an array: expected an index, got `x`");
    let e = set(&mut t, "bodies.0.spacing.x=1").unwrap_err().0;
    assert_eq!(e, "`bodies.0.spacing` is a value, not a table or array");
    assert_eq!(set(&mut t, "scheme").unwrap_err().0, "expected KEY=VALUE");
    assert_eq!(set(&mut t, " =1").unwrap_err().0, "empty key");
    let e = set(&mut t, "bodies..spacing=1").unwrap_err().0;
    assert_eq!(e, "`bodies..spacing` has an empty part");
}

#[test]
fn override_values_are_toml_or_bare_strings() {
    let mut t = toml::Table::new();
    let cases: [(&str, toml::Value); 11] = [
        ("1", toml::Value::Integer(1)),
        ("-3", toml::Value::Integer(-3)),
        ("1e-3", toml::Value::Float(1e-3)),
        ("2.5", toml::Value::Float(2.5)),
        ("true", toml::Value::Boolean(true)),
        ("\"ts2\"", toml::Value::String("ts2".into())),
        ("ts2", toml::Value::String("ts2".into())),
        ("sweby:1.5", toml::Value::String("sweby:1.5".into())),
        ("1 2", toml::Value::String("1 2".into())),
        (
            "[1.0, 2]",
            toml::Value::Array(vec![toml::Value::Float(1.0), toml::Value::Integer(2)]),
        ),
        ("", toml::Value::String(String::new())),
    ];
    for (raw, want) in cases {
        set(&mut t, &format!("k = {raw}")).unwrap();
        assert_eq!(t["k"], want, "value `{raw}`");
    }
    // A value holding a second assignment is not smuggled in as another key.
    set(&mut t, "k=1\ncfl = 0.9").unwrap();
    assert_eq!(t["k"].as_str(), Some("1\ncfl = 0.9"));
    assert!(!t.contains_key("cfl"));
}

#[test]
fn malformed_toml_names_line_and_column() {
    let text = FLYER.replace("cfl = 0.5", "cfl = = 0.5");
    let e = parse_err(&text, &[]);
    assert!(e.starts_with("scene.toml:11:7: malformed TOML: "), "{e}");
    let e = parse_err(&FLYER.replace("dim = 1", "dim = 1\ndim = 2"), &[]);
    assert!(
        e.starts_with("scene.toml:9:1: malformed TOML: duplicate key"),
        "{e}"
    );
}

#[test]
fn schema_errors_name_the_key() {
    let cases: [(&str, &str, &str); 8] = [
        (
            "name = ",
            "colour = 1\nname = ",
            "scene.toml: colour: unknown key (known: name,",
        ),
        (
            "name = \"metal\"",
            "name = \"metal\"\ncolour = 1",
            "scene.toml: materials[0].colour: unknown key",
        ),
        (
            "spacing = 1.0e-4\n\n",
            "spacing = 1.0e-4\ncolour = 1\n\n",
            "scene.toml: bodies[1].colour: unknown key",
        ),
        (
            "name = \"metal\"",
            "name = \"metal\"\neos = { type = \"hugonio\" }",
            "scene.toml: materials[0].eos.type: unknown type `hugonio` (known: linear,",
        ),
        (
            "name = \"metal\"",
            "name = \"metal\"\neos = { c0 = \"fast\" }",
            "scene.toml: materials[0].eos.c0: invalid type: string \"fast\", expected f64",
        ),
        (
            "name = \"metal\"",
            "name = \"metal\"\nrho0 = \"dense\"",
            "scene.toml: materials[0].rho0: invalid type: string \"dense\"",
        ),
        (
            "dim = 1",
            "dim = -1",
            "scene.toml: dim: invalid value: integer `-1`, expected usize",
        ),
        (
            "t_end = 0.5e-6\n",
            "",
            "scene.toml: t_end: missing (this key is required)",
        ),
    ];
    for (from, to, want) in cases {
        let text = FLYER.replacen(from, to, 1);
        assert_ne!(text, FLYER, "{from}");
        let e = parse_err(&text, &[]);
        assert!(e.starts_with(want), "got `{e}`, want `{want}`");
    }
}

#[test]
fn validation_errors_name_the_key() {
    let cases: [(&str, &str); 26] = [
        (
            "materials.0.rho0=-1",
            "materials[0].rho0: must be positive and finite (got -1)",
        ),
        ("materials.0.rho0=0", "materials[0].rho0: must be positive"),
        (
            "bodies.1.spacing=0",
            "bodies[1].spacing: must be positive and finite (got 0)",
        ),
        (
            "bodies.1.spacing=-1e-4",
            "bodies[1].spacing: must be positive",
        ),
        (
            "materials.0.shear_modulus=-1",
            "materials[0].shear_modulus: must be non-negative",
        ),
        (
            "materials.0.shear_modulus=0",
            "materials[0].shear_modulus: must be positive for a material with strength",
        ),
        ("t_end=0", "t_end: must be positive"),
        ("t_end=-1", "t_end: must be positive"),
        ("cfl=1.5", "cfl: must be at most 1 (got 1.5)"),
        ("scheme=rk4", "scheme: unknown scheme `rk4`"),
        ("kernel=box", "kernel: unknown kernel `box`"),
        ("dim=4", "dim: must be 1, 2 or 3 (got 4)"),
        (
            "h_factor=0.1",
            "h_factor: must be between 0.5 and 100 (got 0.1)",
        ),
        (
            "neighbor_capacity=0",
            "neighbor_capacity: must be at least 1",
        ),
        ("output.snapshots=0", "output.snapshots: must be at least 1"),
        ("output.series=0", "output.series: must be at least 1"),
        (
            "output.snapshots=1000000000",
            "output.snapshots: at most 100000 (got 1000000000)",
        ),
        (
            "output.series=100000000",
            "output.series: at most 10000000 (got 100000000;",
        ),
        (
            "options.limiter=best",
            "options.limiter: unknown limiter `best`",
        ),
        (
            "options.riemann=hllc",
            "options.riemann: unknown Riemann solver `hllc`",
        ),
        (
            "bodies.0.velocity.value=[1, 2]",
            "bodies[0].velocity.value: must have 1 component for a 1D scene (got 2)",
        ),
        (
            "bodies.0.shape.max=-1",
            "bodies[0].shape.max: must exceed min (-1 <= 0)",
        ),
        (
            "bodies.1.material=steel",
            "bodies[1].material: unknown material `steel` (known: metal)",
        ),
        (
            "reference.material=steel",
            "reference.material: unknown material `steel`",
        ),
        (
            "bodies.0.lattice=hex",
            "bodies[0].lattice: unknown lattice `hex`",
        ),
        (
            "materials.0.strength.yield_stress=0",
            "materials[0].strength.yield_stress: must be positive",
        ),
    ];
    for (kv, want) in cases {
        let e = parse_err(FLYER, &[kv]);
        let want = format!("--set {kv}: {want}");
        assert!(e.starts_with(&want), "got `{e}`, want `{want}`");
    }
}

#[test]
fn errors_from_the_file_name_the_file() {
    let e = parse_err(
        &FLYER.replace("name = \"metal\"", "name = \"metal\"\nrho0 = -6100.0"),
        &[],
    );
    assert_eq!(
        e,
        "scene.toml: materials[0].rho0: must be positive and finite (got -6100)"
    );
    // An override elsewhere does not take the blame.
    let e = parse_err(
        &FLYER.replace("name = \"metal\"", "name = \"metal\"\nrho0 = 0.0"),
        &["cfl=0.4"],
    );
    assert!(e.starts_with("scene.toml: materials[0].rho0: "), "{e}");
}

#[test]
fn lists_and_names_are_checked() {
    let e = parse_err(FLYER, &["materials=[]"]);
    assert_eq!(
        e,
        "--set materials=[]: materials: at least one material is required"
    );
    let e = parse_err(FLYER, &["bodies=[]"]);
    assert_eq!(e, "--set bodies=[]: bodies: at least one body is required");
    let twice = FLYER.replacen(
        "[[bodies]]",
        "[[materials]]\nname = \"metal\"\nrho0 = 1.0\neos = { type = \"linear\", c0 = 1.0 }\n\n[[bodies]]",
        1,
    );
    let e = parse_err(&twice, &[]);
    assert_eq!(
        e,
        "scene.toml: materials[1].name: duplicate material name `metal`"
    );
}

#[test]
fn particle_counts_are_checked() {
    let e = parse_err(FLYER, &["resolution_scale=1e-3"]);
    assert!(
        e.starts_with("scene.toml: bodies[0]: the shape holds no particle at spacing 1e-1 m"),
        "{e}"
    );
    let e = parse_err(FLYER, &["bodies.1.spacing=1e-12"]);
    assert!(
        e.starts_with("--set bodies.1.spacing=1e-12: bodies[1].spacing: spacing 1e-12 m"),
        "{e}"
    );
    assert!(e.contains("more than the limit 1e8"), "{e}");
    let e = parse_err(FLYER, &["neighbor_capacity=1000000000000"]);
    assert!(
        e.starts_with("--set neighbor_capacity=1000000000000: neighbor_capacity: 100 particles"),
        "{e}"
    );
    let far = ["bodies.1.shape.min=1e6", "bodies.1.shape.max=1.000000005e6"];
    let e = parse_err(FLYER, &far);
    assert!(
        e.starts_with("scene.toml: bodies: the particles span"),
        "{e}"
    );
}

#[test]
fn two_dimensional_disc_smaller_than_half_a_spacing_holds_nothing() {
    let text = r#"
dim = 2
scheme = "pm"
t_end = 1e-6
[[materials]]
name = "al"
rho0 = 2700.0
eos = { type = "linear", c0 = 5000.0 }
[[bodies]]
material = "al"
shape = { type = "disc", center = [0.0, 0.0], radius = 0.4e-3 }
spacing = 1e-3
"#;
    let e = parse_err(text, &[]);
    assert!(
        e.starts_with("scene.toml: bodies[0]: the shape holds no particle"),
        "{e}"
    );
    assert!(parse(text, "s", &["bodies.0.shape.radius=2e-3".into()]).is_ok());
}

#[test]
fn keys_are_written_with_brackets() {
    assert_eq!(
        bracketed("bodies.0.velocity.value.1"),
        "bodies[0].velocity.value[1]"
    );
    assert_eq!(bracketed("t_end"), "t_end");
    assert_eq!(bracketed("0"), "0");
}

const POROUS: &str = include_str!("../../../cases/porous_cu_piston.toml");

#[test]
fn porous_sample_has_the_seed_porosity() {
    let s = parse(POROUS, "porous.toml", &[]).unwrap();
    let parts = build_particles(&s).unwrap();
    // body 1 is the porous sample: m = V / V_solid, as built on the 1 um lattice and from
    // the geometry of two 4.06 um pores per 20 um cell (seed 004: m = 1.35)
    assert!(
        (parts.porosity[1] - 1.35).abs() < 0.01,
        "{}",
        parts.porosity[1]
    );
    assert_eq!(parts.porosity[0], 1.0);
    let pores = s.bodies[1].pores.as_ref().unwrap();
    assert!((pores::geometric_porosity(pores) - 1.3494).abs() < 1e-3);
    // no particle centre inside a pore
    for i in 0..parts.len() {
        if parts.body[i] == 1 {
            assert!(!pores::inside(pores, &parts.x[i]));
        }
    }
}

#[test]
fn pore_errors_name_the_key() {
    let e = parse_err(POROUS, &["bodies.1.pores.radius=1.2e-5"]);
    assert!(
        e.contains("bodies[1].pores.radius: must be below half the smallest cell side"),
        "{e}"
    );
    let e = parse_err(POROUS, &["bodies.1.pores.cell=[2e-5]"]);
    assert!(
        e.contains("bodies[1].pores.cell: must have 2 components (got 1)"),
        "{e}"
    );
    let e = parse_err(POROUS, &["bodies.1.pores.centers=[]"]);
    assert!(
        e.contains("bodies[1].pores.centers: at least one pore centre"),
        "{e}"
    );
    let e = parse_err(POROUS, &["monitor.front.velocity=0"]);
    assert!(
        e.contains("monitor.front.velocity: must be positive"),
        "{e}"
    );
}

#[test]
fn jitter_moves_particles_deterministically_within_the_bound() {
    let plain = parse(FLYER, "flyer.toml", &[]).unwrap();
    let set = ["bodies.0.jitter=0.2".to_string()];
    let jit = parse(FLYER, "flyer.toml", &set).unwrap();
    let (a, b) = (
        build_particles(&plain).unwrap(),
        build_particles(&jit).unwrap(),
    );
    let again = build_particles(&jit).unwrap();
    assert_eq!(a.len(), b.len());
    let mut moved = 0;
    for i in 0..a.len() {
        assert_eq!(b.x[i], again.x[i], "particle {i}: not deterministic");
        let d = (b.x[i][0] - a.x[i][0]).abs();
        assert!(d <= 0.2 * a.spacing[i], "particle {i} moved {d}");
        if a.body[i] == 1 {
            assert_eq!(a.x[i], b.x[i], "body 1 has no jitter");
        } else if d > 0.05 * a.spacing[i] {
            moved += 1;
        }
        assert_eq!(a.m[i], b.m[i]);
    }
    // uniform in [-0.2, 0.2) spacings: about 3/4 of 50 particles move more than 0.05
    assert!(moved > 25, "only {moved} of 50 particles moved");
}

#[test]
fn jitter_outside_its_range_is_rejected() {
    for v in ["0.5", "-0.1", "nan"] {
        let e = parse_err(FLYER, &[&format!("bodies.1.jitter={v}")]);
        assert!(e.contains("bodies[1].jitter: must lie in [0, 0.5)"), "{e}");
    }
}

const RINGS: &str = include_str!("../../../cases/rings.toml");

/// The peers' colliding rings (cases/rings.toml): the square lattice with a node at
/// `-r_o` keeps exactly the particles their scripts keep (PySPH's and LAMMPS SMD's rings
/// examples, `x, y = -r_o + i dx`, `r_i² <= r² < r_o²`): 17,592 at dx = 5e-4, 4,416 at
/// 1e-3, 70,320 at 2.5e-4. The default lattice (offset half a spacing) keeps 17,608.
#[test]
fn rings_have_the_peers_particle_counts() {
    for (scale, n) in [(1.0, 17_592), (0.5, 4_416), (2.0, 70_320)] {
        let o = vec![format!("resolution_scale={scale}")];
        let s = parse(RINGS, "rings.toml", &o).unwrap();
        let parts = build_particles(&s).unwrap();
        assert_eq!(parts.len(), n, "resolution_scale {scale}");
        // no site is outside its annulus
        for i in 0..parts.len() {
            let c = if parts.body[i] == 0 { 0.0 } else { 0.082 };
            let (dx, dy) = (parts.x[i][0] - c, parts.x[i][1]);
            let r2 = dx * dx + dy * dy;
            assert!(
                (0.03 * 0.03 - 1e-12..0.04 * 0.04 + 1e-12).contains(&r2),
                "particle {i} at r {}",
                r2.sqrt()
            );
        }
    }
    let o = vec!["unset:bodies.0.lattice_origin".to_string()];
    let s = parse(RINGS, "rings.toml", &o).unwrap();
    assert_eq!(build_particles(&s).unwrap().len(), 17_608 / 2 + 17_592 / 2);
}

#[test]
fn lattice_origin_errors_name_the_key() {
    for (kv, want) in [
        (
            "bodies.0.lattice_origin=[-0.04]",
            "bodies[0].lattice_origin: must have 2 components (got 1)",
        ),
        (
            "bodies.0.lattice_origin=[-0.05, 0.0]",
            "bodies[0].lattice_origin: -0.05 must lie within the outer radius 0.04 of the centre",
        ),
    ] {
        let e = parse_err(RINGS, &[kv]);
        let want = format!("--set {kv}: {want}");
        assert!(e.starts_with(&want), "got `{e}`, want `{want}`");
    }
    let e = parse_err(RINGS, &["bodies.0.lattice=polar"]);
    assert_eq!(
        e,
        "scene.toml: bodies[0].lattice_origin: a lattice origin is for the square lattice only"
    );
    let e = parse_err(FLYER, &["bodies.0.lattice_origin=[0.0]"]);
    assert!(
        e.contains("bodies[0].lattice_origin: a lattice origin is for discs and annuli only"),
        "{e}"
    );
}

/// The Murnaghan EOS through a scene: read into the core's model (rho0 the material's),
/// its parameters checked by the model with the key's path in the message.
#[test]
fn murnaghan_eos_reads_and_checks_itself() {
    let water = "dim = 1\nscheme = \"ts1\"\nt_end = 2e-6\n\
                 [[materials]]\nname = \"water\"\nrho0 = 1000.0\n\
                 eos = { type = \"murnaghan\", c0 = 1480.0, gamma = 7.0 }\n\
                 [[bodies]]\nmaterial = \"water\"\nspacing = 1e-4\n\
                 shape = { type = \"segment\", min = 0.0, max = 0.01 }\n";
    let s = parse(water, "water.toml", &[]).unwrap();
    let m = materials::material_of(&s.materials[0]);
    assert_eq!(m.eos.name(), "murnaghan");
    assert_eq!(m.eos.rho0(), 1000.0);
    // 1.1 rho0: (rho0 c0²/7)(1.1^7 - 1) (the model's hand-computed value)
    let st = m.eos.eval(1100.0, 0.0);
    assert!((st.p - 296_867_133.69).abs() < 1.0, "{}", st.p);
    assert_eq!(
        parse_err(water, &["materials.0.eos.gamma=-1"]),
        "--set materials.0.eos.gamma=-1: materials[0].eos.gamma: must be positive and finite (got -1)"
    );
    let e = parse_err(water, &["materials.0.eos.k1=1"]);
    assert!(
        e.contains("materials[0].eos.k1") && e.contains("c0, gamma"),
        "{e}"
    );
}

/// A fluid has no shear modulus: `poisson_ratio` beside `strength = fluid` is refused
/// naming the ratio (it gave a shear modulus the fluid then ignored).
#[test]
fn a_poisson_ratio_for_a_fluid_is_refused() {
    let scene = r#"
dim = 1
scheme = "ts2"
t_end = 1e-6
[[materials]]
name = "water"
rho0 = 1000.0
poisson_ratio = 0.3
eos = { type = "murnaghan", c0 = 1480.0, gamma = 7.0 }
strength = { type = "fluid" }
[[bodies]]
material = "water"
shape = { type = "segment", min = 0.0, max = 1e-2 }
spacing = 1e-4
"#;
    let e = parse_err(scene, &[]);
    assert!(
        e.contains("materials[0].poisson_ratio") && e.contains("fluid"),
        "{e}"
    );
    assert!(parse(&scene.replace("poisson_ratio = 0.3\n", ""), "s.toml", &[]).is_ok());
}

/// A NUL in a comment: the parser gives no reason, the message names the character.
#[test]
fn a_nul_in_a_comment_is_named() {
    let e = parse_err("dim = 1\n# a \u{0} b\n", &[]);
    assert!(
        e.starts_with("scene.toml:2:")
            && e.contains("malformed TOML: the control character U+0000"),
        "{e}"
    );
}

/// The cantilever's first mode (`velocity.type = "cantilever"`): clamped at the root (no
/// velocity, no slope), the tip at `tip`, k = 1.875 near the root of 1 + cos k cosh k;
/// SPHinXsys's plate starts with KE0 = 4.0647984 J/m (docs/notes/issue46_peers.md), which
/// `cases/plate_oscillating.toml` reproduces (series.csv's first `kinetic`).
#[test]
fn the_cantilever_mode_is_clamped_at_the_root_and_one_at_the_tip() {
    let k = 1.875_f64;
    assert!((1.0 + k.cos() * k.cosh()).abs() < 2e-3);
    assert_eq!(cantilever_mode(k, 0.0), 0.0);
    assert!((cantilever_mode(k, 1.0) - 1.0).abs() < 1e-14);
    let slope = (cantilever_mode(k, 1e-6) - cantilever_mode(k, -1e-6)) / 2e-6;
    assert!(slope.abs() < 1e-8, "{slope}");
    let plate = include_str!("../../../cases/plate_oscillating.toml");
    let sc = parse(plate, "plate.toml", &[]).unwrap();
    let parts = build_particles(&sc).unwrap();
    let ke: f64 = (0..parts.len())
        .map(|i| 0.5 * parts.m[i] * parts.v[i].iter().map(|v| v * v).sum::<f64>())
        .sum();
    assert!((ke - 4.064_798_4).abs() < 1e-6, "KE0 {ke}");
    let e = parse_err(plate, &["bodies.0.velocity.direction=0"]);
    assert!(
        e.contains("bodies[0].velocity.direction: must differ"),
        "{e}"
    );
}
