//! `tl`'s defining properties on a small 2D body with free surfaces: F and dF/dt are
//! exact for every affine motion and such a motion feels no stiffness and no
//! dissipation; the stiffness's force is minus the gradient of its energy; the forces
//! conserve linear momentum, and angular momentum without dissipation.

use super::pairs::{constitutive, deformation, forces};
use crate::effects::{EffectSet, Effects};
use crate::exec::Serial;
use crate::kernel::Kernel;
use crate::material::eos::Linear;
use crate::material::{Material, Strength};
use crate::math::{Matrix, Real, Sym3, Vector};
use crate::neighbors::{build_naive, NeighborList, Periodic};
use crate::schemes::options::SchemeOptions;
use crate::schemes::pairs::geometry_pass;
use crate::schemes::workspace::StepParams;
use crate::state::{Hourglass, PairGeom, PairSums, System};

#[derive(Clone, Copy, Debug)]
struct Solid;
impl Effects for Solid {
    const STRENGTH: bool = true;
    const CORRECTION: bool = false;
    const MUSCL: bool = false;
    const SET: EffectSet = EffectSet::STRENGTH;
}

const SIDE: usize = 7;
const N: usize = SIDE * SIDE;
const CAP: usize = 40;
const DX: Real = 1e-3;

/// A deterministic number in [-1, 1) from `k`.
fn noise(k: usize) -> Real {
    let mut z = (k as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ 0xD1B5_4A32_D192_ED03;
    z = (z ^ (z >> 31)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^= z >> 29;
    (z >> 11) as Real / (1u64 << 52) as Real - 1.0
}

fn material() -> Material {
    Material {
        rho0: 1000.0,
        eos: Linear {
            rho0: 1000.0,
            c0: 100.0,
            gamma: 0.0,
        }
        .into(),
        shear_modulus: 1e6,
        strength: Strength::Elastic,
        tensile_strength: Real::INFINITY,
    }
}

/// The reference positions: a square block of a slightly disordered lattice, every row
/// of it near a free surface or a corner.
fn reference() -> [Vector<2>; N] {
    core::array::from_fn(|i| {
        let (a, b) = ((i % SIDE) as Real, (i / SIDE) as Real);
        Vector::<2>::new(a + 0.15 * noise(2 * i), b + 0.15 * noise(2 * i + 1)) * DX
    })
}

/// What the passes give for the positions `x` and velocities `v` of the reference block.
struct Out {
    rec: [Hourglass<2>; N],
    force: [Vector<2>; N],
    phi: Real,
}

/// Runs the deformation pass, then (with `stress`) the constitutive update from the
/// deviators `s0`, or else puts the stiffness's stress alone into the records, then the
/// force pass.
fn passes(x: &[Vector<2>; N], v: &[Vector<2>; N], stress: Option<&[Sym3; N]>) -> Out {
    let mats = [material()];
    let mut xr = reference();
    let (mut x, mut v) = (*x, *v);
    let m = [1000.0 * DX * DX; N];
    let vr = [DX * DX; N];
    let mat = [0u16; N];
    let mut rho = [1000.0; N];
    let (mut e, mut p, mut c, mut cl) = ([0.0; N], [0.0; N], [100.0; N], [110.0; N]);
    let mut h = [1.3 * DX; N];
    let mut s = stress.copied().unwrap_or([Sym3::ZERO; N]);
    let mut phi = [0.0; N];
    let mut storage = [0u32; NeighborList::storage_len(N, CAP)];
    let mut list = NeighborList::new(CAP, N, &mut storage).unwrap();
    build_naive(&xr[..], &Periodic::none(), |_, _| 2.0 * 1.3 * DX, &mut list).unwrap();
    let mut sys = System::builder()
        .x(&mut x)
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
        .xr(&mut xr)
        .vr(&vr)
        .phi(&mut phi)
        .build()
        .expect("every field a run stores");
    let params = StepParams {
        dt: 1e-7,
        materials: &mats,
        kernel: Kernel::WendlandC2,
        h_factor: 1.3,
        periodic: Periodic::none(),
        nbrs: list.view(),
        options: SchemeOptions {
            hourglass: 2.0,
            ..SchemeOptions::default()
        },
        effects: EffectSet::STRENGTH.union(EffectSet::REFERENCE),
        simd: crate::simd::SimdLevel::BASELINE,
    };
    let mut geom = [PairGeom::<2>::default(); N * CAP];
    let geom = &mut geom[..params.nbrs.unordered_pairs()];
    geometry_pass::<2, Solid, Serial>(sys.xr, sys.h, &params, geom, &mut [], &Serial);
    let mut rec = [Hourglass::<2>::default(); N];
    deformation::<2, Serial>(&sys, geom, &mut rec, &params, &Serial);
    if stress.is_some() {
        constitutive::<2, Solid, Serial>(&mut sys, &mut rec, &params, &Serial);
    } else {
        for r in rec.iter_mut() {
            r.p *= 1.0 / r.vol;
        }
    }
    let mut sums = [PairSums::<2>::default(); N];
    forces::<2, Serial>(&sys, geom, &rec, &mut sums, &params, &Serial);
    Out {
        rec,
        force: core::array::from_fn(|i| sums[i].acc * m[i]),
        phi: sums.iter().map(|s| s.div).sum(),
    }
}

fn matrix(a: Real, b: Real, c: Real, d: Real) -> Matrix<2> {
    Matrix::<2>::new(a, b, c, d)
}

#[test]
fn an_affine_motion_is_exact_and_feels_no_stiffness_and_no_dissipation() {
    let xr = reference();
    // a stretch, a shear and a rotation of 0.6 rad; velocities of another affine field
    let (cs, sn) = (0.6f64.cos(), 0.6f64.sin());
    let g = matrix(cs, -sn, sn, cs) * matrix(1.2, 0.3, -0.1, 0.9);
    let l = matrix(3.0, -50.0, 40.0, -2.0);
    let x: [Vector<2>; N] = core::array::from_fn(|i| g * xr[i] + Vector::<2>::new(0.01, -0.02));
    let v: [Vector<2>; N] = core::array::from_fn(|i| l * x[i] + Vector::<2>::new(1.0, 2.0));
    let out = passes(&x, &v, None);
    let id = Matrix::<2>::identity();
    let vel_scale = 50.0 * 10.0 * DX;
    let mut worst: [Real; 4] = [0.0; 4];
    for r in &out.rec {
        worst[0] = worst[0].max((r.t + id - g).abs().max());
        worst[1] = worst[1].max((r.l - l * g).abs().max() / 50.0);
        worst[2] = worst[2].max(r.p.abs().max());
    }
    for f in &out.force {
        worst[3] = worst[3].max(f.norm());
    }
    assert!(worst[0] < 1e-12, "F: {worst:?}");
    assert!(worst[1] < 1e-12, "dF/dt: {worst:?}");
    // the stiffness's stress kappa (H M - N) against its scale kappa dx^2 ~ 2e6 Pa
    assert!(worst[2] < 1e-6, "A: {worst:?}");
    assert!(out.phi.abs() < 1e-20, "Phi {}", out.phi);
    // a pair's dissipative force is Z area [v*]; Z area |dv| ~ 1e5 * 1e-3 * vel_scale
    assert!(worst[3] < 1e-9 * 1e5 * DX * vel_scale, "force: {worst:?}");
    // control: a wavy velocity field is dissipated
    let wavy: [Vector<2>; N] =
        core::array::from_fn(|i| Vector::<2>::new(0.0, if i % 2 == 0 { 1.0 } else { -1.0 }));
    let out = passes(&x, &wavy, None);
    assert!(out.force.iter().map(|f| f.norm()).fold(0.0, Real::max) > 1e-2 * 1e5 * DX);
}

/// Positions displaced from the reference by a non-affine field.
fn displaced(amp: Real) -> [Vector<2>; N] {
    let xr = reference();
    core::array::from_fn(|i| xr[i] + Vector::<2>::new(noise(300 + i), noise(600 + i)) * amp * DX)
}

#[test]
fn the_stiffness_force_is_minus_the_gradient_of_its_energy() {
    let x = displaced(0.05);
    let v = [Vector::<2>::zeros(); N];
    let out = passes(&x, &v, None);
    assert!(out.phi > 0.0);
    let scale = out.force.iter().map(|f| f.norm()).fold(0.0, Real::max);
    let step = 1e-6 * DX;
    for a in [0, 3, 24, 31, 48] {
        for c in 0..2 {
            let mut plus = x;
            let mut minus = x;
            plus[a][c] += step;
            minus[a][c] -= step;
            let d_phi = (passes(&plus, &v, None).phi - passes(&minus, &v, None).phi) / (2.0 * step);
            let err = (out.force[a][c] + d_phi).abs();
            assert!(
                err < 1e-6 * scale,
                "particle {a}, axis {c}: {} vs {}",
                out.force[a][c],
                -d_phi
            );
        }
    }
}

#[test]
fn the_forces_conserve_momentum_and_without_dissipation_angular_momentum() {
    let x = displaced(0.1);
    let s: [Sym3; N] = core::array::from_fn(|i| {
        Sym3::new(noise(i), noise(i + 50), 0.0, noise(i + 100), 0.0, 0.0).deviator() * 1e5
    });
    let still = [Vector::<2>::zeros(); N];
    let moving: [Vector<2>; N] =
        core::array::from_fn(|i| Vector::<2>::new(noise(900 + i), noise(950 + i)));
    for (v, torque_free) in [(still, true), (moving, false)] {
        let out = passes(&x, &v, Some(&s));
        let scale = out.force.iter().map(|f| f.norm()).fold(0.0, Real::max);
        let total: Vector<2> = out.force.iter().sum();
        assert!(
            total.norm() < 1e-12 * scale * N as Real,
            "momentum {total:?}"
        );
        let torque: Real = (0..N)
            .map(|i| x[i][0] * out.force[i][1] - x[i][1] * out.force[i][0])
            .sum();
        if torque_free {
            assert!(
                torque.abs() < 1e-12 * scale * DX * N as Real,
                "torque {torque}"
            );
        }
    }
}

/// The neo-Hookean deviator is Hooke's at small strain, objective under rotation, and
/// zero for any volume change alone.
#[test]
fn the_hyperelastic_deviator_is_hookes_at_small_strain_and_objective() {
    use super::pairs::neo_hookean_deviator;
    let g = 3.0e9;
    let eps = 1e-7;
    let h = Matrix::<3>::new(0.3, 0.2, -0.1, 0.2, -0.5, 0.4, -0.1, 0.4, 0.1) * eps;
    let s = neo_hookean_deviator(&(Matrix::<3>::identity() + h), g);
    let hooke = Sym3::sym_of(&h).deviator() * (2.0 * g);
    for (a, b) in [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)] {
        assert!(
            (s.get(a, b) - hooke.get(a, b)).abs() < 1e-6 * g * eps,
            "{a}{b}"
        );
    }
    // a large stretch, then rotated: sigma(R U) = R sigma(U) R^T
    let u = Matrix::<3>::new(1.4, 0.2, 0.0, 0.2, 0.8, 0.1, 0.0, 0.1, 1.1);
    let (c, sn) = (0.6f64, 0.8f64);
    let r = Matrix::<3>::new(c, -sn, 0.0, sn, c, 0.0, 0.0, 0.0, 1.0);
    let su = neo_hookean_deviator(&u, g).block::<3>();
    let sru = neo_hookean_deviator(&(r * u), g).block::<3>();
    assert!((sru - r * su * r.transpose()).norm() < 1e-9 * g);
    let dil = neo_hookean_deviator(&(Matrix::<3>::identity() * 1.3), g);
    assert!(dil.block::<3>().norm() < 1e-9 * g);
    // plane strain: F's out-of-plane stretch is 1
    let s2 = neo_hookean_deviator(&Matrix::<2>::new(1.2, 0.0, 0.0, 1.0), g);
    assert!(s2.zz < 0.0 && s2.xx > 0.0 && (s2.trace()).abs() < 1e-6);
}
