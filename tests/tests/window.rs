//! The moving observation window (seed 004 §3, cases/porous_cu_window.toml) at reduced
//! size (2 um spacing).
//!
//! 1. A uniform flow with no wave (u_p = 0) through a porous sample is an exact steady
//!    state: the feed must join the sample without gaps or overlaps, so every particle
//!    keeps the entry velocity and the unstressed state, and the particle count does not
//!    drift while several feed lengths pass through.
//! 2. A Hugoniot point (u_p = 100 m/s): the wave held in the window must be a steady
//!    shock, so its measured density and stress jumps must satisfy the Rankine–Hugoniot
//!    mass and momentum conditions for the u_s found by the bisection, and u_s must exceed
//!    the full-compaction bound m u_p/(m − 1).

use gsph::driver::{run, RunOptions};
use gsph::window::hugoniot::{hugoniot, HugoniotOptions};

fn scene(sets: &[&str]) -> gsph::scene::Scene {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../cases/porous_cu_window.toml"
    ))
    .unwrap();
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    gsph::scene::parse(&text, "window", &sets).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn uniform_flow_through_the_window_stays_uniform() {
    // 160 um window, 3 feed lengths (60 um) pass at 400 m/s
    let sc = scene(&[
        "resolution_scale=0.5",
        "bodies.0.shape.max=[1.6e-4, 2.0e-5]",
        "window.up=0.0",
        "window.us=400.0",
        "t_end=1.5e-7",
    ]);
    let r = run(
        &sc,
        "window",
        &RunOptions {
            out: None,
            progress: false,
        },
    )
    .unwrap();
    let s = &r.summary;
    let get = |k: &str| s.number(k).unwrap();
    let n0 = gsph::scene::build_particles(&sc).unwrap().len() as f64;
    let mass_in = get("window_mass_in");
    println!(
        "particles {} (start {n0}), mass in {mass_in:e}, out {:e}",
        get("window_particles"),
        get("window_mass_out")
    );
    // three feed lengths entered and left
    assert!(mass_in > 0.0 && get("window_mass_out") > 0.0);
    assert!(
        (get("window_particles") - n0).abs() <= 10.0,
        "particle count drifted: {} vs {n0}",
        get("window_particles")
    );
    let t = &r.table;
    for i in 0..t.len() {
        assert!(
            (t.vx[i] + 400.0).abs() < 1e-6 && t.vy[i].abs() < 1e-6,
            "particle {} moves at ({}, {})",
            t.id[i],
            t.vx[i],
            t.vy[i]
        );
        assert!(
            (t.rho[i] - 8960.0).abs() < 1e-6 && t.p[i].abs() < 1.0,
            "particle {}: rho {}, p {}",
            t.id[i],
            t.rho[i],
            t.p[i]
        );
    }
}

#[test]
fn hugoniot_point_obeys_the_jump_conditions() {
    // 280 um window at 2 um spacing; one settling round, 8 m/s bracket
    let sc = scene(&[
        "resolution_scale=0.5",
        "bodies.0.shape.max=[2.8e-4, 2.0e-5]",
    ]);
    let opts = HugoniotOptions {
        ups: vec![100.0],
        tolerance: 8.0,
        max_rounds: 2,
        average: 3.0,
        profiles: 30,
        verbose: true,
        ..Default::default()
    };
    let p = &hugoniot(&sc, &opts, |_| Ok(())).unwrap()[0];
    let m = 1.3514;
    let bound = m * p.up / (m - 1.0);
    println!(
        "u_s {:.1} m/s (rounds {:?}), bound {bound:.1}; stress behind {:.3e}, precursor {:.3e} Pa; precursor velocity {:.2} m/s; rho ahead {:.1}, behind {:.1}; mass/RH {:.4}, momentum/RH {:.4}; {} trials, {:.0} s",
        p.us,
        p.rounds,
        p.stress_behind,
        p.stress_precursor,
        p.precursor_velocity,
        p.rho_ahead,
        p.rho_behind,
        p.mass_jump_ratio(),
        p.momentum_jump_ratio(),
        p.trials,
        p.wall_s
    );
    assert!(p.bracket <= 8.0);
    assert!(p.us > bound, "u_s {} below the full-compaction bound", p.us);
    // ahead of the front: at least the bulk density fed in (rho0 / m; the precursor
    // compresses), below solid density
    assert!(
        p.rho_ahead > 0.995 * 8960.0 / m && p.rho_ahead < 8960.0,
        "{}",
        p.rho_ahead
    );
    // the held wave is the steady shock of the u_s found: its density jump satisfies the
    // mass condition (measured 1.1 % low: the relaxation zone behind the front is still
    // compacting) and its bulk stress jump the momentum condition (measured 1.0 %). A
    // window held at 415 m/s (the seed's fit) on a sample that compacts to 1.2x, as this
    // one does at 2 um, would be 7 % off in mass.
    assert!((p.mass_jump_ratio() - 1.0).abs() < 0.025);
    assert!((p.momentum_jump_ratio() - 1.0).abs() < 0.03);
    assert!(p.stress_precursor > 0.0 && p.stress_precursor < p.stress_behind);
}

/// Two independent measurements of the same shock speed at the same resolution (2 um,
/// pm, which the seed finds close to tkc: measured 542.4 against tkc's 546.0 m/s at
/// u_p = 100): the window's bisection on dω/dt, and the lab-frame speed of the front that
/// a piston at u_p drives into a 2 mm sample (cases/porous_cu_piston.toml). Measured
/// 542.4 and 520.9 m/s, 4.0 % apart (the piston front's speed varies by ±5 % as it
/// crosses pore rows); the seed's fit, 415.4 m/s, is 25 % from either, so a window that
/// held the wave at the wrong speed, or a piston run that measured it wrongly, fails.
/// Full size (38 s on two cores): `make validate` runs it (`cargo test -p gsph-tests --release -- --ignored`).
#[test]
#[ignore = "full size: make validate"]
fn window_and_piston_agree_on_the_shock_speed() {
    let sc = scene(&[
        "resolution_scale=0.5",
        "bodies.0.shape.max=[2.8e-4, 2.0e-5]",
        "scheme=pm",
        "unset:options.limiter",
    ]);
    let opts = HugoniotOptions {
        ups: vec![100.0],
        verbose: false,
        ..Default::default()
    };
    let window = hugoniot(&sc, &opts, |_| Ok(())).unwrap()[0].us;
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../cases/porous_cu_piston.toml"
    ))
    .unwrap();
    let sets: Vec<String> = ["scheme=pm", "unset:options.limiter", "resolution_scale=0.5"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    let piston = gsph::scene::parse(&text, "piston", &sets).unwrap_or_else(|e| panic!("{e}"));
    let r = run(
        &piston,
        "piston",
        &RunOptions {
            out: None,
            progress: false,
        },
    )
    .unwrap();
    let d = r.summary.measure("front_speed").unwrap();
    println!("window u_s {window:.1} m/s, piston front {d:.1} m/s");
    assert!(
        (window - d).abs() < 0.05 * d,
        "window {window} and piston {d} m/s disagree"
    );
}

/// The window profiles report bulk stress: a periodic porous cell (m = 1.35 as built)
/// whose solid is loaded to a uniform pressure p0 carries, across any section, the
/// traction p0 times the solid fraction of the section; over a whole period that is
/// p0/m, the macroscopic stress of the cell. The profile's bulk stress over bins one
/// period long must give that back, and its matrix stress p0 (the stress in the solid,
/// larger by the factor m that the particle mean used to report).
#[test]
fn bulk_stress_of_a_loaded_porous_cell_is_the_applied_traction() {
    let sc = scene(&[
        "resolution_scale=0.5",
        "bodies.0.shape.max=[1.6e-4, 2.0e-5]",
    ]);
    let geo = sc.window.as_ref().unwrap().geometry(&sc).unwrap();
    let parts = gsph::scene::build_particles(&sc).unwrap();
    let m = parts.porosity[0];
    let mut sim = gsph::sim::Sim::<2>::new(&sc, &parts).unwrap();
    let p0 = 0.2e9;
    for i in 0..sim.len() {
        sim.p[i] = p0;
    }
    // bins one feed period (20 um) long
    let mut prof = gsph::window::Profile::new(&geo, geo.feed);
    prof.add(&sim);
    let bins = prof.bins();
    assert_eq!(bins.len(), 8);
    for b in &bins {
        println!(
            "x {:.1} um: bulk {:.5e} Pa, matrix {:.5e} Pa (p0/m = {:.5e})",
            b.x * 1e6,
            b.stress_bulk,
            b.stress,
            p0 / m
        );
        assert!((b.stress - p0).abs() < 1e-6 * p0, "matrix {}", b.stress);
        assert!(
            (b.stress_bulk - p0 / m).abs() < 1e-9 * p0,
            "bulk {} against the traction p0/m = {}",
            b.stress_bulk,
            p0 / m
        );
    }
}
