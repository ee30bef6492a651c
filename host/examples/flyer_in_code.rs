//! gsph as a Rust library: the flyer plate (seed 000 §4.1) built in code with typed values
//! (scheme, kernel and effects as enums; materials and bodies as the scene schema's
//! types), run, and its results read: the peak stress against the exact solution, energy
//! conservation, and a field.
//!
//! ```text
//! cargo run --release -p gsph --example flyer_in_code
//! ```
//! A library-only build leaves out HDF5, plotting and the command line:
//! `gsph = { path = "host", default-features = false, features = ["dim1", "scheme-ts", "effects-strength"] }`.

use gsph::api::{Effect, SceneBuilder};
use gsph::scene::{BodySpec, MaterialSpec, ShapeSpec, Strength, VelocitySpec};
use gsph_core::kernel::Kernel;
use gsph_core::material::eos::{Eos, Hugoniot};
use gsph_core::schemes::Scheme;

fn plate(min: f64, max: f64, velocity: f64) -> BodySpec {
    BodySpec {
        material: "metal".into(),
        shape: ShapeSpec::Segment { min, max },
        spacing: 1.0e-4,
        lattice: None,
        layout: None,
        relax_iterations: None,
        lattice_origin: None,
        velocity: Some(VelocitySpec::Uniform {
            value: vec![velocity],
        }),
        initial: None,
        pores: None,
        driven: false,
        jitter: 0.0,
    }
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let metal = MaterialSpec {
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
    };
    let v = 602.81;
    let mut sim = SceneBuilder::new(1, Scheme::Ts2, 0.5e-6)
        .name("flyer_in_code")
        .kernel(Kernel::CubicSpline)
        .cfl(0.5)
        .material(metal)
        .body(plate(0.0, 0.005, v))
        .body(plate(0.005, 0.01, 0.0))
        .build()?;
    assert!(sim.simulates(Effect::Plasticity) && !sim.simulates(Effect::Damage));
    let steps = sim.run()?;
    let p = sim.get("pressure")?;
    let s = sim.get("deviator")?;
    let peak = (0..sim.len())
        .map(|i| s[6 * i] - p[i])
        .fold(0.0f64, f64::min);
    // the elastic-plastic exact solution's plateau: the profile's exact value behind the
    // plastic wave, at the impact plane
    let exact = sim
        .profile()?
        .iter()
        .filter(|r| (r[0] - 0.005).abs() < 2e-4 && r[2].is_finite())
        .map(|r| r[2])
        .fold(0.0f64, f64::min);
    let summary = sim.summary();
    println!(
        "{} particles, {steps} steps to t = {:.3e} s: peak sigma_xx {:.4} GPa (exact plateau {:.4} GPa), L1 error {:.4} GPa, energy error {:.1e}",
        sim.len(),
        sim.time(),
        peak / 1e9,
        exact / 1e9,
        summary["l1_error"].as_f64().unwrap_or(f64::NAN) / 1e9,
        summary["energy_rel_error"].as_f64().unwrap_or(f64::NAN),
    );
    Ok(())
}
