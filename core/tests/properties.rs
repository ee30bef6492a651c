//! Property tests (proptest) of the pure physics functions: Riemann solvers (i/j swap
//! symmetry, Galilean invariance, finite answers on physical input), EOS (`c² = dP/drho`
//! along the isentrope on random valid states of random materials) and return mappings
//! (on or inside the yield surface, idempotent, coaxial with the trial deviator). The
//! energy conservation of the ts schemes on random small systems is in
//! `properties_ts.rs`. Each property runs at most 256 cases (well under a second in release).

use gsph_core::material::eos::{
    guard_density, Eos, Hugoniot, Linear, Logarithmic, MieGruneisen, Murnaghan, Polynomial,
    Tillotson, TwoCurve, C2_FLOOR_FRACTION,
};
use gsph_core::material::strength::{radial_return, Jh1, JohnsonCook};
use gsph_core::math::{Real, Sym3, Vector};
use gsph_core::riemann::{
    acoustic_star, acoustic_star_vector, two_shock_star, AcousticSide, ShockSide,
};
use proptest::prelude::*;

/// `cases` cases; failures are reported (with the shrunk input), not persisted to files
/// (proptest cannot place them for an integration test).
fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// `|a - b| <= tol * scale`, reported with both values.
fn near(a: Real, b: Real, tol: Real, scale: Real) -> Result<(), TestCaseError> {
    prop_assert!(
        (a - b).abs() <= tol * scale,
        "{a} vs {b} (diff {}, allowed {})",
        a - b,
        tol * scale
    );
    Ok(())
}

// ---------------------------------------------------------------- Riemann solvers

prop_compose! {
    /// A side with velocity up to 2 km/s, traction up to 50 GPa either sign and an
    /// impedance of 1e5..1e8 kg/(m² s) (air-like to tungsten-like).
    fn acoustic_side()(u in -2e3..2e3, s in -5e10..5e10, lz in 5.0..8.0) -> AcousticSide {
        AcousticSide { u, s, z: (10.0 as Real).powf(lz) }
    }
}

prop_compose! {
    /// A shock side: rho 500..20000 kg/m³, c 500..10000 m/s, slope 0..3.
    fn shock_side()(u in -3e3..3e3, p in -2e10..5e10, rho in 500.0..2e4, c in 500.0..1e4,
                    s in 0.0..3.0) -> ShockSide {
        ShockSide { u, p, rho, c, s }
    }
}

fn vec3() -> impl Strategy<Value = Vector<3>> {
    (-1.0..1.0, -1.0..1.0, -1.0..1.0).prop_map(|(a, b, c)| Vector::<3>::new(a, b, c))
}

proptest! {
    #![proptest_config(config(256))]

    /// Swapping the sides (and so the axis) mirrors the star velocity and keeps the
    /// traction; adding `w` to both velocities adds `w` to `u*` and leaves `s*`.
    #[test]
    fn acoustic_swap_and_galilean(l in acoustic_side(), r in acoustic_side(), w in -3e3..3e3) {
        let (u, s) = acoustic_star(l, r);
        prop_assert!(u.is_finite() && s.is_finite());
        let (us_scale, s_scale) = (5e3, 1e11 + l.z.max(r.z) * 4e3);
        let m = |x: AcousticSide| AcousticSide { u: -x.u, ..x };
        let (u2, s2) = acoustic_star(m(r), m(l));
        near(u2, -u, 1e-12, us_scale)?;
        near(s2, s, 1e-12, s_scale)?;
        let g = |x: AcousticSide| AcousticSide { u: x.u + w, ..x };
        let (u3, s3) = acoustic_star(g(l), g(r));
        near(u3, u + w, 1e-12, us_scale)?;
        near(s3, s, 1e-12, s_scale)?;
        // the star state lies between the two sides' characteristics: s* - Z_l u* = s_l - Z_l u_l
        near(s - l.z * u, l.s - l.z * l.u, 1e-12, s_scale)?;
        near(s + r.z * u, r.s + r.z * r.u, 1e-12, s_scale)?;
    }

    /// The same for the two-shock solver: `(u*, p*) -> (-u*, p*)` under the swap,
    /// `u* + w` under a boost, and the two Hugoniot pressures agree at the root.
    #[test]
    fn two_shock_swap_and_galilean(l in shock_side(), r in shock_side(), w in -3e3..3e3) {
        let (u, p) = two_shock_star(l, r);
        prop_assert!(u.is_finite() && p.is_finite());
        let zmax = (l.rho * l.c).max(r.rho * r.c);
        let kmax = (l.rho * l.s).max(r.rho * r.s);
        // pressure scale: the sides' pressures and the largest Hugoniot jump on |w| <= 6 km/s
        let p_scale = 5e10 + zmax * 6e3 + kmax * 3.6e7;
        let m = |x: ShockSide| ShockSide { u: -x.u, ..x };
        let (u2, p2) = two_shock_star(m(r), m(l));
        near(u2, -u, 1e-9, 6e3)?;
        near(p2, p, 1e-9, p_scale)?;
        let g = |x: ShockSide| ShockSide { u: x.u + w, ..x };
        let (u3, p3) = two_shock_star(g(l), g(r));
        near(u3, u + w, 1e-9, 6e3)?;
        near(p3, p, 1e-9, p_scale)?;
        near(l.p + l.hugoniot(l.u - u), r.p + r.hugoniot(u - r.u), 1e-9, p_scale)?;
        // u* lies between the two velocities' bracket widened by the pressure jump
        let (lo, hi) = (l.u.min(r.u), l.u.max(r.u));
        let zmin = (l.rho * l.c).min(r.rho * r.c);
        let slack = (l.p - r.p).abs() / zmin + 1e-9;
        prop_assert!(u >= lo - slack && u <= hi + slack, "u* {u} outside [{lo}, {hi}] ± {slack}");
    }

    /// Vector (TKC) solver in 3D: swapping i and j (`n -> -n`) gives `V*' = V*`,
    /// `T*' = -T*`; a boost `w` gives `V* + w` and the same traction.
    #[test]
    fn vector_swap_and_galilean(
        n in vec3().prop_filter("non-zero axis", |n| n.norm() > 1e-3),
        vl in vec3(), vr in vec3(), tl in vec3(), tr in vec3(), w in vec3(),
        zl in 1e6..1e8, zr in 1e6..1e8, gl in 0.0..1.0, gr in 0.0..1.0,
    ) {
        let n = n.normalize();
        let (vl, vr, w) = (vl * 1e3, vr * 1e3, w * 1e3);
        let (tl, tr) = (tl * 1e10, tr * 1e10);
        let (zlt, zrt) = (gl * zl, gr * zr);
        let (v, t) = acoustic_star_vector(&n, &vl, &tl, zl, zlt, &vr, &tr, zr, zrt);
        // the tractions on the planes with normal -n are -sigma.n
        let (v2, t2) = acoustic_star_vector(&(-n), &vr, &(-tr), zr, zrt, &vl, &(-tl), zl, zlt);
        let (v3, t3) =
            acoustic_star_vector(&n, &(vl + w), &tl, zl, zlt, &(vr + w), &tr, zr, zrt);
        let t_scale = 1e10 + zl.max(zr) * 4e3;
        for k in 0..3 {
            prop_assert!(v[k].is_finite() && t[k].is_finite());
            near(v2[k], v[k], 1e-11, 1e4)?;
            near(t2[k], -t[k], 1e-11, t_scale)?;
            near(v3[k], v[k] + w[k], 1e-11, 1e4)?;
            near(t3[k], t[k], 1e-11, t_scale)?;
        }
    }
}

// ---------------------------------------------------------------- equations of state

/// One random material of each model, around the parameters of real metals and ceramics.
fn eos_model() -> impl Strategy<Value = Eos> {
    let rho0 = 1000.0..2e4;
    let c0 = 1000.0..1e4;
    prop_oneof![
        (rho0.clone(), c0.clone(), 0.5..3.0).prop_map(|(rho0, c0, gamma)| Eos::Linear(Linear {
            rho0,
            c0,
            gamma
        })),
        (rho0.clone(), c0.clone(), 1.0..8.0)
            .prop_map(|(rho0, c0, gamma)| { Eos::Murnaghan(Murnaghan { rho0, c0, gamma }) }),
        (rho0.clone(), 1e9..5e11)
            .prop_map(|(rho0, bulk_modulus)| Eos::Logarithmic(Logarithmic { rho0, bulk_modulus })),
        (rho0.clone(), c0.clone(), 0.8..2.5, 0.0..3.0).prop_map(|(rho0, c0, s1, gamma0)| {
            Eos::MieGruneisen(MieGruneisen {
                rho0,
                c0,
                s1,
                gamma0,
            })
        }),
        (rho0.clone(), c0.clone(), 0.8..2.5).prop_map(|(rho0, c0, s1)| Eos::Hugoniot(Hugoniot {
            rho0,
            c0,
            s1
        })),
        (rho0.clone(), c0.clone(), 0.8..2.5, 0.0..3.0).prop_map(|(rho0, c_a, s_a, gamma)| {
            Eos::TwoCurve(TwoCurve {
                rho0,
                c_a,
                s_a,
                gamma,
            })
        }),
        (rho0.clone(), 1e10..4e11, -2e11..6e11, -2e11..2e11)
            .prop_map(|(rho0, k1, k2, k3)| { Eos::Polynomial(Polynomial { rho0, k1, k2, k3 }) }),
        // Tillotson: a, b, A, B, alpha, beta, E0, E_iv, E_cv - E_iv
        (
            rho0,
            0.3..0.7,
            0.1..2.0,
            1e10..3e11,
            0.0..3e11,
            1.0..12.0,
            1.0..12.0,
            1e6..1e8,
            1e6..5e6,
            1e6..2e7
        )
            .prop_map(|(rho0, a, b, big_a, big_b, alpha, beta, e0, e_iv, de)| {
                Eos::Tillotson(Tillotson {
                    rho0,
                    a,
                    b,
                    big_a,
                    big_b,
                    alpha,
                    beta,
                    e0,
                    e_iv,
                    e_cv: e_iv + de,
                })
            }),
    ]
}

/// Reference `c0²` of a model (the scale of its floor and of `c²`): its `c²` at the
/// reference state `(rho0, e = 0)`, where no model is floored.
fn c0_squared(eos: &Eos) -> Real {
    eos.eval(eos.rho0(), 0.0).c2
}

/// Densities where a model is only C¹ (a central difference straddling them is not
/// second-order accurate): the reference density and the compression guard.
fn kinks(eos: &Eos) -> [Real; 2] {
    let rho0 = eos.rho0();
    let s = match *eos {
        Eos::MieGruneisen(m) => m.s1,
        Eos::Hugoniot(m) => m.s1,
        Eos::TwoCurve(m) => m.s_a,
        _ => 0.0,
    };
    [rho0, guard_density(rho0, s)]
}

/// Energies where a model's `c²` jumps (a difference straddling them is meaningless): the
/// Tillotson interpolation ends `E_iv`, `E_cv` (NaN: none).
fn energy_kinks(eos: &Eos) -> [Real; 2] {
    match *eos {
        Eos::Tillotson(m) => [m.e_iv, m.e_cv],
        _ => [Real::NAN; 2],
    }
}

proptest! {
    #![proptest_config(config(256))]

    /// `c² = dP/drho|_s`: a central difference of `P` along `de = P/rho² drho` matches
    /// the analytic `c²` to 1e-5 (relative to `c0²`) wherever the model is smooth and not
    /// floored; where floored, the model's own derivative is below the floor. Densities
    /// 0.6..3 rho0 (past the guard for steep `Us`-`up` slopes), energies -1e5..2e6 J/kg.
    #[test]
    fn eos_c2_is_the_isentropic_derivative(eos in eos_model(), eta in 0.6..3.0,
                                           e in -1e5..2e6) {
        let rho = eta * eos.rho0();
        let st = eos.eval(rho, e);
        let c02 = c0_squared(&eos);
        prop_assert!(st.p.is_finite() && st.c2.is_finite() && st.c2 > 0.0, "{st:?}");
        let d = 1e-5 * rho;
        prop_assume!(kinks(&eos).iter().all(|k| (rho - k).abs() > 3.0 * d));
        let de = st.p / (rho * rho) * d;
        prop_assume!(energy_kinks(&eos).iter().all(|k| k.is_nan() || (e - k).abs() > 3.0 * de.abs()));
        let fd = (eos.eval(rho + d, e + de).p - eos.eval(rho - d, e - de).p) / (2.0 * d);
        let floor = C2_FLOOR_FRACTION * c02;
        if st.c2 <= floor * (1.0 + 1e-12) {
            prop_assert!(fd <= floor + 1e-5 * c02.max(fd.abs()), "floored but dP/drho = {fd}");
        } else {
            // the scale: c², and the size of the terms that cancel in it
            let scale = st.c2.max(c02).max(st.p.abs() / rho);
            near(fd, st.c2, 1e-5, scale)?;
        }
    }

    /// Every model gives a finite `P` and a finite positive `c²` for every finite
    /// positive density (1e-6..1e6 rho0) and finite energy: the contract the Riemann
    /// solvers rely on.
    #[test]
    fn eos_finite_on_all_positive_densities(eos in eos_model(), log_eta in -6.0..6.0,
                                            e in -1e8..1e8) {
        let rho = eos.rho0() * (10.0 as Real).powf(log_eta);
        let st = eos.eval(rho, e);
        prop_assert!(st.p.is_finite() && st.c2.is_finite() && st.c2 > 0.0,
                     "{eos:?} at rho {rho}, e {e}: {st:?}");
    }
}

// ---------------------------------------------------------------- return mappings

prop_compose! {
    /// A random deviator (trace removed) with von Mises stress up to 1e10 Pa.
    fn deviator()(c in proptest::array::uniform6(-1.0..1.0), scale in 1e6..1e10) -> Sym3 {
        let s = Sym3 { xx: c[0], yy: c[1], zz: c[2], xy: c[3], xz: c[4], yz: c[5] } * scale;
        s.deviator()
    }
}

/// `out = k trial` with `0 <= k <= 1`: the return is radial (coaxial, never amplifies).
fn radial(out: &Sym3, trial: &Sym3) -> Result<(), TestCaseError> {
    let tt = trial.ddot(trial);
    prop_assume!(tt > 0.0);
    let k = out.ddot(trial) / tt;
    prop_assert!((-1e-15..=1.0 + 1e-12).contains(&k), "scale factor {k}");
    let resid = *out - *trial * k;
    prop_assert!(resid.ddot(&resid) <= 1e-24 * tt, "not coaxial: {resid:?}");
    Ok(())
}

fn jc_model() -> impl Strategy<Value = JohnsonCook> {
    (
        (1e8..2e9, 0.0..2e9, 0.05..1.0, 0.0..0.1, 0.3..2.0),
        (200.0..400.0, 800.0..3000.0, 100.0..1000.0, 0.0..1.0),
    )
        .prop_map(
            |((a, b, n, c, m), (t_room, dt_melt, cp, chi))| JohnsonCook {
                a,
                b,
                n,
                c,
                m,
                eps_dot0: 1.0,
                t_room,
                t_melt: t_room + dt_melt,
                specific_heat: cp,
                taylor_quinney: chi,
            },
        )
}

proptest! {
    #![proptest_config(config(256))]

    /// Von Mises: the returned deviator is on or inside `sigma_vm = Y`, a second return
    /// does nothing, and the return is radial.
    #[test]
    fn von_mises_return(s in deviator(), y in 1e6..5e9, g in 1e9..3e11) {
        let r = radial_return(s, y, g);
        let vm = r.s.von_mises();
        prop_assert!(vm <= y * (1.0 + 1e-12), "sigma_vm {vm} > Y {y}");
        prop_assert!(r.d_eps_p >= 0.0 && r.plastic_work >= 0.0);
        if s.von_mises() > y {
            near(vm, y, 1e-12, y)?;
        }
        let again = radial_return(r.s, y, g);
        prop_assert!(again.d_eps_p <= 1e-12 * y / g);
        radial(&again.s, &r.s)?;
        near(again.s.von_mises(), vm, 1e-12, y)?;
        radial(&r.s, &s)?;
    }

    /// Johnson–Cook: the returned deviator is on or inside the flow surface at the updated
    /// plastic strain and rate; rate-independent (C = 0), a second return from the updated
    /// state does nothing; the return is radial.
    #[test]
    fn johnson_cook_return(jc in jc_model(), s in deviator(), g in 1e9..3e11,
                           eps_p in 0.0..2.0, dtemp in -100.0..2000.0, dt in 1e-10..1e-6,
                           rate_free in any::<bool>()) {
        let jc = if rate_free { JohnsonCook { c: 0.0, ..jc } } else { jc };
        let t = jc.t_room + dtemp;
        let r = jc.return_map(s, g, 7800.0, eps_p, t, dt);
        prop_assert!(r.d_eps_p >= 0.0 && r.plastic_work >= 0.0 && r.d_temperature >= 0.0);
        let y = jc.flow_stress(eps_p + r.d_eps_p, r.d_eps_p / dt, t);
        let vm = r.s.von_mises();
        prop_assert!(vm <= y * (1.0 + 1e-9) + 1e-6, "sigma_vm {vm} > sigma_y {y}");
        radial(&r.s, &s)?;
        if rate_free {
            let again = jc.return_map(r.s, g, 7800.0, eps_p + r.d_eps_p, t, dt);
            prop_assert!(again.d_eps_p <= 1e-9 * (eps_p + r.d_eps_p) + 1e-12,
                         "second return yields again: {}", again.d_eps_p);
            near(again.s.von_mises(), vm, 1e-9, vm.max(1.0))?;
        }
    }

    /// JH1: the returned deviator is within the strength of the resulting state (intact or
    /// failed), the damage never decreases, a second return from the updated state does
    /// nothing, and the return is radial.
    #[test]
    fn jh1_return(s in deviator(), g in 1e10..3e11, p in -2e9..2e10, damage in 0.0..1.2,
                  rate in 0.0..1e6) {
        let m = Jh1::sic_seed000();
        let r = m.update(s, g, p, damage, rate);
        let y = m.strength(p, r.failed, rate);
        let vm = r.s.von_mises();
        prop_assert!(vm <= y * (1.0 + 1e-12), "sigma_vm {vm} > strength {y}");
        prop_assert!(r.damage >= damage.min(1.0) && r.damage <= 1.0);
        prop_assert_eq!(r.failed, r.damage >= 1.0);
        prop_assert!(r.d_eps_p >= 0.0 && r.plastic_work >= 0.0);
        radial(&r.s, &s)?;
        let again = m.update(r.s, g, p, r.damage, rate);
        prop_assert!(again.d_eps_p <= 1e-12 * y.max(1.0) / g);
        near(again.damage, r.damage, 1e-12, 1.0)?;
        near(again.s.von_mises(), vm, 1e-12, vm.max(1.0))?;
    }
}
