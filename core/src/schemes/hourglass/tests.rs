//! The stiffness's defining properties on a small 2D body with a free surface: the rate
//! vanishes for every affine velocity field, the force is the exact adjoint of the rate
//! (its power is `-sum q . a` for any velocities), and it conserves linear and angular
//! momentum.

use super::*;
use crate::exec::Serial;
use crate::kernel::Kernel;
use crate::material::eos::Linear;
use crate::material::{Material, Strength};
use crate::math::Sym3;
use crate::neighbors::{build_naive, NeighborList, Periodic};
use crate::schemes::common::refresh_aux;
use crate::schemes::options::SchemeOptions;
use crate::schemes::pairs::geometry_pass;

#[derive(Clone, Copy, Debug)]
struct Solid;
impl crate::effects::Effects for Solid {
    const STRENGTH: bool = true;
    const CORRECTION: bool = false;
    const MUSCL: bool = false;
    const SET: EffectSet = EffectSet::STRENGTH;
}

const SIDE: usize = 7;
const N: usize = SIDE * SIDE;
const CAP: usize = 40;
const DX: Real = 1e-3;

/// A deterministic number in [-1, 1) from `k` (a fixed hash; no generator needed).
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

/// What a test sees after `update` with the velocities `vel` and displacements `d0`
/// over `dt`: the new displacements and records, and the stiffness's acceleration.
struct Out {
    x: [Vector<2>; N],
    m: [Real; N],
    d: [Vector<2>; N],
    rec: [Hourglass<2>; N],
    acc: [Vector<2>; N],
    power: [Real; N],
}

/// A square block of a slightly disordered lattice (every row of it near a free
/// surface or a corner) stepped once by the stiffness alone.
fn block(vel: impl Fn(&Vector<2>) -> Vector<2>, d0: impl Fn(usize) -> Vector<2>, dt: Real) -> Out {
    let mats = [material()];
    let mut x = [Vector::<2>::zeros(); N];
    let mut v = [Vector::<2>::zeros(); N];
    let mut d = [Vector::<2>::zeros(); N];
    for i in 0..N {
        let (a, b) = ((i % SIDE) as Real, (i / SIDE) as Real);
        x[i] = Vector::<2>::new(a + 0.15 * noise(2 * i), b + 0.15 * noise(2 * i + 1)) * DX;
        v[i] = vel(&x[i]);
        d[i] = d0(i);
    }
    let m = [1000.0 * DX * DX; N];
    let mat = [0u16; N];
    let mut rho = [1000.0 * (1.0 + 0.01 * noise(7)); N];
    for (i, r) in rho.iter_mut().enumerate() {
        *r *= 1.0 + 0.02 * noise(1000 + i);
    }
    let (mut e, mut p, mut c, mut cl) = ([0.0; N], [0.0; N], [100.0; N], [100.0; N]);
    let mut h = [1.3 * DX; N];
    let mut s = [Sym3::ZERO; N];
    let mut storage = [0u32; NeighborList::storage_len(N, CAP)];
    let mut list = NeighborList::new(CAP, N, &mut storage).unwrap();
    build_naive(&x[..], &Periodic::none(), |_, _| 2.0 * 1.3 * DX, &mut list).unwrap();
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
        .hg(&mut d)
        .build()
        .expect("every field a run stores");
    let options = SchemeOptions {
        hourglass: 2.0,
        ..SchemeOptions::default()
    };
    let params = StepParams {
        dt,
        materials: &mats,
        kernel: Kernel::WendlandC2,
        h_factor: 1.3,
        periodic: Periodic::none(),
        nbrs: list.view(),
        options,
        effects: EffectSet::STRENGTH.union(EffectSet::HOURGLASS),
        simd: crate::simd::SimdLevel::BASELINE,
    };
    let mut geom = [PairGeom::<2>::default(); N * CAP];
    let geom = &mut geom[..params.nbrs.unordered_pairs()];
    geometry_pass::<2, Solid, Serial>(sys.x, sys.h, &params, geom, &mut [], &Serial);
    let mut aux = [Aux::default(); N];
    refresh_aux::<2, false, Serial>(&sys, &mut aux, &params, &Serial);
    let mut rec = [Hourglass::<2>::default(); N];
    update::<2, Serial>(&mut sys, geom, &aux, &mut rec, &params, &Serial);
    let mut sums = [PairSums::<2>::default(); N];
    add_forces::<2, Serial, false>(&sys, geom, &rec, &mut sums, &params, &Serial);
    let mut out = Out {
        x: [Vector::<2>::zeros(); N],
        m,
        d: [Vector::<2>::zeros(); N],
        rec,
        acc: [Vector::<2>::zeros(); N],
        power: [0.0; N],
    };
    for i in 0..N {
        out.x[i] = sys.x[i];
        out.d[i] = sys.hg[i];
        out.acc[i] = sums[i].acc;
        out.power[i] = sums[i].power;
    }
    out
}

fn affine(x: &Vector<2>) -> Vector<2> {
    let g = crate::math::Matrix::<2>::new(3.0, -7.0, 11.0, -2.0);
    g * x + Vector::<2>::new(5.0, -4.0)
}

fn wavy(x: &Vector<2>) -> Vector<2> {
    Vector::<2>::new(
        (x[0] * 2.1e3).sin() + 0.3 * (x[1] * 3.7e3).cos(),
        (x[1] * 1.3e3 + x[0] * 0.7e3).cos(),
    )
}

fn random_d(i: usize) -> Vector<2> {
    Vector::<2>::new(noise(5000 + 2 * i), noise(5001 + 2 * i)) * 1e-5
}

#[test]
fn an_affine_velocity_field_stores_nothing_free_surfaces_included() {
    let o = block(affine, |_| Vector::<2>::zeros(), 1.0);
    let scale = 20.0 * DX; // |G x + c| over the block
    for i in 0..N {
        assert!(
            o.d[i].norm() < 1e-12 * scale,
            "particle {i}: d = {:?}",
            o.d[i]
        );
    }
}

#[test]
fn a_wavy_velocity_field_does_store_something() {
    // the test above cannot pass by a rate that is always zero
    let o = block(wavy, |_| Vector::<2>::zeros(), 1.0);
    let stored = o.d.iter().filter(|d| d.norm() > 1e-6).count();
    assert!(
        stored > N / 2,
        "only {stored} particles moved off the affine motion"
    );
}

#[test]
fn the_force_is_the_exact_adjoint_of_the_rate() {
    // a_i from d = 0 over dt = 1; the records of random d over dt = 0 (d unchanged)
    let rate = block(wavy, |_| Vector::<2>::zeros(), 1.0);
    let o = block(wavy, random_d, 0.0);
    let mut dphi = 0.0; // sum q . a
    let mut work = 0.0; // sum f . v
    let mut scale = 0.0;
    for i in 0..N {
        assert_eq!(o.d[i], random_d(i));
        dphi += o.rec[i].q.dot(&rate.d[i]);
        let f = o.acc[i] * o.m[i];
        work += f.dot(&wavy(&o.x[i]));
        scale += o.rec[i].q.norm() * rate.d[i].norm();
    }
    assert!(scale > 0.0);
    assert!(
        (work + dphi).abs() < 1e-12 * scale,
        "power {work:e} against -dPhi/dt {:e}",
        -dphi
    );
}

#[test]
fn the_force_conserves_linear_and_angular_momentum_and_books_its_power_in_pairs() {
    let o = block(wavy, random_d, 0.0);
    let (mut p, mut l, mut booked, mut scale) = (Vector::<2>::zeros(), 0.0, 0.0, 0.0);
    for i in 0..N {
        let f = o.acc[i] * o.m[i];
        p += f;
        l += o.x[i][0] * f[1] - o.x[i][1] * f[0];
        booked += o.power[i] * o.m[i];
        scale += f.norm();
    }
    assert!(scale > 0.0);
    assert!(p.norm() < 1e-13 * scale, "net force {p:?}");
    assert!(
        l.abs() < 1e-13 * scale * SIDE as Real * DX,
        "net torque {l:e}"
    );
    // the pair-mean power cancels in pairs (what keeps the scheme's total energy exact)
    assert!(booked.abs() < 1e-12 * scale, "booked power {booked:e}");
}

#[test]
fn the_spin_rotates_the_displacement_without_changing_its_length() {
    // a rigid rotation at 1e3 rad/s over 1e-4 s: d turns by 0.1 rad, |d| is kept
    let w = 1e3;
    let spin = |x: &Vector<2>| Vector::<2>::new(-w * x[1], w * x[0]);
    let o = block(spin, random_d, 1e-4);
    for i in 0..N {
        let (d0, d) = (random_d(i), o.d[i]);
        assert!(
            (d.norm() - d0.norm()).abs() < 1e-12 * d0.norm(),
            "particle {i}"
        );
        let angle = (d0[0] * d[1] - d0[1] * d[0]).atan2(d0.dot(&d));
        assert!((angle - 0.1).abs() < 1e-3, "particle {i}: turned {angle}");
    }
}
