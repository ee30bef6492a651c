//! The return mappings (von Mises, Johnson–Cook, JH1) on arbitrary `f64` input.
//!
//! Contract: no input panics, and the Johnson–Cook iteration ends (it is bounded). On
//! physical input (deviator components up to 1e13 Pa, moduli and strengths positive up to
//! 1e13 Pa, parameters the scene validator accepts within generous bounds) every output is
//! finite, the plastic strain increment, work and heating are >= 0, the returned deviator
//! is coaxial with the trial one, no larger, and within the flow surface of the updated
//! state; JH1 damage never decreases and stays <= 1.
#![no_main]
mod common;
use common::{all_finite, fit, fit_log};
use gsph_core::material::strength::{radial_return, Jh1, JohnsonCook};
use gsph_core::math::Sym3;
use libfuzzer_sys::fuzz_target;

fn sym(c: &[f64]) -> Sym3 {
    Sym3 {
        xx: c[0],
        yy: c[1],
        zz: c[2],
        xy: c[3],
        xz: c[4],
        yz: c[5],
    }
}

/// (`+ 1e-150` Pa: `sigma_vm` squares the components, which loses precision in the
/// subnormal range below ~1e-154 Pa.)
fn check_radial(out: &Sym3, trial: &Sym3, y: f64, what: &str) {
    let (o, t) = (out.von_mises(), trial.von_mises());
    all_finite(what, &[out.xx, out.yy, out.zz, out.xy, out.xz, out.yz]);
    assert!(o <= t * (1.0 + 1e-12), "{what}: |S| grew {t} -> {o}");
    assert!(
        o <= y * (1.0 + 1e-9) + 1e-150,
        "{what}: sigma_vm {o} > flow stress {y}"
    );
    if t > 0.0 {
        let k = o / t;
        let r = *out - *trial * k;
        assert!(r.von_mises() <= 1e-9 * t, "{what}: not coaxial ({r:?})");
    }
}

fuzz_target!(|input: (bool, [f64; 6], [f64; 11], [f64; 5])| {
    let (physical, c, p, x) = input;
    if !physical {
        let s = sym(&c);
        let _ = radial_return(s, p[0], p[1]);
        let jc = JohnsonCook {
            a: p[0],
            b: p[1],
            n: p[2],
            c: p[3],
            m: p[4],
            eps_dot0: p[5],
            t_room: p[6],
            t_melt: p[7],
            specific_heat: p[8],
            taylor_quinney: p[9],
        };
        let _ = jc.return_map(s, x[0], x[1], x[2], x[3], x[4]);
        let jh = Jh1 {
            sigma_i1: p[0],
            p1: p[1],
            sigma_i2: p[2],
            p2: p[3],
            sigma_f_max: p[4],
            c_f: p[5],
            tensile_limit: p[6],
            eps_f_max: p[7],
            p_max: p[8],
            c: p[9],
            eps_dot0: p[10],
        };
        let _ = jh.update(s, x[0], x[1], x[2], x[3]);
        return;
    }
    let smax = 1e13;
    let s = sym(&c.map(|v| fit(v, -smax, smax)));
    let g = fit_log(x[0], 1e-3, 1e13);

    // von Mises
    let y = fit(p[0], 0.0, smax);
    let r = radial_return(s, y, g);
    all_finite("von Mises", &[r.d_eps_p, r.plastic_work]);
    assert!(r.d_eps_p >= 0.0 && r.plastic_work >= 0.0);
    check_radial(&r.s, &s, y, "von Mises");

    // Johnson–Cook (validator: a, n, m, eps_dot0, t_room, c_p > 0; b, c >= 0; t_melt > t_room)
    let t_room = fit_log(p[6], 1e-3, 1e4);
    let jc = JohnsonCook {
        a: fit_log(p[0], 1e-3, 1e11),
        b: fit(p[1], 0.0, 1e11),
        n: fit_log(p[2], 1e-3, 10.0),
        c: fit(p[3], 0.0, 10.0),
        m: fit_log(p[4], 1e-3, 10.0),
        eps_dot0: fit_log(p[5], 1e-6, 1e6),
        t_room,
        t_melt: t_room + fit_log(p[7], 1e-3, 1e5),
        specific_heat: fit_log(p[8], 1e-3, 1e5),
        taylor_quinney: fit(p[9], 0.0, 1.0),
    };
    let (rho, eps_p) = (fit_log(x[1], 1e-3, 1e6), fit(x[2], 0.0, 100.0));
    let (temp, dt) = (fit(x[3], 0.0, 1e5), fit_log(x[4], 1e-15, 1.0));
    let r = jc.return_map(s, g, rho, eps_p, temp, dt);
    all_finite(
        "Johnson-Cook",
        &[r.d_eps_p, r.plastic_work, r.d_temperature],
    );
    assert!(r.d_eps_p >= 0.0 && r.plastic_work >= 0.0 && r.d_temperature >= 0.0);
    let y = jc.flow_stress(eps_p + r.d_eps_p, r.d_eps_p / dt, temp);
    check_radial(&r.s, &s, y, "Johnson-Cook");

    // JH1 (validator: sigma_i1, p1, sigma_i2 > 0, p2 > p1, sigma_f_max, c_f >= 0, T < 0)
    let p1 = fit_log(p[1], 1e-3, 1e12);
    let jh = Jh1 {
        sigma_i1: fit_log(p[0], 1e-3, 1e12),
        p1,
        sigma_i2: fit_log(p[2], 1e-3, 1e12),
        p2: p1 + fit_log(p[3], 1e-3, 1e12),
        sigma_f_max: fit(p[4], 0.0, 1e12),
        c_f: fit(p[5], 0.0, 10.0),
        tensile_limit: -fit_log(p[6], 1e-3, 1e12),
        eps_f_max: fit(p[7], 0.0, 10.0),
        p_max: fit_log(p[8], 1e-3, 1e13),
        c: fit(p[9], 0.0, 10.0),
        eps_dot0: fit_log(p[10], 1e-6, 1e6),
    };
    let (pr, damage, rate) = (
        fit(x[1], -1e12, 1e13),
        fit(x[2], -1.0, 2.0),
        fit(x[4], 0.0, 1e12),
    );
    let r = jh.update(s, g, pr, damage, rate);
    all_finite("JH1", &[r.d_eps_p, r.plastic_work, r.damage]);
    assert!(r.d_eps_p >= 0.0 && r.plastic_work >= 0.0);
    assert!(
        r.damage >= damage.clamp(0.0, 1.0) && r.damage <= 1.0,
        "JH1 damage {damage} -> {}",
        r.damage
    );
    check_radial(&r.s, &s, jh.strength(pr, r.failed, rate), "JH1");
});
