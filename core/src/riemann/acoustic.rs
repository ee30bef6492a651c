//! The linearised (acoustic) Riemann solver.
//!
//! # Derivation
//!
//! Along the pair axis `x` (pointing from the left particle i to the right particle j) the
//! linear elastic wave system for the velocity `u` and the normal traction `s` (tension
//! positive) is
//!
//! ```text
//! rho du/dt = ds/dx,        ds/dt = rho c² du/dx.
//! ```
//!
//! With the impedance `Z = rho c`:
//! `d(s - Z u)/dt = rho c² u_x - c s_x = -c d(s - Z u)/dx`, so `s - Z u` is constant along
//! the right-going characteristics `dx/dt = +c`; likewise `s + Z u` is constant along the
//! left-going ones `dx/dt = -c`. For piecewise-constant data (left state for `x < 0`,
//! right state for `x > 0`, each side with its own impedance), the contact `x = 0` is reached
//! at `t > 0` by the right-going characteristic from the left and the left-going one from the
//! right, and `u`, `s` are continuous across it (star state):
//!
//! ```text
//! s* - Z_l u* = s_l - Z_l u_l,        s* + Z_r u* = s_r + Z_r u_r,
//! u* = (Z_l u_l + Z_r u_r + s_r - s_l) / (Z_l + Z_r),
//! s* = (Z_r s_l + Z_l s_r + Z_l Z_r (u_r - u_l)) / (Z_l + Z_r).
//! ```
//!
//! A symmetric collision (`u_l = +u`, `u_r = -u`, equal `Z`, no stress) gives `u* = 0`,
//! `s* = -Z u` (compression). This is the Parshikov–Medin star state of seed 000 eq 15 and
//! seed 004 with the pair axis taken from i to j and `c^l` in the longitudinal row (DESIGN
//! §8 errata); the formulas are derived here, not copied.
//!
//! The same system with `s` the shear traction `sigma_tn = t·e_t` and `c = c_t` describes the
//! transverse waves (`rho dv_t/dt = d sigma_tn/dx`, `d sigma_tn/dt = G dv_t/dx`), which
//! [`acoustic_star_vector`] uses for the tangential part.
use crate::math::{Real, Vector};
use crate::simd::arith::Arith;

/// One side of the linearised (acoustic) Riemann problem along the pair axis.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AcousticSide {
    /// Velocity component along the axis, m/s.
    pub u: Real,
    /// Traction component along the axis (normal stress, tension positive), Pa.
    pub s: Real,
    /// Impedance rho*c, kg/(m² s).
    pub z: Real,
}

/// Star state of the acoustic Riemann problem: left side `l` (particle i), right side `r`
/// (particle j), axis pointing from l to r. Returns `(u*, s*)`, `s*` tension positive.
///
/// `u* = (Z_l u_l + Z_r u_r + s_r - s_l)/(Z_l + Z_r)`,
/// `s* = (Z_r s_l + Z_l s_r + Z_l Z_r (u_r - u_l))/(Z_l + Z_r)` (derivation in the module
/// documentation). One impedance may be zero (a free surface: `s* = s` of that side). If
/// `Z_l + Z_r` is not positive and finite (both sides without impedance, or invalid input)
/// the answer is the arithmetic mean of the two sides, which is finite and keeps the i/j
/// swap symmetry.
///
/// One function for the portable path and the lanes (`acoustic_in`, which the vectorised
/// star rows run on their registers: issue 44, docs/performance.md "SIMD levels").
#[inline(always)]
pub fn acoustic_star(l: AcousticSide, r: AcousticSide) -> (Real, Real) {
    // SAFETY: one lane of `Real` needs no instructions beyond the target's
    unsafe { acoustic_in::<Real>(l.u, l.s, l.z, r.u, r.s, r.z) }
}

/// [`acoustic_star`] written once for one lane and for the vectorised loops' registers
/// ([`Arith`]): the same IEEE operations in the same order, both sides of the branch
/// computed and the valid one selected.
///
/// # Safety
/// `A`'s level must be one the CPU has (nothing for `Real`).
#[inline(always)]
pub(crate) unsafe fn acoustic_in<A: Arith>(ul: A, sl: A, zl: A, ur: A, sr: A, zr: A) -> (A, A) {
    let zs = A::add(zl, zr);
    let ok = A::and(A::gt(zs, A::zero()), A::finite(zs));
    let inv = A::div(A::splat(1.0), zs);
    let u = A::mul(
        A::sub(A::add(A::add(A::mul(zl, ul), A::mul(zr, ur)), sr), sl),
        inv,
    );
    let s = A::mul(
        A::add(
            A::add(A::mul(zr, sl), A::mul(zl, sr)),
            A::mul(A::mul(zl, zr), A::sub(ur, ul)),
        ),
        inv,
    );
    let half = A::splat(0.5);
    (
        A::select(ok, u, A::mul(half, A::add(ul, ur))),
        A::select(ok, s, A::mul(half, A::add(sl, sr))),
    )
}

/// One side of the acoustic Riemann problem written with the pressure (hydrodynamic step of
/// the time-split schemes).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PressureSide {
    /// Velocity component along the axis (from i to j), m/s.
    pub u: Real,
    /// Pressure, Pa, positive in compression (`p = -s`).
    pub p: Real,
    /// Impedance rho*c, kg/(m² s).
    pub z: Real,
}

/// Star state `(u*, p*)` of the acoustic Riemann problem with pressures (`p = -s`):
/// [`acoustic_star`] with `s = -p`, that is
/// `u* = (Z_l u_l + Z_r u_r + p_l - p_r)/(Z_l + Z_r)`,
/// `p* = (Z_r p_l + Z_l p_r + Z_l Z_r (u_l - u_r))/(Z_l + Z_r)`.
/// Axis from l (particle i) to r (particle j); `p*` is positive in compression.
///
/// Lane twin: `pressure_star` in `core/src/simd/riemann.rs` (held bitwise equal through the star tests,
/// `schemes/star_tests.rs`).
#[inline(always)]
pub fn pressure_star(l: PressureSide, r: PressureSide) -> (Real, Real) {
    let (u, s) = acoustic_star(
        AcousticSide {
            u: l.u,
            s: -l.p,
            z: l.z,
        },
        AcousticSide {
            u: r.u,
            s: -r.p,
            z: r.z,
        },
    );
    (u, -s)
}

/// Vector star state `(V*, T*)` of the Parshikov–Medin / TKC pair interaction.
///
/// `n` is the **unit** pair axis from particle i (left) to particle j (right); `v_l`, `v_r`
/// are the velocities and `t_l = sigma_i·n`, `t_r = sigma_j·n` the traction vectors (tension
/// positive) of the two sides on the plane with normal `n`. Each vector is split into its
/// normal part (`(x·n) n`) and its tangential part (`x - (x·n) n`):
///
/// * the normal components are solved with [`acoustic_star`] and the longitudinal
///   impedances `rho c_l` (`zl_long`, `zr_long`);
/// * the tangential vectors are solved with the same formulas, applied to the vectors
///   (equivalently component-wise in any tangential basis, as the transverse problem is
///   isotropic in the plane), with the transverse impedances `rho c_t` (`zl_trans`,
///   `zr_trans`). If the transverse impedances sum to zero (two fluids), the tangential star
///   velocity is the mean of the two tangential velocities and the tangential star traction
///   is zero (a fluid carries no shear); one fluid against a solid follows the general
///   formula, which gives the free-slip answer `T*_t = t_l,t = 0`.
///
/// No rotation matrices are needed and the result is frame invariant; it works for `D` = 1,
/// 2 and 3 (in 1D the tangential part is empty). Under the swap of i and j (`n -> -n`) the
/// result transforms as `V*' = V*`, `T*' = -T*` (the traction on the opposite face).
///
/// Lane twin: `star_vector` in `core/src/simd/riemann.rs` (held bitwise equal through the star tests,
/// `schemes/star_tests.rs`).
#[inline(always)]
#[allow(clippy::too_many_arguments)] // API fixed: two sides of four quantities plus the axis
pub fn acoustic_star_vector<const D: usize>(
    n: &Vector<D>,
    v_l: &Vector<D>,
    t_l: &Vector<D>,
    zl_long: Real,
    zl_trans: Real,
    v_r: &Vector<D>,
    t_r: &Vector<D>,
    zr_long: Real,
    zr_trans: Real,
) -> (Vector<D>, Vector<D>) {
    elastic_star_vector(
        n,
        v_l,
        t_l,
        zl_trans,
        v_r,
        t_r,
        zr_trans,
        |vln, tln, vrn, trn| {
            acoustic_star(
                AcousticSide {
                    u: vln,
                    s: tln,
                    z: zl_long,
                },
                AcousticSide {
                    u: vrn,
                    s: trn,
                    z: zr_long,
                },
            )
        },
    )
}

/// The vector star state of [`acoustic_star_vector`] with the longitudinal problem solved
/// by `longitudinal(u_l, s_l, u_r, s_r) -> (u*, s*)` (normal velocities and tractions,
/// tension positive) and the transverse one acoustically with the impedances `z*_trans`.
///
/// Lane twin: `star_vector` in `core/src/simd/riemann.rs` (held bitwise equal through the star tests,
/// `schemes/star_tests.rs`).
#[inline(always)]
#[allow(clippy::too_many_arguments)]
pub fn elastic_star_vector<const D: usize>(
    n: &Vector<D>,
    v_l: &Vector<D>,
    t_l: &Vector<D>,
    zl_trans: Real,
    v_r: &Vector<D>,
    t_r: &Vector<D>,
    zr_trans: Real,
    longitudinal: impl FnOnce(Real, Real, Real, Real) -> (Real, Real),
) -> (Vector<D>, Vector<D>) {
    let (vln, tln, vrn, trn) = (v_l.dot(n), t_l.dot(n), v_r.dot(n), t_r.dot(n));
    let (u_n, s_n) = longitudinal(vln, tln, vrn, trn);
    let (vlt, tlt) = (v_l - n * vln, t_l - n * tln);
    let (vrt, trt) = (v_r - n * vrn, t_r - n * trn);
    let zs = zl_trans + zr_trans;
    let (v_t, t_t) = if zs > 0.0 && zs.is_finite() {
        let inv = 1.0 / zs;
        (
            (vlt * zl_trans + vrt * zr_trans + trt - tlt) * inv,
            (tlt * zr_trans + trt * zl_trans + (vrt - vlt) * (zl_trans * zr_trans)) * inv,
        )
    } else {
        ((vlt + vrt) * 0.5, Vector::<D>::zeros())
    };
    (n * u_n + v_t, n * s_n + t_t)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Matrix;

    fn side(u: Real, s: Real, z: Real) -> AcousticSide {
        AcousticSide { u, s, z }
    }
    fn close(a: Real, b: Real, scale: Real) -> bool {
        (a - b).abs() <= 1e-12 * scale
    }
    use crate::math::Lcg;

    #[test]
    fn symmetric_collision_is_compressive() {
        let (z, u) = (7.8e3 * 5.0e3, 100.0);
        let (us, ss) = acoustic_star(side(u, 0.0, z), side(-u, 0.0, z));
        assert_eq!(us, 0.0);
        assert!(close(ss, -z * u, z * u));
        let (up, pp) = pressure_star(
            PressureSide { u, p: 0.0, z },
            PressureSide { u: -u, p: 0.0, z },
        );
        assert_eq!(up, 0.0);
        assert!(close(pp, z * u, z * u));
    }

    #[test]
    fn galilean_invariance_and_swap_symmetry() {
        let mut g = Lcg(1);
        for _ in 0..200 {
            let l = side(300.0 * g.next(), 1e9 * g.next(), 4e7 * (1.1 + g.next()));
            let r = side(300.0 * g.next(), 1e9 * g.next(), 4e7 * (1.1 + g.next()));
            let (us, ss) = acoustic_star(l, r);
            let w = 500.0 * g.next();
            let (uw, sw) = acoustic_star(side(l.u + w, l.s, l.z), side(r.u + w, r.s, r.z));
            assert!(close(uw, us + w, 1e3) && close(sw, ss, 1e10));
            let (u2, s2) = acoustic_star(side(-r.u, r.s, r.z), side(-l.u, l.s, l.z));
            assert!(close(u2, -us, 1e3) && close(s2, ss, 1e10));
        }
    }

    #[test]
    fn degenerate_impedances_stay_finite() {
        // free surface on the left: traction of the left side is kept
        let (u, s) = acoustic_star(side(1.0, 0.0, 0.0), side(2.0, -5.0, 10.0));
        assert!(close(s, 0.0, 1.0) && close(u, 2.0 - 0.5, 1.0));
        let (u, s) = acoustic_star(side(1.0, 2.0, 0.0), side(3.0, 4.0, 0.0));
        assert_eq!((u, s), (2.0, 3.0));
    }

    /// d'Alembert: u(x,t) = [u0(x-ct)+u0(x+ct)]/2 + [s0(x+ct)-s0(x-ct)]/(2 rho c),
    /// s(x,t) = [s0(x-ct)+s0(x+ct)]/2 + rho c [u0(x+ct)-u0(x-ct)]/2, for one material.
    #[test]
    fn matches_dalembert_solution_of_a_homogeneous_riemann_problem() {
        let (rho, c) = (2700.0, 6000.0);
        let (ul, sl, ur, sr) = (120.0, -2e8, -30.0, 5e7);
        let u0 = |x: Real| if x < 0.0 { ul } else { ur };
        let s0 = |x: Real| if x < 0.0 { sl } else { sr };
        let (us, ss) = acoustic_star(side(ul, sl, rho * c), side(ur, sr, rho * c));
        let t = 1e-6;
        for x in [-0.9 * c * t, -0.3 * c * t, 0.0, 0.5 * c * t, 0.99 * c * t] {
            let (a, b) = (x - c * t, x + c * t);
            let u = 0.5 * (u0(a) + u0(b)) + (s0(b) - s0(a)) / (2.0 * rho * c);
            let s = 0.5 * (s0(a) + s0(b)) + 0.5 * rho * c * (u0(b) - u0(a));
            assert!(
                close(u, us, 1e3) && close(s, ss, 1e9),
                "x = {x}: {u} {s} vs {us} {ss}"
            );
        }
    }

    /// Two materials: a staggered leap-frog grid at Courant number one on each side (exact
    /// transport in each homogeneous part) with a lumped interface node. The jump excites
    /// the odd-even (period-2) mode of the grid, so the interface velocity and the stresses
    /// next to it alternate between two values whose mean is the star state.
    #[test]
    fn matches_staggered_grid_solution_of_a_bimaterial_riemann_problem() {
        const N: usize = 400; // nodes; interface at node N/2
        let (rl, cl, rr, cr) = (8900.0, 4700.0, 2700.0, 6300.0);
        let (ul, sl, ur, sr) = (200.0, -1e8, -50.0, 3e8);
        let dt = 1e-9;
        let (dxl, dxr) = (cl * dt, cr * dt);
        let m = N / 2;
        let mut u = [0.0; N];
        let mut s = [0.0; N - 1]; // cell k between nodes k and k+1
        for (k, uk) in u.iter_mut().enumerate() {
            *uk = if k < m {
                ul
            } else if k > m {
                ur
            } else {
                0.5 * (ul + ur)
            };
        }
        for (k, sk) in s.iter_mut().enumerate() {
            *sk = if k < m { sl } else { sr };
        }
        let node_mass = |k: usize| -> Real {
            if k < m {
                rl * dxl
            } else if k > m {
                rr * dxr
            } else {
                0.5 * (rl * dxl + rr * dxr)
            }
        };
        let (mut u_sum, mut s_sum) = (0.0, 0.0);
        for step in 0..120 {
            for k in 1..N - 1 {
                u[k] += dt * (s[k] - s[k - 1]) / node_mass(k);
            }
            for (k, sk) in s.iter_mut().enumerate() {
                let (rho, c, dx) = if k < m { (rl, cl, dxl) } else { (rr, cr, dxr) };
                *sk += dt * rho * c * c * (u[k + 1] - u[k]) / dx;
            }
            if step >= 118 {
                u_sum += 0.5 * u[m];
                s_sum += 0.25 * (s[m - 1] + s[m]);
            }
        }
        let (us, ss) = acoustic_star(side(ul, sl, rl * cl), side(ur, sr, rr * cr));
        assert!((u_sum - us).abs() < 1e-9 * 250.0, "{u_sum} vs {us}");
        assert!((s_sum - ss).abs() < 1e-9 * 4e9, "{s_sum} vs {ss}");
    }

    fn rot2(a: Real) -> Matrix<2> {
        Matrix::<2>::new(a.cos(), -a.sin(), a.sin(), a.cos())
    }
    fn rot3(a: Real, b: Real, c: Real) -> Matrix<3> {
        let rz =
            |t: Real| Matrix::<3>::new(t.cos(), -t.sin(), 0., t.sin(), t.cos(), 0., 0., 0., 1.);
        let rx =
            |t: Real| Matrix::<3>::new(1., 0., 0., 0., t.cos(), -t.sin(), 0., t.sin(), t.cos());
        rz(a) * rx(b) * rz(c)
    }

    fn check_vector<const D: usize>(g: &mut Lcg, rot: Matrix<D>) {
        let rv = |g: &mut Lcg, a: Real| Vector::<D>::from_fn(|_, _| a * g.next());
        let n = rv(g, 1.0).normalize();
        let (vl, tl, vr, tr) = (rv(g, 100.0), rv(g, 1e8), rv(g, 100.0), rv(g, 1e8));
        let (zl, zlt, zr, zrt) = (4e7, 2e7, 1.7e7, 0.8e7);
        let (vs, ts) = acoustic_star_vector(&n, &vl, &tl, zl, zlt, &vr, &tr, zr, zrt);
        // normal part = scalar solver along n
        let (us, ss) = acoustic_star(
            side(vl.dot(&n), tl.dot(&n), zl),
            side(vr.dot(&n), tr.dot(&n), zr),
        );
        assert!(close(vs.dot(&n), us, 1e3) && close(ts.dot(&n), ss, 1e9));
        // frame rotation: solving rotated data gives the rotated answer
        let q = |x: &Vector<D>| rot * x;
        let (vq, tq) =
            acoustic_star_vector(&q(&n), &q(&vl), &q(&tl), zl, zlt, &q(&vr), &q(&tr), zr, zrt);
        assert!((vq - q(&vs)).norm() < 1e-11 * 1e3 && (tq - q(&ts)).norm() < 1e-11 * 1e9);
        // swap i and j: n -> -n, t -> -t
        let m = -n;
        let (v2, t2) = acoustic_star_vector(&m, &vr, &(-tr), zr, zrt, &vl, &(-tl), zl, zlt);
        assert!((v2 - vs).norm() < 1e-11 * 1e3 && (t2 + ts).norm() < 1e-11 * 1e9);
        // fluid pair: mean tangential velocity, no tangential traction
        let (vf, tf) = acoustic_star_vector(&n, &vl, &tl, zl, 0.0, &vr, &tr, zr, 0.0);
        let tang = |x: Vector<D>| x - n * x.dot(&n);
        assert!((tang(vf) - tang(vl + vr) * 0.5).norm() < 1e-9 && tang(tf).norm() < 1e-3);
        assert!(vf.iter().chain(tf.iter()).all(|x| x.is_finite()));
    }

    #[test]
    fn vector_form_reduces_to_scalar_and_is_frame_invariant() {
        let mut g = Lcg(7);
        for _ in 0..50 {
            let a = 3.0 * g.next();
            check_vector::<2>(&mut g, rot2(a));
            let (a, b, c) = (3.0 * g.next(), 3.0 * g.next(), 3.0 * g.next());
            check_vector::<3>(&mut g, rot3(a, b, c));
            check_vector::<1>(&mut g, Matrix::<1>::new(-1.0));
        }
    }

    #[test]
    fn vector_tangential_part_matches_scalar_transverse_solve() {
        let n = Vector::<2>::new(1.0, 0.0);
        let (vl, tl) = (Vector::<2>::new(10.0, 5.0), Vector::<2>::new(-1e8, 3e7));
        let (vr, tr) = (Vector::<2>::new(-4.0, -2.0), Vector::<2>::new(2e7, -1e7));
        let (vs, ts) = acoustic_star_vector(&n, &vl, &tl, 4e7, 2e7, &vr, &tr, 3e7, 1e7);
        let (ut, st) = acoustic_star(side(5.0, 3e7, 2e7), side(-2.0, -1e7, 1e7));
        assert!(close(vs[1], ut, 10.0) && close(ts[1], st, 1e8));
    }
}
