//! Results are bitwise identical for 1, 2 and 4 threads. Every per-particle loop is a
//! gather over a sorted neighbour list (no floating-point reduction across particles), the
//! rayon executor splits work at boundaries that depend only on the particle count, and
//! global sums (energy, momentum, time step) are taken serially in particle order.

use gsph::driver::{run, RunOptions};

fn final_state(threads: usize, case: &str, set: &[&str]) -> gsph::output::ParticleTable {
    let path = gsph_tests::case(case);
    let set: Vec<String> = set.iter().map(|s| s.to_string()).collect();
    let scene = gsph::scene::load(&path, &set).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        run(
            &scene,
            case,
            &RunOptions {
                out: None,
                progress: false,
            },
        )
    })
    .unwrap()
    .table
}

#[test]
fn bitwise_identical_for_1_2_and_4_threads() {
    for (case, set) in [
        (
            "ring_collapse",
            vec!["scheme=ts2", "resolution_scale=0.5", "t_end=2e-5"],
        ),
        (
            "verney_al",
            vec!["scheme=tkc", "resolution_scale=0.5", "t_end=1e-5"],
        ),
        ("riemann_al_2d", vec!["scheme=av"]),
    ] {
        let one = final_state(1, case, &set);
        for threads in [2, 4] {
            let many = final_state(threads, case, &set);
            assert_eq!(one, many, "{case}: {threads} threads differ from 1");
        }
    }
}
