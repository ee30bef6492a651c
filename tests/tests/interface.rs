//! Multi-material pairs: each side of a contact uses its own impedance and wave speeds.
//! An elastic steel bar at 10 m/s strikes an elastic SiC bar at rest (1D, uniaxial
//! strain). The contact stress is the impedance formula sigma = -Z1 Z2 v0 / (Z1 + Z2)
//! with Z = rho c_l and c_l² = c_b² + 4G/(3 rho); it is carried into SiC (transmitted
//! wave) and back into steel (reflected wave). Checked for every scheme on the plateaus
//! behind both fronts.

use gsph::driver::{run, RunOptions};

const SCENE: &str = r#"
dim = 1
scheme = "SCHEME"
t_end = 1.2e-6
[output]
snapshots = 1
[[materials]]
name = "steel"
rho0 = 7903.0
shear_modulus = 74.8e9
eos = { type = "linear", c0 = 4552.0 }
strength = { type = "elastic" }
[[materials]]
name = "sic"
rho0 = 3215.0
shear_modulus = 1.93e11
eos = { type = "polynomial", k1 = 2.2e11 }
strength = { type = "elastic" }
[[bodies]]
material = "steel"
shape = { type = "segment", min = -0.02, max = 0.0 }
spacing = 1.0e-4
velocity = { type = "uniform", value = [10.0] }
[[bodies]]
material = "sic"
shape = { type = "segment", min = 0.0, max = 0.04 }
spacing = 1.0e-4
"#;

#[test]
fn contact_stress_follows_the_impedance_formula() {
    let (rho1, c1) = (
        7903.0_f64,
        (4552.0_f64.powi(2) + 4.0 * 74.8e9 / (3.0 * 7903.0)).sqrt(),
    );
    let (rho2, c2) = (
        3215.0_f64,
        (2.2e11_f64 / 3215.0 + 4.0 * 1.93e11 / (3.0 * 3215.0)).sqrt(),
    );
    let (z1, z2) = (rho1 * c1, rho2 * c2);
    let exact = -z1 * z2 * 10.0 / (z1 + z2);
    let t = 1.2e-6;
    for scheme in ["av", "pm", "ts1", "ts2", "tkc"] {
        let sc = gsph::scene::parse(&SCENE.replace("SCHEME", scheme), "interface", &[]).unwrap();
        let res = run(
            &sc,
            "interface",
            &RunOptions {
                out: None,
                progress: false,
            },
        )
        .unwrap();
        let tab = &res.table;
        // plateaus: the middle half of the region each wave has swept (contact moves at ~v0/2)
        let mean = |lo: f64, hi: f64| {
            let v: Vec<f64> = (0..tab.len())
                .filter(|&i| tab.x[i] > lo && tab.x[i] < hi)
                .map(|i| tab.sxx[i] - tab.p[i])
                .collect();
            v.iter().sum::<f64>() / v.len() as f64
        };
        let steel = mean(-0.75 * c1 * t, -0.25 * c1 * t);
        let sic = mean(0.25 * c2 * t, 0.75 * c2 * t);
        println!("{scheme}: steel {steel:.4e}, SiC {sic:.4e}, impedance formula {exact:.4e} Pa");
        for (side, v) in [("steel (reflected)", steel), ("SiC (transmitted)", sic)] {
            assert!(
                ((v - exact) / exact).abs() < 0.03,
                "{scheme}: {side} stress {v:e} vs {exact:e}"
            );
        }
    }
}
