//! The AVX2 star states of the time-split family against the portable `star`, bit for bit.

extern crate std;

use crate::effects::{EffectSet, Effects};
use crate::exec::Serial;
use crate::kernel::Kernel;
use crate::limiter::Limiter;
use crate::material::eos::Hugoniot;
use crate::material::{Material, Strength};
use crate::math::{Lcg, Matrix, Real, Sym3, Vector};
use crate::neighbors::{build_naive, NeighborList, Periodic};
use crate::schemes::common::geometry_pass;
use crate::schemes::ts::pairs::star;
use crate::simd::{ts_star_row, Simd, SimdLevel};
use crate::state::{Gradients, PairGeom, RiemannSolver, SchemeOptions, StepParams, System, TsStar};
use std::vec;
use std::vec::Vec;

#[derive(Clone, Copy, Debug)]
struct First;
impl Effects for First {
    const STRENGTH: bool = false;
    const CORRECTION: bool = false;
    const MUSCL: bool = false;
    const SET: EffectSet = EffectSet::HYDRO;
}

#[derive(Clone, Copy, Debug)]
struct Muscl;
impl Effects for Muscl {
    const STRENGTH: bool = true;
    const CORRECTION: bool = false;
    const MUSCL: bool = true;
    const SET: EffectSet = EffectSet::STRENGTH.union(EffectSet::MUSCL);
}

fn material(s1: Real) -> Material {
    Material {
        rho0: 6100.0,
        eos: Hugoniot {
            rho0: 6100.0,
            c0: 5077.0,
            s1,
        }
        .into(),
        shear_modulus: 48.1e9,
        strength: Strength::Elastic,
        tensile_strength: Real::INFINITY,
    }
}

/// What the lanes met: pairs solved, failed pairs, pairs with a side without impedance.
#[derive(Default)]
struct Met {
    pairs: usize,
    failed: usize,
    no_impedance: usize,
}

/// Every owned pair's star state of `n` jittered particles with scattered states and
/// gradients (some zero; some densities zero, where the reconstruction falls back to first order; some particles failed, some without sound speed; three materials, one with a
/// negative Hugoniot slope), by the AVX2 row and by the portable `star`: asserts every
/// bit equal.
fn same_stars<const D: usize, E: Effects>(
    riemann: RiemannSolver,
    limiter: Limiter,
    seed: u64,
) -> Met {
    const CAP: usize = 96;
    let side = match D {
        1 => 100,
        2 => 9,
        _ => 4,
    };
    let n = (0..D).fold(1, |a, _| a * side);
    let mut g = Lcg(seed);
    let x: Vec<Vector<D>> = (0..n)
        .map(|i| {
            let mut c = i;
            Vector::<D>::from_fn(|_, _| {
                let k = c % side;
                c /= side;
                1e-3 * (k as Real + 0.3 * (g.unit() - 0.5))
            })
        })
        .collect();
    let mut h: Vec<Real> = (0..n).map(|_| 1e-3 * (1.0 + 0.6 * g.unit())).collect();
    let mut storage = vec![0u32; NeighborList::storage_len(n, CAP)];
    let mut list = NeighborList::new(CAP, n, &mut storage).unwrap();
    let hmax = h.iter().cloned().fold(0.0, Real::max);
    build_naive(&x, &Periodic::none(), |_, _| 2.4 * hmax, &mut list).unwrap();
    let mats = [material(1.2), material(1.5), material(-0.5)];
    let mut v: Vec<Vector<D>> = (0..n)
        .map(|_| Vector::<D>::from_fn(|_, _| 300.0 * g.next()))
        .collect();
    let mut m = vec![6100.0e-9; n];
    let mut mat: Vec<u16> = (0..n).map(|_| (3.0 * g.unit()) as u16 % 3).collect();
    // a zero density now and then: the reconstruction's positivity check falls back to
    // first order (the bounded extrapolation keeps a positive pair positive)
    let mut rho: Vec<Real> = (0..n)
        .map(|k| {
            if k % 31 == 7 {
                0.0
            } else {
                6100.0 * (1.0 + 0.1 * g.next())
            }
        })
        .collect();
    let mut e = vec![0.0; n];
    // pressures in tension and compression; some equal to a neighbour's exactly
    let mut p: Vec<Real> = (0..n).map(|_| 5e9 * g.next()).collect();
    for k in (0..n).step_by(7) {
        p[k] = 1e9;
    }
    let mut c: Vec<Real> = (0..n)
        .map(|k| {
            if k % 29 == 3 {
                0.0
            } else {
                5000.0 * (1.0 + 0.2 * g.next())
            }
        })
        .collect();
    let mut cl = c.clone();
    let mut s = vec![Sym3::ZERO; n];
    let mut eps = vec![0.0; n];
    let mut damage: Vec<Real> = (0..n)
        .map(|k| if k % 11 == 5 { 1.0 } else { 0.5 * g.unit() })
        .collect();
    let grad: Vec<Gradients<D>> = (0..n)
        .map(|k| {
            let mut gr = Gradients::<D>::default();
            if k % 5 != 0 {
                gr.rho = Vector::<D>::from_fn(|_, _| 6100.0e3 * g.next());
                gr.p = Vector::<D>::from_fn(|_, _| 5e12 * g.next());
                gr.v = Matrix::<D>::from_fn(|_, _| 3e5 * g.next());
            }
            gr
        })
        .collect();
    let sys = System {
        x: &mut x.clone(),
        v: &mut v,
        m: &mut m,
        mat: &mut mat,
        rho: &mut rho,
        e: &mut e,
        p: &mut p,
        c: &mut c,
        cl: &mut cl,
        h: &mut h,
        s: &mut s,
        eps_p: &mut eps,
        damage: &mut damage,
        temp: &mut [],
    };
    let options = SchemeOptions {
        riemann,
        limiter,
        ..SchemeOptions::default()
    };
    // SAFETY: the caller checked that the CPU has AVX2
    let avx2 = unsafe { SimdLevel::assume(Simd::Avx2) };
    let params = StepParams {
        dt: 1e-9,
        materials: &mats,
        kernel: Kernel::CubicSpline,
        h_factor: 1.2,
        periodic: Periodic::none(),
        nbrs: list.view(),
        options,
        effects: E::SET.union(EffectSet::DAMAGE),
        simd: avx2,
    };
    let nb = list.view();
    let mut geom = vec![PairGeom::<D>::default(); nb.unordered_pairs()];
    geometry_pass::<D, First, Serial>(sys.x, sys.h, &params, &mut geom, &mut [], &Serial);
    let mut met = Met::default();
    for i in 0..n {
        let (p0, owned) = (nb.pair_start[i] as usize, nb.owned(i));
        let gs = &geom[p0..p0 + owned.len()];
        let mut simd = vec![TsStar { u: 7.0, p: 7.0 }; owned.len()];
        let done = ts_star_row::<D, E>(&sys, &grad, &params, i, gs, owned, &mut simd, true);
        assert_eq!(done, owned.len(), "the row does every pair");
        for (q, (&j, pg)) in owned.iter().zip(gs).enumerate() {
            let j = j as usize;
            let (u, p) = if pg.r > 0.0 {
                met.pairs += 1;
                met.failed += usize::from(sys.damage[i] >= 1.0 || sys.damage[j] >= 1.0);
                met.no_impedance += usize::from(sys.c[i] == 0.0 || sys.c[j] == 0.0);
                star::<D, E>(&sys, &grad, &params, i, j, &pg.n, pg.r)
            } else {
                (0.0, 0.0)
            };
            assert_eq!(
                (simd[q].u.to_bits(), simd[q].p.to_bits()),
                (u.to_bits(), p.to_bits()),
                "{D}D {riemann} {limiter} seed {seed}: pair ({i}, {j}): {:?} against ({u:e}, {p:e})",
                simd[q]
            );
        }
        // without the pressure, the same velocities and p* = 0
        let mut simd_u = vec![TsStar { u: 7.0, p: 7.0 }; owned.len()];
        ts_star_row::<D, E>(&sys, &grad, &params, i, gs, owned, &mut simd_u, false);
        for (a, b) in simd.iter().zip(&simd_u) {
            assert_eq!(
                (a.u.to_bits(), 0.0f64.to_bits()),
                (b.u.to_bits(), b.p.to_bits())
            );
        }
    }
    met
}

fn every_case<const D: usize>() {
    if !std::is_x86_feature_detected!("avx2") {
        std::eprintln!("this CPU has no AVX2: the AVX2 loops are not tested here");
        return;
    }
    let mut met = Met::default();
    for riemann in [RiemannSolver::Acoustic, RiemannSolver::TwoShock] {
        for seed in [1, 2, 3] {
            for limiter in [Limiter::Superbee, Limiter::Minmod] {
                let m = same_stars::<D, Muscl>(riemann, limiter, seed);
                met.pairs += m.pairs;
                met.failed += m.failed;
                met.no_impedance += m.no_impedance;
            }
            same_stars::<D, First>(riemann, Limiter::Superbee, seed);
        }
    }
    // the test reaches the lanes the portable solver redoes
    assert!(
        met.pairs > 1000 && met.failed > 20 && met.no_impedance > 5,
        "{} {} {}",
        met.pairs,
        met.failed,
        met.no_impedance
    );
}

#[test]
fn avx2_ts_stars_are_bitwise_the_portable_ones_1d() {
    every_case::<1>();
}

#[test]
fn avx2_ts_stars_are_bitwise_the_portable_ones_2d() {
    every_case::<2>();
}

#[test]
fn avx2_ts_stars_are_bitwise_the_portable_ones_3d() {
    every_case::<3>();
}
