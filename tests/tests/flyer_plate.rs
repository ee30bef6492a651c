//! Seed 000 §4.1: the 1D flyer plate against its exact solution (elastic precursor and
//! plastic shock; exact solution in `gsph_core::exact::FlyerPlate`).

use gsph_tests::{num, run_case};

/// Relative L1 error of sigma_xx (mean |error| over particles / |final stress|) at 100
/// particles, t = 0.5 us. Bounds sit ~25 % above the values measured when they were set
/// (av 0.062, pm 0.061, ts1 0.073, ts2 0.035), so a regression of the schemes fails them.
#[test]
fn every_scheme_stays_within_its_l1_bound() {
    for (scheme, bound) in [("av", 0.08), ("pm", 0.08), ("ts1", 0.09), ("ts2", 0.045)] {
        let s = run_case("flyer_plate", &[&format!("scheme={scheme}")]);
        let l1 = num(&s, "l1_error_relative");
        println!("{scheme}: L1 relative {l1:.4e}");
        assert!(l1 < bound, "{scheme}: L1 relative {l1} exceeds {bound}");
    }
}

/// The elastic precursor (half-HEL crossing of sigma_xx, interpolated) against its exact
/// position 0.5 us after impact (x = 8.086 mm, 3.086 mm from the impact plane).
///
/// Every scheme smears the plastic shock, which trails the precursor by only 0.29 mm (three
/// spacings at 100 particles), into the precursor's foot, so the half-HEL point runs ahead:
/// by 3.4 % (ts2) to 10 % (ts1) of the distance travelled at 100 particles, i.e. 1.3-3.8 %
/// of the x coordinate. The offset shrinks as the resolution doubles until it meets the
/// uncorrected kernel's zero-order bias (the cubic spline at h = 1.2 dx has M = 1.022 in
/// the 1D interior, so waves run slightly fast whatever the resolution): ts2 reaches that
/// floor at about 1 % of the travel by 400 particles (measured 0.01027 at 400, 0.01043 at
/// 800), so from 400 to 800 the test allows 5 % of scatter at the floor. Every scheme is
/// within 2 % of the exact position from 800 particles on (ts2 from 100, av and pm from
/// 400, ts1 at 800: 1.6 %). The test checks both.
#[test]
fn elastic_precursor_position() {
    for scheme in ["av", "pm", "ts1", "ts2"] {
        let runs: Vec<_> = [1, 2, 4, 8]
            .iter()
            .map(|r| {
                run_case(
                    "flyer_plate",
                    &[
                        &format!("scheme={scheme}"),
                        &format!("resolution_scale={r}"),
                    ],
                )
            })
            .collect();
        let travel: Vec<f64> = runs
            .iter()
            .map(|s| num(s, "precursor_position_error_relative"))
            .collect();
        let at800 = &runs[3];
        let rel_x = (num(at800, "precursor_position") - num(at800, "precursor_position_exact"))
            .abs()
            / num(at800, "precursor_position_exact");
        println!("{scheme}: error / travel at 100..800 particles: {travel:?}; error / x at 800: {rel_x:.4}");
        assert!(
            rel_x < 0.02,
            "{scheme}: precursor off by {rel_x} of its position at 800 particles"
        );
        assert!(
            travel[1] < travel[0] && travel[2] < travel[1] && travel[3] < 1.05 * travel[2],
            "{scheme}: offset does not shrink: {travel:?}"
        );
    }
}

/// L1 falls as the resolution doubles (100 -> 200 -> 400 particles).
#[test]
fn l1_falls_as_resolution_doubles() {
    for scheme in ["av", "pm", "ts1", "ts2"] {
        let l1: Vec<f64> = [1, 2, 4]
            .iter()
            .map(|r| {
                num(
                    &run_case(
                        "flyer_plate",
                        &[
                            &format!("scheme={scheme}"),
                            &format!("resolution_scale={r}"),
                        ],
                    ),
                    "l1_error",
                )
            })
            .collect();
        println!("{scheme}: L1 {l1:?}");
        assert!(
            l1[1] < l1[0] && l1[2] < l1[1],
            "{scheme}: L1 does not fall: {l1:?}"
        );
    }
}

/// Momentum is conserved to round-off by every scheme (antisymmetric pair forces).
#[test]
fn momentum_conserved_to_round_off() {
    for scheme in ["av", "pm", "ts1", "ts2", "tkc"] {
        let s = run_case("flyer_plate", &[&format!("scheme={scheme}")]);
        let p0 = s["momentum_initial"][0].as_f64().unwrap();
        let p1 = s["momentum_final"][0].as_f64().unwrap();
        assert!(
            ((p1 - p0) / p0).abs() < 1e-12,
            "{scheme}: momentum {p0} -> {p1}"
        );
    }
}

/// Seed 000 table 2: total energy error of ts1 and ts2 at round-off (the paper reports
/// 1.48e-8 %), and of tkc (total-energy form, seed 004 eq 11); av and pm are not energy
/// conserving (paper: 1.51 % and 2.34 %; measured here 1.4 % and 1.9 %, printed, not
/// asserted).
#[test]
fn energy_table() {
    for scheme in ["av", "pm", "ts1", "ts2", "tkc"] {
        let e = num(
            &run_case("flyer_plate", &[&format!("scheme={scheme}")]),
            "energy_rel_error",
        );
        println!("{scheme}: {:.3e} %", 100.0 * e);
        if scheme.starts_with("ts") || scheme == "tkc" {
            assert!(e.abs() <= 1e-10, "{scheme}: energy error {e}");
        }
    }
}
