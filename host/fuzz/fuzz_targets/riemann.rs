//! The Riemann solvers on arbitrary `f64` input.
//!
//! Contract: no input panics. On physical input (finite velocities up to 1e5 m/s,
//! tractions/pressures up to 1e13 Pa, densities 1e-3..1e6 kg/m³, sound speeds 1e-3..1e5
//! m/s, impedances 0 (free surface, fluid) or 1..1e11 kg/(m² s), shock slopes 0..100; real materials have 0.5..4. Far larger
//! slopes make the two-shock star pressure ill-conditioned: docs/fuzzing.md)
//! the star state is finite, the i/j swap mirrors it and the star velocity lies within
//! the bracket the characteristics allow.
#![no_main]
mod common;
use common::{all_finite, fit, fit_log};
use gsph_core::math::Vector;
use gsph_core::riemann::{
    acoustic_star, acoustic_star_vector, two_shock_star, AcousticSide, ShockSide,
};
use libfuzzer_sys::fuzz_target;

/// An impedance: exactly 0 for a zero input, else 1..1e11 kg/(m² s). The star velocity
/// scales as (traction jump)/Z, so impedances of 1e-300 overflow it (that is arithmetic,
/// not a defect).
fn impedance(x: f64) -> f64 {
    if x == 0.0 {
        0.0
    } else {
        fit_log(x, 1.0, 1e11)
    }
}

/// `a == b` to 1e-9 of `scale` or of the values themselves (round-off is relative).
fn near(a: f64, b: f64, scale: f64, what: &str) {
    let scale = scale.max(a.abs()).max(b.abs());
    assert!((a - b).abs() <= 1e-9 * scale, "{what}: {a} vs {b}");
}

fuzz_target!(|input: (bool, [f64; 10], [f64; 12])| {
    let (physical, a, v) = input;
    if !physical {
        // anything goes: only no panic
        let l = AcousticSide {
            u: a[0],
            s: a[1],
            z: a[2],
        };
        let r = AcousticSide {
            u: a[3],
            s: a[4],
            z: a[5],
        };
        let _ = acoustic_star(l, r);
        let sl = ShockSide {
            u: a[0],
            p: a[1],
            rho: a[2],
            c: a[6],
            s: a[7],
        };
        let sr = ShockSide {
            u: a[3],
            p: a[4],
            rho: a[5],
            c: a[8],
            s: a[9],
        };
        let _ = two_shock_star(sl, sr);
        let n = Vector::<3>::new(v[0], v[1], v[2]);
        let vec = |k: usize| Vector::<3>::new(v[k], v[k + 1], v[k + 2]);
        let _ = acoustic_star_vector(
            &n,
            &vec(3),
            &vec(6),
            a[0],
            a[1],
            &vec(9),
            &vec(3),
            a[2],
            a[3],
        );
        return;
    }
    let (umax, pmax) = (1e5, 1e13);
    let l = AcousticSide {
        u: fit(a[0], -umax, umax),
        s: fit(a[1], -pmax, pmax),
        z: impedance(a[2]),
    };
    let r = AcousticSide {
        u: fit(a[3], -umax, umax),
        s: fit(a[4], -pmax, pmax),
        z: impedance(a[5]),
    };
    let (u, s) = acoustic_star(l, r);
    all_finite("acoustic", &[u, s]);
    let m = |x: AcousticSide| AcousticSide { u: -x.u, ..x };
    let (u2, s2) = acoustic_star(m(r), m(l));
    // round-off of u* is that of the traction jump over the impedance
    let u_scale = umax + pmax / (l.z + r.z).max(1e-300);
    near(u2, -u, u_scale, "acoustic swap u");
    near(s2, s, pmax + l.z.max(r.z) * umax, "acoustic swap s");
    if l.z + r.z > 0.0 {
        // u* is a weighted mean of the sides' velocities plus the traction jump over Z
        let zs = l.z + r.z;
        // plus the round-off of the sum (z u + s) / Z
        let slack =
            (l.s - r.s).abs() / zs + 1e-9 * umax + 1e-12 * (u.abs() + (l.s.abs() + r.s.abs()) / zs);
        assert!(
            u >= l.u.min(r.u) - slack && u <= l.u.max(r.u) + slack,
            "acoustic u* {u}"
        );
    }

    let side = |k: usize, b: &[f64]| ShockSide {
        u: fit(b[0], -umax, umax),
        p: fit(b[1], -pmax, pmax),
        rho: fit_log(b[2], 1e-3, 1e6),
        c: fit_log(a[6 + 2 * k], 1e-3, 1e5),
        s: fit(a[7 + 2 * k], 0.0, 100.0),
    };
    let (sl, sr) = (side(0, &a[0..3]), side(1, &a[3..6]));
    let (u, p) = two_shock_star(sl, sr);
    all_finite("two-shock", &[u, p]);
    let m = |x: ShockSide| ShockSide { u: -x.u, ..x };
    let (u2, p2) = two_shock_star(m(sr), m(sl));
    let zmin = (sl.rho * sl.c).min(sr.rho * sr.c);
    near(u2, -u, umax + pmax / zmin, "two-shock swap u");
    let p_scale = pmax + (sl.rho * sl.c).max(sr.rho * sr.c) * umax;
    near(p2, p, p_scale.max(p.abs()), "two-shock swap p");
    let slack =
        (sl.p - sr.p).abs() / zmin + 1e-9 * (umax + u.abs() + (sl.p.abs() + sr.p.abs()) / zmin);
    assert!(
        u >= sl.u.min(sr.u) - slack && u <= sl.u.max(sr.u) + slack,
        "two-shock u* {u} outside [{}, {}] +- {slack}",
        sl.u.min(sr.u),
        sl.u.max(sr.u)
    );

    let nv = Vector::<3>::new(
        fit(v[0], -1.0, 1.0),
        fit(v[1], -1.0, 1.0),
        fit(v[2], -1.0, 1.0),
    );
    if nv.norm() < 1e-3 {
        return;
    }
    let n = nv.normalize();
    let vec = |k: usize, m: f64| {
        Vector::<3>::new(fit(v[k], -m, m), fit(v[k + 1], -m, m), fit(v[k + 2], -m, m))
    };
    let (vl, tl, vr) = (vec(3, umax), vec(6, pmax), vec(9, umax));
    let tr = vec(3, pmax);
    let (zl, zr) = (impedance(a[2]), impedance(a[5]));
    let (zlt, zrt) = (impedance(a[8]).min(zl), impedance(a[9]).min(zr));
    let (vs, ts) = acoustic_star_vector(&n, &vl, &tl, zl, zlt, &vr, &tr, zr, zrt);
    all_finite("vector", &[vs[0], vs[1], vs[2], ts[0], ts[1], ts[2]]);
    // the tractions on the planes with normal -n are -sigma.n
    let (vs2, ts2) = acoustic_star_vector(&(-n), &vr, &(-tr), zr, zrt, &vl, &(-tl), zl, zlt);
    for k in 0..3 {
        near(vs2[k], vs[k], 4.0 * (umax + pmax), "vector swap v"); // impedances >= 1
        near(
            ts2[k],
            -ts[k],
            4.0 * (pmax + zl.max(zr) * umax),
            "vector swap t",
        );
    }
});
