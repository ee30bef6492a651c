//! The pair interactions of `av`: the rates of every particle from its neighbours.

use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::math::{Matrix, Real, Sym3, Vector};
use crate::schemes::artificial_stress::pair_acceleration;
use crate::schemes::common::{
    artificial_stress_tensors, cauchy, deviator_rate, equivalent_strain_rate, outer, refresh_aux,
};
use crate::schemes::common::{Pair, PairGeometry};
use crate::state::{Aux, AvRates, StepParams, System, Workspace};

/// Evaluates the rates of every particle at the current state into `ws.av` (the
/// artificial-stress tensors and per-particle aux of `ws` are its scratch; the pair
/// geometry is computed in the loop, `PairGeometry::seen_from_i`).
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
    // the pair geometry computed in this, av's one pair loop: storing it in a pass of its
    // own (40 bytes per pair) and reading it back from both sides cost more than computing
    // it on each side (issue 28: rings 1,336 -> 669 bytes per particle, step about 17 %
    // faster), and the result is bitwise the same (`PairGeometry::seen_from_i`)
    let pg = PairGeometry::<D>::new::<E>(params);
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
                let (pr, f_art) = pg.seen_from_i(sys.x, sys.h, &xi, hi, e);
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
