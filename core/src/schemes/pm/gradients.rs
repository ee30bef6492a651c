//! The kernel gradient correction and the MUSCL gradients of the contact family (passes
//! over the pairs before the Riemann problems).

use crate::effects::Effects;
use crate::exec::Executor;
use crate::math::{det, inverse, Matrix, Real, Sym3, Vector};
use crate::schemes::common::{
    cauchy, for_each_pair, min_sym_eigenvalue, open_neighbourhood, outer, Pair,
};
use crate::state::{Aux, Correction, Gradients, PairGeom, PairSums, StepParams, System};

/// Relative tolerance of the near-surface test: a boundary particle at `r <= h (1 + tol)`
/// counts as within the smoothing length `h`.
///
/// Seed 004 sets `L = I` for a particle "with a boundary particle within its smoothing
/// length". At its theta = 0.5 (h_factor 1) the first neighbour shell of a regular lattice
/// lies at exactly `h`, so `r < h` decided by round-off (`5.000000000000004e-4` against
/// `5e-4`) whether the row next to a free surface was flagged, and the answer changed with
/// the resolution. A neighbour at `h` counts as within: then theta = 0.5 flags that row as
/// theta = 0.6–0.7 do. 1e-9 is far above round-off in `r` and `h` and far below any lattice
/// irregularity (a polar lattice's rings differ from `h` by ~1e-4 relative).
pub const NEAR_SURFACE_TOLERANCE: Real = 1e-9;

/// Kernel correction: L_i, its inverse and the free-surface flags (2: smallest
/// eigenvalue of L below `surface_lambda`; 1: a flag-2 particle within `h_i`, up to
/// [`NEAR_SURFACE_TOLERANCE`]; 0 otherwise).
pub(crate) fn correction_pass<const D: usize, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    corr: &mut [Correction<D>],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let lam = params.options.surface_lambda;
    let eps = params.options.det_epsilon;
    exec.run(&mut *corr, |off, chunk: &mut [Correction<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let mut l = Matrix::<D>::zeros();
            for_each_pair(params, geom, i, |pr, _| {
                let vol = aux[pr.j].vol;
                // L = sum V_j grad_i W_ij ⊗ (x_j - x_i), with x_j - x_i = r n
                l += outer(&pr.grad, &(pr.n * pr.r)) * vol;
            });
            let lam_min = min_sym_eigenvalue(&l);
            out.lambda_min = lam_min;
            let open = lam_min < lam
                && (!params.options.surface_scan
                    || open_neighbourhood(params, geom, aux, i, sys.h[i]));
            out.boundary = if open { 2 } else { 0 };
            out.l_inv = match inverse(&l) {
                Some(inv) if det(&l) >= eps => inv,
                _ => Matrix::<D>::identity(),
            };
        }
    });
    // Particles with a boundary particle within their smoothing length use L = I
    // (marked with `PairSums::set_surface`).
    let within = 1.0 + NEAR_SURFACE_TOLERANCE;
    let c: &[Correction<D>] = corr;
    exec.run(&mut *sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let mut near = c[i].boundary == 2;
            let reach = sys.h[i] * within;
            for_each_pair(params, geom, i, |pr, _| {
                if c[pr.j].boundary == 2 && pr.r > 0.0 && pr.r <= reach {
                    near = true;
                }
            });
            out.set_surface(near);
        }
    });
    let s: &[PairSums<D>] = sums;
    exec.run(corr, |off, chunk: &mut [Correction<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            if s[off + k].surface() {
                if out.boundary == 0 {
                    out.boundary = 1;
                }
                out.l_inv = Matrix::<D>::identity();
            }
        }
    });
}

/// The sums behind a particle's spin ([`Gradients::w`]): `G = sum V_j (v_j - v_i) ⊗ grad W`
/// and `L = sum V_j grad W ⊗ (x_j - x_i)`, uncorrected.
#[derive(Clone, Copy)]
pub(super) struct SpinSums<const D: usize> {
    g: Matrix<D>,
    l: Matrix<D>,
}

impl<const D: usize> SpinSums<D> {
    pub(super) fn new() -> Self {
        SpinSums {
            g: Matrix::<D>::zeros(),
            l: Matrix::<D>::zeros(),
        }
    }

    /// Adds neighbour `pr.j` of volume `vol` whose velocity differs by `dv`.
    #[inline(always)]
    pub(super) fn add(&mut self, pr: &Pair<D>, vol: Real, dv: &Vector<D>) {
        let gw = pr.grad * vol;
        self.g += outer(dv, &gw);
        self.l += outer(&gw, &(pr.n * pr.r));
    }

    /// The spin `W = (G L^-T - (G L^-T)^T)/2`: an affine velocity field `v = v0 + A x` has
    /// `G = A L^T`, so `G L^-T = A` whatever the neighbourhood (a free surface included)
    /// as long as `det L >= eps`; below that (a particle with too few neighbours to span
    /// the plane) no spin is known and zero is returned, so its pairs' transverse
    /// problems see the whole velocity jump, as without `options.objective`.
    pub(super) fn spin(&self, eps: Real) -> Matrix<D> {
        match inverse(&self.l) {
            Some(inv) if det(&self.l) >= eps => {
                let a = self.g * inv.transpose();
                (a - a.transpose()) * 0.5
            }
            _ => Matrix::<D>::zeros(),
        }
    }
}

/// The spin of every particle into [`Gradients::w`], for `pm` without MUSCL (with MUSCL
/// [`gradient_pass`] computes it with the other gradients).
pub(super) fn spin_pass<const D: usize, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    grad: &mut [Gradients<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let eps = params.options.det_epsilon;
    exec.run(grad, |off, chunk: &mut [Gradients<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let mut acc = SpinSums::<D>::new();
            for_each_pair(params, geom, i, |pr, _| {
                acc.add(pr, aux[pr.j].vol, &(sys.v[pr.j] - sys.v[i]));
            });
            out.w = acc.spin(eps);
        }
    });
}

/// Gradients of the reconstructed quantities (corrected when `E::CORRECTION`), and the
/// spin with `options.objective`.
#[allow(clippy::too_many_arguments)]
pub(super) fn gradient_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    corr: &[Correction<D>],
    grad: &mut [Gradients<D>],
    grad_stress: &mut [[Vector<D>; 6]],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let objective = objective::<D, E>(params);
    let eps = params.options.det_epsilon;
    exec.run(
        (grad, grad_stress),
        |off, (g, gs): (&mut [Gradients<D>], &mut [[Vector<D>; 6]])| {
            for (k, out) in g.iter_mut().enumerate() {
                let i = off + k;
                let mut acc = Gradients::<D>::default();
                let mut acc_s = [Vector::<D>::zeros(); 6];
                let si = cauchy::<D, E>(sys, i).to_array();
                let cti = aux[i].ct;
                let mut spin = SpinSums::<D>::new();
                let m = if E::CORRECTION {
                    slope_correction(&corr[i], i, aux, geom, params)
                } else {
                    Matrix::<D>::identity()
                };
                for_each_pair(params, geom, i, |pr, _| {
                    let j = pr.j;
                    let vol = aux[j].vol;
                    let gw = if E::CORRECTION { m * pr.grad } else { pr.grad } * vol;
                    acc.rho += gw * (sys.rho[j] - sys.rho[i]);
                    if !E::STRENGTH {
                        // the pressure's slope reconstructs the traction only without
                        // strength (`pair_star`); with it the stress slopes do
                        acc.p += gw * (sys.p[j] - sys.p[i]);
                    }
                    acc.cl += gw * (sys.cl[j] - sys.cl[i]);
                    acc.ct += gw * (aux[j].ct - cti);
                    let dv = sys.v[j] - sys.v[i];
                    acc.v += outer(&dv, &gw);
                    if objective {
                        spin.add(pr, vol, &dv);
                    }
                    if E::STRENGTH {
                        let sj = cauchy::<D, E>(sys, j).to_array();
                        // only the components the pairs read (`pair_star`'s traction
                        // `sigma . axis`, with a D-vector axis, reads (a, b) with a, b < D:
                        // in 2D xx, yy and xy; the slopes of the others stay zero)
                        for a in 0..D {
                            for b in a..D {
                                let c = Sym3::voigt(a, b);
                                acc_s[c] += gw * (sj[c] - si[c]);
                            }
                        }
                    }
                });
                if objective {
                    acc.w = spin.spin(eps);
                }
                *out = acc;
                if E::STRENGTH {
                    gs[k] = acc_s;
                }
            }
        },
    );
}

/// The matrix that corrects particle i's MUSCL slopes: its `L^-1` (the identity near a
/// free surface, seed 004), or with `options.corrected_slopes` the inverse of its full `L`
/// there too, where `det L >= det_epsilon` (a slope of a linear field is then exact at the
/// surface as inside; the forces keep the surface rule).
fn slope_correction<const D: usize>(
    c: &Correction<D>,
    i: usize,
    aux: &[Aux],
    geom: &[PairGeom<D>],
    params: &StepParams<'_, D>,
) -> Matrix<D> {
    if !params.options.corrected_slopes || c.boundary == 0 {
        return c.l_inv;
    }
    let mut l = Matrix::<D>::zeros();
    for_each_pair(params, geom, i, |pr, _| {
        l += outer(&pr.grad, &(pr.n * pr.r)) * aux[pr.j].vol;
    });
    match inverse(&l) {
        Some(inv) if det(&l) >= params.options.det_epsilon => inv,
        _ => c.l_inv,
    }
}

/// Whether the step removes the pairs' rigid rotation from the transverse Riemann problems
/// (`options.objective`; there are transverse problems only with strength and in 2D/3D).
#[inline(always)]
pub(crate) fn objective<const D: usize, E: Effects>(params: &StepParams<'_, D>) -> bool {
    D > 1 && E::STRENGTH && params.options.objective
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The spin of an affine velocity field `v = A x` is `(A - A^T)/2` to round-off, inside
    /// and on a free surface (neighbours on one side only), and zero where the neighbours
    /// cannot span the plane (one row).
    #[test]
    fn the_spin_of_an_affine_field_is_exact_on_a_free_surface_too() {
        let a = Matrix::<2>::new(0.1, -2.0, 3.0, 0.4);
        let want = (a - a.transpose()) * 0.5;
        let spin_of = |offsets: &[(Real, Real)]| {
            let mut s = SpinSums::<2>::new();
            for (k, &(dx, dy)) in offsets.iter().enumerate() {
                let d = Vector::<2>::new(dx, dy);
                let r = d.norm();
                let n = d / r;
                // any kernel slope: W'(r) < 0
                let dw = -crate::math::real::exp(-r);
                let pr = Pair {
                    j: k,
                    r,
                    n,
                    dw,
                    grad: n * -dw,
                };
                s.add(&pr, 0.7, &(a * d));
            }
            s.spin(1e-12)
        };
        let (mut inside, mut surface) = ([(0.0, 0.0); 20], [(0.0, 0.0); 20]);
        let (mut ni, mut ns) = (0, 0);
        for p in -2i32..=2 {
            for q in -2i32..=2 {
                if (p, q) != (0, 0) && p * p + q * q <= 5 {
                    inside[ni] = (p as Real, q as Real);
                    ni += 1;
                    if q >= 0 {
                        surface[ns] = (p as Real, q as Real);
                        ns += 1;
                    }
                }
            }
        }
        assert!((spin_of(&inside[..ni]) - want).norm() < 1e-13);
        assert!((spin_of(&surface[..ns]) - want).norm() < 1e-13);
        let row = [(-2.0, 0.0), (-1.0, 0.0), (1.0, 0.0), (2.0, 0.0)];
        assert_eq!(spin_of(&row), Matrix::<2>::zeros());
    }
}
