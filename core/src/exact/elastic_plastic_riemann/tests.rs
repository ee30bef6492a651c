//! Tests of the elastic–plastic Riemann solution (seed 004 §2.1.1).
extern crate std;

use super::*;
use crate::math::real::abs;

fn al() -> ElasticPlasticRiemann {
    ElasticPlasticRiemann::new(EpRiemannParams::seed004_aluminium()).unwrap()
}

fn rel(a: Real, b: Real, scale: Real) -> Real {
    abs(a - b) / scale
}

/// Mass and momentum jumps across a right-going shock of Eulerian speed `d` from the
/// state ahead `a` to the state behind `b`: `rho_a (d - u_a) = rho_b (d - u_b) = m` and
/// `sigma_b - sigma_a = -m (u_b - u_a)`. Returns the two relative residuals.
fn rh_residuals(a: EpState, b: EpState, d: Real) -> (Real, Real) {
    let (ma, mb) = (a.rho * (d - a.u), b.rho * (d - b.u));
    let mass = rel(ma, mb, abs(ma));
    let mom = rel(
        b.sigma_xx - a.sigma_xx,
        -ma * (b.u - a.u),
        abs(b.sigma_xx - a.sigma_xx),
    );
    (mass, mom)
}

/// The seed's discontinuous treatment: both rarefactions as jumps obeying the Rayleigh
/// line (eqs 28–29, 33–37), solved for the contact stress. Returns `(sigma_c, u_c)`.
fn paper_discontinuous_contact(p: &EpRiemannParams) -> (Real, Real) {
    let br = Branches::new(p);
    let (s1, v1, ser, ver) = (br.sigma1, br.v1, br.sigma_er(), br.v_er());
    let u_er = sqrt((ser - s1) * (ver - v1));
    let left = |s: Real| {
        let v = br.left_volume(s);
        if s <= ser {
            sqrt((s - s1) * (v - v1))
        } else {
            u_er + sqrt((s - ser) * (v - ver))
        }
    };
    let sc = brent(|s| left(s) - br.right_velocity(s), s1, 0.0, 0.0, "paper").unwrap();
    (sc, br.right_velocity(sc))
}

#[test]
fn exact_ep_rankine_hugoniot_both_shocks() {
    let ep = al();
    let w = ep.wave_speeds();
    let (r0, ec, pc) = (
        ep.right_state(),
        ep.precursor_state(),
        ep.contact_states().1,
    );
    let (m1, p1) = rh_residuals(r0, ec, w.precursor);
    let (m2, p2) = rh_residuals(ec, pc, w.plastic_shock);
    for r in [m1, p1, m2, p2] {
        assert!(r < 1e-10, "RH residual {r}");
    }
    // HEL on the yield surface: S = sigma + P = -2Y/3 with P = B ln(V0/V) (eqs 30-31).
    let p = ep.params();
    let s_ec = ec.sigma_xx + p.bulk_modulus * ln(ec.rho / p.rho0);
    assert!(rel(s_ec, -2.0 * p.yield_stress / 3.0, p.yield_stress) < 1e-12);
    // Plastic shock state on the compressive plastic branch.
    let s_pc = pc.sigma_xx + p.bulk_modulus * ln(pc.rho / p.rho0);
    assert!(rel(s_pc, -2.0 * p.yield_stress / 3.0, p.yield_stress) < 1e-12);
    // Seed's D_ec closed form, corrected with rho0 in the denominator (erratum):
    // D_ec² = (2/3 + B/(2G)) Y / (rho0 (1 - exp(-Y/(2G)))).
    let (b, g, y) = (p.bulk_modulus, p.shear_modulus, p.yield_stress);
    let d2 = (2.0 / 3.0 + b / (2.0 * g)) * y / (p.rho0 * (1.0 - exp(-y / (2.0 * g))));
    assert!(rel(w.precursor, sqrt(d2), w.precursor) < 1e-12);
}

#[test]
fn exact_ep_fans_and_contact_continuous() {
    let ep = al();
    let w = ep.wave_speeds();
    let t = 2e-6;
    let (ss, us) = (4e9, ep.contact_velocity());
    // Just inside / outside each fan edge: the fan matches the adjacent constant state.
    let eps = 1e-9 * w.precursor;
    for edge in [
        w.elastic_fan_head,
        w.elastic_fan_tail,
        w.plastic_fan_head,
        w.plastic_fan_tail,
    ] {
        let (l, r) = (
            ep.sample((edge - eps) * t, t),
            ep.sample((edge + eps) * t, t),
        );
        assert!(
            rel(l.sigma_xx, r.sigma_xx, ss) < 1e-7,
            "sigma jump at {edge}"
        );
        assert!(rel(l.u, r.u, us) < 1e-7, "u jump at {edge}");
        assert!(rel(l.rho, r.rho, l.rho) < 1e-7, "rho jump at {edge}");
    }
    // Through each fan the stress and velocity rise monotonically and continuously.
    for (a, b) in [
        (w.elastic_fan_head, w.elastic_fan_tail),
        (w.plastic_fan_head, w.plastic_fan_tail),
    ] {
        let (sa, sb) = (ep.sample(a * t, t), ep.sample(b * t, t));
        let mut prev = sa;
        for i in 1..=400 {
            let xi = a + (b - a) * (i as Real) / 400.0;
            let s = ep.sample(xi * t, t);
            assert!(s.sigma_xx >= prev.sigma_xx && s.u >= prev.u && s.rho <= prev.rho);
            let step = s.sigma_xx - prev.sigma_xx;
            assert!(
                step < 0.01 * (sb.sigma_xx - sa.sigma_xx),
                "stress step at {xi}"
            );
            prev = s;
        }
    }
    // Across the contact: stress and velocity continuous, density jumps.
    let (l, r) = (
        ep.sample((w.contact - eps) * t, t),
        ep.sample((w.contact + eps) * t, t),
    );
    assert_eq!(l.sigma_xx, r.sigma_xx);
    assert_eq!(l.u, r.u);
    // Same stress, opposite yield branches (S = +2Y/3 left, -2Y/3 right): the released side
    // carries the higher pressure, rho_l / rho_r = exp(4Y/(3B)).
    let p = ep.params();
    let ratio = exp(4.0 * p.yield_stress / (3.0 * p.bulk_modulus));
    assert!(rel(l.rho / r.rho, ratio, 1.0) < 1e-12);
    // The left (fan) curve evaluated at sigma_c gives the same velocity as the shocks.
    let br = Branches::new(ep.params());
    assert!(rel(br.left_velocity(ep.contact_stress()), us, us) < 1e-12);
}

#[test]
fn exact_ep_small_yield_limits() {
    let p = EpRiemannParams {
        yield_stress: 1e3,
        ..EpRiemannParams::seed004_aluminium()
    };
    let ep = ElasticPlasticRiemann::new(p).unwrap();
    let w = ep.wave_speeds();
    let k = p.bulk_modulus + 4.0 * p.shear_modulus / 3.0;
    let cl0 = sqrt(k / p.rho0);
    assert!(
        rel(w.precursor, cl0, cl0) < 1e-6,
        "{} vs {cl0}",
        w.precursor
    );
    let cl1 = ep.c_long_left();
    let rho1 = ep.left_state().rho;
    assert!(rel(cl1, sqrt(k / rho1), cl1) < 1e-14);
    assert!(rel(-w.elastic_fan_head, cl1, cl1) < 1e-14);
    assert!(rel(-w.elastic_fan_tail, cl1, cl1) < 1e-6);
    // The seed's discontinuous elastic release speed D_er tends to -c_l(rho1) as well.
    let br = Branches::new(&p);
    let (rho_er, u_er) = (
        1.0 / br.v_er(),
        sqrt((br.sigma_er() - br.sigma1) * (br.v_er() - br.v1)),
    );
    let d_er = rho_er * u_er / (rho_er - rho1);
    assert!(rel(-d_er, cl1, cl1) < 1e-6, "{d_er} vs {cl1}");
}

#[test]
fn exact_ep_far_field_ordering_and_validity() {
    let ep = al();
    let t = 2e-6;
    assert_eq!(ep.sample(-0.05, t), ep.left_state());
    assert_eq!(ep.sample(0.05, t), ep.right_state());
    assert_eq!(ep.sample(-1e-3, 0.0), ep.left_state());
    assert_eq!(ep.sample(0.0, 0.0), ep.right_state());
    let l = ep.left_state();
    let p = ep.params();
    assert_eq!(l.sigma_xx, p.sigma1);
    let p1 = -p.sigma1 - 2.0 * p.yield_stress / 3.0;
    assert!(rel(l.rho, p.rho0 * exp(p1 / p.bulk_modulus), l.rho) < 1e-14);
    let a = ep.wave_speeds().as_array();
    for i in 1..a.len() {
        assert!(a[i - 1] < a[i], "wave order broken at {i}: {a:?}");
    }
    assert!(ep.contact_velocity() > 0.0);
    let x_left = -0.025;
    let xv = ep.valid_from(x_left, t);
    assert!(rel(xv, x_left + ep.c_long_left() * t, 1.0) < 1e-15);
    // At the case's t = 2 us with L = 0.05 the release from the left end has not reached
    // the elastic fan head.
    assert!(xv < ep.wave_positions(t).elastic_fan_head);
}

#[test]
fn exact_ep_self_similar() {
    let ep = al();
    let t = 1.3e-6;
    for i in -200..=200 {
        let x = 0.02 * (i as Real) / 200.0;
        assert_eq!(ep.sample(x, t), ep.sample(2.0 * x, 2.0 * t));
    }
}

#[test]
fn exact_ep_paper_discontinuous_contact_agrees() {
    let ep = al();
    let (sc, uc) = paper_discontinuous_contact(ep.params());
    let ds = rel(sc, ep.contact_stress(), abs(ep.contact_stress()));
    let du = rel(uc, ep.contact_velocity(), ep.contact_velocity());
    std::println!(
        "fan vs seed discontinuous: d(sigma_c)/sigma_c = {ds:.3e}, d(u_c)/u_c = {du:.3e}"
    );
    // Measured: ~1e-6 relative in sigma_c (the rarefaction-shock error is third order in
    // the wave amplitude, (Y/G)³ and (Δσ/B)³ ~ 1e-6).
    assert!(ds < 1e-5 && ds > 0.0);
    assert!(du < 1e-5);
}

#[test]
fn exact_ep_key_numbers() {
    let ep = al();
    let w = ep.wave_speeds();
    std::println!(
        "u_c = {:.6} m/s, sigma_c = {:.6e} Pa, sigma_ec = {:.6e}, sigma_er = {:.6e}",
        ep.contact_velocity(),
        ep.contact_stress(),
        ep.precursor_state().sigma_xx,
        ep.elastic_release_state().sigma_xx
    );
    std::println!("waves (m/s): {:?}", w);
    // Hand check: sigma_ec = -2Y/3 - B Y/(2G) = -0.2 GPa - 73*0.3/46 GPa = -0.676087 GPa;
    // sigma_er = sigma1 + 4Y/3 + B Y/G = -4 + 0.4 + 0.952174 = -2.647826 GPa;
    // c_l(rho0) = sqrt((73 + 30.667) GPa / 2688.9) = 6209.15 m/s (precursor a bit faster).
    assert!(rel(ep.precursor_state().sigma_xx, -0.676_087e9, 1e9) < 1e-6);
    assert!(rel(ep.elastic_release_state().sigma_xx, -2.647_826e9, 1e9) < 1e-6);
    assert!(w.precursor > 6209.15 && w.precursor < 6300.0);
    let sc = ep.contact_stress();
    assert!(sc > -2.647_826e9 && sc < -0.676_087e9);
}

#[test]
fn exact_ep_rejects_bad_params() {
    let base = EpRiemannParams::seed004_aluminium();
    let bad = |p| ElasticPlasticRiemann::new(p).unwrap_err();
    let e = bad(EpRiemannParams {
        bulk_modulus: -1.0,
        ..base
    });
    assert!(matches!(
        e,
        ExactError::BadParameter {
            name: "bulk_modulus",
            ..
        }
    ));
    let e = bad(EpRiemannParams {
        sigma1: 1e9,
        ..base
    });
    assert!(matches!(e, ExactError::BadParameter { name: "sigma1", .. }));
    // Too weak to reach tensile yield on release: not a four-wave configuration.
    let e = bad(EpRiemannParams {
        sigma1: -0.5e9,
        ..base
    });
    assert!(matches!(e, ExactError::BadParameter { name: "sigma1", .. }));
    let _ = std::format!("{e}");
}

/// The contact state of seed 004 §2.1.1 as published digits, independent of the branch
/// code above: sigma_c = -1.931995 GPa, u_c = 129.3952 m/s (an independent evaluation of
/// the fan solution, bisection on u_L(sigma) = u_R(sigma) in Python double precision, gives
/// -1.9319945 GPa and 129.39523 m/s). Tolerance: one unit of the last printed digit.
#[test]
fn exact_ep_contact_state_hard_coded() {
    let ep = ElasticPlasticRiemann::new(EpRiemannParams {
        rho0: 2688.9,
        bulk_modulus: 73.0e9,
        shear_modulus: 23.0e9,
        yield_stress: 0.3e9,
        sigma1: -4.0e9,
    })
    .unwrap();
    let (sc, uc) = (ep.contact_stress(), ep.contact_velocity());
    std::println!("sigma_c = {sc:.1} Pa, u_c = {uc:.6} m/s");
    assert!(abs(sc - -1.931_995e9) <= 1e3, "sigma_c = {sc} Pa");
    assert!(abs(uc - 129.3952) <= 1e-4, "u_c = {uc} m/s");
    // both contact sides carry the same state
    let (l, r) = ep.contact_states();
    assert!(abs(l.sigma_xx - sc) <= 1e3 && abs(r.sigma_xx - sc) <= 1e3);
    assert!(abs(l.u - uc) <= 1e-4 && abs(r.u - uc) <= 1e-4);
}
