//! The AVX2 star states against the portable ones, bit for bit: the time-split family's
//! `star` and the contact family's `pair_star`.

extern crate std;

use crate::effects::{EffectSet, Effects};
use crate::exec::Serial;
use crate::kernel::Kernel;
use crate::limiter::Limiter;
use crate::material::eos::Hugoniot;
use crate::material::{Material, Strength};
use crate::math::{Lcg, Matrix, Real, Sym3, Vector};
use crate::neighbors::{build_naive, NeighborList, Periodic};
use crate::schemes::options::{RiemannSolver, SchemeOptions};
use crate::schemes::pairs::geometry_pass;
use crate::schemes::pairs::Pair;
use crate::schemes::pm::lanes as pm_star;
use crate::schemes::pm::pairs::{pair_star, StarRows as PmRows};
use crate::schemes::pm::records::PmStar;
use crate::schemes::ts::lanes as ts_star;
use crate::schemes::ts::pairs::{star, StarRows};
use crate::schemes::ts::records::TsStar;
use crate::schemes::workspace::StepParams;
use crate::simd::{tested_levels, SimdLevel};
use crate::state::{Aux, Correction, Gradients, PairGeom, System};
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

pub(super) fn material(s1: Real) -> Material {
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

impl Met {
    fn add(&mut self, o: Met) {
        self.pairs += o.pairs;
        self.failed += o.failed;
        self.no_impedance += o.no_impedance;
    }
}

/// `n` jittered particles with scattered states and gradients: some gradients zero, some
/// densities zero (where the reconstruction falls back to first order), some particles
/// failed, some without sound speed; three materials, one with a negative Hugoniot slope.
pub(super) struct Scene<const D: usize> {
    x: Vec<Vector<D>>,
    h: Vec<Real>,
    v: Vec<Vector<D>>,
    m: Vec<Real>,
    mat: Vec<u16>,
    pub(super) rho: Vec<Real>,
    e: Vec<Real>,
    p: Vec<Real>,
    c: Vec<Real>,
    cl: Vec<Real>,
    s: Vec<Sym3>,
    eps: Vec<Real>,
    damage: Vec<Real>,
    grad: Vec<Gradients<D>>,
    grad_s: Vec<[Vector<D>; 6]>,
    aux: Vec<Aux>,
    corr: Vec<Correction<D>>,
    /// The periodic box ([`Scene::periodic_along_x`]; none by default).
    periodic: Periodic<D>,
}

impl<const D: usize> Scene<D> {
    /// Makes the scene periodic along x: its particles (`1e-3 (k + jitter)`, `k` below
    /// `side`) in a box of `side` spacings from -0.5e-3, so the pairs across the box's
    /// faces take the minimum image from either side.
    pub(super) fn periodic_along_x(&mut self) {
        let mut p = Periodic::<D>::none();
        p.lo[0] = -0.5e-3;
        p.len[0] = 1e-3 * side::<D>() as Real;
        p.axes[0] = true;
        self.periodic = p;
    }
}

fn side<const D: usize>() -> usize {
    match D {
        1 => 100,
        2 => 9,
        _ => 4,
    }
}

const CAP: usize = 96;

pub(super) fn scene<const D: usize>(seed: u64) -> Scene<D> {
    let side = side::<D>();
    let n = (0..D).fold(1, |a, _| a * side);
    let mut g = Lcg(seed);
    let mut vec = |k: Real| Vector::<D>::from_fn(|_, _| k * g.next());
    let mut x = Vec::new();
    for i in 0..n {
        let mut c = i;
        let jitter = vec(0.15);
        x.push(Vector::<D>::from_fn(|a, _| {
            let k = c % side;
            c /= side;
            1e-3 * (k as Real + jitter[a])
        }));
    }
    let mut g = Lcg(seed + 100);
    let h = (0..n).map(|_| 1e-3 * (1.0 + 0.6 * g.unit())).collect();
    let v = (0..n)
        .map(|_| Vector::<D>::from_fn(|_, _| 300.0 * g.next()))
        .collect();
    let mat = (0..n).map(|_| (3.0 * g.unit()) as u16 % 3).collect();
    // a zero density now and then: the reconstruction's positivity check falls back to
    // first order (the bounded extrapolation keeps a positive pair positive)
    let rho = (0..n)
        .map(|k| {
            if k % 31 == 7 {
                0.0
            } else {
                6100.0 * (1.0 + 0.1 * g.next())
            }
        })
        .collect();
    // pressures in tension and compression; some equal to a neighbour's exactly
    let mut p: Vec<Real> = (0..n).map(|_| 5e9 * g.next()).collect();
    for k in (0..n).step_by(7) {
        p[k] = 1e9;
    }
    let c: Vec<Real> = (0..n)
        .map(|k| {
            if k % 29 == 3 {
                0.0
            } else {
                5000.0 * (1.0 + 0.2 * g.next())
            }
        })
        .collect();
    let cl = c.iter().map(|c| 1.5 * c).collect();
    let s = (0..n)
        .map(|k| {
            if k % 6 == 0 {
                Sym3::ZERO
            } else {
                Sym3::from_array(core::array::from_fn(|_| 1e9 * g.next()))
            }
        })
        .collect();
    let damage = (0..n)
        .map(|k| if k % 11 == 5 { 1.0 } else { 0.5 * g.unit() })
        .collect();
    let mut grad = Vec::new();
    let mut grad_s = Vec::new();
    for k in 0..n {
        let mut gr = Gradients::<D>::default();
        let mut gs = [Vector::<D>::zeros(); 6];
        if k % 5 != 0 {
            gr.rho = Vector::<D>::from_fn(|_, _| 6100.0e3 * g.next());
            gr.p = Vector::<D>::from_fn(|_, _| 5e12 * g.next());
            gr.cl = Vector::<D>::from_fn(|_, _| 5e6 * g.next());
            gr.ct = Vector::<D>::from_fn(|_, _| 3e6 * g.next());
            gr.v = Matrix::<D>::from_fn(|_, _| 3e5 * g.next());
            gr.w = Matrix::<D>::from_fn(|_, _| 1e5 * g.next());
            gs = core::array::from_fn(|_| Vector::<D>::from_fn(|_, _| 1e12 * g.next()));
        }
        grad.push(gr);
        grad_s.push(gs);
    }
    let aux = (0..n)
        .map(|k| Aux {
            inv_rho: 1.0 / 6100.0,
            vol: 1e-9,
            ct: if k % 23 == 4 {
                0.0
            } else {
                3000.0 * (1.0 + 0.2 * g.next())
            },
        })
        .collect();
    let corr = (0..n)
        .map(|_| Correction {
            l_inv: Matrix::<D>::identity() + Matrix::<D>::from_fn(|_, _| 0.2 * g.next()),
            ..Correction::default()
        })
        .collect();
    Scene {
        x,
        h,
        v,
        m: vec![6100.0e-9; n],
        mat,
        rho,
        e: vec![0.0; n],
        p,
        c,
        cl,
        s,
        eps: vec![0.0; n],
        damage,
        grad,
        grad_s,
        aux,
        corr,
        periodic: Periodic::none(),
    }
}

/// Calls `f` with the scene's particles, the step's parameters (the level `level`, the
/// options `options`, the effects of `E`, damage and the scene's periodic box) and every
/// pair's geometry.
pub(super) fn with_pairs<const D: usize, E: Effects>(
    level: SimdLevel,
    sc: &mut Scene<D>,
    options: SchemeOptions,
    f: impl FnOnce(&System<'_, D>, &StepParams<'_, D>, &[PairGeom<D>]),
) {
    let n = sc.x.len();
    let mut storage = vec![0u32; NeighborList::storage_len(n, CAP)];
    let mut list = NeighborList::new(CAP, n, &mut storage).unwrap();
    let hmax = sc.h.iter().cloned().fold(0.0, Real::max);
    build_naive(&sc.x, &sc.periodic, |_, _| 2.4 * hmax, &mut list).unwrap();
    let mats = [material(1.2), material(1.5), material(-0.5)];
    let params = StepParams {
        dt: 1e-9,
        materials: &mats,
        kernel: Kernel::CubicSpline,
        h_factor: 1.2,
        periodic: sc.periodic,
        nbrs: list.view(),
        options,
        effects: if sc.periodic.any() {
            E::SET.union(EffectSet::DAMAGE).union(EffectSet::PERIODIC)
        } else {
            E::SET.union(EffectSet::DAMAGE)
        },
        simd: level,
    };
    let mut geom = vec![PairGeom::<D>::default(); list.view().unordered_pairs()];
    let mut fac = vec![
        0.0;
        if params.has::<E>(EffectSet::ARTIFICIAL_STRESS) {
            geom.len()
        } else {
            0
        }
    ];
    geometry_pass::<D, First, Serial>(&sc.x, &sc.h, &params, &mut geom, &mut fac, &Serial);
    let sys = System::builder()
        .x(&mut sc.x)
        .v(&mut sc.v)
        .m(&sc.m)
        .mat(&sc.mat)
        .rho(&mut sc.rho)
        .e(&mut sc.e)
        .p(&mut sc.p)
        .c(&mut sc.c)
        .cl(&mut sc.cl)
        .h(&mut sc.h)
        .s(&mut sc.s)
        .eps_p(&mut sc.eps)
        .damage(&mut sc.damage)
        .build()
        .expect("every field a run stores");
    f(&sys, &params, &geom);
}

/// The rows of owned pairs: `(i, first pair, neighbours)`.
fn rows<'a, const D: usize>(
    params: &'a StepParams<'_, D>,
) -> impl Iterator<Item = (usize, usize, &'a [u32])> + 'a {
    let nb = params.nbrs;
    (0..nb.pair_start.len() - 1).map(move |i| (i, nb.pair_start[i] as usize, nb.owned(i)))
}

/// Every owned pair's `ts` star state by the AVX2 row and by the portable `star`: asserts
/// every bit equal.
fn same_stars<const D: usize, E: Effects>(
    level: SimdLevel,
    riemann: RiemannSolver,
    limiter: Limiter,
    seed: u64,
) -> Met {
    let mut sc = scene::<D>(seed);
    let options = SchemeOptions {
        riemann,
        limiter,
        ..SchemeOptions::default()
    };
    let grad = core::mem::take(&mut sc.grad);
    let mut met = Met::default();
    with_pairs::<D, E>(level, &mut sc, options, |sys, params, geom| {
        // the neighbour records the rows read (stale values where the writer leaves a field)
        let mut rec = vec![Real::NAN; sys.x.len() * crate::schemes::ts::record_len(D)];
        ts_star::write_records::<D, E, Serial>(sys, &grad, params, &mut rec, &Serial);
        for (i, p0, owned) in rows(params) {
            let gs = &geom[p0..p0 + owned.len()];
            let mut simd = vec![TsStar { u: 7.0, p: 7.0 }; owned.len()];
            // the kernel itself, whether or not it pays for E (`stars_pay`)
            assert!(ts_star::covers(params));
            // SAFETY: the caller checked that the CPU has the level; the options are covered
            let done = unsafe {
                let rows = StarRows {
                    sys,
                    grad: &grad,
                    rec: &rec,
                    params,
                    with_p: true,
                };
                ts_star::star_row_at::<D, E>(level, &rows, i, gs, owned, &mut simd)
            };
            assert_eq!(done, owned.len(), "the row does every pair");
            for (q, (&j, pg)) in owned.iter().zip(gs).enumerate() {
                let j = j as usize;
                let (u, p) = if pg.r > 0.0 {
                    met.pairs += 1;
                    met.failed += usize::from(sys.damage[i] >= 1.0 || sys.damage[j] >= 1.0);
                    met.no_impedance += usize::from(sys.c[i] == 0.0 || sys.c[j] == 0.0);
                    star::<D, E>(sys, &grad, params, i, j, &pg.n, pg.r)
                } else {
                    (0.0, 0.0)
                };
                assert_eq!(
                    (simd[q].u.to_bits(), simd[q].p.to_bits()),
                    (u.to_bits(), p.to_bits()),
                    "{} {D}D {riemann} {limiter} seed {seed}: pair ({i}, {j}): {:?} against ({u:e}, {p:e})",
                    level.get(),
                    simd[q]
                );
            }
            // without the pressure, the same velocities and p* = 0
            let mut simd_u = vec![TsStar { u: 7.0, p: 7.0 }; owned.len()];
            // SAFETY: as above
            unsafe {
                let rows = StarRows {
                    sys,
                    grad: &grad,
                    rec: &rec,
                    params,
                    with_p: false,
                };
                ts_star::star_row_at::<D, E>(level, &rows, i, gs, owned, &mut simd_u)
            };
            for (a, b) in simd.iter().zip(&simd_u) {
                assert_eq!(
                    (a.u.to_bits(), 0.0f64.to_bits()),
                    (b.u.to_bits(), b.p.to_bits())
                );
            }
        }
    });
    met
}

/// Every owned pair's `pm`/`tkc` star state by the AVX2 row and by the portable
/// `pair_star`: asserts every bit equal.
fn same_pm_stars<const D: usize, E: Effects>(
    level: SimdLevel,
    riemann: RiemannSolver,
    limiter: Limiter,
    objective: bool,
    seed: u64,
) -> Met {
    let mut sc = scene::<D>(seed);
    let options = SchemeOptions {
        riemann,
        limiter,
        objective,
        ..SchemeOptions::default()
    };
    let grad = core::mem::take(&mut sc.grad);
    let grad_s = core::mem::take(&mut sc.grad_s);
    let aux = core::mem::take(&mut sc.aux);
    let corr = core::mem::take(&mut sc.corr);
    let mut met = Met::default();
    with_pairs::<D, E>(level, &mut sc, options, |sys, params, geom| {
        // the neighbour records the rows read (stale values where the writer leaves a field)
        let mut rec = vec![Real::NAN; sys.x.len() * crate::schemes::pm::record_len(D)];
        pm_star::write_records::<D, E, Serial>(
            sys, &aux, &corr, &grad, &grad_s, params, &mut rec, &Serial,
        );
        for (i, p0, owned) in rows(params) {
            let gs = &geom[p0..p0 + owned.len()];
            let mut simd = vec![PmStar::<D>::default(); owned.len()];
            // the kernel itself, whether or not it pays for E (`stars_pay`)
            assert!(pm_star::covers(params));
            // SAFETY: the caller checked that the CPU has the level; the options are covered
            let done = unsafe {
                let rows = PmRows {
                    sys,
                    aux: &aux,
                    corr: &corr,
                    grad: &grad,
                    grad_s: &grad_s,
                    rec: &rec,
                    params,
                };
                pm_star::star_row_at::<D, E>(level, &rows, i, gs, owned, &mut simd)
            };
            assert_eq!(done, owned.len(), "the row does every pair");
            for (q, (&j, pg)) in owned.iter().zip(gs).enumerate() {
                let j = j as usize;
                let want = if pg.r > 0.0 {
                    met.pairs += 1;
                    met.failed += usize::from(sys.damage[i] >= 1.0 || sys.damage[j] >= 1.0);
                    met.no_impedance += usize::from(aux[i].ct == 0.0 || aux[j].ct == 0.0);
                    let pr = Pair {
                        j,
                        r: pg.r,
                        n: pg.n,
                        dw: pg.dw,
                        grad: pg.n * (-pg.dw),
                    };
                    pair_star::<D, E>(sys, &aux, &corr, &grad, &grad_s, params, i, &pr)
                } else {
                    PmStar::default()
                };
                let bits = |s: &PmStar<D>| {
                    s.v.iter()
                        .chain(s.t.iter())
                        .map(|v| v.to_bits())
                        .collect::<Vec<_>>()
                };
                assert_eq!(
                    bits(&simd[q]),
                    bits(&want),
                    "{} {D}D {riemann} {limiter} objective {objective} seed {seed}: pair ({i}, {j}): {:?} against {want:?}",
                    level.get(),
                    simd[q]
                );
            }
        }
    });
    met
}

fn every_case<const D: usize>() {
    for level in tested_levels() {
        every_case_at::<D>(level);
    }
}

fn every_case_at<const D: usize>(level: SimdLevel) {
    let mut met = Met::default();
    for riemann in [RiemannSolver::Acoustic, RiemannSolver::TwoShock] {
        for seed in [1, 2, 3] {
            for limiter in [Limiter::Superbee, Limiter::Minmod] {
                met.add(same_stars::<D, Muscl>(level, riemann, limiter, seed));
            }
            same_stars::<D, First>(level, riemann, Limiter::Superbee, seed);
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

/// `tkc`: strength, correction, MUSCL.
#[derive(Clone, Copy, Debug)]
struct Tkc;
impl Effects for Tkc {
    const STRENGTH: bool = true;
    const CORRECTION: bool = true;
    const MUSCL: bool = true;
    const SET: EffectSet = EffectSet::STRENGTH
        .union(EffectSet::CORRECTION)
        .union(EffectSet::MUSCL);
}

/// `tkc` on a fluid: correction and MUSCL, no strength (the pressure reconstructed).
#[derive(Clone, Copy, Debug)]
struct TkcFluid;
impl Effects for TkcFluid {
    const STRENGTH: bool = false;
    const CORRECTION: bool = true;
    const MUSCL: bool = true;
    const SET: EffectSet = EffectSet::CORRECTION.union(EffectSet::MUSCL);
}

/// `pm`: strength, first order.
#[derive(Clone, Copy, Debug)]
struct Pm;
impl Effects for Pm {
    const STRENGTH: bool = true;
    const CORRECTION: bool = false;
    const MUSCL: bool = false;
    const SET: EffectSet = EffectSet::STRENGTH;
}

fn every_pm_case<const D: usize>() {
    for level in tested_levels() {
        every_pm_case_at::<D>(level);
    }
}

fn every_pm_case_at<const D: usize>(level: SimdLevel) {
    let mut met = Met::default();
    for riemann in [RiemannSolver::Acoustic, RiemannSolver::TwoShock] {
        for seed in [1, 2, 3] {
            for objective in [true, false] {
                for limiter in [Limiter::Minmod, Limiter::Superbee] {
                    met.add(same_pm_stars::<D, Tkc>(
                        level, riemann, limiter, objective, seed,
                    ));
                    same_pm_stars::<D, TkcFluid>(level, riemann, limiter, objective, seed);
                }
                same_pm_stars::<D, Pm>(level, riemann, Limiter::Minmod, objective, seed);
            }
        }
    }
    assert!(
        met.pairs > 1000 && met.failed > 20 && met.no_impedance > 5,
        "{} {} {}",
        met.pairs,
        met.failed,
        met.no_impedance
    );
}

#[test]
fn vectorised_pm_stars_are_bitwise_the_portable_ones_1d() {
    every_pm_case::<1>();
}

#[test]
fn vectorised_pm_stars_are_bitwise_the_portable_ones_2d() {
    every_pm_case::<2>();
}

#[test]
fn vectorised_pm_stars_are_bitwise_the_portable_ones_3d() {
    every_pm_case::<3>();
}

#[test]
fn vectorised_ts_stars_are_bitwise_the_portable_ones_1d() {
    every_case::<1>();
}

#[test]
fn vectorised_ts_stars_are_bitwise_the_portable_ones_2d() {
    every_case::<2>();
}

#[test]
fn vectorised_ts_stars_are_bitwise_the_portable_ones_3d() {
    every_case::<3>();
}
