//! The reference position and det F (issue 26): `reference_position` is where each
//! particle was created and never changes; `det_f`, computed from the positions and the
//! reference positions, is det of an affine motion imposed on a whole body (its free
//! surface included), 1 for a rigid rotation, and follows rho0/rho in a run (the volume the
//! continuity equation and the positions agree on); both are read-only, and both are
//! columns of final.csv.

use gsph::api::Simulation;
use std::path::Path;

fn case(name: &str) -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../cases")
        .join(name)
}

fn open(name: &str) -> Simulation {
    Simulation::from_file(&case(name), &[]).unwrap()
}

#[test]
fn reference_position_is_where_a_particle_was_created() {
    let mut sim = open("flyer_plate.toml");
    let x0 = sim.get("position").unwrap();
    assert_eq!(sim.get("reference_position").unwrap(), x0);
    assert_eq!(sim.get("x0").unwrap(), x0);
    for _ in 0..20 {
        sim.step(None).unwrap();
    }
    assert_ne!(sim.get("position").unwrap(), x0, "the plates moved");
    assert_eq!(sim.get("reference_position").unwrap(), x0);
    for name in ["reference_position", "det_f"] {
        let n = sim.get(name).unwrap().len();
        let e = sim.write(name, &vec![0.0; n]).unwrap_err().to_string();
        assert!(e.contains("read-only"), "{e}");
    }
}

#[test]
fn det_f_of_an_imposed_affine_motion_is_its_determinant_at_every_particle() {
    // the 2D rings: two bodies, free surfaces everywhere
    let mut sim = open("rings.toml");
    let x0 = sim.get("position").unwrap();
    let ones = sim.get("det_f").unwrap();
    assert!(ones.iter().all(|&d| (d - 1.0).abs() < 1e-12), "{ones:?}");
    let (c, s) = (0.6f64.cos(), 0.6f64.sin());
    for (f, want) in [
        ([[c, -s], [s, c]], 1.0),                 // rigid rotation
        ([[1.1, 0.2], [0.0, 0.9]], 1.1 * 0.9),    // stretch and shear
        ([[0.7, 0.0], [-0.3, 1.25]], 0.7 * 1.25), // compression and shear
    ] {
        let x: Vec<f64> = x0
            .chunks_exact(2)
            .flat_map(|p| {
                [
                    f[0][0] * p[0] + f[0][1] * p[1] + 0.01,
                    f[1][0] * p[0] + f[1][1] * p[1] - 0.02,
                ]
            })
            .collect();
        sim.write("position", &x).unwrap();
        let d = sim.get("det_f").unwrap();
        for (i, v) in d.iter().enumerate() {
            assert!(
                (v - want).abs() < 1e-10 * want,
                "particle {i}: det F {v}, want {want}"
            );
        }
    }
}

#[test]
fn det_f_follows_rho0_over_rho_in_a_run() {
    // the flyer plate: a shock through both plates; det F from the positions and
    // rho0/rho from the continuity equation agree to a fraction of the compression
    let mut sim = open("flyer_plate.toml");
    let rho0 = sim.get("density").unwrap();
    sim.run().unwrap();
    let rho = sim.get("density").unwrap();
    let d = sim.get("det_f").unwrap();
    let compressed = rho.iter().zip(&rho0).any(|(r, r0)| r / r0 > 1.04);
    assert!(compressed, "the shock compressed the plates");
    for (i, ((v, r), r0)) in d.iter().zip(&rho).zip(&rho0).enumerate() {
        let drift = v * r / r0 - 1.0;
        assert!(
            drift.abs() < 0.01,
            "particle {i}: det F rho / rho0 - 1 = {drift:e}"
        );
    }
    let t = sim.table();
    assert_eq!(t.det_f, d, "final.csv's det_f column");
}
