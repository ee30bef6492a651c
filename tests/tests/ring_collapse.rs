//! Seed 000 §4.2: the collapsing beryllium ring at reduced size (1,809 particles, half the
//! coarse resolution of the seed) against the analytic stopping radii of an incompressible
//! rigid-plastic shell (`gsph_core::exact::ShellCollapse`: 0.0500 m and 0.0781 m).
//! Full-size runs (8,172 and 23,780 particles) are documented commands (README).

use gsph_tests::{num, run_case};

fn ring(scheme: &str) -> serde_json::Map<String, serde_json::Value> {
    run_case(
        "ring_collapse",
        &[&format!("scheme={scheme}"), "resolution_scale=0.5"],
    )
}

/// ts1 and ts2 conserve total energy to round-off in 2D too (seed 000 table 3 reports
/// 3e-2 % and 7e-4 % at 8,012 particles).
#[test]
fn time_split_schemes_conserve_energy() {
    for scheme in ["ts1", "ts2"] {
        let s = ring(scheme);
        let e = num(&s, "energy_rel_error").abs();
        println!("{scheme}: energy error {e:e}");
        assert!(e < 1e-10, "{scheme}: energy error {e}");
    }
}

/// At this resolution ts2 stops within 6 % of the analytic radii (measured 3.4 %), closer
/// than ts1 (measured 12 %), and keeps the inner surface circular: the spread of the inner
/// row's radii stays below 10 % of its mean (measured 3.3 %).
#[test]
fn ts2_stops_near_the_analytic_radii_and_keeps_symmetry() {
    let s2 = ring("ts2");
    let s1 = ring("ts1");
    let (e2, e1) = (num(&s2, "radius_error"), num(&s1, "radius_error"));
    println!(
        "ts2: inner {:.5} outer {:.5} (exact {:.5} {:.5}), error {e2:.4}, spread {:.4}; ts1 error {e1:.4}",
        num(&s2, "inner_radius"),
        num(&s2, "outer_radius"),
        num(&s2, "inner_radius_exact"),
        num(&s2, "outer_radius_exact"),
        num(&s2, "inner_spread")
    );
    assert!((num(&s2, "inner_radius_exact") - 0.0500).abs() < 1e-4);
    assert!((num(&s2, "outer_radius_exact") - 0.0781).abs() < 1e-4);
    assert!(e2 < 0.06, "ts2 radius error {e2}");
    assert!(e2 < e1, "ts2 ({e2}) not closer than ts1 ({e1})");
    assert!(num(&s2, "inner_spread") < 0.1, "inner row lost symmetry");
}
