//! The pair interactions of `av`: the rates of every particle from its neighbours.

use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::kernel::Kernel;
use crate::math::real;
use crate::math::{Matrix, Real, Sym3, Vector};
use crate::neighbors::Entry;
use crate::schemes::artificial_stress::pair_acceleration;
use crate::schemes::common::Pair;
use crate::schemes::common::{
    artificial_stress_tensors, cauchy, deviator_rate, equivalent_strain_rate, outer, refresh_aux,
};
use crate::state::{Aux, AvRates, StepParams, System, Workspace};

/// The pair geometry computed in the pair loop. `av` has one pair loop, so storing each
/// pair's geometry (40 bytes) in a pass of its own and reading it back from both sides
/// cost more than computing it on each side (issue 28: the rings' step 17 % faster, 1,336
/// → 669 bytes per particle). It is bitwise the geometry pass's: `x_i - x_j = -(x_j - x_i)`
/// and `h_i + h_j = h_j + h_i` exactly, so either side computes the owner's `r`, `dW/dr`
/// and factor and the negated `n`.
struct FusedGeometry<const D: usize> {
    kernel: Kernel,
    support: Real,
    periodic: Option<crate::neighbors::Periodic<D>>,
    /// `(1/W_ref shape, n)` with artificial stress.
    art: Option<(Real, u32)>,
}

impl<const D: usize> FusedGeometry<D> {
    fn new<E: Effects>(params: &StepParams<'_, D>) -> Self {
        let art = params.has::<E>(EffectSet::ARTIFICIAL_STRESS).then(|| {
            (
                crate::schemes::artificial_stress::inverse_reference::<D>(
                    params.kernel,
                    params.h_factor,
                ),
                params.options.artificial_stress.exponent,
            )
        });
        FusedGeometry {
            kernel: params.kernel,
            support: params.kernel.support(),
            periodic: params
                .has::<E>(EffectSet::PERIODIC)
                .then_some(params.periodic),
            art,
        }
    }

    /// The pair (i, j) seen from i and its artificial-stress factor, exactly as
    /// `geometry_pass` and `for_each_pair` give them (zero geometry outside the support).
    #[inline(always)]
    fn pair(
        &self,
        x: &[Vector<D>],
        h: &[Real],
        xi: &Vector<D>,
        hi: Real,
        e: Entry,
    ) -> (Pair<D>, Real) {
        let j = e.j;
        let mut rij = xi - x[j];
        if let Some(p) = &self.periodic {
            rij = p.min_image(rij);
        }
        let r2 = rij.norm_squared();
        let hij = 0.5 * (hi + h[j]);
        let rmax = self.support * hij;
        if r2 < rmax * rmax && r2 > 0.0 {
            let r = real::sqrt(r2);
            let (shape, dw) = self.kernel.shape_dw::<D>(r, hij);
            let n = rij * (-1.0 / r);
            let f = match self.art {
                Some((inv_wref, exponent)) => real::powi(shape * inv_wref, exponent),
                None => 0.0,
            };
            (
                Pair {
                    j,
                    r,
                    n,
                    dw,
                    grad: n * (-dw),
                },
                f,
            )
        } else {
            // the stored zero geometry as `for_each_pair` hands it over: n = -0 on the side
            // that does not own the pair
            let z = Vector::<D>::zeros();
            let n = if e.owner { z } else { -z };
            (
                Pair {
                    j,
                    r: 0.0,
                    n,
                    dw: 0.0,
                    grad: n * (-0.0),
                },
                0.0,
            )
        }
    }
}

/// Evaluates the rates of every particle at the current state into `ws.av` (the
/// artificial-stress tensors and per-particle aux of `ws` are its scratch; the pair
/// geometry is computed in the loop, [`FusedGeometry`]).
pub(super) fn rates<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    ws: &mut Workspace<'_, D>,
    params: &StepParams<'_, D>,
    exec: &X,
) {
    let (rates, art, aux) = (&mut *ws.av, &mut *ws.art, &mut *ws.aux);
    refresh_aux::<D, false, X>(sys, aux, params, exec);
    let art_on = params.has::<E>(EffectSet::ARTIFICIAL_STRESS);
    if art_on {
        artificial_stress_tensors::<D, E, X>(sys, art, params, exec);
    }
    let (art, aux): (&[Matrix<D>], &[Aux]) = (art, aux);
    let alpha = params.options.av_alpha;
    let beta = params.options.av_beta;
    let fg = FusedGeometry::<D>::new::<E>(params);
    exec.run(rates, |off, chunk: &mut [AvRates<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let sig_i = cauchy::<D, E>(sys, i);
            let (vi, rhoi, hi, cli) = (sys.v[i], sys.rho[i], sys.h[i], sys.cl[i]);
            let inv_i = aux[i].inv_rho;
            let mut acc = Vector::<D>::zeros();
            let mut de: Real = 0.0;
            let mut div: Real = 0.0;
            let mut grad_v = Matrix::<D>::zeros();
            let xi = sys.x[i];
            let mut body = |pr: &Pair<D>, f_art: Real| {
                let j = pr.j;
                let aj = aux[j];
                let vij = vi - sys.v[j];
                // (v_i - v_j).(x_i - x_j) = -r (v_ij . n)
                let vr = -pr.r * vij.dot(&pr.n);
                let mut pi_ij = 0.0;
                if vr < 0.0 {
                    let hij = 0.5 * (hi + sys.h[j]);
                    let mu = hij * vr / (pr.r * pr.r + 0.01 * hij * hij);
                    let cij = 0.5 * (cli + sys.cl[j]);
                    pi_ij = (-alpha * cij * mu + beta * mu * mu) / (0.5 * (rhoi + sys.rho[j]));
                }
                let sig = sig_i + cauchy::<D, E>(sys, j);
                let mut t = sig.dot_vec(&pr.grad) * (inv_i * aj.inv_rho) - pr.grad * pi_ij;
                if art_on {
                    t += pair_acceleration(1.0, f_art, &art[i], &art[j], &pr.grad);
                }
                let mj = sys.m[j];
                acc += t * mj;
                de -= 0.5 * mj * vij.dot(&t);
                div -= aj.vol * vij.dot(&pr.grad);
                if E::STRENGTH {
                    grad_v -= outer(&vij, &pr.grad) * aj.vol;
                }
            };
            params.nbrs.for_each(i, |e| {
                let (pr, f_art) = fg.pair(sys.x, sys.h, &xi, hi, e);
                body(&pr, f_art);
            });
            out.acc = acc;
            out.de = de;
            out.drho = -rhoi * div;
            out.rate = if E::STRENGTH {
                equivalent_strain_rate(&grad_v)
            } else {
                0.0
            };
            out.ds = if E::STRENGTH {
                deviator_rate(&sys.s[i], &params.materials[sys.mat[i] as usize], &grad_v)
            } else {
                Sym3::ZERO
            };
        }
    });
}
