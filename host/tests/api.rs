//! The library interface (gsph::api): the runs equal `gsph run`'s bit for bit (final
//! state, series.csv with the monitor's columns, summary measures, snapshots.h5), fields in
//! id order, the checks on every argument, the momentum budget of external forces,
//! caller-given particles, the typed builder, checkpoints, overrides that unset keys, and
//! every bundled scene built and stepped. The C ABI over it is tested in host/capi.

use gsph::api::{unset, Effect, Particles, SceneBuilder, Simulation};
use gsph::driver::{run, RunOptions};
use gsph::scene::{self, BodySpec, MaterialSpec, ShapeSpec, Strength, VelocitySpec};
use gsph_core::material::eos::{Eos, Hugoniot};
use gsph_core::schemes::Scheme;
use std::path::Path;

fn case(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../cases")
        .join(name)
}

fn flyer() -> Simulation {
    Simulation::from_file(&case("flyer_plate.toml"), &[]).unwrap()
}

#[test]
fn run_equals_the_driver_bit_for_bit() {
    let mut sim = flyer();
    let steps = sim.run().unwrap();
    let scene = scene::load(&case("flyer_plate.toml"), &[]).unwrap();
    let opts = RunOptions {
        out: None,
        progress: false,
    };
    let r = run(&scene, "flyer_plate", &opts).unwrap();
    assert_eq!(sim.table(), r.table);
    assert_eq!(r.summary.steps, steps);
    let s = sim.summary();
    assert_eq!(s["l1_error"].as_f64(), r.summary.measure("l1_error"));
    assert_eq!(
        s["energy_rel_error"].as_f64(),
        Some(r.summary.energy_rel_error)
    );
}

fn plate(min: f64, max: f64, v: f64) -> BodySpec {
    BodySpec {
        material: "metal".into(),
        shape: ShapeSpec::Segment { min, max },
        spacing: 1.0e-4,
        lattice: None,
        layout: None,
        relax_iterations: None,
        lattice_origin: None,
        velocity: Some(VelocitySpec::Uniform { value: vec![v] }),
        initial: None,
        pores: None,
        driven: false,
        jitter: 0.0,
    }
}

fn metal() -> MaterialSpec {
    MaterialSpec {
        name: "metal".into(),
        rho0: 6100.0,
        shear_modulus: 48.1e9,
        poisson_ratio: None,
        eos: Eos::Hugoniot(Hugoniot {
            rho0: 0.0, // the material's rho0 is used
            c0: 5077.0,
            s1: 1.201,
        }),
        strength: Some(Strength::VonMises {
            yield_stress: 2.5e9,
        }),
        tensile_strength: None,
    }
}

#[test]
fn builder_scene_equals_the_file() {
    let built = SceneBuilder::new(1, Scheme::Ts2, 0.5e-6)
        .cfl(0.5)
        .snapshots(10)
        .material(metal())
        .body(plate(0.0, 0.005, 602.81))
        .body(plate(0.005, 0.01, 0.0));
    let mut a = built.build().unwrap();
    let mut b = flyer();
    // ts2 is the ts family with MUSCL; strength and plasticity come from the material
    assert!(a.simulates(Effect::Strength) && a.simulates(Effect::Plasticity));
    assert!(a.simulates(Effect::Muscl) && !a.simulates(Effect::Damage));
    a.run().unwrap();
    b.run().unwrap();
    assert_eq!(a.steps(), b.steps());
    assert!(
        a.table() == b.table(),
        "the builder's run differs from the file's"
    );
    // a bad value is refused naming the key, as in a file
    let e = SceneBuilder::new(1, Scheme::Ts2, -1.0)
        .material(metal())
        .body(plate(0.0, 0.005, 0.0))
        .build()
        .err()
        .unwrap();
    assert!(e.to_string().contains("t_end"), "{e}");
    // an effect that is not an option is refused, not ignored
    let e = SceneBuilder::new(1, Scheme::Ts2, 1e-6)
        .with(Effect::Damage)
        .material(metal())
        .body(plate(0.0, 0.005, 0.0))
        .build()
        .err()
        .unwrap();
    assert!(e.to_string().contains("options.damage"), "{e}");
}

#[test]
fn fields_by_name_in_id_order_and_their_checks() {
    let mut sim = flyer();
    let n = sim.len();
    let x = sim.get("position").unwrap();
    assert!(x.windows(2).all(|w| w[0] < w[1]));
    for _ in 0..5 {
        sim.step(None).unwrap();
    }
    assert_eq!(sim.ids(), (0..n as u32).collect::<Vec<_>>());
    let err = |r: Result<Vec<f64>, gsph::api::ApiError>| r.err().unwrap().to_string();
    assert!(err(sim.get("nope")).starts_with("unknown field `nope` (fields: position"));
    assert!(err(sim.get("damage"))
        .contains("not simulated by this scene (ts2 scheme): no material has a damage model"));
    let e = sim
        .write("pressure", &vec![0.0; n])
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("read-only"), "{e}");
    let e = sim.write("rho", &[1.0; 3]).err().unwrap().to_string();
    assert!(e.contains("buffer of 3 values, 100 needed"), "{e}");
    let mut rho = sim.get("rho").unwrap();
    let before = rho.clone();
    rho[7] = -1.0;
    let e = sim.write("density", &rho).err().unwrap().to_string();
    assert_eq!(
        e,
        "field `density`: value 7 (particle 7) must be positive (got -1e0)"
    );
    assert_eq!(sim.get("rho").unwrap(), before, "nothing written on error");
    let e = sim.step(Some(1.0)).err().unwrap().to_string();
    assert!(e.contains("dt"), "{e}");
}

#[test]
fn external_forces_close_the_momentum_budget() {
    let mut sim = flyer();
    let n = sim.len();
    let m = sim.get("mass").unwrap();
    let p0 = sim.momentum()[0];
    let mut applied = 0.0;
    let mut work = 0.0;
    for k in 0..40 {
        let x = sim.get("x").unwrap();
        let a: Vec<f64> = x
            .iter()
            .map(|x| 3e6 * (x / 0.01) * (k as f64).cos())
            .collect();
        sim.set_external_acceleration(&a).unwrap();
        let dt = sim.step(None).unwrap();
        applied += (0..n).map(|i| m[i] * a[i] * dt).sum::<f64>();
        work = sim.external_work();
    }
    let change = sim.momentum()[0] - p0;
    assert!(
        ((change - applied) / applied).abs() < 1e-10,
        "momentum change {change:e}, impulse {applied:e}"
    );
    assert!(((sim.external_impulse()[0] - applied) / applied).abs() < 1e-12);
    // energy: the scheme conserves total energy, so its change is the kicks' work
    let s = sim.summary();
    assert!(work != 0.0);
    assert!(
        s["energy_rel_error"].as_f64().unwrap().abs() < 1e-9,
        "{s:?}"
    );
    let e = sim
        .set_external_acceleration(&[1.0; 3])
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("3 values given, 100 needed"), "{e}");
}

#[test]
fn particles_from_arrays() {
    let settings = r#"
dim = 1
scheme = "ts1"
t_end = 1e-7
[[materials]]
name = "metal"
rho0 = 6100.0
shear_modulus = 48.1e9
eos = { type = "hugoniot", c0 = 5077.0, s1 = 1.201 }
strength = { type = "von_mises", yield_stress = 2.5e9 }
"#;
    // the file's lattice positions (its second plate starts at 0.005: (i + 0.5) dx would
    // differ in the last bit)
    let mut b = Simulation::from_file(
        &case("flyer_plate.toml"),
        &["scheme=ts1".into(), "t_end=1e-7".into()],
    )
    .unwrap();
    let x = b.get("position").unwrap();
    let v: Vec<f64> = (0..100)
        .map(|i| if i < 50 { 602.81 } else { 0.0 })
        .collect();
    let mat = vec![0u32; 100];
    let parts = Particles {
        position: &x,
        velocity: &v,
        material: &mat,
        spacing: &[1e-4],
        ..Default::default()
    };
    let mut a = Simulation::from_particles(settings, "settings", &[], &parts).unwrap();
    a.advance_to(1e-7).unwrap();
    b.advance_to(1e-7).unwrap();
    assert!(a.get("deviator").unwrap() == b.get("deviator").unwrap());
    assert!(a.get("position").unwrap() == b.get("position").unwrap());
    let bad = Particles {
        material: &[0, 3],
        position: &[0.0, 1e-4],
        spacing: &[1e-4],
        ..Default::default()
    };
    let e = Simulation::from_particles(settings, "settings", &[], &bad)
        .err()
        .unwrap()
        .to_string();
    assert_eq!(
        e,
        "particles.material: particle 1 has material 3, but the settings define 1 material(s)"
    );
    let short = Particles {
        position: &x[..10],
        ..parts
    };
    let e = Simulation::from_particles(settings, "settings", &[], &short)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.starts_with("particles.position: 10 values given, 100 needed"),
        "{e}"
    );
}

#[test]
fn checkpoint_continues_bit_for_bit() {
    let dir = tempfile::tempdir().unwrap();
    // the same steps: both land on 0.2 us first
    let mut whole = flyer();
    whole.advance_to(0.2e-6).unwrap();
    whole.advance_to(0.4e-6).unwrap();
    let mut half = flyer();
    half.advance_to(0.2e-6).unwrap();
    half.write_checkpoint(dir.path()).unwrap();
    let mut again = Simulation::from_checkpoint(dir.path()).unwrap();
    assert_eq!(again.steps(), half.steps());
    again.advance_to(0.4e-6).unwrap();
    assert!(again.table() == whole.table(), "the continued run differs");
    // a time already passed is refused, not 0 steps (issue 45); the present is 0 steps
    let e = again.advance_to(-1.0).unwrap_err().to_string();
    assert!(
        e.contains("t: -1e0 s lies before the simulation's time"),
        "{e}"
    );
    assert!(again.advance_to(0.1e-6).is_err());
    assert_eq!(again.advance_to(again.time()).unwrap(), 0);
}

#[test]
fn a_failed_step_stops_the_simulation_and_writes_keep_h_consistent() {
    let mut sim = flyer();
    // density brings h along (h = h_factor (m / rho)^(1/D)), as the step's EOS refresh does
    let mut rho = sim.get("rho").unwrap();
    let h0 = sim.get("h").unwrap();
    rho[3] *= 1.1;
    sim.write("rho", &rho).unwrap();
    let h1 = sim.get("h").unwrap();
    assert!((h1[3] / h0[3] - 1.0 / 1.1).abs() < 1e-12 && h1[4] == h0[4]);
    // a deviator no material can hold overflows the step: the error names it, and the
    // half-stepped state refuses to go on
    let mut s = sim.get("deviator").unwrap();
    s[6 * 50] = 1e307;
    sim.write("deviator", &s).unwrap();
    let first = sim.step(None).expect_err("the step overflows").to_string();
    assert!(first.starts_with("step 1"), "{first}");
    let again = sim.step(None).err().unwrap().to_string();
    assert!(
        again.starts_with("this simulation failed (step 1"),
        "{again}"
    );
    assert!(sim.write("rho", &rho).is_err());
    // reading still works (for a post-mortem)
    assert_eq!(sim.get("rho").unwrap().len(), 100);
}

#[test]
fn a_checkpoint_refuses_state_it_cannot_hold() {
    let dir = tempfile::tempdir().unwrap();
    let mut sim = flyer();
    sim.set_external_acceleration(&[1e3; 100]).unwrap();
    sim.step(None).unwrap();
    let e = sim.write_checkpoint(dir.path()).err().unwrap().to_string();
    assert!(e.contains("external accelerations have acted"), "{e}");
    let parts = Particles {
        position: &[0.0, 1e-4, 2e-4],
        material: &[0, 0, 0],
        spacing: &[1e-4],
        ..Default::default()
    };
    let settings = "dim = 1\nscheme = \"ts1\"\nt_end = 1e-7\n[[materials]]\nname = \"m\"\nrho0 = 1000.0\neos = { type = \"linear\", c0 = 1000.0 }\n";
    let sim = Simulation::from_particles(settings, "settings", &[], &parts).unwrap();
    let e = sim.write_checkpoint(dir.path()).err().unwrap().to_string();
    assert!(e.contains("only a simulation built from scene text"), "{e}");
    // keys the library does not use are refused, not ignored
    let e = Simulation::from_file(
        &case("flyer_plate.toml"),
        &["output.checkpoint_steps=5".into()],
    )
    .err()
    .unwrap()
    .to_string();
    assert_eq!(
        e,
        "output.checkpoint_steps: not used by the library (call write_checkpoint instead)"
    );
}

fn gsph(args: &[&str]) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_gsph"))
        .args(args)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "gsph {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
}

/// A scene with a `[monitor]` and `output.series` (was refused by the library: "monitor: not
/// used by the library") run through the library and through `gsph run`: series.csv equal
/// byte for byte (the monitor's columns included), the summary's measures equal, and the
/// library's snapshots.h5 + .xdmf the CLI's frames, read by the HDF5 reader and by `gsph
/// plot particles`.
#[test]
fn monitor_series_and_snapshots_equal_gsph_run() {
    let dir = tempfile::tempdir().unwrap();
    let scene = case("steel_sic_impact.toml");
    let set = [
        "resolution_scale=0.1",
        "t_end=2e-6",
        "output.snapshots=4",
        "output.series=50",
    ];
    let cli = dir.path().join("cli");
    let mut args = vec!["run", scene.to_str().unwrap(), "--quiet"];
    args.extend(["--out", cli.to_str().unwrap()]);
    for s in &set {
        args.extend(["--set", s]);
    }
    gsph(&args);
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let mut sim = Simulation::from_file(&scene, &set).unwrap();
    let lib = dir.path().join("lib");
    sim.open_snapshots(&lib).unwrap();
    sim.run().unwrap();
    sim.close_snapshots().unwrap();
    sim.write_series(&lib.join("series.csv")).unwrap();
    let series = std::fs::read_to_string(lib.join("series.csv")).unwrap();
    assert_eq!(
        series,
        std::fs::read_to_string(cli.join("series.csv")).unwrap()
    );
    let header = series.lines().next().unwrap();
    assert!(header.ends_with(",back_face_velocity"), "{header}");
    // the series as numbers, a row per line of series.csv
    let s = sim.series();
    assert_eq!(s.rows.len(), series.lines().count() - 1);
    assert_eq!(s.names.join(","), header);
    assert_eq!(
        s.column("step").unwrap().last(),
        Some(&(sim.steps() as f64))
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(cli.join("summary.json")).unwrap()).unwrap();
    let ours = serde_json::Value::Object(sim.summary());
    for key in [
        "back_face_velocity_peak",
        "back_face_velocity_peak_time",
        "damaged_area_fraction",
        "temperature_max",
        "density_min",
        "kinetic_max",
        "energy_final",
    ] {
        assert!(!summary[key].is_null(), "{key}");
        assert_eq!(ours[key], summary[key], "{key}");
    }
    // the snapshots: the CLI's times and frames
    let (h5, h5_cli) = (lib.join("snapshots.h5"), cli.join("snapshots.h5"));
    let times = gsph::output::read_snapshot_times(&h5).unwrap();
    assert_eq!(times, gsph::output::read_snapshot_times(&h5_cli).unwrap());
    assert_eq!(times.len(), 5);
    for (step, _) in times {
        let (a, b) = (
            gsph::output::read_frame(&h5, step, usize::MAX).unwrap(),
            gsph::output::read_frame(&h5_cli, step, usize::MAX).unwrap(),
        );
        assert!(a.table == b.table && a.time == b.time, "step {step}");
    }
    assert!(std::fs::read_to_string(lib.join("snapshots.xdmf"))
        .unwrap()
        .contains("complete"));
    assert!(!lib.join("snapshots.partial.h5").exists());
    let png = dir.path().join("eps_p.png");
    gsph(&[
        "plot",
        "particles",
        lib.to_str().unwrap(),
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(png.metadata().unwrap().len() > 0);
    // one frame at once; a CSV path for HDF5 is refused
    sim.write_snapshots(&dir.path().join("one")).unwrap();
    let one = gsph::output::read_snapshot_times(dir.path().join("one/snapshots.h5")).unwrap();
    assert_eq!(one, vec![(sim.steps(), sim.time())]);
    let e = sim.write_snapshot(&dir.path().join("x.h5")).err().unwrap();
    assert!(e.to_string().contains("write_snapshot writes CSV"), "{e}");
    assert!(sim.append_snapshot().is_err() && sim.close_snapshots().is_err());
}

/// Overrides remove keys as `gsph run --unset` does (`unset:KEY`), in order with the sets.
#[test]
fn overrides_unset_keys() {
    let file = case("flyer_plate.toml");
    let with = flyer();
    let without = Simulation::from_file(&file, &[unset("reference")]).unwrap();
    assert!(with.summary().contains_key("l1_error"));
    assert!(!without.summary().contains_key("l1_error"));
    assert!(without.profile().is_err());
    let e = Simulation::from_file(&file, &[unset("nope")])
        .err()
        .unwrap();
    assert!(e.to_string().starts_with("--unset nope: "), "{e}");
}

/// The scene files of cases/ and cases/hard/, sorted.
fn scene_files() -> Vec<std::path::PathBuf> {
    let mut files = Vec::new();
    for dir in ["", "hard"] {
        for e in std::fs::read_dir(case(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.extension().is_some_and(|x| x == "toml") {
                files.push(p);
            }
        }
    }
    files.sort();
    files
}

/// Every bundled scene builds through the library (coarse and short) and takes a step
/// (6 of the 15 in cases/ were refused for their `[monitor]`, `output.series` or
/// `[window]`); a moving-window scene is refused in one line naming `[window]` and the
/// command that runs it.
#[test]
fn every_bundled_scene_builds_and_steps() {
    let files = scene_files();
    assert!(files.len() >= 15, "{files:?}");
    let (mut refused, mut windowed_scenes) = (0, 0);
    for file in &files {
        let set = [
            "resolution_scale=0.5".to_string(),
            "output.snapshots=1".to_string(),
        ];
        let windowed = scene::load(file, &set).unwrap().window.is_some();
        windowed_scenes += windowed as usize;
        match Simulation::from_file(file, &set) {
            Ok(mut sim) => {
                assert!(!windowed);
                let dt = sim
                    .step(None)
                    .unwrap_or_else(|e| panic!("{}: {e}", file.display()));
                assert!(dt > 0.0 && !sim.series().rows.is_empty());
            }
            Err(e) => {
                assert!(windowed, "{}: {e}", file.display());
                let f = file.display();
                assert_eq!(
                    e.to_string(),
                    format!("window: the moving window ([window]) is not run by the library; run this scene with `gsph run {f}` (its Hugoniot with `gsph hugoniot {f}`)")
                );
                refused += 1;
            }
        }
    }
    assert!(windowed_scenes > 0 && refused == windowed_scenes);
}

/// The library reads a scene file as `gsph run` does: only a regular file (`/dev/zero` was
/// read until memory ran out), and its messages quote a short excerpt of what it read
/// (`/proc/self/environ` reached `gsph_last_error` and Python exceptions whole).
#[test]
fn from_file_reads_only_regular_files_and_quotes_excerpts() {
    let e = match gsph::api::Simulation::from_file(Path::new("/dev/zero"), &[]) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("/dev/zero accepted as a scene"),
    };
    assert!(
        e.contains("/dev/zero") && e.contains("not a regular file"),
        "{e}"
    );
    let tmp = tempfile::tempdir().unwrap();
    let secret = format!("GSPH_SECRET_{}", "x".repeat(200));
    let p = tmp.path().join("scene.toml");
    std::fs::write(&p, format!("{secret}=1\0\n")).unwrap();
    let e = match gsph::api::Simulation::from_file(&p, &[]) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("a file that is not a scene was accepted"),
    };
    assert!(
        !e.contains(&secret),
        "the message quotes the whole line: {e}"
    );
    assert!(e.len() < 400, "{} bytes: {e}", e.len());
    assert_eq!(e.lines().count(), 1, "{e}");
}
