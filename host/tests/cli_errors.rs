//! Bad input through the real `gsph` binary: each case must exit non-zero with exactly one
//! line on stderr, `error: ...`, naming the key, particle or step; never a panic; a `run`
//! refused before it starts leaves an earlier run's results alone, one that fails after it
//! started leaves no result file; neither leaves a `*.tmp`. Positive controls check the
//! DESIGN §6 outputs of a good run.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const RESULTS: [&str; 4] = [
    "summary.json",
    "final.csv",
    "snapshots.h5",
    "snapshots.xdmf",
];

fn case_text(name: &str) -> String {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../cases")
        .join(name);
    std::fs::read_to_string(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

fn impact() -> String {
    case_text("steel_sic_impact.toml")
}

fn flyer() -> String {
    case_text("flyer_plate.toml")
}

/// `flyer_plate.toml` with the first `from` replaced by `to` (which must occur).
fn flyer_with(from: &str, to: &str) -> String {
    let t = flyer();
    assert!(t.contains(from), "flyer_plate.toml has no `{from}`");
    t.replacen(from, to, 1)
}

const DISC_2D: &str = r#"
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

/// A 1D bar of the library's Tillotson aluminium (fluid).
const TILLOTSON_BAR: &str = r#"
dim = 1
scheme = "ts1"
t_end = 1e-6
[[materials]]
name = "al"
library = "al_tillotson"
[[bodies]]
material = "al"
shape = { type = "segment", min = 0.0, max = 0.01 }
spacing = 1e-3
"#;

/// A 2D strip on the floor of a 45° wedge, near its apex (walls that meet at an angle other
/// than 90° within the kernel's reach of a particle).
const WEDGE_2D: &str = r#"
dim = 2
scheme = "ts2"
t_end = 1e-7
[[materials]]
name = "steel"
rho0 = 7850.0
shear_modulus = 80.0e9
eos = { type = "linear", c0 = 4600.0 }
strength = { type = "von_mises", yield_stress = 2.0e9 }
[[bodies]]
material = "steel"
shape = { type = "box", min = [2.0e-4, 0.0], max = [4.2e-3, 1.0e-4] }
spacing = 1.0e-4
[[walls]]
point = [0.0, 0.0]
normal = [0.0, 1.0]
[[walls]]
point = [0.0, 0.0]
normal = [1.0, -1.0]
"#;

fn gsph(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gsph"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("gsph starts")
}

/// Names in `dir` that a failed run must not leave (results and temp files).
fn leftovers(dir: &Path) -> Vec<String> {
    let Ok(rd) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    rd.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| RESULTS.contains(&n.as_str()) || n.ends_with(".tmp"))
        .collect()
}

/// One bad-input case: scene text (None: no scene file is written), command and its extra
/// arguments, and the words the one-line message must contain.
struct Case {
    name: &'static str,
    scene: Option<String>,
    cmd: &'static str,
    args: Vec<&'static str>,
    expect: Vec<&'static str>,
}

fn case(
    name: &'static str,
    scene: impl Into<Option<String>>,
    cmd: &'static str,
    args: &[&'static str],
    expect: &[&'static str],
) -> Case {
    Case {
        name,
        scene: scene.into(),
        cmd,
        args: args.to_vec(),
        expect: expect.to_vec(),
    }
}

fn cases() -> Vec<Case> {
    let f = flyer;
    let riemann_b0 = case_text("riemann_al.toml").replacen(
        "name = \"aluminium\"",
        "name = \"aluminium\"\neos = { bulk_modulus = 0.0 }",
        1,
    );
    let window = || case_text("porous_cu_window.toml");
    let strip = || case_text("sound_cu_2d.toml");
    let window_open = window().replacen(
        "[periodic]\naxes = [1]\nlo = [0.0, 0.0]\nhi = [0.0, 2.0e-5]\n",
        "",
        1,
    );
    let wall_bar = || case_text("wall_bar.toml");
    // the bar's wall and 49 more behind it, 1 µm apart
    let fifty_walls = {
        let t = wall_bar();
        let cut = t.find("[[walls]]").expect("a wall");
        let walls: String = (0..50)
            .map(|k| {
                format!(
                    "[[walls]]\npoint = [{:e}]\nnormal = [1.0]\n",
                    -1e-6 * k as f64
                )
            })
            .collect();
        format!("{}{walls}", &t[..cut])
    };
    let second_metal = flyer_with(
        "[[bodies]]",
        "[[materials]]\nname = \"metal\"\nrho0 = 1.0\neos = { type = \"linear\", c0 = 1.0 }\n\n[[bodies]]",
    );
    vec![
        case("malformed TOML", flyer_with("cfl = 0.5", "cfl = = 0.5"), "check", &[], &["scene.toml:11:7: malformed TOML"]),
        case("unknown top-level key", format!("colour = 1\n{}", f()), "check", &[], &["scene.toml: colour: unknown key (known: name,"]),
        case("unknown key in a material", flyer_with("name = \"metal\"", "name = \"metal\"\ncolour = 1"), "check", &[], &["materials[0].colour: unknown key"]),
        case("unknown key in a body", flyer_with("spacing = 1.0e-4\nvelocity", "colour = 1\nspacing = 1.0e-4\nvelocity"), "check", &[], &["bodies[0].colour: unknown key"]),
        case("unknown key via --set", f(), "check", &["--set", "materials.0.eos.colour=1"], &["--set materials.0.eos.colour=1: materials[0].eos.colour: unknown key (known: c0, s1)"]),
        case("missing key", flyer_with("t_end = 0.5e-6\n", ""), "check", &[], &["scene.toml: t_end: missing"]),
        case("unknown material", f(), "check", &["--set", "bodies.1.material=steel"], &["bodies[1].material: unknown material `steel` (known: metal)"]),
        case("unknown EOS type", flyer_with("name = \"metal\"", "name = \"metal\"\neos = { type = \"hugonio\" }"), "check", &[], &["scene.toml: materials[0].eos.type: unknown type `hugonio`"]),
        case("unknown scheme", f(), "check", &["--set", "scheme=rk4"], &["scheme: unknown scheme `rk4`"]),
        case("negative rho0", flyer_with("name = \"metal\"", "name = \"metal\"\nrho0 = -6100.0"), "check", &[], &["scene.toml: materials[0].rho0: must be positive and finite (got -6100)"]),
        case("zero rho0", f(), "run", &["--set", "materials.0.rho0=0"], &["materials[0].rho0: must be positive"]),
        case("zero spacing", f(), "check", &["--set", "bodies.0.spacing=0"], &["bodies[0].spacing: must be positive"]),
        case("negative spacing", flyer_with("spacing = 1.0e-4\n\n", "spacing = -1.0e-4\n\n"), "check", &[], &["scene.toml: bodies[1].spacing: must be positive and finite (got -1e-4)"]),
        case("negative shear modulus", f(), "check", &["--set", "materials.0.shear_modulus=-1"], &["materials[0].shear_modulus: must be non-negative"]),
        case("zero bulk modulus", riemann_b0, "check", &[], &["scene.toml: materials[0].eos.bulk_modulus: must be positive"]),
        case("von Mises without shear modulus", f(), "check", &["--set", "materials.0.shear_modulus=0"], &["materials[0].shear_modulus: must be positive for a material with strength"]),
        case("wrong number of components", f(), "check", &["--set", "bodies.0.velocity.value=[1.0, 2.0]"], &["bodies[0].velocity.value: must have 1 component for a 1D scene (got 2)"]),
        case("segment max <= min", f(), "check", &["--set", "bodies.0.shape.max=0"], &["bodies[0].shape.max: must exceed min (0 <= 0)"]),
        case("wrong value type via --set", f(), "check", &["--set", "materials.0.rho0=dense"], &["materials[0].rho0: invalid type: string \"dense\", expected f64"]),
        case("wrong type inside a tagged table", flyer_with("name = \"metal\"", "name = \"metal\"\neos = { c0 = \"fast\" }"), "check", &[], &["scene.toml: materials[0].eos.c0: invalid type"]),
        case("body with no particle (2D disc)", DISC_2D.to_string(), "check", &[], &["scene.toml: bodies[0]: the shape holds no particle"]),
        case("too many particles", f(), "run", &["--set", "resolution_scale=1e9"], &["bodies[0].spacing", "limit 1e8 (`max_particles` raises it)"]),
        case("no bodies", f(), "check", &["--set", "bodies=[]"], &["bodies: at least one body is required"]),
        case("no materials", f(), "check", &["--set", "materials=[]"], &["materials: at least one material is required"]),
        case("duplicate material name", second_metal, "check", &[], &["scene.toml: materials[1].name: duplicate material name `metal`"]),
        case("overlapping bodies (check)", f(), "check", &["--set", "bodies.0.shape.max=0.01"], &["particles 51 and 101 are at the same point (5.1500e-3,"]),
        case("overlapping bodies (run)", f(), "run", &["--set", "bodies.0.shape.max=0.01"], &["particles 51 and 101 are at the same point (5.1500e-3,"]),
        case("overlapping bodies off the lattice", f(), "check", &["--set", "bodies.0.shape.max=0.00802"], &["particles 50 and 80 overlap: 1.263e-5 m apart"]),
        case("neighbour capacity (check)", f(), "check", &["--set", "neighbor_capacity=1"], &["neighbour-capacity overflow: particle 0", "neighbor_capacity"]),
        case("neighbour capacity (run)", f(), "run", &["--set", "neighbor_capacity=1"], &["neighbour-capacity overflow: particle 0", "neighbor_capacity"]),
        case("blow-up at step 1", f(), "run", &["--set", "bodies.0.velocity.value=[1e200]"], &["step 1 ", "particle ", "not finite"]),
        case("blow-up mid-run", f(), "run", &["--set", "scheme=ts1", "--set", "bodies.0.velocity.value=[1e150]"], &["step ", "particle ", "not finite"]),
        case("particles overrun each other mid-run", f(), "run", &["--set", "bodies.0.velocity.value=[1e150]"], &["step 197 ", "neighbour-capacity overflow: particle 0"]),
        case("--set index out of range", f(), "check", &["--set", "bodies.5.spacing=1"], &["--set bodies.5.spacing=1: `bodies` has 2 elements, index 5 is out of range"]),
        case("--set without =", f(), "run", &["--set", "scheme"], &["--set scheme: expected KEY=VALUE"]),
        case("zero t_end", f(), "check", &["--set", "t_end=0"], &["t_end: must be positive"]),
        case("negative t_end", f(), "run", &["--set", "t_end=-1e-6"], &["t_end: must be positive"]),
        case("cfl above 1", f(), "check", &["--set", "cfl=1.5"], &["cfl: must be at most 1 (got 1.5)"]),
        case("zero threads", f(), "run", &["--threads", "0"], &["--threads must be at least 1"]),
        case("usage: threads not a number", f(), "run", &["--threads", "many"], &["'many'", "--threads"]),
        case("usage: negative threads", f(), "run", &["--threads", "-1"], &["'-1'", "--threads"]),
        case("usage: negative checkpoint interval", f(), "run", &["--checkpoint-every-steps", "-3"], &["'-3'", "--checkpoint-every-steps"]),
        case("sound speed beyond every material", f(), "check", &["--set", "materials.0.eos.c0=1e300"], &["materials[0].eos.c0: must be at most 100000 m/s, beyond every real material (got 1e300)"]),
        case("density below every material", f(), "check", &["--set", "materials.0.rho0=1e-300"], &["materials[0].rho0: must be at least 0.001 kg/m^3, below every real material (got 1e-300)"]),
        case("shear modulus of a fluid's order", f(), "check", &["--set", "materials.0.shear_modulus=1e-20"], &["materials[0].shear_modulus: must be 0 (a fluid) or at least 1e-8 of the bulk modulus"]),
        case("hugoniot u_p faster than any impact", window(), "hugoniot", &["--up", "100,1e300"], &["--up: 1e300 m/s is faster than any impact or shock (at most 1e5 m/s)"]),
        case("unknown SIMD level", f(), "run", &["--simd", "sse"], &["--simd sse: unknown instruction-set level `sse` (one of auto, baseline, avx2, avx512)"]),
        case("nonexistent scene file", None, "check", &[], &["missing.toml: cannot read scene"]),
        case("JH1 tensile limit not a tension", impact(), "check", &["--set", "materials.1.strength.tensile_limit=7.5e8"], &["materials[1].strength.tensile_limit: must be negative"]),
        case("Johnson-Cook melt below room temperature", impact(), "check", &["--set", "materials.0.strength.t_melt=200"], &["materials[0].strength.t_melt: must exceed t_room = 298 K (got 200)"]),
        case("Taylor-Quinney factor above 1", impact(), "check", &["--set", "materials.0.strength.taylor_quinney=1.5"], &["materials[0].strength.taylor_quinney: must lie in [0, 1] (got 1.5)"]),
        case("unknown strength model", impact().replacen("name = \"sic\"", "name = \"sic\"\nstrength = { type = \"jh2\" }", 1), "check", &[], &["materials[1].strength.type: unknown type `jh2`"]),
        case("back face with no particle on it", impact(), "run", &["--set", "monitor.back_face.position=0.5"], &["monitor.back_face: no particle of `sic` starts within one spacing of x[0] = 5e-1 m"]),
        case("monitor on an unknown material", impact(), "check", &["--set", "monitor.back_face.material=alumina"], &["monitor.back_face.material: unknown material `alumina`"]),
        case("window not periodic across the flow", window_open, "check", &[], &["periodic.axes: a window must be periodic across the flow (axis 1 missing)"]),
        case("window feed not whole spacings", window(), "check", &["--set", "window.feed=2.05e-5"], &["window.feed: must be a whole number of lattice spacings"]),
        case("window sample driven", window(), "run", &["--set", "bodies.0.driven=true"], &["bodies[0]: a window's sample takes its velocity from the window"]),
        case("window shock speed negative", window(), "check", &["--set", "window.us=-5"], &["window.us: must be positive and finite (got -5)"]),
        case("window exit regions too wide", window(), "check", &["--set", "window.d_out1=5.5e-4"], &["window.d_out1: entry and exit regions plus one feed length must leave room"]),
        case("hugoniot without a window", f(), "hugoniot", &[], &["no [window] section"]),
        case("hugoniot bracket not LO,HI", window(), "hugoniot", &["--bracket", "500"], &["--bracket: `500` must be LO,HI with LO < HI"]),
        case("hugoniot negative u_p", window(), "hugoniot", &["--up", "100,-5"], &["--up: `-5` is not a positive number"]),
        case("option the scheme does not read", f(), "check", &["--set", "scheme=av", "--set", "options.limiter=mc"], &["options.limiter: not read by scheme av"]),
        case("Riemann solver for scheme av", impact(), "run", &["--set", "scheme=av"], &["options.riemann: not read by scheme av (it solves no Riemann problem)"]),
        case("tkc half switched", f(), "check", &["--set", "scheme=tkc", "--set", "options.correction=true"], &["options.correction: scheme tkc always has correction"]),
        case("--unset a key that is not there", f(), "check", &["--unset", "options.riemann"], &["--unset options.riemann: `options.riemann` is not in the scene"]),
        case("negative tensile strength", f(), "check", &["--set", "materials.0.tensile_strength=-1"], &["materials[0].tensile_strength: must be positive"]),
        case("tensile strength with JH1", impact(), "check", &["--set", "materials.1.tensile_strength=1e9"], &["materials[1].tensile_strength: JH1 has its own tensile limit"]),
        case("periodic length below twice the kernel support", strip(), "check", &["--set", "h_factor=2.6"], &["periodic.hi: the periodic length along axis 1 is 1e-3 m, below twice the kernel support, 2 x 2 h = 1.04e-3 m (h = h_factor 2.6 x spacing 1e-4 m of bodies[0])"]),
        case("array where a table is expected", f(), "check", &["--set", "options=[0.0, 0.0]"], &["--set options=[0.0, 0.0]: options: expected a table, found an array"]),
        case("unknown library material", f(), "check", &["--set", "materials.0.library=steel_434"], &["materials[0].library: `steel_434` is not in the material library (close: steel_4340"]),
        case("snapshots above the limit", f(), "run", &["--set", "output.snapshots=1000000000"], &["output.snapshots: at most 100000 (got 1000000000)"]),
        case("particle file missing", f(), "run", &["--set", "bodies.0.shape={ type = \"particles\", file = \"gone.csv\" }"], &["bodies[0].shape.file: gone.csv: cannot read"]),
        case("STL shape in 1D", f(), "check", &["--set", "bodies.0.shape={ type = \"stl\", file = \"rod.stl\" }"], &["bodies[0].shape: an `stl` shape is a closed surface in 3D; the scene is 1D"]),
        case("Tillotson e_cv not above e_iv", TILLOTSON_BAR.to_string(), "check", &["--set", "materials.0.eos.e_cv=2e6"], &["materials[0].eos.e_cv: must exceed e_iv = 3e6 J/kg (got 2e6)"]),
        case("Tillotson negative A", TILLOTSON_BAR.to_string(), "run", &["--set", "materials.0.eos.big_a=-1e9"], &["materials[0].eos.big_a: must be positive and finite (got -1e9)"]),
        case("t_end no run could reach", f(), "run", &["--set", "t_end=1e300"], &["t_end: 1e300 s would take about 1.0e308 steps of about 1.0e-8 s", "set max_steps to run it anyway"]),
        case("two coincident walls", wall_bar(), "run", &["--set", "walls=[{point=[0.0],normal=[1.0]},{point=[0.0],normal=[1.0]}]"], &["walls: walls[0] and walls[1] are the same plane with the same normal"]),
        case("50 parallel walls closer than the kernel's reach", fifty_walls, "run", &[], &["walls[0] and walls[1] are parallel and 1.000e-6 m apart, less than the kernel's reach"]),
        case("walls meeting at 45° near the particles", WEDGE_2D.to_string(), "run", &[], &["walls[0] and walls[1] meet at 45.0°, not at a right angle, within the kernel's reach"]),
        case("particle file that is a device", f(), "run", &["--set", "bodies.0.shape={ type = \"particles\", file = \"/dev/zero\" }"], &["bodies[0].shape.file: /dev/zero: not a regular file"]),
        case("long value quoted as an excerpt", f(), "check", &["--set", "materials.0.rho0=dddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddddd"], &["materials[0].rho0: invalid type: string \"dddddddddddddddddddddddddddddddddddddddd…\", expected f64"]),
        case("more particles than max_particles", f(), "run", &["--set", "max_particles=50"], &["bodies[1].spacing", "more than the limit 5e1 (`max_particles` raises it)"]),
        case("key an elastic material does not read", f(), "check", &["--set", "materials.0.strength={ type = \"elastic\", yield_stress = 1e9 }"], &["materials[0].strength.yield_stress: unknown key (this table takes no other keys)"]),
        case("key of the Johnson-Cook model misspelt", impact(), "check", &["--set", "materials.0.strength.t_mel=1800"], &["materials[0].strength.t_mel: unknown key (known: a, b, n, c, m, eps_dot0, t_room, t_melt, specific_heat, taylor_quinney)"]),
    ]
}

/// Runs every case; with `GSPH_CATALOGUE=FILE` set, also writes the Markdown table of
/// inputs and messages (host/docs/bad_input.md is generated this way).
#[test]
fn bad_input_gives_one_line_and_no_results() {
    let mut failures = Vec::new();
    let mut table = String::from("| # | input | command | message |\n| ---: | --- | --- | --- |\n");
    for (k, c) in cases().into_iter().enumerate() {
        let tmp = tempfile::tempdir().unwrap();
        let dir = tmp.path();
        let scene = match &c.scene {
            Some(text) => {
                std::fs::write(dir.join("scene.toml"), text).unwrap();
                "scene.toml"
            }
            None => "missing.toml",
        };
        let out: PathBuf = dir.join("out");
        let mut args = vec![c.cmd, scene];
        if c.cmd == "run" {
            args.extend(["--out", "out", "--quiet"]);
            // An earlier run's results: a command refused before its run starts leaves
            // them as they were; a run that fails after it started has removed them (it
            // was replacing them). Either way no other result file and no temp file.
            std::fs::create_dir_all(&out).unwrap();
            if !c.name.starts_with("usage:") {
                std::fs::write(out.join("summary.json"), "{}").unwrap();
            }
        }
        args.extend(c.args.iter().copied());
        let o = gsph(dir, &args);
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        let mut why = Vec::new();
        if o.status.success() {
            why.push("exit status 0".to_string());
        }
        if o.status.code().is_none() {
            why.push(format!("killed: {:?}", o.status));
        }
        if err.trim_end_matches('\n').lines().count() != 1 || !err.starts_with("error: ") {
            why.push("stderr is not one `error: ` line".into());
        }
        if err.contains("panicked") {
            why.push("panicked".into());
        }
        for w in &c.expect {
            if !err.contains(w) {
                why.push(format!("missing `{w}`"));
            }
        }
        table.push_str(&format!(
            "| {} | {} | `gsph {} SCENE {}` | {} |\n",
            k + 1,
            c.name,
            c.cmd,
            c.args.join(" ").replace('|', "\\|"),
            err.trim_end()
                .replace('|', "\\|")
                .replace(dir.to_str().unwrap_or("?"), "DIR")
        ));
        let marker = std::fs::read(out.join("summary.json")).ok();
        let mut left = leftovers(&out);
        if marker.as_deref() == Some(b"{}".as_slice()) {
            left.retain(|n| n != "summary.json");
        }
        if c.cmd == "run" && !left.is_empty() {
            why.push(format!("left {left:?}"));
        }
        if !why.is_empty() {
            failures.push(format!("{}: {} -- stderr: {err:?}", c.name, why.join(", ")));
        }
    }
    if let Some(path) = std::env::var_os("GSPH_CATALOGUE") {
        std::fs::write(path, &table).unwrap();
    }
    assert!(failures.is_empty(), "\n{}", failures.join("\n"));
}

#[test]
fn check_of_the_flyer_plate_prints_counts_and_effects() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let o = gsph(&dir, &["check", "cases/flyer_plate.toml"]);
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(out.contains("particles 100"), "{out}");
    assert!(
        out.contains("\nmaterial  metal: library connolly2013_flyer_metal\n"),
        "{out}"
    );
    assert!(out.contains("effects   strength+plasticity+muscl"), "{out}");
    assert!(o.stderr.is_empty());
}

fn summary(dir: &Path) -> serde_json::Map<String, serde_json::Value> {
    let text = std::fs::read_to_string(dir.join("summary.json")).unwrap();
    match serde_json::from_str(&text).unwrap() {
        serde_json::Value::Object(m) => m,
        v => panic!("summary.json is not an object: {v}"),
    }
}

#[test]
fn run_of_the_flyer_plate_writes_every_output() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("scene.toml"), flyer()).unwrap();
    let o = gsph(
        tmp.path(),
        &["run", "scene.toml", "--out", "out", "--quiet"],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = tmp.path().join("out");
    for f in RESULTS {
        assert!(out.join(f).is_file(), "no {f}");
    }
    let tmps: Vec<_> = leftovers(&out)
        .into_iter()
        .filter(|n| n.ends_with(".tmp"))
        .collect();
    assert!(tmps.is_empty(), "{tmps:?}");
    let s = summary(&out);
    for k in [
        "scene",
        "dim",
        "scheme",
        "effects",
        "particles",
        "steps",
        "t_end",
        "wall_s",
        "simd",
        "energy_initial",
        "energy_final",
        "energy_rel_error",
        "momentum_initial",
        "momentum_final",
        "l1_error",
    ] {
        assert!(s.contains_key(k), "summary.json has no `{k}`");
    }
    assert_eq!(s["particles"], 100);
    let csv = std::fs::read_to_string(out.join("final.csv")).unwrap();
    let mut lines = csv.lines();
    // the documented columns: those of every gsph first (new ones are appended before the
    // stress columns), the header the library writes
    let header = lines.next().unwrap();
    assert!(header.starts_with("id,material,x,y,z,vx,vy,vz,m,rho,p,e,sxx,syy,szz,sxy,sxz,syz,eps_p,damage,temperature,h,"), "{header}");
    assert!(
        header.ends_with(",sigma_xx,sigma_yy,sigma_zz,sigma_xy,sigma_xz,sigma_yz,von_mises"),
        "{header}"
    );
    assert_eq!(header, gsph::output::csv::csv_header());
    assert_eq!(lines.filter(|l| !l.is_empty()).count(), 100);
    assert_eq!(s["ended"], "t_end");
}

/// `GSPH_SIMD` picks the level (recorded in summary.json and run.log); one the code does
/// not know is refused with a line naming the variable, before the output folder exists.
#[test]
fn gsph_simd_picks_the_level_and_a_bad_one_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("scene.toml"), flyer()).unwrap();
    let run = |env: &str, out: &str, more: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_gsph"))
            .args(["run", "scene.toml", "--out", out, "--quiet"])
            .args(more)
            .env("GSPH_SIMD", env)
            .current_dir(tmp.path())
            .output()
            .expect("gsph starts")
    };
    let o = run("baseline", "a", &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(summary(&tmp.path().join("a"))["simd"], "baseline");
    let log = std::fs::read_to_string(tmp.path().join("a/run.log")).unwrap();
    assert!(log.contains("SIMD: baseline"), "{log}");
    // the flag wins over the variable
    let o = run("bogus", "b", &["--simd", "baseline"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let o = run("bogus", "c", &[]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(
        err.contains("GSPH_SIMD=bogus: unknown instruction-set level `bogus`"),
        "{err}"
    );
    assert!(
        !tmp.path().join("c").exists(),
        "a refused run made its folder"
    );
}

/// A run that `max_steps` stops says so (issue 25: it looked finished in summary.json).
#[test]
fn a_run_stopped_by_max_steps_says_how_it_ended() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("scene.toml"), flyer()).unwrap();
    let o = gsph(
        dir,
        &[
            "run",
            "scene.toml",
            "--out",
            "out",
            "--quiet",
            "--set",
            "max_steps=7",
        ],
    );
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = summary(&dir.join("out"));
    assert_eq!(s["ended"], "max_steps");
    assert_eq!(s["steps"], 7);
    assert!(s["t_end"].as_f64().unwrap() < 0.5e-6);
    let o = gsph(
        dir,
        &["run", "scene.toml", "--out", "out2", "--set", "max_steps=7"],
    );
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(text.contains("stopped by max_steps = 7 at t = "), "{text}");
}

#[test]
fn overrides_change_scheme_and_resolution() {
    let tmp = tempfile::tempdir().unwrap();
    std::fs::write(tmp.path().join("scene.toml"), flyer()).unwrap();
    let args = [
        "run",
        "scene.toml",
        "--out",
        "out",
        "--quiet",
        "--set",
        "scheme=pm",
        "--set",
        "resolution_scale=0.5",
    ];
    let o = gsph(tmp.path(), &args);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let s = summary(&tmp.path().join("out"));
    assert_eq!(s["particles"], 50);
    assert_eq!(s["scheme"], "pm");
}

/// Points given many times over in a particle file overflow the neighbour lists before the
/// Issue 45: 20,000 particles at one point with `neighbor_capacity = 20000` are named as
/// coincident before any list is built (the lists asked for 7 GB and the run aborted).
#[test]
fn a_crowd_at_one_point_is_named_before_the_lists_are_built() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let csv = format!("x\n{}", "2.5e-3\n".repeat(20_000));
    std::fs::write(dir.join("points.csv"), csv).unwrap();
    let scene = flyer().replacen(
        "shape = { type = \"segment\", min = 0.0, max = 0.005 }",
        "shape = { type = \"particles\", file = \"points.csv\" }",
        1,
    );
    std::fs::write(
        dir.join("scene.toml"),
        format!("neighbor_capacity = 20000\n{scene}"),
    )
    .unwrap();
    let o = gsph(dir, &["check", "scene.toml"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("are at the same point (2.5000e-3,"), "{err}");
}

/// Issue 45: `gsph plot profile` reads profile.csv as carefully as series.csv: an empty,
/// ragged or foreign file is refused in one line naming the file and line.
#[test]
fn plot_profile_refuses_an_empty_or_ragged_table() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    std::fs::write(dir.join("scene.toml"), case_text("riemann_al.toml")).unwrap();
    let o = gsph(dir, &["run", "scene.toml", "--out", "r", "--quiet"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let good = std::fs::read_to_string(dir.join("r/profile.csv")).unwrap();
    assert!(gsph(dir, &["plot", "profile", "r"]).status.success());
    for (text, expect) in [
        (String::new(), "the header is ``, not gsph's"),
        (
            "x,sigma_xx,sigma_xx_exact\n".to_string(),
            "no rows after the header",
        ),
        (format!("{good}1e-3,2e8\n"), "values, the header names 3"),
        (
            good.replacen("\n", "\nabc,1,2\n", 1),
            "line 2, column x: `abc` is not a number",
        ),
    ] {
        std::fs::write(dir.join("r/profile.csv"), &text).unwrap();
        let o = gsph(dir, &["plot", "profile", "r"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{text:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.contains("profile.csv") && err.contains(expect), "{err}");
    }
}

/// overlap check can run: the message names two coincident particles, not the capacity
/// (issue 25: "raise `neighbor_capacity`" was the advice).
#[test]
fn duplicate_points_are_named_not_blamed_on_the_capacity() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let mut csv = String::from("x\n");
    for k in 0..10 {
        for _ in 0..30 {
            csv.push_str(&format!("{:e}\n", (k as f64 + 0.5) * 1e-4));
        }
    }
    std::fs::write(dir.join("points.csv"), csv).unwrap();
    std::fs::write(
        dir.join("scene.toml"),
        flyer().replacen(
            "shape = { type = \"segment\", min = 0.0, max = 0.005 }",
            "shape = { type = \"particles\", file = \"points.csv\" }",
            1,
        ),
    )
    .unwrap();
    let o = gsph(dir, &["check", "scene.toml"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.contains("are at the same point (5.0000e-5,"), "{err}");
    assert!(
        err.contains("a point given twice in a particle file"),
        "{err}"
    );
    assert!(!err.contains("neighbor_capacity"), "{err}");
}
