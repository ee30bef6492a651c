//! Scheme-level tests on a small 1D flyer plate, stepped serially on fixed arrays.

use super::{av::Av, pm::Pm, ts::Ts, SchemeFamily};
use crate::effects::{EffectSet, Effects};
use crate::exec::Serial;
use crate::kernel::Kernel;
use crate::material::eos::Hugoniot;
use crate::material::{Material, Strength};
use crate::math::{Real, Sym3, Vector};
use crate::neighbors::{build_naive, NeighborList, Periodic};
use crate::state::*;

macro_rules! fx {
    ($name:ident, $s:expr, $p:expr, $m:expr, $c:expr) => {
        #[derive(Clone, Copy, Debug)]
        struct $name;
        impl Effects for $name {
            const STRENGTH: bool = $s;
            const PLASTICITY: bool = $p;
            const DAMAGE: bool = false;
            const HEAT: bool = false;
            const CORRECTION: bool = $c;
            const MUSCL: bool = $m;
            const PERIODIC: bool = false;
            const SET: EffectSet = EffectSet::HYDRO;
        }
    };
}
fx!(Plastic, true, true, false, false);
fx!(PlasticMuscl, true, true, true, false);
fx!(PlasticTkc, true, true, true, true);
fx!(Hydro, false, false, false, false);

const N: usize = 100;
const CAP: usize = 8;

struct Flyer {
    x: [Vector<1>; N],
    v: [Vector<1>; N],
    m: [Real; N],
    mat: [u16; N],
    rho: [Real; N],
    e: [Real; N],
    p: [Real; N],
    c: [Real; N],
    cl: [Real; N],
    h: [Real; N],
    s: [Sym3; N],
    eps: [Real; N],
    sums: [PairSums<1>; N],
    grad: [Gradients<1>; N],
    gs: [[Vector<1>; 6]; N],
    corr: [Correction<1>; N],
    av: [AvRates<1>; N],
    idx: [u32; N * CAP],
    cnt: [u32; N],
}

fn material() -> Material {
    Material {
        rho0: 6100.0,
        eos: Hugoniot {
            rho0: 6100.0,
            c0: 5077.0,
            s1: 1.201,
        }
        .into(),
        shear_modulus: 48.1e9,
        strength: Strength::VonMises {
            yield_stress: 2.5e9,
        },
    }
}

fn flyer() -> Flyer {
    let dx = 1e-4;
    let mat = material();
    let mut f = Flyer {
        x: [Vector::<1>::zeros(); N],
        v: [Vector::<1>::zeros(); N],
        m: [6100.0 * dx; N],
        mat: [0; N],
        rho: [6100.0; N],
        e: [0.0; N],
        p: [0.0; N],
        c: [0.0; N],
        cl: [0.0; N],
        h: [1.2 * dx; N],
        s: [Sym3::ZERO; N],
        eps: [0.0; N],
        sums: [PairSums::default(); N],
        grad: [Gradients::default(); N],
        gs: [[Vector::<1>::zeros(); 6]; N],
        corr: [Correction::default(); N],
        av: [AvRates::default(); N],
        idx: [0; N * CAP],
        cnt: [0; N],
    };
    for i in 0..N {
        f.x[i] = Vector::<1>::new((i as Real + 0.5) * dx);
        if i < N / 2 {
            f.v[i] = Vector::<1>::new(602.81);
        }
        let st = mat.eos(f.rho[i], 0.0);
        f.p[i] = st.p;
        f.c[i] = st.c2.sqrt();
        f.cl[i] = mat.c_long(f.rho[i], st.c2);
    }
    f
}

fn run<F: SchemeFamily, E: Effects>(t_end: Real) -> (Real, Real, Real, Real, Flyer) {
    let mats = [material()];
    let mut f = flyer();
    let mut primed = false;
    let mut t = 0.0;
    let mut energy0 = 0.0;
    let mut mom0 = 0.0;
    let mut first = true;
    while t < t_end {
        let Flyer {
            x,
            v,
            m,
            mat,
            rho,
            e,
            p,
            c,
            cl,
            h,
            s,
            eps,
            sums,
            grad,
            gs,
            corr,
            av,
            idx,
            cnt,
        } = &mut f;
        let mut list = NeighborList::new(CAP, idx, cnt).unwrap();
        let hh: &[Real] = h;
        build_naive(
            &x[..],
            &Periodic::none(),
            |i, j| 2.0 * 0.5 * (hh[i] + hh[j]) * 1.05,
            &mut list,
        )
        .unwrap();
        let mut sys = System {
            x,
            v,
            m,
            mat,
            rho,
            e,
            p,
            c,
            cl,
            h,
            s: if E::STRENGTH { &mut s[..] } else { &mut [] },
            eps_p: if E::PLASTICITY { &mut eps[..] } else { &mut [] },
            damage: &mut [],
            temp: &mut [],
        };
        if first {
            energy0 = total_energy(&sys);
            mom0 = total_momentum(&sys)[0];
            first = false;
        }
        let dt = stable_dt(&sys, 0.5).min(t_end - t);
        let params = StepParams {
            dt,
            materials: &mats,
            kernel: Kernel::CubicSpline,
            h_factor: 1.2,
            periodic: Periodic::none(),
            nbrs: list.view(),
            options: SchemeOptions::default(),
        };
        let mut ws = Workspace {
            sums,
            grad,
            grad_stress: gs,
            corr,
            av,
            primed,
        };
        F::step::<1, E, Serial>(&mut sys, &mut ws, &params, &Serial).unwrap();
        primed = ws.primed;
        check_finite(&sys).unwrap();
        t += dt;
    }
    let Flyer {
        x,
        v,
        m,
        mat,
        rho,
        e,
        p,
        c,
        cl,
        h,
        s,
        eps,
        ..
    } = &mut f;
    let sys = System {
        x,
        v,
        m,
        mat,
        rho,
        e,
        p,
        c,
        cl,
        h,
        s,
        eps_p: eps,
        damage: &mut [],
        temp: &mut [],
    };
    let energy1 = total_energy(&sys);
    let mom1 = total_momentum(&sys)[0];
    (energy0, energy1, mom0, mom1, f)
}

#[test]
fn ts_conserves_energy_to_round_off_on_the_flyer_plate() {
    for (name, (e0, e1, m0, m1, _)) in [
        ("ts1", run::<Ts, Plastic>(0.5e-6)),
        ("ts2", run::<Ts, PlasticMuscl>(0.5e-6)),
    ] {
        let rel = ((e1 - e0) / e0).abs();
        std::println!("{name}: energy {rel:e}");
        assert!(rel < 1e-10, "{name}: relative energy error {rel:e}");
        assert!(
            ((m1 - m0) / m0).abs() < 1e-12,
            "{name}: momentum {m0} -> {m1}"
        );
    }
}

#[test]
fn every_family_conserves_momentum_and_stays_finite() {
    for (name, (e0, e1, m0, m1, f)) in [
        ("av", run::<Av, Plastic>(0.5e-6)),
        ("pm", run::<Pm, Plastic>(0.5e-6)),
        ("tkc", run::<Pm, PlasticTkc>(0.5e-6)),
        ("ts-hydro", run::<Ts, Hydro>(0.5e-6)),
    ] {
        assert!(
            ((m1 - m0) / m0).abs() < 1e-12,
            "{name}: momentum {m0} -> {m1}"
        );
        let rel = ((e1 - e0) / e0).abs();
        std::println!(
            "{name}: energy {rel:e} peak rho {}",
            f.rho.iter().cloned().fold(0.0, Real::max)
        );
        // explicit Euler (pm, tkc) and leap-frog (av) are not energy conserving: a few
        // percent over the run (seed 000 table 2: pm 2.34 %, av 1.51 %)
        assert!(rel < 0.1, "{name}: relative energy error {rel:e}");
        // the impact compresses the middle: peak density above rho0 by a few percent
        let rmax = f.rho.iter().cloned().fold(0.0, Real::max);
        assert!(
            rmax > 6200.0 && rmax < 7000.0,
            "{name}: peak density {rmax}"
        );
    }
}
