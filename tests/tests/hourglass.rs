//! The hourglass stiffness (issue 46; effect `hourglass`, `options.hourglass = xi`,
//! `gsph_core::schemes::hourglass`): with Riemann dissipation only where pairs compress,
//! the free elastic rings of issue 27 keep their energy and their lattice in ts1 and ts2,
//! total energy stays exact, and the spinning ring keeps its angular momentum.
//!
//! Without the stiffness the same runs clump (the nearest pair at 0.007-0.035 spacings)
//! and the breathing ring keeps half its energy: the controls below show it, so the
//! targets cannot pass by themselves. The rings at dx = 2e-3 (552 particles); the
//! issue's targets: breathing ts1/ts2 >= 0.97, spinning >= 0.99 of (KE + SE)/E0.

use gsph::driver::{run, RunOptions};
use serde_json::{Map, Value};

fn summary(case: &str, set: &[&str]) -> Result<Map<String, Value>, String> {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let sc = gsph::scene::load(&gsph_tests::case(case), &set).map_err(|e| e.to_string())?;
    let r = run(
        &sc,
        case,
        &RunOptions {
            out: None,
            progress: false,
        },
    )
    .map_err(|e| e.to_string())?;
    Ok(r.summary.to_map())
}

fn num(s: &Map<String, Value>, k: &str) -> f64 {
    s[k].as_f64().unwrap_or_else(|| panic!("{k} missing"))
}

const COARSE: &str = "resolution_scale=0.5";
const COMPRESSION: &str = "options.dissipation=compression";
const STIFF: &str = "options.hourglass=1";

#[test]
fn the_breathing_ring_keeps_its_energy_and_its_lattice() {
    for scheme in ["ts1", "ts2"] {
        let sch = format!("scheme={scheme}");
        let with = summary("ring_breathing", &[&sch, COARSE, COMPRESSION, STIFF]).unwrap();
        let without = summary("ring_breathing", &[&sch, COARSE, COMPRESSION]).unwrap();
        let (m1, m0) = (
            num(&with, "mechanical_energy_ratio"),
            num(&without, "mechanical_energy_ratio"),
        );
        let (d1, d0) = (
            num(&with, "min_distance_min"),
            num(&without, "min_distance_min"),
        );
        assert!(
            (0.97..=1.01).contains(&m1),
            "{scheme}: (KE+SE)/E0 {m1} with the stiffness"
        );
        assert!(
            d1 > 0.75,
            "{scheme}: pairs came to {d1} dx with the stiffness"
        );
        assert!(
            num(&with, "energy_rel_error").abs() < 1e-12,
            "{scheme}: total energy not exact"
        );
        // the control: the same run without the stiffness clumps and loses half
        assert!(m0 < 0.8 && d0 < 0.1, "{scheme}: control {m0}, {d0} dx");
    }
}

#[test]
fn the_spinning_ring_keeps_its_energy_and_angular_momentum() {
    for scheme in ["ts1", "ts2"] {
        let sch = format!("scheme={scheme}");
        let with = summary("ring_spin", &[&sch, COARSE, COMPRESSION, STIFF]).unwrap();
        let without = summary("ring_spin", &[&sch, COARSE, COMPRESSION]).unwrap();
        let m1 = num(&with, "mechanical_energy_ratio");
        let dl1 = num(&with, "angular_momentum_change");
        assert!((0.99..=1.01).contains(&m1), "{scheme}: (KE+SE)/E0 {m1}");
        assert!(
            dl1.abs() < 2e-3,
            "{scheme}: angular momentum changed by {dl1}"
        );
        assert!(num(&with, "min_distance_min") > 0.75);
        // the control: without it the ring clumps and loses 4-5 % of its spin
        let dl0 = num(&without, "angular_momentum_change");
        assert!(
            dl0.abs() > 10.0 * dl1.abs() && num(&without, "min_distance_min") < 0.1,
            "{scheme}: control dL {dl0}"
        );
    }
}

/// A block of a fluid (no strength model).
const FLUID: &str = r#"
name = "fluid"
dim = 2
scheme = "ts2"
t_end = 1e-6
[options]
hourglass = 1.0
[[materials]]
name = "water"
rho0 = 1000.0
eos = { type = "linear", c0 = 1500.0 }
[[bodies]]
material = "water"
shape = { type = "box", min = [0.0, 0.0], max = [0.01, 0.01] }
spacing = 1.0e-3
"#;

#[test]
fn the_stiffness_is_refused_where_it_cannot_act() {
    // no shear modulus to scale it
    let e = gsph::scene::parse(FLUID, "fluid", &[]).map_err(|e| e.0);
    let e = e.and_then(|sc| {
        run(
            &sc,
            "fluid",
            &RunOptions {
                out: None,
                progress: false,
            },
        )
        .map(|_| ())
        .map_err(|e| e.to_string())
    });
    let e = e.expect_err("a fluid with the hourglass stiffness ran");
    assert!(
        e.contains("options.hourglass") && e.contains("strength") && !e.contains('\n'),
        "{e}"
    );
    // av has no stiffness: refused naming the key and the scheme
    let e = summary("ring_spin", &["scheme=av", COARSE, STIFF]).unwrap_err();
    assert!(
        e.contains("options.hourglass") && e.contains("av") && !e.contains('\n'),
        "{e}"
    );
    // xi must be positive
    for bad in ["options.hourglass=0", "options.hourglass=-1"] {
        let e = summary("ring_spin", &[COARSE, bad]).unwrap_err();
        assert!(e.contains("options.hourglass") && !e.contains('\n'), "{e}");
    }
}
