//! `options.specific_volume = "interpolated"`: the specific volumes of the contact
//! family's pair force interpolated along the pair, after Sugiura & Inutsuka (J. Comput.
//! Phys. 2016, "An extension of Godunov SPH: application to negative pressure media";
//! 2017, "... II: application to elastic dynamics"), who build on Inutsuka (2002).
//!
//! The seeds' pair force carries `1/(rho_i rho_j)`. Godunov SPH (Inutsuka 2002) carries
//! instead `V_ij^2 = <V(s)^2>`, the mean of the squared specific volume `V = 1/rho`
//! along the pair line under the product of the two particles' kernels, a Gaussian
//! about the pair's midpoint with `<s^2> = mu`; with `V` a cubic
//! `A s^3 + B s^2 + C s + D` (`s` from the midpoint towards `i`) the Gaussian moments
//! `<s^4> = 3 mu^2`, `<s^6> = 15 mu^3` give
//!
//! `V_ij^2 = 15 A^2 mu^3 + 3 (2 A C + B^2) mu^2 + (2 B D + C^2) mu + D^2`.
//!
//! Linear (`A = B = 0`, `C = (V_i - V_j)/ds`, `D = (V_i + V_j)/2`) through the two values
//! where the pair is compressed; cubic through the values and the slopes `V'_i`, `V'_j`
//! along the pair where it is stretched (Sugiura & Inutsuka choose the order by the sign
//! of the pair's pressure; here the normal traction of the pair's Riemann solution). The
//! slopes come from the plain kernel sum `grad rho_i = sum_j m_j grad W_ij` as in
//! Inutsuka (2002) ([`specific_volume_pass`]). gsph's kernels are not Gaussians: `mu` is
//! the Gaussian's of the same second moment, a quarter of the kernel's per-coordinate
//! variance `<r^2>/D` ([`crate::kernel::Kernel::second_moment`]) times `h_i h_j`.
//!
//! The force and the power of a pair carry the same factor, so momentum and (tkc's
//! total) energy are conserved as before. What it does to the tensile instability is
//! measured in docs/elastic.md; `scripts/tensile_modes.py` is the linear analysis.

use crate::exec::Executor;
use crate::math::Real;
use crate::schemes::pairs::for_each_pair;
use crate::schemes::workspace::StepParams;
use crate::state::{Gradients, PairGeom, System};

/// `V_ij^2` of a pair at distance `ds` with specific volumes `vi`, `vj`, their slopes
/// `vpi`, `vpj` along the pair (towards `i`) and the kernel width `mu = <s^2>`: cubic
/// when `cubic`, else linear (module doc).
#[inline(always)]
pub(super) fn pair_v2(
    vi: Real,
    vj: Real,
    vpi: Real,
    vpj: Real,
    ds: Real,
    mu: Real,
    cubic: bool,
) -> Real {
    if !cubic {
        let c = (vi - vj) / ds;
        let d = 0.5 * (vi + vj);
        return d * d + c * c * mu;
    }
    let (dv, sp, dp) = (vi - vj, vpi + vpj, vpi - vpj);
    let a = (sp - 2.0 * dv / ds) / (ds * ds);
    let b = dp / (2.0 * ds);
    let c = 1.5 * dv / ds - 0.25 * sp;
    let d = 0.5 * (vi + vj) - dp * ds / 8.0;
    ((15.0 * a * a * mu + 3.0 * (2.0 * a * c + b * b)) * mu + (2.0 * b * d + c * c)) * mu + d * d
}

/// The specific volume's gradient by the plain kernel sum into [`Gradients::sv`]:
/// `-(1/rho_i^2) sum_j m_j grad W_ij`.
pub(super) fn specific_volume_pass<const D: usize, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    grad: &mut [Gradients<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    exec.run(grad, |off, chunk: &mut [Gradients<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let mut g = crate::math::Vector::<D>::zeros();
            for_each_pair(params, geom, i, |pr, _| {
                g += pr.grad * sys.m[pr.j];
            });
            let inv = 1.0 / sys.rho[i];
            out.sv = g * -(inv * inv);
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closed form is the Gaussian average of the squared cubic through both values
    /// and slopes: compared with a quadrature of `V(s)^2` against the Gaussian of
    /// variance `mu` (the cubic's coefficients found independently, by solving the four
    /// conditions), and the linear form with that of the chord.
    #[test]
    fn the_pair_average_is_the_gaussian_mean_of_the_interpolant_squared() {
        let (vi, vj, vpi, vpj, ds, mu) = (1.3, 0.9, 0.7, -2.1, 0.8, 0.15);
        // V(s) = a s^3 + b s^2 + c s + d with V(+-ds/2) = vi, vj and V'(+-ds/2) = vpi, vpj
        let h = ds / 2.0;
        let m = [
            [h * h * h, h * h, h, 1.0, vi],
            [-h * h * h, h * h, -h, 1.0, vj],
            [3.0 * h * h, 2.0 * h, 1.0, 0.0, vpi],
            [3.0 * h * h, -2.0 * h, 1.0, 0.0, vpj],
        ];
        let coef = solve4(m);
        let mean = |f: &dyn Fn(Real) -> Real| {
            let (n, lim) = (20000, 12.0 * crate::math::real::sqrt(mu));
            let dx = 2.0 * lim / n as Real;
            let mut s = 0.0;
            for k in 0..=n {
                let x = -lim + k as Real * dx;
                let w = if k == 0 || k == n { 0.5 } else { 1.0 };
                s += w * f(x) * crate::math::real::exp(-x * x / (2.0 * mu));
            }
            s * dx / crate::math::real::sqrt(2.0 * crate::math::PI * mu)
        };
        let cubic = |x: Real| {
            let v = ((coef[0] * x + coef[1]) * x + coef[2]) * x + coef[3];
            v * v
        };
        let got = pair_v2(vi, vj, vpi, vpj, ds, mu, true);
        assert!((got - mean(&cubic)).abs() < 1e-10 * got, "{got}");
        let chord = |x: Real| {
            let v = 0.5 * (vi + vj) + (vi - vj) / ds * x;
            v * v
        };
        let lin = pair_v2(vi, vj, vpi, vpj, ds, mu, false);
        assert!((lin - mean(&chord)).abs() < 1e-10 * lin, "{lin}");
        // a uniform state: both give V^2
        assert_eq!(pair_v2(0.5, 0.5, 0.0, 0.0, ds, mu, true), 0.25);
        assert_eq!(pair_v2(0.5, 0.5, 0.0, 0.0, ds, mu, false), 0.25);
    }

    /// Seen from j (the pair line reversed: the slopes change sign and swap) the pair has
    /// the same `V_ij^2`, so the pair force stays antisymmetric.
    #[test]
    fn the_pair_average_is_the_same_from_either_side() {
        let (vi, vj, vpi, vpj, ds, mu) = (1.3, 0.9, 0.7, -2.1, 0.8, 0.15);
        for cubic in [true, false] {
            let a = pair_v2(vi, vj, vpi, vpj, ds, mu, cubic);
            let b = pair_v2(vj, vi, -vpj, -vpi, ds, mu, cubic);
            assert!((a - b).abs() < 1e-14 * a, "{cubic}: {a} {b}");
        }
    }

    /// Gaussian elimination with partial pivoting of a 4x4 system (augmented rows).
    fn solve4(mut m: [[Real; 5]; 4]) -> [Real; 4] {
        for c in 0..4 {
            let p = (c..4)
                .max_by(|&a, &b| m[a][c].abs().partial_cmp(&m[b][c].abs()).unwrap())
                .unwrap();
            m.swap(c, p);
            for r in 0..4 {
                if r != c {
                    let f = m[r][c] / m[c][c];
                    for k in c..5 {
                        m[r][k] -= f * m[c][k];
                    }
                }
            }
        }
        core::array::from_fn(|r| m[r][4] / m[r][r])
    }
}
