//! The eight equations of state on arbitrary `f64` input.
//!
//! Contract: no input panics. With parameters the scene validator accepts (the ranges of
//! real materials, `gsph_core::material::params::ranges`: rho0 1e-3..1e5 kg/m³, c0
//! 1..1e5 m/s, slopes 0..20, Grüneisen coefficients -20..20, bulk moduli 1e3..1e13 Pa,
//! higher-order moduli -1e13..1e13 Pa; Tillotson: a, b, alpha, beta 0..20, E0
//! 1e-3..1e10 J/kg, E_iv 0..1e10 J/kg, E_cv - E_iv 1e-3..1e10 J/kg; Murnaghan: gamma
//! 1e-300..20), every
//! density 1e-12..1e12
//! rho0 with |e| <= 1e12 J/kg gives a finite pressure and a finite, positive c² (far beyond
//! these bounds plain overflow of `c0² rho` or `k3 z³` is possible). Non-finite or
//! non-positive input may give non-finite output.
#![no_main]
mod common;
use common::{fit, fit_log};
use gsph_core::material::eos::*;
use libfuzzer_sys::fuzz_target;

fn models(a: &[f64; 5]) -> [Eos; 8] {
    let rho0 = fit_log(a[0], 1e-3, 1e5);
    let c0 = fit_log(a[1], 1.0, 1e5);
    let s = fit(a[2], 0.0, 20.0);
    let g = fit(a[3], -20.0, 20.0);
    let k = fit_log(a[4], 1e3, 1e13);
    [
        Eos::Linear(Linear { rho0, c0, gamma: g }),
        Eos::Logarithmic(Logarithmic {
            rho0,
            bulk_modulus: k,
        }),
        Eos::MieGruneisen(MieGruneisen {
            rho0,
            c0,
            s1: s,
            gamma0: g,
        }),
        Eos::Hugoniot(Hugoniot { rho0, c0, s1: s }),
        Eos::TwoCurve(TwoCurve {
            rho0,
            c_a: c0,
            s_a: s,
            gamma: g,
        }),
        Eos::Polynomial(Polynomial {
            rho0,
            k1: k,
            k2: fit(a[1], -1e13, 1e13),
            k3: fit(a[2], -1e13, 1e13),
        }),
        Eos::Tillotson(Tillotson {
            rho0,
            a: s,
            b: fit(a[3], 0.0, 20.0),
            big_a: k,
            big_b: fit(a[1], -1e13, 1e13),
            alpha: s,
            beta: fit(a[3], 0.0, 20.0),
            e0: fit_log(a[1], 1e-3, 1e10),
            e_iv: fit(a[4], 0.0, 1e10),
            e_cv: fit(a[4], 0.0, 1e10) + fit_log(a[0], 1e-3, 1e10),
        }),
        Eos::Murnaghan(Murnaghan {
            rho0,
            c0,
            gamma: fit_log(a[2], 1e-300, 20.0),
        }),
    ]
}

fuzz_target!(|input: (bool, [f64; 5], f64, f64)| {
    let (physical, a, eta, e) = input;
    if !physical {
        let raw = [
            Eos::Linear(Linear {
                rho0: a[0],
                c0: a[1],
                gamma: a[3],
            }),
            Eos::Logarithmic(Logarithmic {
                rho0: a[0],
                bulk_modulus: a[4],
            }),
            Eos::MieGruneisen(MieGruneisen {
                rho0: a[0],
                c0: a[1],
                s1: a[2],
                gamma0: a[3],
            }),
            Eos::Hugoniot(Hugoniot {
                rho0: a[0],
                c0: a[1],
                s1: a[2],
            }),
            Eos::TwoCurve(TwoCurve {
                rho0: a[0],
                c_a: a[1],
                s_a: a[2],
                gamma: a[3],
            }),
            Eos::Polynomial(Polynomial {
                rho0: a[0],
                k1: a[4],
                k2: a[1],
                k3: a[2],
            }),
            Eos::Tillotson(Tillotson {
                rho0: a[0],
                a: a[2],
                b: a[3],
                big_a: a[4],
                big_b: a[1],
                alpha: a[2],
                beta: a[3],
                e0: a[1],
                e_iv: a[4],
                e_cv: a[0],
            }),
            Eos::Murnaghan(Murnaghan {
                rho0: a[0],
                c0: a[1],
                gamma: a[2],
            }),
        ];
        for m in raw {
            let _ = m.eval(eta, e);
        }
        return;
    }
    let log_eta = fit(eta, -12.0, 12.0);
    let e = fit(e, -1e12, 1e12);
    for m in models(&a) {
        let rho = m.rho0() * 10f64.powf(log_eta);
        let st = m.eval(rho, e);
        assert!(
            st.p.is_finite() && st.c2.is_finite() && st.c2 > 0.0,
            "{m:?} at rho {rho:e}, e {e:e}: {st:?}"
        );
    }
});
