//! Monaghan's artificial stress against the tensile instability (Monaghan 2000; Gray,
//! Monaghan & Swift 2001, "SPH elastic dynamics", CMAME 190, eqs 4.6–4.9), the effect
//! `artificial_stress`.
//!
//! In tension, SPH particles clump in pairs: the pair force of a stretched lattice pulls
//! neighbours together where the kernel gradient should push them apart. Gray et al. add
//! to the pair force a small repulsive stress that grows as a pair comes closer than the
//! lattice spacing:
//!
//! ```text
//! dv_i/dt += sum_j m_j f_ij^n (R_i + R_j) . grad_i W_ij,     f_ij = W(r_ij) / W(dp),
//! R_i = Q diag(r_1, r_2, ..) Q^T,   r_k = -eps sigma_k / rho_i²  if sigma_k > 0, else 0,
//! ```
//!
//! with `sigma_k` the principal stresses of the Cauchy stress of particle i (its in-plane
//! `D x D` block in 2D plane strain), `Q` their directions, `dp` the mean particle spacing
//! and (their values) `eps = 0.3`, `n = 4`. With the smoothing length tied to the
//! spacing by `h = h_factor dp`, `W(r, h)/W(dp, h) = f(r/h)/f(1/h_factor)` with the
//! kernel's shape `f` ([`crate::kernel::Kernel::shape_value`]): the reference is the mean
//! spacing for any resolution and smoothing length (with a constant `h` it is `W(r)/W(dx)`
//! exactly). The force is antisymmetric in i, j, so momentum stays conserved; each scheme
//! books its work in the internal energy the way it books the stress's (see the schemes),
//! so total energy is conserved as before. Its parameters are the scheme options
//! `artificial_stress` (epsilon, 0.3 in Gray et al.) and `artificial_stress_exponent` (n, 4).

use crate::kernel::Kernel;
use crate::math::{real, Matrix, Real, Sym3, Vector};

/// `r_k` of one principal stress.
#[inline(always)]
fn principal(sigma: Real, eps_over_rho2: Real) -> Real {
    if sigma > 0.0 {
        -eps_over_rho2 * sigma
    } else {
        0.0
    }
}

/// `R_i` of a particle with Cauchy stress `sigma` (tension positive) and density `rho`:
/// the tensile principal stresses of the `D x D` block, scaled by `-eps/rho²`.
pub fn tensor<const D: usize>(sigma: &Sym3, rho: Real, eps: Real) -> Matrix<D> {
    let k = eps / (rho * rho);
    match D {
        1 => Matrix::<D>::from_fn(|_, _| principal(sigma.xx, k)),
        2 => {
            let (a, b, c) = (sigma.xx, sigma.yy, sigma.xy);
            let mean = 0.5 * (a + b);
            let rad = real::sqrt(0.25 * (a - b) * (a - b) + c * c);
            let (r1, r2) = (principal(mean + rad, k), principal(mean - rad, k));
            if r1 == r2 {
                return Matrix::<D>::identity() * r1;
            }
            // direction (cos t, sin t) of the larger principal stress, without
            // trigonometry: cos 2t = (a - b)/(2 rad), sin 2t = c/rad, so cos² t = (1 +
            // cos 2t)/2, sin² t = (1 - cos 2t)/2, cos t sin t = sin 2t / 2 (rad > 0 here:
            // r1 != r2 needs distinct principal stresses)
            let (c2t, s2t) = (0.5 * (a - b) / rad, c / rad);
            let (cc, ss, cs) = (0.5 * (1.0 + c2t), 0.5 * (1.0 - c2t), 0.5 * s2t);
            let (xx, yy, xy) = (r1 * cc + r2 * ss, r1 * ss + r2 * cc, (r1 - r2) * cs);
            Matrix::<D>::from_fn(|p, q| match (p, q) {
                (0, 0) => xx,
                (1, 1) => yy,
                _ => xy,
            })
        }
        _ => {
            let (vals, vecs) = symmetric_eigen3(sigma);
            let r = [
                principal(vals[0], k),
                principal(vals[1], k),
                principal(vals[2], k),
            ];
            Matrix::<D>::from_fn(|p, q| {
                (0..3)
                    .map(|m| r[m] * vecs[p][m] * vecs[q][m])
                    .fold(0.0, |s, t| s + t)
            })
        }
    }
}

/// Eigenvalues and eigenvectors (columns: `vecs[row][k]` belongs to `vals[k]`) of a
/// symmetric 3x3 tensor, by cyclic Jacobi rotations until the off-diagonal part is below
/// round-off (converges quadratically; at most 16 sweeps).
pub fn symmetric_eigen3(s: &Sym3) -> ([Real; 3], [[Real; 3]; 3]) {
    let mut a = [[s.xx, s.xy, s.xz], [s.xy, s.yy, s.yz], [s.xz, s.yz, s.zz]];
    let mut v = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    let scale = real::abs(s.xx) + real::abs(s.yy) + real::abs(s.zz);
    for _ in 0..16 {
        let off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
        if off <= (1e-32 * scale * scale) || off == 0.0 {
            break;
        }
        for (p, q) in [(0usize, 1usize), (0, 2), (1, 2)] {
            if a[p][q] == 0.0 {
                continue;
            }
            let theta = (a[q][q] - a[p][p]) / (2.0 * a[p][q]);
            // the smaller root of t² + 2 theta t - 1 = 0 (t = 1 when theta = 0)
            let t = if theta >= 0.0 { 1.0 } else { -1.0 }
                / (real::abs(theta) + real::sqrt(theta * theta + 1.0));
            let c = 1.0 / real::sqrt(t * t + 1.0);
            let sn = t * c;
            for k in 0..3 {
                let (akp, akq) = (a[k][p], a[k][q]);
                a[k][p] = c * akp - sn * akq;
                a[k][q] = sn * akp + c * akq;
            }
            for k in 0..3 {
                let (apk, aqk) = (a[p][k], a[q][k]);
                a[p][k] = c * apk - sn * aqk;
                a[q][k] = sn * apk + c * aqk;
            }
            for row in v.iter_mut() {
                let (vp, vq) = (row[p], row[q]);
                row[p] = c * vp - sn * vq;
                row[q] = sn * vp + c * vq;
            }
        }
    }
    ([a[0][0], a[1][1], a[2][2]], v)
}

/// The pair's `f_ij^n` for a pair at distance `r` with smoothing length `h_ij`:
/// `(f(r/h_ij) / f(1/h_factor))^n` (module docs).
#[inline(always)]
pub fn pair_factor<const D: usize>(
    kernel: Kernel,
    r: Real,
    h_ij: Real,
    inv_w_ref: Real,
    exponent: u32,
) -> Real {
    let f = kernel.shape_value::<D>(r / h_ij) * inv_w_ref;
    real::powi(f, exponent)
}

/// `1 / f(1/h_factor)`, the reference of [`pair_factor`].
pub fn inverse_reference<const D: usize>(kernel: Kernel, h_factor: Real) -> Real {
    1.0 / kernel.shape_value::<D>(1.0 / h_factor)
}

/// The acceleration `m_j f^n (R_i + R_j) . grad_i W` of a pair.
#[inline(always)]
pub(crate) fn pair_acceleration<const D: usize>(
    m_j: Real,
    fact: Real,
    r_i: &Matrix<D>,
    r_j: &Matrix<D>,
    grad: &Vector<D>,
) -> Vector<D> {
    (r_i + r_j) * grad * (m_j * fact)
}

#[cfg(all(test, not(feature = "f32")))]
mod tests {
    use super::*;

    fn sym(xx: Real, yy: Real, xy: Real) -> Sym3 {
        Sym3::new(xx, yy, 0.0, xy, 0.0, 0.0)
    }

    #[test]
    fn only_tensile_principal_stresses_count() {
        // uniaxial tension along x: R_xx = -eps sigma / rho², nothing across
        let r = tensor::<2>(&sym(2.0e6, -1.0e6, 0.0), 2.0, 0.3);
        assert!((r[(0, 0)] + 0.3 * 2.0e6 / 4.0).abs() < 1e-9);
        assert_eq!(r[(1, 1)], 0.0);
        assert_eq!(r[(0, 1)], 0.0);
        // pure compression: no artificial stress
        assert_eq!(
            tensor::<2>(&sym(-1.0, -2.0, 0.5), 1.0, 0.3),
            Matrix::<2>::zeros()
        );
        assert_eq!(
            tensor::<1>(&sym(-1.0, 0.0, 0.0), 1.0, 0.3),
            Matrix::<1>::zeros()
        );
        assert!((tensor::<1>(&sym(1.0, 0.0, 0.0), 1.0, 0.3)[(0, 0)] + 0.3).abs() < 1e-15);
    }

    #[test]
    fn the_tensor_turns_with_the_stress() {
        // tension s along the diagonal (1, 1)/sqrt 2: sigma = s/2 [[1, 1], [1, 1]]
        let s = 4.0;
        let r = tensor::<2>(&sym(s / 2.0, s / 2.0, s / 2.0), 1.0, 0.5);
        // R = -eps s n n^T
        for (p, q) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            assert!(
                (r[(p, q)] + 0.5 * s * 0.5).abs() < 1e-12,
                "{p}{q} {}",
                r[(p, q)]
            );
        }
        // the same in 3D, about the z axis, with a compressive z
        let sig = Sym3::new(s / 2.0, s / 2.0, -3.0, s / 2.0, 0.0, 0.0);
        let r3 = tensor::<3>(&sig, 1.0, 0.5);
        for (p, q) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
            assert!((r3[(p, q)] + 0.5 * s * 0.5).abs() < 1e-12);
        }
        assert!(r3[(2, 2)].abs() < 1e-12 && r3[(0, 2)].abs() < 1e-12);
    }

    #[test]
    fn jacobi_diagonalises_a_general_symmetric_tensor() {
        let s = Sym3::new(3.0, -1.0, 2.0, 0.7, -0.4, 1.1);
        let (vals, v) = symmetric_eigen3(&s);
        for k in 0..3 {
            // A v_k = lambda_k v_k
            for p in 0..3 {
                let av: Real = (0..3).map(|q| s.get(p, q) * v[q][k]).sum();
                assert!((av - vals[k] * v[p][k]).abs() < 1e-12);
            }
        }
        let tr: Real = vals.iter().sum();
        assert!((tr - s.trace()).abs() < 1e-12);
    }

    #[test]
    fn the_factor_is_one_at_the_spacing_and_falls_off_beyond() {
        let k = Kernel::CubicSpline;
        let (h_factor, dx) = (1.5, 5e-4);
        let h = h_factor * dx;
        let inv = inverse_reference::<2>(k, h_factor);
        let at = |r: Real| pair_factor::<2>(k, r, h, inv, 4);
        assert!((at(dx) - 1.0).abs() < 1e-14);
        assert!(at(0.5 * dx) > 1.0 && at(1.5 * dx) < 1.0);
        assert_eq!(at(2.0 * h), 0.0);
        // W(r)/W(dx) from the kernel values themselves
        let w = |r: Real| k.w::<2>(r, h);
        assert!((at(0.7 * dx) - (w(0.7 * dx) / w(dx)).powi(4)).abs() < 1e-13);
    }
}
