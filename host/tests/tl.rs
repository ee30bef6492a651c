//! The total-Lagrangian scheme `tl` in the host (issue 47): its updated reference keeps
//! every pair's stretch within the threshold after each step, counts its updates and
//! leaves total energy where the run without updates leaves it; its symmetry planes
//! reproduce the whole body; what it cannot run (rigid walls, bodies apart at the start)
//! is refused in one line naming the key and the scheme.

use gsph::api::Simulation;
use std::path::{Path, PathBuf};

fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../cases")
        .join(name)
}

fn sets(s: &[&str]) -> Vec<String> {
    s.iter().map(|x| x.to_string()).collect()
}

/// The Taylor rod in tl, its rigid wall a symmetry plane, shortened.
fn taylor(extra: &[&str]) -> Simulation {
    let mut all = vec!["scheme=tl", "walls.0.type=symmetry", "t_end=2e-5"];
    all.extend_from_slice(extra);
    Simulation::from_file(&case("taylor_copper.toml"), &sets(&all))
        .unwrap_or_else(|e| panic!("{e}"))
}

fn points(v: &[f64]) -> Vec<[f64; 3]> {
    v.chunks(3).map(|c| [c[0], c[1], c[2]]).collect()
}

fn dist(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

/// The largest |r/R - 1| over the pairs closer than `reach` in the reference
/// configuration (brute force), and the number of such pairs.
fn largest_stretch(sim: &mut Simulation, reach: f64) -> (f64, usize) {
    let x = points(&sim.get("position").unwrap());
    let xr = points(&sim.get("tl_reference_position").unwrap());
    let (mut most, mut pairs) = (0.0f64, 0);
    for i in 0..x.len() {
        for j in i + 1..x.len() {
            let big_r = dist(&xr[i], &xr[j]);
            if big_r < reach {
                pairs += 1;
                most = most.max((dist(&x[i], &x[j]) / big_r - 1.0).abs());
            }
        }
    }
    (most, pairs)
}

#[test]
fn the_updated_reference_keeps_every_stretch_within_its_threshold_and_the_energy() {
    let threshold = 0.1;
    let mut sim = taylor(&[&format!("options.reference_update={threshold}")]);
    let h = sim.get("h").unwrap()[0];
    // cubic spline: support 2h
    let reach = 2.0 * h;
    let (e0k, e0i) = sim.energy();
    let mut updates_seen = 0;
    let mut last = sim.get("tl_reference_position").unwrap();
    let mut most_before = 0.0f64;
    for _ in 0..400 {
        sim.step(None).unwrap();
        let xr = sim.get("tl_reference_position").unwrap();
        if xr != last {
            // an update: the reference is the positions now
            assert_eq!(xr, sim.get("position").unwrap());
            updates_seen += 1;
            last = xr;
        }
        let (most, pairs) = largest_stretch(&mut sim, reach);
        assert!(pairs > 1000, "{pairs}");
        assert!(most <= threshold, "stretch {most} after an update step");
        most_before = most_before.max(most);
    }
    assert!(
        updates_seen >= 1,
        "the rod's face stretches its pairs past 0.1"
    );
    assert!(most_before > 0.5 * threshold, "{most_before}");
    let (ek, ei) = sim.energy();
    let err = ((ek + ei) - (e0k + e0i)) / (e0k + e0i);
    // the same run without updates
    let mut plain = taylor(&[]);
    for _ in 0..400 {
        plain.step(None).unwrap();
    }
    let (pk, pi) = plain.energy();
    let plain_err = ((pk + pi) - (e0k + e0i)) / (e0k + e0i);
    eprintln!("updates {updates_seen}, energy error {err:.3e} (without updates {plain_err:.3e})");
    assert!(
        err.abs() < 3.0 * plain_err.abs().max(1e-4),
        "{err} vs {plain_err}"
    );
}

#[test]
fn rigid_walls_and_bodies_apart_are_refused_naming_the_key_and_the_scheme() {
    let e = Simulation::from_file(&case("taylor_copper.toml"), &sets(&["scheme=tl"]))
        .err()
        .expect("refused")
        .to_string();
    assert!(
        e.contains("walls[0].type") && e.contains("scheme tl"),
        "{e}"
    );
    assert!(!e.contains('\n'), "{e}");
    let e = Simulation::from_file(
        &case("rings.toml"),
        &sets(&["scheme=tl", "unset:options.artificial_stress"]),
    )
    .err()
    .expect("refused")
    .to_string();
    assert!(e.contains("bodies[") && e.contains("scheme tl"), "{e}");
    assert!(!e.contains('\n'), "{e}");
    // a key of the updated-Lagrangian schemes, and the updated reference elsewhere
    let e = Simulation::from_file(
        &case("ring_breathing.toml"),
        &sets(&["scheme=tl", "options.limiter=minmod"]),
    )
    .err()
    .expect("refused")
    .to_string();
    assert!(
        e.contains("options.limiter") && e.contains("scheme tl"),
        "{e}"
    );
    let e = Simulation::from_file(
        &case("ring_breathing.toml"),
        &sets(&["scheme=ts2", "options.reference_update=0.3"]),
    )
    .err()
    .expect("refused")
    .to_string();
    assert!(
        e.contains("options.reference_update") && e.contains("scheme ts2"),
        "{e}"
    );
}

/// A quarter of a rod on a symmetry plane (its face) with two more symmetry planes, and
/// the whole rod on the face's plane alone: the same motion, particle for particle.
#[test]
fn a_quarter_rod_with_symmetry_planes_reproduces_the_whole_in_tl() {
    let run = |quarter: bool| {
        let mut s = vec![
            "scheme=tl".to_string(),
            "walls.0.type=symmetry".to_string(),
            "t_end=1e-5".to_string(),
        ];
        if !quarter {
            s.push("bodies.0.shape.quarter=false".into());
            s.push("walls=[{ point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0], type = \"symmetry\" }]".into());
        }
        let mut sim = Simulation::from_file(&case("taylor_copper.toml"), &s)
            .unwrap_or_else(|e| panic!("{e}"));
        // the API's arrays hold the walls' mirrors after the particles (in id order):
        // the particles are those of the scene without walls
        let mut bare = s.clone();
        bare.push("walls=[]".into());
        let n = Simulation::from_file(&case("taylor_copper.toml"), &bare)
            .unwrap_or_else(|e| panic!("{e}"))
            .len();
        let x0 = points(&sim.get("position").unwrap())[..n].to_vec();
        sim.advance_to(1e-5).unwrap();
        let x = points(&sim.get("position").unwrap())[..n].to_vec();
        (x0, x, sim.get("pressure").unwrap()[..n].to_vec())
    };
    let (q0, q, qp) = run(true);
    let (w0, w, wp) = run(false);
    assert_eq!(4 * q0.len(), w0.len());
    let key = |x: &[f64; 3]| [0, 1, 2].map(|k| (x[k] * 1e8).round() as i64);
    let whole: std::collections::HashMap<_, usize> =
        w0.iter().enumerate().map(|(i, x)| (key(x), i)).collect();
    let (mut dx, mut dp, mut pmax) = (0.0f64, 0.0f64, 0.0f64);
    for (j, x) in q0.iter().enumerate() {
        let i = whole[&key(x)];
        dx = dx.max(dist(&w[i], &q[j]));
        dp = dp.max((wp[i] - qp[j]).abs());
        pmax = pmax.max(wp[i].abs());
    }
    eprintln!(
        "quarter vs whole: positions {dx:.3e} m, pressure {:.3e} of its peak",
        dp / pmax
    );
    assert!(pmax > 1e8, "the rod is loaded: {pmax:e}");
    assert!(dx < 1e-12 && dp / pmax < 1e-9, "{dx:e} {dp:e}");
}
