//! Seed 004 §2.1: TKC-MUSCL-SPH against the contact SPH it improves (`pm`) on the
//! elastic–plastic Riemann problem in 2D (periodic strip), the sound wave in 1D and 2D,
//! and the Verney cylinder, at reduced sizes. Full figures: `make validate`.

use gsph_tests::{num, run_case};

/// Seed 004 fig 2b: L1(sigma_xx) of tkc below pm at 100 and 200 particles along x.
#[test]
fn riemann_2d_tkc_below_pm() {
    for r in [1, 2] {
        let res = format!("resolution_scale={r}");
        let pm = num(&run_case("riemann_al_2d", &["scheme=pm", &res]), "l1_error");
        let tkc = num(
            &run_case("riemann_al_2d", &["scheme=tkc", &res]),
            "l1_error",
        );
        println!(
            "{} particles along x: pm {pm:.4e} Pa, tkc {tkc:.4e} Pa",
            100 * r
        );
        assert!(tkc < pm, "tkc {tkc} not below pm {pm}");
    }
}

/// Seed 004 fig 3: the pulse centres of tkc sit within half a particle spacing of the
/// exact positions (pm lags by about one spacing in 1D, two in 2D), its L1 of U_x is below
/// pm's, and it conserves total energy (seed 004 eq 11 in total-energy form).
#[test]
fn sound_wave_tkc_centres_and_l1() {
    for case in ["sound_cu", "sound_cu_2d"] {
        let tkc = run_case(case, &["scheme=tkc"]);
        let pm = run_case(case, &["scheme=pm"]);
        let off = num(&tkc, "pulse_centre_error_spacings");
        println!(
            "{case}: centre offset tkc {off:.3} / pm {:.3} spacings; L1 tkc {:.4e} / pm {:.4e} m/s",
            num(&pm, "pulse_centre_error_spacings"),
            num(&tkc, "l1_error"),
            num(&pm, "l1_error")
        );
        assert!(
            off.abs() < 0.5,
            "{case}: tkc pulse centre off by {off} spacings"
        );
        assert!(num(&tkc, "l1_error") < num(&pm, "l1_error"));
        assert!(num(&tkc, "energy_rel_error").abs() < 1e-10);
    }
}

/// Seed 004 §2.1.2 convergence: tkc's L1(U_x) against the exact linear pulse keeps
/// falling, by at least 1.8x per doubling of the particles, at 800, 1,600 and 3,200
/// particles (1D). The graded runs use an amplitude of 0.05 m/s (scene and reference both
/// overridden) instead of the seed's 5 m/s, where the nonlinear wave runs ahead of the
/// linear reference (measured at 1 us: the centroid of the right-going pulse 0.9 um
/// further than at 0.05 m/s, at 3,200 and at 6,400 particles) and L1 stalls near 1.3e-4 of
/// the amplitude. Measured l1_error_relative (L1 / amplitude):
///
/// | particles | 200 | 400 | 800 | 1,600 | 3,200 | 6,400 |
/// | --- | --- | --- | --- | --- | --- | --- |
/// | A = 0.05 m/s | 4.513e-3 | 1.874e-3 | 8.425e-4 | 3.957e-4 | 1.930e-4 | 9.53e-5 |
/// | A = 5 m/s | 4.513e-3 | 1.876e-3 | 8.477e-4 | 4.004e-4 | 2.013e-4 | 1.387e-4 |
///
/// At 5 m/s the last doubling gains only 1.45x (the reference's error); at 0.05 m/s every
/// doubling gains 2.0-2.4x.
#[test]
fn sound_wave_tkc_l1_keeps_falling() {
    let amp = 0.05;
    let set = [
        format!("bodies.0.velocity.amplitude={amp}"),
        format!("reference.amplitude={amp}"),
    ];
    let mut last: Option<f64> = None;
    for r in [4, 8, 16] {
        let res = format!("resolution_scale={r}");
        let s = run_case("sound_cu", &["scheme=tkc", &set[0], &set[1], &res]);
        let l1 = num(&s, "l1_error_relative");
        println!("{} particles: L1 / A = {l1:.4e}", num(&s, "particles"));
        if let Some(prev) = last {
            assert!(
                l1 * 1.8 <= prev,
                "L1 / A fell only from {prev:e} to {l1:e} at {} particles",
                num(&s, "particles")
            );
        }
        last = Some(l1);
    }
}

/// Seed 004 fig 5 at the coarse particle size D0 = 2 mm (2,827 particles): tkc stops the
/// Verney cylinder within 1 % of the analytic 0.0667 m (measured -0.55 %).
#[test]
fn verney_tkc_within_one_percent() {
    let s = run_case("verney_al", &["scheme=tkc", "resolution_scale=0.5"]);
    let (r, exact) = (num(&s, "inner_radius"), num(&s, "inner_radius_exact"));
    println!(
        "inner radius {r:.5} m, analytic {exact:.5} m, spread {:.4}",
        num(&s, "inner_spread")
    );
    assert!((exact - 0.0667).abs() < 1e-4);
    assert!(
        ((r - exact) / exact).abs() < 0.01,
        "inner radius {r} vs {exact}"
    );
}

/// Issue 27 part 5: tkc with `options.integrator = "leapfrog"` is second order in time. The
/// sound pulse at the scene's CFL 0.5 (A = 0.05 m/s, 800 to 3,200 particles, dt halving
/// with the spacing): the observed order of the L1 error against the exact solution is at
/// least 1.8 at every doubling (measured 1.84, 1.88; 1.85 to 6,400), and the total energy
/// stays exact. The seeds' Euler steps of the same runs converge at first order (1.09,
/// 1.04): their time error dominates.
#[test]
fn sound_wave_tkc_is_second_order_with_the_leapfrog() {
    let amp = 0.05;
    let order = |integrator: &str| {
        let mut errs = vec![];
        for r in [4, 8, 16] {
            let s = run_case(
                "sound_cu",
                &[
                    "scheme=tkc",
                    &format!("bodies.0.velocity.amplitude={amp}"),
                    &format!("reference.amplitude={amp}"),
                    &format!("resolution_scale={r}"),
                    &format!("options.integrator={integrator}"),
                ],
            );
            if integrator == "leapfrog" {
                let de = num(&s, "energy_rel_error");
                assert!(de.abs() < 1e-12, "energy error {de:e}");
            }
            errs.push(num(&s, "l1_error_relative"));
        }
        let orders: Vec<f64> = errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
        println!("{integrator}: L1/A {errs:?}, orders {orders:?}");
        orders
    };
    for o in order("leapfrog") {
        assert!(o >= 1.8, "leapfrog order {o}");
    }
    for o in order("euler") {
        assert!(
            o < 1.3,
            "euler order {o}: the test no longer tells the integrators apart"
        );
    }
}
