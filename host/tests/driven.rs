//! Driven bodies (`driven = true`, the piston of cases/porous_cu_piston.toml) move at
//! exactly their prescribed velocity: after N steps each driven particle sits at
//! `x0 + u_p t` to round-off and still has velocity `u_p`, however hard the sample pushes
//! back.

use gsph::scene::{build_particles, parse};
use gsph::sim::Sim;

/// A 1D copper piston at 100 m/s into a copper sample, 10 um spacing.
const PISTON: &str = r#"
dim = 1
scheme = "SCHEME"
t_end = 1.0
kernel = "wendland_c2"
h_factor = 1.2

[[materials]]
name = "copper"
rho0 = 8960.0
shear_modulus = 43.0e9
eos = { type = "linear", c0 = 3930.0 }
strength = { type = "von_mises", yield_stress = 0.35e9 }

[[bodies]]
material = "copper"
shape = { type = "segment", min = -2.0e-4, max = 0.0 }
spacing = 1.0e-5
velocity = { type = "uniform", value = [100.0] }
driven = true

[[bodies]]
material = "copper"
shape = { type = "segment", min = 0.0, max = 1.0e-3 }
spacing = 1.0e-5
"#;

#[test]
fn driven_particles_move_exactly_at_the_prescribed_velocity() {
    let u_p = 100.0;
    for scheme in ["av", "pm", "ts1", "ts2", "tkc"] {
        let scene = parse(&PISTON.replace("SCHEME", scheme), "piston", &[]).unwrap();
        let parts = build_particles(&scene).unwrap();
        let mut sim = Sim::<1>::new(&scene, &parts).unwrap();
        // particles are renumbered at rebuilds: follow them by id
        let ids: Vec<u32> = sim.driven.iter().map(|&(i, _)| sim.ids[i]).collect();
        assert_eq!(ids.len(), 20, "{scheme}: the piston's particles");
        let at = |sim: &Sim<1>| -> Vec<usize> {
            ids.iter()
                .map(|&id| sim.ids.iter().position(|&k| k == id).unwrap())
                .collect()
        };
        let x0: Vec<f64> = at(&sim).iter().map(|&i| sim.x[i][0]).collect();
        let face0 = x0.iter().cloned().fold(f64::MIN, f64::max);
        let mut t = 0.0;
        for _ in 0..200 {
            let dt = sim.checked_dt(0.5).unwrap();
            sim.step(dt).unwrap();
            t += dt;
        }
        let driven = at(&sim);
        let mut worst: f64 = 0.0;
        for (k, &i) in driven.iter().enumerate() {
            worst = worst.max((sim.x[i][0] - (x0[k] + u_p * t)).abs());
            assert_eq!(sim.v[i][0], u_p, "{scheme}: particle {i} velocity");
        }
        let face = driven.iter().map(|&i| sim.x[i][0]).fold(f64::MIN, f64::max);
        println!(
            "{scheme}: t = {t:.3e} s, face {face:.9e} m (x0 + u_p t = {:.9e}), worst offset {worst:.2e} m",
            face0 + u_p * t
        );
        // round-off of 200 additions to positions of ~1e-4 m
        assert!(
            worst <= 1e-15,
            "{scheme}: a driven particle is {worst:e} m off x0 + u_p t"
        );
    }
}
