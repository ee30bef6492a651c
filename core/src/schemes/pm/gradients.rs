//! The kernel gradient correction and the MUSCL gradients of the contact family (passes
//! over the pairs before the Riemann problems).

use crate::effects::Effects;
use crate::exec::{Executor, Optional};
use crate::math::{det, inverse, Matrix, Real, Sym3, Vector};
use crate::schemes::common::{cauchy, min_sym_eigenvalue, open_neighbourhood, outer};
use crate::schemes::pairs::{for_each_pair, Pair};
use crate::schemes::workspace::StepParams;
use crate::state::{Aux, Correction, Gradients, PairGeom, PairSums, System};

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

/// `L = sum V_j grad_i W_ij ⊗ (x_j - x_i)` (with `x_j - x_i = r n`) of neighbour `pr` of
/// volume `vol`, added to `l`.
#[inline(always)]
fn add_l<const D: usize>(l: &mut Matrix<D>, pr: &Pair<D>, vol: Real) {
    *l += outer(&(pr.grad * vol), &(pr.n * pr.r));
}

/// Particle i's kernel correction from its uncorrected `L`, before the near-surface rule
/// ([`near_surface`]): the smallest eigenvalue of `L`, flag 2 where it is below
/// `surface_lambda` (and, with `surface_scan`, the neighbourhood is open), and `L^-1`
/// (the identity where `det L < det_epsilon`).
fn classify<const D: usize>(
    l: &Matrix<D>,
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    i: usize,
    params: &StepParams<'_, D>,
) -> Correction<D> {
    let lam_min = min_sym_eigenvalue(l);
    let open = lam_min < params.options.surface_lambda
        && (!params.options.surface_scan || open_neighbourhood(params, geom, aux, i, sys.h[i]));
    Correction {
        lambda_min: lam_min,
        boundary: if open { 2 } else { 0 },
        l_inv: match inverse(l) {
            Some(inv) if det(l) >= params.options.det_epsilon => inv,
            _ => Matrix::<D>::identity(),
        },
    }
}

/// Seed 004's near-surface rule, first half: marks (with [`PairSums::set_surface`]) every
/// particle that is a boundary particle or has one within its smoothing length, up to
/// [`NEAR_SURFACE_TOLERANCE`]. [`apply_near_surface`] is the second half.
fn near_surface<const D: usize, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    corr: &[Correction<D>],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let within = 1.0 + NEAR_SURFACE_TOLERANCE;
    exec.run(sums, |off, chunk: &mut [PairSums<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let mut near = corr[i].boundary == 2;
            if !near {
                // the flag first: the distance (the same seen from either side) is read
                // only for the few boundary neighbours
                let reach = sys.h[i] * within;
                params.nbrs.for_each(i, |e| {
                    if corr[e.j].boundary == 2 {
                        let r = geom[e.pair].r;
                        near |= r > 0.0 && r <= reach;
                    }
                });
            }
            out.set_surface(near);
        }
    });
}

/// A marked particle ([`near_surface`]) uses `L = I` (flag 1 unless it is a boundary
/// particle itself).
#[inline(always)]
fn apply_near_surface<const D: usize>(c: &mut Correction<D>, near: bool) {
    if near {
        if c.boundary == 0 {
            c.boundary = 1;
        }
        c.l_inv = Matrix::<D>::identity();
    }
}

/// Kernel correction: L_i, its inverse and the free-surface flags (2: smallest
/// eigenvalue of L below `surface_lambda`; 1: a flag-2 particle within `h_i`, up to
/// [`NEAR_SURFACE_TOLERANCE`]; 0 otherwise). With MUSCL [`gradient_pass`] computes the
/// same with the gradients.
pub(crate) fn correction_pass<const D: usize, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    corr: &mut [Correction<D>],
    sums: &mut [PairSums<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    exec.run(&mut *corr, |off, chunk: &mut [Correction<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let mut l = Matrix::<D>::zeros();
            for_each_pair(params, geom, i, |pr, _| add_l(&mut l, pr, aux[pr.j].vol));
            *out = classify(&l, sys, geom, aux, i, params);
        }
    });
    near_surface::<D, X>(sys, geom, corr, sums, params, exec);
    let s: &[PairSums<D>] = sums;
    exec.run(corr, |off, chunk: &mut [Correction<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            apply_near_surface(out, s[off + k].surface());
        }
    });
}

/// The spin `W = (G L^-T - (G L^-T)^T)/2` from `G = sum V_j (v_j - v_i) ⊗ grad W` and
/// `L = sum V_j grad W ⊗ (x_j - x_i)`, both uncorrected: an affine velocity field
/// `v = v0 + A x` has `G = A L^T`, so `G L^-T = A` whatever the neighbourhood (a free
/// surface included) as long as `det L >= eps`; below that (a particle with too few
/// neighbours to span the plane) no spin is known and zero is returned, so its pairs'
/// transverse problems see the whole velocity jump, as without `options.objective`.
fn spin<const D: usize>(g: &Matrix<D>, l: &Matrix<D>, eps: Real) -> Matrix<D> {
    match inverse(l) {
        Some(inv) if det(l) >= eps => {
            let a = g * inv.transpose();
            (a - a.transpose()) * 0.5
        }
        _ => Matrix::<D>::zeros(),
    }
}

/// The sums behind a particle's spin ([`Gradients::w`], [`spin`]), for `pm` without MUSCL.
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
        self.g += outer(dv, &(pr.grad * vol));
        add_l(&mut self.l, pr, vol);
    }

    /// [`spin`] of the sums.
    pub(super) fn spin(&self, eps: Real) -> Matrix<D> {
        spin(&self.g, &self.l, eps)
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

/// Gradients of the reconstructed quantities and, with `E::CORRECTION`, the kernel
/// correction of [`correction_pass`], in one pass over the pairs: the sums are taken
/// uncorrected (`sum V_j (phi_j - phi_i) grad W`) beside `L`, and multiplied by the
/// particle's correction matrix `M` once the near-surface rule is known
/// (`sum V_j dphi M grad W = M sum V_j dphi grad W`; the same slopes as correcting each
/// kernel gradient, to round-off). With `options.objective` the spin comes from the same
/// uncorrected velocity sum and `L` ([`spin`]).
#[allow(clippy::too_many_arguments)]
pub(crate) fn gradient_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    corr: &mut [Correction<D>],
    sums: &mut [PairSums<D>],
    grad: &mut [Gradients<D>],
    grad_stress: &mut [[Vector<D>; 6]],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let objective = objective::<D, E>(params);
    let eps = params.options.det_epsilon;
    // the pressure's slope also where the star carries the pressure only
    let p_slope = !E::STRENGTH || super::split_stress::<D, E>(params);
    exec.run(
        (
            Optional(&mut *corr),
            (&mut *grad, Optional(&mut *grad_stress)),
        ),
        |off, (c, (g, gs)): (Optional<Correction<D>>, (&mut [Gradients<D>], Optional<_>))| {
            for (k, out) in g.iter_mut().enumerate() {
                let i = off + k;
                let mut acc = Gradients::<D>::default();
                let mut acc_s = [Vector::<D>::zeros(); 6];
                let mut l = Matrix::<D>::zeros();
                let si = cauchy::<D, E>(sys, i).to_array();
                let cti = aux[i].ct;
                for_each_pair(params, geom, i, |pr, _| {
                    let j = pr.j;
                    let vol = aux[j].vol;
                    if E::CORRECTION || objective {
                        add_l(&mut l, pr, vol);
                    }
                    let gw = pr.grad * vol;
                    acc.rho += gw * (sys.rho[j] - sys.rho[i]);
                    if p_slope {
                        // the pressure's slope reconstructs the traction without strength
                        // and where the star carries the pressure only (`pair_star`);
                        // otherwise the stress slopes do
                        acc.p += gw * (sys.p[j] - sys.p[i]);
                    }
                    acc.cl += gw * (sys.cl[j] - sys.cl[i]);
                    acc.ct += gw * (aux[j].ct - cti);
                    acc.v += outer(&(sys.v[j] - sys.v[i]), &gw);
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
                    acc.w = spin(&acc.v, &l, eps);
                }
                if E::CORRECTION {
                    c.0[k] = classify(&l, sys, geom, aux, i, params);
                }
                *out = acc;
                if E::STRENGTH {
                    gs.0[k] = acc_s;
                }
            }
        },
    );
    if !E::CORRECTION {
        return;
    }
    near_surface::<D, X>(sys, geom, corr, sums, params, exec);
    let s: &[PairSums<D>] = sums;
    // with `options.corrected_slopes` the slopes keep the full `L^-1` at the surface too
    // (a slope of a linear field is then exact there as inside; the forces keep the rule)
    let full = params.options.corrected_slopes;
    exec.run(
        (corr, (grad, Optional(grad_stress))),
        |off, (c, (g, gs)): (&mut [Correction<D>], (&mut [Gradients<D>], Optional<_>))| {
            for (k, out) in c.iter_mut().enumerate() {
                let l_inv = out.l_inv;
                apply_near_surface(out, s[off + k].surface());
                let m = if full { l_inv } else { out.l_inv };
                let gk = &mut g[k];
                gk.rho = m * gk.rho;
                if p_slope {
                    gk.p = m * gk.p;
                }
                gk.cl = m * gk.cl;
                gk.ct = m * gk.ct;
                gk.v *= m.transpose();
                if E::STRENGTH {
                    for a in 0..D {
                        for b in a..D {
                            let v = &mut gs.0[k][Sym3::voigt(a, b)];
                            *v = m * *v;
                        }
                    }
                }
            }
        },
    );
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
