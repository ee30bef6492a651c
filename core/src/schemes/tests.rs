//! Scheme-level tests on a small 1D flyer plate, stepped serially on fixed arrays.

use super::{av::Av, pm::Pm, ts::Ts, SchemeFamily};
use crate::effects::{EffectSet, Effects};
use crate::exec::Serial;
use crate::kernel::Kernel;
use crate::material::eos::Hugoniot;
use crate::material::{Material, Strength};
use crate::math::{Real, Sym3, Vector};
use crate::neighbors::{build_naive, NeighborList, Periodic};
use crate::schemes::options::*;
use crate::schemes::workspace::*;
use crate::schemes::{AvRates, PmStar, TsStar};
use crate::state::*;

/// Whether a test's effect set stores plastic strains (the run-time effect `plasticity`).
trait Plasticity {
    const PLASTIC: bool;
}

macro_rules! fx {
    ($name:ident, $s:expr, $p:expr, $m:expr, $c:expr) => {
        #[derive(Clone, Copy, Debug)]
        struct $name;
        impl Effects for $name {
            const STRENGTH: bool = $s;
            const CORRECTION: bool = $c;
            const MUSCL: bool = $m;
            const SET: EffectSet = EffectSet::HYDRO;
        }
        impl Plasticity for $name {
            const PLASTIC: bool = $p;
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
    nb: [u32; NeighborList::storage_len(N, CAP)],
    geom: [PairGeom<1>; N * CAP],
    ts_star: [TsStar; N * CAP],
    pm_star: [PmStar<1>; N * CAP],
    aux: [Aux; N],
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
        tensile_strength: Real::INFINITY,
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
        nb: [0; NeighborList::storage_len(N, CAP)],
        geom: [PairGeom::default(); N * CAP],
        ts_star: [TsStar::default(); N * CAP],
        pm_star: [PmStar::default(); N * CAP],
        aux: [Aux::default(); N],
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

fn run<F: SchemeFamily, E: Effects + Plasticity>(t_end: Real) -> (Real, Real, Real, Real, Flyer) {
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
            nb,
            geom,
            ts_star,
            pm_star,
            aux,
        } = &mut f;
        let mut list = NeighborList::new(CAP, N, nb).unwrap();
        let hh: &[Real] = h;
        build_naive(
            &x[..],
            &Periodic::none(),
            |i, j| 2.0 * 0.5 * (hh[i] + hh[j]) * 1.05,
            &mut list,
        )
        .unwrap();
        let mut sys = System::builder()
            .x(x)
            .v(v)
            .m(m)
            .mat(mat)
            .rho(rho)
            .e(e)
            .p(p)
            .c(c)
            .cl(cl)
            .h(h)
            .s(if E::STRENGTH { &mut s[..] } else { &mut [] })
            .eps_p(if E::PLASTIC { &mut eps[..] } else { &mut [] })
            .build()
            .expect("every field a run stores");
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
            effects: EffectSet::HYDRO,
            simd: crate::simd::SimdLevel::BASELINE,
        };
        let pairs = list.view().unordered_pairs();
        let mut ws = Workspace {
            sums,
            grad,
            grad_stress: gs,
            corr,
            hg: &mut [],
            av,
            art: &mut [],
            rec: &mut [],
            fac: &mut [],
            aux,
            geom: &mut geom[..pairs],
            ts_star: &mut ts_star[..pairs],
            pm_star: &mut pm_star[..pairs],
            primed,
        };
        F::step::<1, E, Serial>(
            &mut sys,
            &mut ws,
            &params,
            &Serial,
            &mut crate::halo::NoHalo,
        )
        .unwrap();
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
    let sys = System::builder()
        .x(x)
        .v(v)
        .m(m)
        .mat(mat)
        .rho(rho)
        .e(e)
        .p(p)
        .c(c)
        .cl(cl)
        .h(h)
        .s(s)
        .eps_p(eps)
        .build()
        .expect("every field a run stores");
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
        // explicit Euler (pm) and leap-frog (av) are not energy conserving: a few percent
        // over the run (seed 000 table 2: pm 2.34 %, av 1.51 %). tkc's energy equation is
        // in total-energy form (seed 004 eq 11), conservative to round-off.
        let bound = if name == "tkc" { 1e-10 } else { 0.1 };
        assert!(rel < bound, "{name}: relative energy error {rel:e}");
        // the impact compresses the middle: peak density above rho0 by a few percent
        let rmax = f.rho.iter().cloned().fold(0.0, Real::max);
        assert!(
            rmax > 6200.0 && rmax < 7000.0,
            "{name}: peak density {rmax}"
        );
    }
}

/// The kernel corrections of the 100 particles `x` (unit mass and density, h = 1.2,
/// Wendland C2) with `options`.
fn corrections(x: &mut [Vector<2>; 100], options: SchemeOptions) -> [Correction<2>; 100] {
    let zero = crate::math::Matrix::<2>::zeros();
    neighbourhood::<PlasticTkc>(x, options, zero, Vector::<2>::zeros()).0
}

/// The kernel corrections of the 100 particles `x` as [`corrections`], from the contact
/// family's gradient pass with effects `E` (with correction they must agree with the
/// correction pass: the same flags, `L^-1` to round-off), and the gradients that pass
/// gives the linear fields `rho = 1 + g . x`, `v = A x` and `sigma_xy = g . x`.
fn neighbourhood<E: Effects>(
    x: &mut [Vector<2>; 100],
    options: SchemeOptions,
    a: crate::math::Matrix<2>,
    g: Vector<2>,
) -> (
    [Correction<2>; 100],
    [Gradients<2>; 100],
    [[Vector<2>; 6]; 100],
) {
    const M: usize = 100;
    let (mut v, mut m, mat) = ([Vector::<2>::zeros(); M], [1.0; M], [0u16; M]);
    let (mut rho, mut e, mut p, mut c, mut cl, mut h) =
        ([1.0; M], [0.0; M], [0.0; M], [1.0; M], [1.0; M], [1.2; M]);
    let mut s = [Sym3::default(); M];
    for k in 0..M {
        // unit volumes
        rho[k] = 1.0 + g.dot(&x[k]);
        m[k] = rho[k];
        v[k] = a * x[k];
        s[k].xy = g.dot(&x[k]);
    }
    let mut storage = [0u32; NeighborList::storage_len(M, 64)];
    let mut list = NeighborList::new(64, M, &mut storage).unwrap();
    build_naive(&x[..], &Periodic::none(), |_, _| 2.4, &mut list).unwrap();
    let sys = System::builder()
        .x(x)
        .v(&mut v)
        .m(&m)
        .mat(&mat)
        .rho(&mut rho)
        .e(&mut e)
        .p(&mut p)
        .c(&mut c)
        .cl(&mut cl)
        .h(&mut h)
        .s(&mut s)
        .build()
        .expect("every field a run stores");
    let mats = [material()];
    let params = StepParams {
        dt: 0.0,
        materials: &mats,
        kernel: Kernel::WendlandC2,
        h_factor: 1.2,
        periodic: Periodic::none(),
        nbrs: list.view(),
        options,
        effects: EffectSet::HYDRO,
        simd: crate::simd::SimdLevel::BASELINE,
    };
    let mut corr = [Correction::<2>::default(); M];
    let mut sums = [PairSums::<2>::default(); M];
    let mut geom = [PairGeom::<2>::default(); M * 64];
    let geom = &mut geom[..params.nbrs.unordered_pairs()];
    super::pairs::geometry_pass::<2, PlasticTkc2, Serial>(
        sys.x,
        sys.h,
        &params,
        geom,
        &mut [],
        &Serial,
    );
    let mut aux = [Aux::default(); M];
    super::common::refresh_aux::<2, false, Serial>(&sys, &mut aux, &params, &Serial);
    super::pm::correction_pass::<2, Serial>(
        &sys, geom, &aux, &mut corr, &mut sums, &params, &Serial,
    );
    let mut fused = [Correction::<2>::default(); M];
    let mut grad = [Gradients::<2>::default(); M];
    let mut gs = [[Vector::<2>::zeros(); 6]; M];
    super::pm::gradient_pass::<2, E, Serial>(
        &sys, geom, &aux, &mut fused, &mut sums, &mut grad, &mut gs, &params, &Serial,
    );
    for k in (0..M).filter(|_| E::CORRECTION) {
        assert_eq!(fused[k].boundary, corr[k].boundary, "particle {k}");
        assert_eq!(fused[k].lambda_min, corr[k].lambda_min, "particle {k}");
        let scale = corr[k].l_inv.norm();
        assert!(
            (fused[k].l_inv - corr[k].l_inv).norm() <= 1e-14 * scale,
            "particle {k}: {} against {}",
            fused[k].l_inv,
            corr[k].l_inv
        );
    }
    (corr, grad, gs)
}

/// A 10 x 10 block with spacings `dx`, `dy`.
fn block(dx: Real, dy: Real) -> [Vector<2>; 100] {
    core::array::from_fn(|k| Vector::<2>::new((k % 10) as Real * dx, (k / 10) as Real * dy))
}

/// Free-surface detection of `tkc` (seed 004 §2): on a 10 x 10 block, edge particles
/// have a small eigenvalue of L (about 0.5 across the surface) and are flagged; their
/// neighbours within h use L = I; interior particles keep L^-1 ~ I. The seed's literal
/// criterion, the smallest eigenvalue of L^-1 below 0.75, would flag nothing: truncating
/// the kernel shrinks L, so L^-1 grows (its smallest eigenvalue stays near 1). The same
/// with and without the umbrella scan (`options.surface_scan`).
#[test]
fn tkc_free_surface_detection_uses_the_eigenvalues_of_l() {
    use crate::math::{inverse, Matrix};
    use crate::schemes::common::min_sym_eigenvalue;
    let at = |i: usize, j: usize| i + 10 * j;
    // an edge particle, its inner neighbour, and a centre particle
    let (edge, second, centre) = (at(0, 5), at(1, 5), at(5, 5));
    for scan in [true, false] {
        let mut x = block(1.0, 1.0);
        let options = SchemeOptions {
            surface_scan: scan,
            ..SchemeOptions::default()
        };
        let corr = corrections(&mut x, options);
        assert_eq!(
            corr[edge].boundary, 2,
            "edge lambda_min {}",
            corr[edge].lambda_min
        );
        assert!(corr[edge].lambda_min < 0.75);
        assert_eq!(corr[second].boundary, 1);
        assert_eq!(corr[second].l_inv, Matrix::<2>::identity());
        assert_eq!(corr[centre].boundary, 0);
        assert!((corr[centre].l_inv - Matrix::<2>::identity()).norm() < 0.1);
        // every particle of the outer ring is a boundary particle, and only those
        for k in 0..100 {
            let ring = [k % 10, k / 10].iter().any(|&q| q == 0 || q == 9);
            assert_eq!(corr[k].boundary == 2, ring, "particle {k}, scan {scan}");
        }
        // the literal criterion on L^-1 of the edge particle: its smallest eigenvalue is >= 1
        let mut l = Matrix::<2>::zeros();
        for j in 0..100 {
            let rij = x[edge] - x[j];
            let r = rij.norm();
            if r > 0.0 && r < 2.4 {
                let grad = rij * (Kernel::WendlandC2.dw::<2>(r, 1.2) / r);
                l += grad * (x[j] - x[edge]).transpose();
            }
        }
        assert!(min_sym_eigenvalue(&inverse(&l).unwrap()) > 0.9);
    }
}

/// Issue 27 part 4: a block stretched 1.8x along x and compressed to 0.55 along y (the
/// Taylor rod's face: radial neighbours leave the kernel, axial ones crowd in) has an
/// interior whose L has its smallest eigenvalue far below 0.75 although nothing of it is
/// a surface. Seed 004's eigenvalue test flags it and switches its correction off; the
/// umbrella scan (`options.surface_scan = true`) keeps the interior corrected and flags
/// only particles of the block's outer ring.
#[test]
fn a_stretched_interior_is_not_a_free_surface_with_the_scan() {
    let centre = 5 + 10 * 5;
    let mut x = block(1.8, 0.55);
    let seed = corrections(
        &mut x,
        SchemeOptions {
            surface_scan: false,
            ..SchemeOptions::default()
        },
    );
    assert!(
        seed[centre].lambda_min < 0.6,
        "lambda_min {}",
        seed[centre].lambda_min
    );
    assert_eq!(seed[centre].boundary, 2);
    let mut x = block(1.8, 0.55);
    let scan = corrections(
        &mut x,
        SchemeOptions {
            surface_scan: true,
            ..SchemeOptions::default()
        },
    );
    for k in 0..100 {
        // a ring particle is flagged, or near one (the scan's one normal points to the
        // nearer surface: next to a corner, the other surface's particle is flag 1)
        let ring = [k % 10, k / 10].iter().any(|&q| q == 0 || q == 9);
        assert!(!ring || scan[k].boundary > 0, "ring particle {k}");
        assert!(
            scan[k].boundary < 2 || ring,
            "interior particle {k} flagged"
        );
    }
    assert_eq!(scan[centre].boundary, 0);
    assert_ne!(scan[centre].l_inv, crate::math::Matrix::<2>::identity());
}

#[derive(Clone, Copy, Debug)]
struct PlasticTkc2;
impl Effects for PlasticTkc2 {
    const STRENGTH: bool = false;
    const CORRECTION: bool = true;
    const MUSCL: bool = true;
    const SET: EffectSet = EffectSet::HYDRO;
}

/// A 10 x 10 unit block sheared by 0.3 along x, so that `L` is not diagonal.
fn sheared_block() -> [Vector<2>; 100] {
    let mut x = block(1.0, 1.0);
    for p in x.iter_mut() {
        p[0] += 0.3 * p[1];
    }
    x
}

/// Every particle's spin is `spin` to round-off or zero (where det L < det_epsilon, no
/// spin is known: the block's corners), and at least 96 of the 100 have one.
fn assert_spins(grad: &[Gradients<2>; 100], spin: crate::math::Matrix<2>) {
    let zero = crate::math::Matrix::<2>::zeros();
    for (k, gk) in grad.iter().enumerate() {
        assert!(
            gk.w == zero || (gk.w - spin).norm() < 1e-12,
            "particle {k}: {}",
            gk.w
        );
    }
    let spun = grad.iter().filter(|gk| gk.w != zero).count();
    assert!(spun >= 96, "{spun} particles with a spin");
}

/// `tkc`'s gradient pass (which sums uncorrected and corrects once per particle) gives the
/// exact slopes of linear fields where the correction is on (flag 0), and everywhere
/// with `options.corrected_slopes`; the spin of `v = A x` is `(A - A^T)/2` on every
/// particle whose `det L >= det_epsilon`, the surface included. On a sheared block.
#[test]
fn tkc_gradients_of_linear_fields_are_exact_where_corrected() {
    use crate::math::Matrix;
    let a = Matrix::<2>::new(0.1, -2.0, 3.0, 0.4);
    let g = Vector::<2>::new(0.3, -0.7);
    let spin = (a - a.transpose()) * 0.5;
    for corrected_slopes in [false, true] {
        let options = SchemeOptions {
            corrected_slopes,
            ..SchemeOptions::default()
        };
        let (corr, grad, gs) = neighbourhood::<PlasticTkc>(&mut sheared_block(), options, a, g);
        assert_spins(&grad, spin);
        let (mut exact, mut interior) = (0, 0);
        for k in 0..100 {
            if corr[k].boundary == 0 || corrected_slopes {
                interior += usize::from(corr[k].boundary == 0);
                exact += 1;
                assert!(
                    (grad[k].rho - g).norm() < 1e-12,
                    "particle {k}: {}",
                    grad[k].rho
                );
                assert!(
                    (grad[k].v - a).norm() < 1e-12,
                    "particle {k}: {}",
                    grad[k].v
                );
                let xy = Sym3::voigt(0, 1);
                assert!(
                    (gs[k][xy] - g).norm() < 1e-12,
                    "particle {k}: {}",
                    gs[k][xy]
                );
            }
        }
        // the interior of the block (6 x 6 minus what the surface rule takes) and, with
        // corrected slopes, all 100
        assert!(interior >= 16, "{interior} interior particles");
        assert_eq!(exact == 100, corrected_slopes, "{exact} exact slopes");
    }
    // pm with MUSCL and without correction: the same spin from the same pass (its own
    // `L`), the slopes uncorrected
    let options = SchemeOptions::default();
    let (_, grad, _) = neighbourhood::<PlasticMuscl>(&mut sheared_block(), options, a, g);
    assert_spins(&grad, spin);
}
