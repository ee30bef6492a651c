//! Property test (proptest) of the time-split schemes: on random small systems (a handful
//! of particles on a jittered lattice in 1D and 2D, random velocities, random initial
//! internal energy, elastic-plastic material) `ts1` and `ts2`, with the acoustic or the
//! two-shock Riemann solver, conserve the total energy to ~1e-10 relative and the
//! momentum to round-off over a few tens of steps (see `schemes::ts` for why they must).

use gsph_core::effects::{EffectSet, Effects};
use gsph_core::exec::Serial;
use gsph_core::kernel::Kernel;
use gsph_core::material::eos::MieGruneisen;
use gsph_core::material::{Material, Strength};
use gsph_core::math::{Real, Sym3, Vector};
use gsph_core::neighbors::{build_naive, NeighborList, Periodic};
use gsph_core::schemes::*;
use gsph_core::schemes::{ts::Ts, SchemeFamily};
use gsph_core::state::*;
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

/// `ts1` (strength; plasticity is the run-time flag its plastic-strain storage gives) or,
/// with `MUSCL`, `ts2`: the effect sets the dispatch table names `ts_strength[_muscl]`,
/// stepped directly (monomorphising the whole dispatch table here would take a while to
/// compile).
#[derive(Clone, Copy, Debug)]
struct Plastic<const MUSCL: bool>;
impl<const M: bool> Effects for Plastic<M> {
    const STRENGTH: bool = true;
    const CORRECTION: bool = false;
    const MUSCL: bool = M;
    const SET: EffectSet = if M {
        EffectSet::STRENGTH.union(EffectSet::MUSCL)
    } else {
        EffectSet::STRENGTH
    };
}

const H_FACTOR: Real = 1.3;
const STEPS: usize = 30;

fn material(yield_stress: Real) -> Material {
    Material {
        rho0: 7900.0,
        eos: MieGruneisen {
            rho0: 7900.0,
            c0: 4570.0,
            s1: 1.49,
            gamma0: 1.93,
        }
        .into(),
        shear_modulus: 80e9,
        strength: Strength::VonMises { yield_stress },
        tensile_strength: Real::INFINITY,
    }
}

/// A random small system: lattice points, jitter and velocity per particle.
#[derive(Clone, Debug)]
struct Case {
    dims: [usize; 2],
    jitter: Vec<[Real; 2]>,
    vel: Vec<[Real; 2]>,
    e0: Vec<Real>,
    yield_stress: Real,
    muscl: bool,
    two_shock: bool,
}

fn case(dim: usize) -> impl Strategy<Value = Case> {
    let dims = if dim == 1 {
        (4usize..=10, Just(1usize)).boxed()
    } else {
        (2usize..=4, 2usize..=4).boxed()
    };
    (dims, 1e8..3e9, any::<bool>(), any::<bool>()).prop_flat_map(|((nx, ny), y, muscl, ts)| {
        let n = nx * ny;
        (
            proptest::collection::vec([-0.2..0.2, -0.2..0.2], n),
            proptest::collection::vec([-300.0..300.0, -300.0..300.0], n),
            proptest::collection::vec(0.0..1e5, n),
        )
            .prop_map(move |(jitter, vel, e0)| Case {
                dims: [nx, ny],
                jitter,
                vel,
                e0,
                yield_stress: y,
                muscl,
                two_shock: ts,
            })
    })
}

/// Total energy and momentum before and after `STEPS` steps of `ts1`/`ts2`.
type Totals = (Real, Real, [Real; 2], [Real; 2]);

fn run<const D: usize, E: Effects>(c: &Case) -> Result<Totals, StepError> {
    let dx: Real = 1e-3;
    let mat = material(c.yield_stress);
    let n = c.jitter.len();
    let vol = dx.powi(D as i32);
    let mut x = vec![Vector::<D>::zeros(); n];
    let mut v = vec![Vector::<D>::zeros(); n];
    for k in 0..n {
        let (i, j) = (k % c.dims[0], k / c.dims[0]);
        let lattice = [i as Real, j as Real];
        for a in 0..D {
            x[k][a] = (lattice[a] + c.jitter[k][a]) * dx;
            v[k][a] = c.vel[k][a];
        }
    }
    let m = vec![mat.rho0 * vol; n];
    let matv = vec![0u16; n];
    let mut rho = vec![mat.rho0; n];
    let mut e = c.e0.clone();
    let (mut p, mut cs, mut cl) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    for k in 0..n {
        let st = mat.eos(rho[k], e[k]);
        p[k] = st.p;
        cs[k] = st.c2.sqrt();
        cl[k] = mat.c_long(rho[k], st.c2);
    }
    let mut h = vec![smoothing_length::<D>(H_FACTOR, m[0], mat.rho0); n];
    let mut s = vec![Sym3::ZERO; n];
    let mut eps = vec![0.0; n];
    let mut sums = vec![PairSums::<D>::default(); n];
    let mut grad = vec![Gradients::<D>::default(); if c.muscl { n } else { 0 }];
    let mut storage = vec![0u32; NeighborList::storage_len(n, n)];
    let mut geom = vec![PairGeom::<D>::default(); n * n];
    let mut stars = vec![TsStar::default(); n * n];
    let mut aux = vec![Aux::default(); n];
    let mats = [mat];
    let options = SchemeOptions {
        riemann: if c.two_shock {
            RiemannSolver::TwoShock
        } else {
            RiemannSolver::Acoustic
        },
        ..SchemeOptions::default()
    };
    let mut out: Totals = (0.0, 0.0, [0.0; 2], [0.0; 2]);
    for it in 0..=STEPS {
        let mut list = NeighborList::new(n, n, &mut storage).expect("storage");
        let hh = h.clone();
        build_naive(&x, &Periodic::none(), |i, j| hh[i] + hh[j], &mut list).expect("list");
        let mut sys = System::builder()
            .x(&mut x)
            .v(&mut v)
            .m(&m)
            .mat(&matv)
            .rho(&mut rho)
            .e(&mut e)
            .p(&mut p)
            .c(&mut cs)
            .cl(&mut cl)
            .h(&mut h)
            .s(&mut s)
            .eps_p(&mut eps)
            .build()
            .expect("every field a run stores");
        let energy = total_energy(&sys);
        let mut mom = [0.0; 2];
        mom[..D].copy_from_slice(total_momentum(&sys).as_slice());
        if it == 0 {
            (out.0, out.2) = (energy, mom);
        }
        if it == STEPS {
            (out.1, out.3) = (energy, mom);
            break;
        }
        let params = StepParams {
            dt: stable_dt(&sys, 0.3),
            materials: &mats,
            kernel: Kernel::CubicSpline,
            h_factor: H_FACTOR,
            periodic: Periodic::none(),
            nbrs: list.view(),
            options,
            effects: E::SET.union(EffectSet::PLASTICITY),
            simd: gsph_core::simd::SimdLevel::BASELINE,
        };
        let pairs = list.view().unordered_pairs();
        let mut ws = Workspace {
            sums: &mut sums,
            grad: &mut grad,
            grad_stress: &mut [],
            corr: &mut [],
            hg: &mut [],
            av: &mut [],
            art: &mut [],
            rec: &mut [],
            fac: &mut [],
            aux: &mut aux,
            geom: &mut geom[..pairs],
            ts_star: &mut stars[..pairs],
            pm_star: &mut [],
            primed: false,
        };
        Ts::step::<D, E, Serial>(
            &mut sys,
            &mut ws,
            &params,
            &Serial,
            &mut gsph_core::halo::NoHalo,
        )?;
        check_finite(&sys)?;
    }
    Ok(out)
}

/// Scale of the momentum round-off: the sum of `m |v|`.
fn momentum_scale(c: &Case, dim: usize) -> Real {
    let vol = (1e-3 as Real).powi(dim as i32);
    c.vel
        .iter()
        .map(|v| 7900.0 * vol * (v[0].abs() + v[1].abs()))
        .sum::<Real>()
}

fn check(c: &Case, r: Result<Totals, StepError>, dim: usize) -> Result<(), TestCaseError> {
    let (e0, e1, m0, m1) = r.map_err(|e| TestCaseError::fail(format!("step failed: {e}")))?;
    // (e0 is 0 only for a system at rest without internal energy, which stays so)
    prop_assert!(
        (e1 - e0).abs() <= 1e-10 * e0.abs(),
        "energy {e0} -> {e1} (rel {:e})",
        (e1 - e0) / e0
    );
    let scale = momentum_scale(c, dim).max(1e-30);
    // each component against the round-off scale (a total may be ~0 by chance)
    for a in 0..2 {
        prop_assert!(
            (m1[a] - m0[a]).abs() <= 1e-12 * scale,
            "momentum {m0:?} -> {m1:?}"
        );
    }
    Ok(())
}

proptest! {
    #![proptest_config(config(256))]

    #[test]
    fn ts_conserves_energy_and_momentum_1d(c in case(1)) {
        let r = if c.muscl { run::<1, Plastic<true>>(&c) } else { run::<1, Plastic<false>>(&c) };
        check(&c, r, 1)?;
    }

    #[test]
    fn ts_conserves_energy_and_momentum_2d(c in case(2)) {
        let r = if c.muscl { run::<2, Plastic<true>>(&c) } else { run::<2, Plastic<false>>(&c) };
        check(&c, r, 2)?;
    }
}
