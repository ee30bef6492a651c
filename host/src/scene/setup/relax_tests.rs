//! Unit tests of the relaxed (body-fitted) layouts: a lattice that already fits its shape
//! is a fixed point, a staircase becomes a smooth surface row, the layout is the same on
//! any thread count, STL surfaces relax too, and the keys' refusals.

use super::import::tests::{cube, icosphere, scene_in, write_stl};
use super::relax::{relax, roughness};
use super::sdf::Surface;
use crate::scene::{build_particles, InitialParticles};

const RUBBER_2D: &str = r#"name = "layout"
dim = 2
scheme = "ts2"
t_end = 1e-9
[[materials]]
name = "rubber"
rho0 = 1.0
poisson_ratio = 0.3975
eos = { type = "linear", c0 = 4032.0 }
strength = { type = "elastic" }
"#;

fn body(shape: &str, extra: &str) -> String {
    format!(
        "{RUBBER_2D}[[bodies]]\nmaterial = \"rubber\"\nshape = {shape}\nspacing = 1e-3\n{extra}\n"
    )
}

fn build(text: &str, set: &[&str]) -> (crate::scene::Scene, InitialParticles) {
    let dir = tempfile::tempdir().unwrap();
    let sc = scene_in(dir.path(), text, set).unwrap_or_else(|e| panic!("{e}"));
    let parts = build_particles(&sc).unwrap();
    (sc, parts)
}

fn surface(sc: &crate::scene::Scene) -> Surface {
    Surface::of(&sc.bodies[0].shape, sc.dim, None, 1.0).unwrap()
}

/// The nearest pair, in spacings `dx`.
fn nearest(parts: &InitialParticles, dx: f64) -> f64 {
    let x: Vec<gsph_core::math::Vector<3>> = parts.x.iter().map(|p| (*p).into()).collect();
    crate::neighbors::nearest_distances(&x, 2.0 * dx)
        .into_iter()
        .fold(f64::INFINITY, f64::min)
        / dx
}

#[test]
fn a_lattice_that_fits_its_box_is_a_fixed_point() {
    // the mirror images across the faces, edges and corners continue the lattice exactly
    for (shape, dim) in [
        (
            "{ type = \"box\", min = [0.0, 0.0], max = [0.02, 0.01] }",
            2,
        ),
        (
            "{ type = \"box\", min = [0.0, 0.0, 0.0], max = [0.006, 0.005, 0.004] }",
            3,
        ),
    ] {
        // (a scene refuses `relaxed` for a box, whose lattice always fits it: the
        // relaxation is called directly)
        let text = body(shape, "").replace("dim = 2", &format!("dim = {dim}"));
        let (sc, lattice) = build(&text, &[]);
        let surf = surface(&sc);
        let mut relaxed = lattice.x.clone();
        relax(dim, &mut relaxed, 1e-3, &surf, 400, &mut |_, _| {});
        for (i, (p, q)) in lattice.x.iter().zip(&relaxed).enumerate() {
            for (pa, qa) in p.iter().zip(q) {
                let d = (pa - qa).abs();
                assert!(d < 1e-12 * 1e-3, "{dim}D particle {i} moved {d:e} m");
            }
        }
        let r = roughness(&relaxed, 1e-3, &surf);
        assert!(r < 1e-9, "{dim}D roughness {r}");
    }
}

#[test]
fn a_relaxed_ring_follows_its_surface_and_keeps_its_particles() {
    let text = body(
        "{ type = \"annulus\", center = [0.0, 0.0], r_inner = 0.03, r_outer = 0.04 }",
        "lattice_origin = [-0.04, -0.04]",
    );
    let (sc, lattice) = build(&text, &[]);
    let (_, relaxed) = build(&text, &["bodies.0.layout=relaxed"]);
    let surf = surface(&sc);
    let (before, after) = (
        roughness(&lattice.x, 1e-3, &surf),
        roughness(&relaxed.x, 1e-3, &surf),
    );
    // a staircase's surface row lies anywhere within a spacing of the surface
    assert!(before > 0.25, "lattice roughness {before}");
    assert!(after < 0.05, "relaxed roughness {after} (lattice {before})");
    // count, masses and order kept; every particle inside, the surface row half a spacing
    // in; no pair closer than the lattice allows
    assert_eq!(lattice.len(), relaxed.len());
    assert_eq!(lattice.m, relaxed.m);
    for (i, x) in relaxed.x.iter().enumerate() {
        let phi = surf.phi(x) / 1e-3;
        assert!(phi < -0.45, "particle {i} at phi = {phi} spacings");
    }
    let near = nearest(&relaxed, 1e-3);
    assert!(near > 0.85, "nearest pair {near} spacings");
    assert_eq!(relaxed.layout.len(), 1);
    assert!(
        relaxed.layout[0].starts_with("bodies[0]: relaxed layout, 2208 particles, 400 iterations")
            && relaxed.layout[0].contains("surface roughness"),
        "{}",
        relaxed.layout[0]
    );
    assert!(lattice.layout.is_empty());
}

#[test]
fn a_relaxed_layout_is_the_same_on_any_thread_count() {
    let text = body(
        "{ type = \"disc\", center = [0.0, 0.0], radius = 0.012 }",
        "layout = \"relaxed\"\nrelax_iterations = 60",
    );
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| build(&text, &[]).1)
    };
    let (one, three) = (on(1), on(3));
    assert_eq!(one.x, three.x);
    // and it moved something
    let (_, lattice) = build(
        &text,
        &["unset:bodies.0.layout", "unset:bodies.0.relax_iterations"],
    );
    assert_ne!(lattice.x, one.x);
}

#[test]
fn stl_surfaces_relax_a_cube_in_place_and_a_sphere_to_its_surface() {
    let dir = tempfile::tempdir().unwrap();
    write_stl(
        &dir.path().join("cube.stl"),
        &cube([0.0; 3], [6.0, 5.0, 4.0]),
    );
    write_stl(&dir.path().join("ball.stl"), &icosphere([0.0; 3], 8.0, 3));
    let scene = |file: &str, layout: &str| {
        let text = format!(
            "{}[[bodies]]\nmaterial = \"rubber\"\nshape = {{ type = \"stl\", file = \"{file}\", scale = 1e-3 }}\nspacing = 1e-3\nlayout = \"{layout}\"\n",
            RUBBER_2D.replace("dim = 2", "dim = 3")
        );
        let sc = scene_in(dir.path(), &text, &[]).unwrap_or_else(|e| panic!("{e}"));
        let parts = build_particles(&sc).unwrap();
        (sc, parts)
    };
    // the cube's lattice fits it: its facets' planes mirror it exactly
    let (_, lattice) = scene("cube.stl", "lattice");
    let (_, relaxed) = scene("cube.stl", "relaxed");
    for i in 0..lattice.len() {
        for a in 0..3 {
            let d = (lattice.x[i][a] - relaxed.x[i][a]).abs();
            assert!(d < 1e-15, "cube particle {i} moved {d:e} m");
        }
    }
    // the sphere (1,280 facets) against its exact surface
    let (_, lattice) = scene("ball.stl", "lattice");
    let (_, relaxed) = scene("ball.stl", "relaxed");
    let ball = Surface::Ball {
        c: [0.0; 3],
        r: 8e-3,
        dim: 3,
    };
    let (before, after) = (
        roughness(&lattice.x, 1e-3, &ball),
        roughness(&relaxed.x, 1e-3, &ball),
    );
    assert!(after < 0.5 * before, "roughness {before} -> {after}");
    let near = nearest(&relaxed, 1e-3);
    assert!(near > 0.7, "nearest pair {near} spacings");
}

#[test]
fn layout_keys_are_refused_where_they_cannot_act() {
    let dir = tempfile::tempdir().unwrap();
    let err = |text: &str, set: &[&str]| {
        let e = scene_in(dir.path(), text, set).expect_err("refused");
        assert!(!e.contains('\n'), "not one line: {e}");
        e
    };
    let disc = body(
        "{ type = \"disc\", center = [0.0, 0.0], radius = 0.01 }",
        "",
    );
    let e = err(
        &body(
            "{ type = \"box\", min = [0.0, 0.0], max = [0.02, 0.01] }",
            "",
        ),
        &["bodies.0.layout=relaxed"],
    );
    assert!(
        e.contains("bodies[0].layout: a box's lattice already fits it"),
        "{e}"
    );
    let e = err(&disc, &["bodies.0.layout=smooth"]);
    assert!(
        e.contains("bodies[0].layout: unknown layout `smooth` (known: lattice, relaxed)"),
        "{e}"
    );
    let e = err(&disc, &["bodies.0.relax_iterations=10"]);
    assert!(
        e.contains("bodies[0].relax_iterations: only with layout = \"relaxed\""),
        "{e}"
    );
    let e = err(
        &disc,
        &["bodies.0.layout=relaxed", "bodies.0.relax_iterations=0"],
    );
    assert!(
        e.contains("bodies[0].relax_iterations: must lie in 1..=100000"),
        "{e}"
    );
    let e = err(
        &disc,
        &[
            "bodies.0.layout=relaxed",
            "bodies.0.pores={ cell = [0.004, 0.004], centers = [[0.002, 0.002]], radius = 0.001 }",
        ],
    );
    assert!(e.contains("bodies[0].layout: not with pores"), "{e}");
    let flyer = include_str!("../../../../cases/flyer_plate.toml");
    let e = err(flyer, &["bodies.0.layout=relaxed"]);
    assert!(
        e.contains("bodies[0].layout: a relaxed layout needs 2 or 3 dimensions"),
        "{e}"
    );
    std::fs::write(dir.path().join("p.csv"), "x,y\n0.0,0.0\n0.001,0.0\n").unwrap();
    let e = err(
        &disc,
        &[
            "bodies.0.shape={ type = \"particles\", file = \"p.csv\" }",
            "bodies.0.layout=relaxed",
        ],
    );
    assert!(
        e.contains("bodies[0].layout: a particle file's layout is left as given"),
        "{e}"
    );
}
