//! The keys other codes' users expect: a fixed time step (`dt`), a constant smoothing
//! length (`constant_h`), and the elastic-body diagnostics of `[monitor]` (`bodies`,
//! `strain_energy`, `close_pairs`) that the colliding rings are judged by.

use gsph::driver::{run, RunOptions};
use gsph::scene::parse;
use serde_json::{Map, Value};

/// Two blocks of the rings' rubber closing at +-10 m/s, 5 spacings apart (beyond the
/// kernel support), the left one compressed 1 %.
const BLOCKS: &str = r#"
dim = 2
scheme = "av"
t_end = 2.0e-6
h_factor = 1.5
[output]
snapshots = 1
[[materials]]
name = "rubber"
rho0 = 1.0
poisson_ratio = 0.3975
eos = { type = "linear", c0 = 4032.3891927275595 }
strength = { type = "elastic" }
[[bodies]]
material = "rubber"
shape = { type = "box", min = [0.0, 0.0], max = [0.01, 0.01] }
spacing = 5.0e-4
velocity = { type = "uniform", value = [10.0, 0.0] }
initial = { type = "density", rho = 1.01, e = 0.0 }
[[bodies]]
material = "rubber"
shape = { type = "box", min = [0.012, 0.0], max = [0.022, 0.01] }
spacing = 5.0e-4
velocity = { type = "uniform", value = [-10.0, 0.0] }
[monitor]
bodies = true
strain_energy = true
close_pairs = 0.75
"#;

fn go(set: &[&str]) -> Result<(Map<String, Value>, gsph::output::ParticleTable), String> {
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let sc = parse(BLOCKS, "blocks", &set).map_err(|e| e.0)?;
    let r = run(
        &sc,
        "blocks",
        &RunOptions {
            out: None,
            progress: false,
        },
    )
    .map_err(|e| e.to_string())?;
    Ok((r.summary.to_map(), r.table))
}

fn num(s: &Map<String, Value>, k: &str) -> f64 {
    s[k].as_f64().unwrap_or_else(|| panic!("{k} missing"))
}

#[test]
fn a_fixed_time_step_is_taken_exactly_and_an_unstable_one_refused() {
    let (s, _) = go(&["dt=1e-8"]).unwrap();
    assert_eq!(s["steps"].as_u64(), Some(200));
    let (cfl, _) = go(&[]).unwrap();
    assert!(
        cfl["steps"].as_u64().unwrap() < 200,
        "the CFL step is longer here"
    );
    // h / (c_l + |v|) = 7.5e-4 / (4590 + 10) = 1.63e-7 s
    let e = go(&["dt=2e-7"]).unwrap_err();
    assert!(
        e.starts_with("step 1 ") && e.contains("dt = 2.0000e-7 s") && !e.contains('\n'),
        "{e}"
    );
    for (set, key) in [
        (vec!["dt=1e-8", "cfl=0.3"], "dt"),
        (vec!["dt=1e-5"], "dt"),
        (vec!["dt=-1e-8"], "dt"),
        (vec!["cfl=2"], "cfl"),
    ] {
        let e = go(&set).unwrap_err();
        assert!(e.contains(key) && !e.contains('\n'), "{set:?}: {e}");
    }
}

#[test]
fn constant_h_keeps_every_smoothing_length() {
    // a particle's mass is its initial density times its lattice cell: h starts at 1.5 dx
    let h0 = 1.5 * 5.0e-4;
    let (_, fixed) = go(&["constant_h=true", "dt=1e-8"]).unwrap();
    let (_, free) = go(&["dt=1e-8"]).unwrap();
    let left = |t: &gsph::output::ParticleTable| -> Vec<f64> {
        (0..t.len())
            .filter(|&i| t.id[i] < 400)
            .map(|i| t.h[i])
            .collect()
    };
    assert!(left(&fixed).iter().all(|&h| (h - h0).abs() < 1e-18));
    assert!(left(&free).iter().any(|&h| (h - h0).abs() > 1e-9));
}

#[test]
fn elastic_diagnostics_against_hand_values() {
    // at t = 0 (one step of 1e-12 s): each block moves at +-10 m/s, the left one holds
    // V p²/(2K) with p = c0² 0.01 rho0 and K = rho0 c0², the right one nothing
    let (s, _) = go(&["dt=1e-12", "t_end=1e-12"]).unwrap();
    assert!((num(&s, "body0_vx") - 10.0).abs() < 1e-6);
    assert!((num(&s, "body1_vx") + 10.0).abs() < 1e-6);
    assert!(num(&s, "body0_vy").abs() < 1e-9);
    let c2 = 4032.3891927275595f64.powi(2);
    let p = c2 * 0.01;
    let volume = 0.01 * 0.01; // 400 lattice cells of dx² (mass 1.01 rho0 dx² each)
    let se = volume * p * p / (2.0 * c2);
    let got = num(&s, "strain_energy");
    assert!((got - se).abs() < 1e-3 * se, "{got} against {se}");
    // a square lattice: no close pair, nearest neighbours one spacing apart
    assert_eq!(num(&s, "close_fraction"), 0.0);
    assert!((num(&s, "min_distance") - 1.0).abs() < 1e-6);
    let e = go(&["monitor.close_pairs=1.5"]).unwrap_err();
    assert!(e.contains("monitor.close_pairs"), "{e}");
}
