//! The kernel gradient correction and the MUSCL gradients of the contact family (passes
//! over the pairs before the Riemann problems).

use crate::effects::Effects;
use crate::exec::Executor;
use crate::math::{det, inverse, Matrix, Real, Vector};
use crate::schemes::common::{cauchy, for_each_pair, min_sym_eigenvalue, outer};
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
            out.boundary = if lam_min < lam { 2 } else { 0 };
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

/// Gradients of the reconstructed quantities (corrected when `E::CORRECTION`).
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
    exec.run(
        (grad, grad_stress),
        |off, (g, gs): (&mut [Gradients<D>], &mut [[Vector<D>; 6]])| {
            for (k, out) in g.iter_mut().enumerate() {
                let i = off + k;
                let mut acc = Gradients::<D>::default();
                let mut acc_s = [Vector::<D>::zeros(); 6];
                let si = cauchy::<D, E>(sys, i).to_array();
                let cti = aux[i].ct;
                for_each_pair(params, geom, i, |pr, _| {
                    let j = pr.j;
                    let vol = aux[j].vol;
                    let gw = if E::CORRECTION {
                        corr[i].l_inv * pr.grad
                    } else {
                        pr.grad
                    } * vol;
                    acc.rho += gw * (sys.rho[j] - sys.rho[i]);
                    acc.p += gw * (sys.p[j] - sys.p[i]);
                    acc.cl += gw * (sys.cl[j] - sys.cl[i]);
                    acc.ct += gw * (aux[j].ct - cti);
                    acc.v += outer(&(sys.v[j] - sys.v[i]), &gw);
                    if E::STRENGTH {
                        let sj = cauchy::<D, E>(sys, j).to_array();
                        for c in 0..6 {
                            acc_s[c] += gw * (sj[c] - si[c]);
                        }
                    }
                });
                *out = acc;
                if E::STRENGTH {
                    gs[k] = acc_s;
                }
            }
        },
    );
}
