//! The gradients of the time-split family at the start of a step (MUSCL slopes, the
//! correction matrix and the free-surface divergence rule).

use crate::effects::Effects;
use crate::exec::{Executor, Optional};
use crate::math::{det, inverse, Matrix, Real};
use crate::schemes::common::{failed, min_sym_eigenvalue, outer, pair_pressure};
use crate::schemes::pairs::for_each_pair;
use crate::schemes::workspace::StepParams;
use crate::state::{Aux, Gradients, PairGeom, PairSums, System};

/// Gradients at the start of the step: the velocity gradient
/// `dv_a/dx_b = sum_j V_j (v_j - v_i)_a (grad_i W_ij)_b` (for the deviator) and, with MUSCL,
/// grad rho and grad P for the reconstruction; also records the start-of-step velocity,
/// and whether the particle is a free-surface particle of the continuity equation (see
/// [`continuity_pass`]; [`PairSums::set_surface`]).
pub(super) fn front_gradient_pass<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    geom: &[PairGeom<D>],
    aux: &[Aux],
    sums: &mut [PairSums<D>],
    grad: &mut [Gradients<D>],
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let (lam, eps) = (params.options.surface_lambda, params.options.det_epsilon);
    exec.run(
        (&mut *sums, Optional(grad)),
        |off, (chunk, g): (&mut [PairSums<D>], Optional<'_, Gradients<D>>)| {
            for (k, out) in chunk.iter_mut().enumerate() {
                let i = off + k;
                let vi = sys.v[i];
                out.v0 = vi;
                let mut gr = Gradients::<D>::default();
                let mut m = Matrix::<D>::zeros();
                let pi = pair_pressure::<D, E>(sys, i);
                for_each_pair(params, geom, i, |pr, _| {
                    let j = pr.j;
                    let gw = pr.grad * aux[j].vol;
                    m += outer(&gw, &(pr.n * pr.r));
                    if E::STRENGTH || E::MUSCL {
                        gr.v += outer(&(sys.v[j] - vi), &gw);
                    }
                    if E::MUSCL {
                        gr.rho += gw * (sys.rho[j] - sys.rho[i]);
                        gr.p += gw * (pair_pressure::<D, E>(sys, j) - pi);
                    }
                });
                out.set_surface(surface_divergence(&m, lam, eps) && !failed::<D, E>(sys, i));
                out.grad_v = gr.v;
                if E::MUSCL {
                    g.0[k] = gr;
                }
            }
        },
    );
}

/// True when a particle with `M = sum_j V_j grad_i W_ij ⊗ (x_j - x_i)` takes the consistent
/// divergence (seed 004's free-surface criterion; see [`continuity_pass`]).
#[inline(always)]
pub(super) fn surface_divergence<const D: usize>(m: &Matrix<D>, lam: Real, eps: Real) -> bool {
    min_sym_eigenvalue(m) < lam && det(m) >= eps && inverse(m).is_some()
}
