//! Piston-driven compaction of porous copper (cases/porous_cu_piston.toml, seed 004 §4) at
//! reduced size: the driven piston keeps its velocity exactly, the sample has the seed's
//! porosity, and the compaction front obeys mass conservation across it. Full compaction
//! to solid density gives the slowest possible front, D = m u_p / (m - 1) (Rankine–Hugoniot
//! mass balance rho_00 D = rho_1 (D - u_p) with rho_1 <= m rho_00); a front slower than that
//! would create mass. It must also stay below the elastic wave speed of copper.

use gsph::driver::{run, RunOptions};

#[test]
fn piston_drives_a_compaction_front_that_conserves_mass() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../cases/porous_cu_piston.toml"
    ))
    .unwrap();
    // 120 um of sample for 90 ns: the precursor reflected from the free rear end reaches the
    // front after about 0.1 us
    let sets: Vec<String> = [
        "scheme=pm",
        // pm has no MUSCL reconstruction: the scene's limiter is tkc's
        "unset:options.limiter",
        "t_end=9.0e-8",
        "bodies.1.shape.max=[1.2e-4, 2.0e-5]",
        "monitor.front.fit_from=0.3",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    let scene = gsph::scene::parse(&text, "porous", &sets).unwrap_or_else(|e| panic!("{e}"));
    let parts = gsph::scene::build_particles(&scene).unwrap();
    let m = parts.porosity[1];
    assert!((m - 1.35).abs() < 0.01, "porosity {m}");
    let r = run(
        &scene,
        "porous",
        &RunOptions {
            out: None,
            progress: false,
        },
    )
    .unwrap();
    let tab = &r.table;
    let piston: Vec<usize> = (0..tab.len())
        .filter(|&i| (tab.id[i] as usize) < 400)
        .collect();
    assert_eq!(piston.len(), 400);
    assert!(piston
        .iter()
        .all(|&i| tab.vx[i] == 100.0 && tab.vy[i] == 0.0));
    let d = r.summary.measure("front_speed").unwrap();
    let u_p = 100.0;
    let slowest = m * u_p / (m - 1.0);
    let c_l = (3930.0_f64.powi(2) + 4.0 * 43.0e9 / (3.0 * 8960.0)).sqrt();
    println!(
        "front speed {d:.1} m/s (mass balance: >= {slowest:.1}; c_l {c_l:.0}); porosity {m:.4}"
    );
    assert!(d > 0.97 * slowest && d < c_l, "front speed {d}");
}
