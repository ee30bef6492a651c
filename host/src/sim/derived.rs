//! Quantities derived from the particle state for output and the library API, one function
//! per row of the core's [`gsph_core::derived_fields!`] table, named after it: each takes
//! the simulation and returns one value per particle in memory order. They are computed
//! when a table is written or a caller reads them, never by a step.

use super::Sim;
use crate::neighbors::{build, Lists};
use gsph_core::kernel::Kernel;
use gsph_core::math::{det, Matrix, Real, Vector};
use gsph_core::neighbors::Periodic;
use rayon::prelude::*;

/// det F of each particle, F = dx/dx0 the deformation gradient from the reference
/// positions `x0` to the positions now (NaN for wall mirrors and ghosts, and where it is
/// undefined: a particle without neighbours, or whose reference neighbourhood is
/// degenerate, `det A = 0`).
///
/// With `B = sum_j V_j (x_j - x_i) (x) grad_i W_ij` and `A = sum_j V_j (x0_j - x0_i) (x)
/// grad_i W_ij` over the neighbours now (`V_j = m_j / rho_j`, `W_ij` at the mean smoothing
/// length), `A = F^-1 B` holds exactly for an affine motion whatever the neighbourhood (a
/// free surface included): the corrected SPH estimate `F^-1 = A B^-1`, so
/// `det F = det B / det A`. Where the motion keeps mass, `det F = rho0 / rho`; the
/// difference is the volume a scheme's continuity equation has drifted from its
/// positions. Periodic runs take both differences by the minimum image (valid while a
/// particle has moved less than half the box relative to its neighbours).
pub fn det_f<const D: usize>(sim: &Sim<D>) -> Vec<f64> {
    let n = sim.owned;
    let mut out = vec![f64::NAN; sim.len()];
    let state = Positions {
        x: &sim.x[..n],
        x0: &sim.x0[..n],
        m: &sim.m[..n],
        rho: &sim.rho[..n],
        h: &sim.h[..n],
    };
    if let Some(v) = det_f_of(&state, &sim.ids[..n], sim.kernel, &sim.periodic) {
        out[..n].copy_from_slice(&v);
    }
    out
}

/// What [`det_f_of`] reads of each particle.
struct Positions<'a, const D: usize> {
    x: &'a [Vector<D>],
    x0: &'a [Vector<D>],
    m: &'a [Real],
    rho: &'a [Real],
    h: &'a [Real],
}

/// det F of each particle of `s` (see [`det_f`]); `None` if the neighbour search fails.
fn det_f_of<const D: usize>(
    s: &Positions<'_, D>,
    ids: &[u32],
    kernel: Kernel,
    periodic: &Periodic<D>,
) -> Option<Vec<f64>> {
    let mut lists = Lists::default();
    build(
        s.x,
        s.h,
        ids,
        kernel.support(),
        0.0,
        periodic,
        usize::MAX,
        &mut lists,
    )
    .ok()?;
    let rows = lists.view();
    Some(
        (0..s.x.len())
            .into_par_iter()
            .map(|i| {
                let (mut a, mut b) = (Matrix::<D>::zeros(), Matrix::<D>::zeros());
                let row = &rows.index[rows.start[i] as usize..rows.start[i + 1] as usize];
                for &j in row {
                    let j = j as usize;
                    let dx = periodic.min_image(s.x[j] - s.x[i]);
                    let r = dx.norm();
                    if r == 0.0 {
                        continue;
                    }
                    // grad_i W(x_i - x_j) = dW/dr (x_i - x_j) / r
                    let g = kernel.gradient::<D>(&-dx, r, 0.5 * (s.h[i] + s.h[j]));
                    let vol = s.m[j] / s.rho[j];
                    b += dx * g.transpose() * vol;
                    a += periodic.min_image(s.x0[j] - s.x0[i]) * g.transpose() * vol;
                }
                // F is undefined where a neighbourhood does not span D dimensions (a
                // fragment of one particle, a row of particles in 2D): NaN, not 0/0 or inf
                let spans = |m: &Matrix<D>| {
                    let d = det(m);
                    d.is_finite() && d.abs() > 1e-12 * m.norm().powi(D as i32)
                };
                if spans(&a) && spans(&b) {
                    det(&b) / det(&a)
                } else {
                    f64::NAN
                }
            })
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A lattice of `n` particles per axis, spacing `dx`, reference positions `x0`, moved
    /// by `x = f x0 + c`: det F must be det f at every particle, the surface included.
    fn affine<const D: usize>(f: Matrix<D>, n: usize) -> Vec<f64> {
        let dx = 0.1;
        let count = n.pow(D as u32);
        let x0: Vec<Vector<D>> = (0..count)
            .map(|k| Vector::<D>::from_fn(|a, _| ((k / n.pow(a as u32)) % n) as f64 * dx))
            .collect();
        let c = Vector::<D>::from_fn(|a, _| 0.3 - 0.1 * a as f64);
        let x: Vec<Vector<D>> = x0.iter().map(|p| f * p + c).collect();
        let rho0 = 1000.0;
        let m = vec![rho0 * dx.powi(D as i32); count];
        let rho = vec![rho0 / det(&f); count];
        let h = vec![1.3 * dx; count];
        let ids: Vec<u32> = (0..count as u32).collect();
        let s = Positions {
            x: &x,
            x0: &x0,
            m: &m,
            rho: &rho,
            h: &h,
        };
        det_f_of(&s, &ids, Kernel::CubicSpline, &Periodic::none()).unwrap()
    }

    #[test]
    fn det_f_of_an_affine_motion_is_its_determinant_everywhere() {
        let f1 = Matrix::<1>::new(0.8);
        let f2 = Matrix::<2>::new(1.2, 0.3, -0.1, 0.7);
        let f3 = Matrix::<3>::new(0.9, 0.2, 0.0, 0.1, 1.1, -0.3, 0.05, 0.0, 0.75);
        for (got, want) in [
            (affine(f1, 12), det(&f1)),
            (affine(f2, 9), det(&f2)),
            (affine(f3, 6), det(&f3)),
        ] {
            for (i, v) in got.iter().enumerate() {
                assert!(
                    (v - want).abs() < 1e-12 * want,
                    "particle {i}: {v} != {want}"
                );
            }
        }
    }

    #[test]
    fn det_f_is_nan_where_the_neighbourhood_spans_no_area() {
        // a row of particles in 2D: A and B have rank 1
        let x0: Vec<Vector<2>> = (0..5)
            .map(|k| Vector::<2>::new(k as f64 * 0.1, 0.0))
            .collect();
        let (m, rho, h) = (vec![1.0; 5], vec![100.0; 5], vec![0.13; 5]);
        let s = Positions {
            x: &x0,
            x0: &x0,
            m: &m,
            rho: &rho,
            h: &h,
        };
        let ids: Vec<u32> = (0..5).collect();
        let d = det_f_of(&s, &ids, Kernel::CubicSpline, &Periodic::none()).unwrap();
        assert!(d.iter().all(|v| v.is_nan()), "{d:?}");
    }

    #[test]
    fn det_f_of_the_reference_configuration_is_one() {
        for v in affine(Matrix::<2>::identity(), 7) {
            assert!((v - 1.0).abs() < 1e-14, "{v}");
        }
    }
}
