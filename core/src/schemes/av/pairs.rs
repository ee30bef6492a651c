//! The pair interactions of `av`: the rates of every particle from its neighbours.

use super::records::{record_len, sym_at, RecordAt};
use crate::effects::{EffectSet, Effects};
use crate::exec::{for_each_record, Executor};
use crate::math::{Matrix, Real, Sym3, Vector};
use crate::schemes::artificial_stress::pair_acceleration;
use crate::schemes::av::records::AvRates;
use crate::schemes::common::{
    artificial_stress_tensors, cauchy, deviator_rate, equivalent_strain_rate, outer, refresh_aux,
};
use crate::schemes::pairs::{Pair, PairGeometry};
use crate::schemes::workspace::{StepParams, Workspace};
use crate::state::{Aux, System};

/// The pair sums of one particle: `sum_j m_j t_ij`, `-1/2 sum_j m_j v_ij . t_ij`,
/// `-sum_j V_j v_ij . grad_i W_ij` and `-sum_j V_j v_ij ⊗ grad_i W_ij` (module docs of
/// [`super`]), summed in the order of the particle's list.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Sums<const D: usize> {
    pub acc: Vector<D>,
    pub de: Real,
    pub div: Real,
    pub grad_v: Matrix<D>,
}

impl<const D: usize> Sums<D> {
    pub fn zero() -> Sums<D> {
        Sums {
            acc: Vector::<D>::zeros(),
            de: 0.0,
            div: 0.0,
            grad_v: Matrix::<D>::zeros(),
        }
    }
}

/// What particle i brings to each of its pairs.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Owner<const D: usize> {
    pub x: Vector<D>,
    pub h: Real,
    pub v: Vector<D>,
    pub rho: Real,
    pub cl: Real,
    pub inv_rho: Real,
    /// The pair Cauchy stress ([`cauchy`]).
    pub sig: Sym3,
    /// The artificial-stress tensor (zero without the effect).
    pub art: Matrix<D>,
}

/// Evaluates the rates of every particle at the current state into `ws.av` (the
/// artificial-stress tensors, per-particle aux and neighbour records of `ws` are its
/// scratch; the pair geometry is computed in the loop, `PairGeometry::seen_from_i`).
///
/// Lane twin: `rates_row` in `schemes/av/lanes.rs` (entered by [`av_row`]), held bitwise
/// equal by `schemes/av/lanes_tests.rs`; a change here is a change there.
pub(crate) fn rates<const D: usize, E: Effects, X: Executor>(
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
    // the vectorised loop reads each neighbour's compact record: written here where it
    // runs (and the caller gave the room)
    let records = av_rows(params, &pg) && ws.rec.len() == aux.len() * record_len(D);
    if records {
        write_records::<D, E, X>(sys, aux, art, art_on, ws.rec, exec);
    }
    let rec: &[Real] = ws.rec;
    exec.run(rates, |off, chunk: &mut [AvRates<D>]| {
        for (k, out) in chunk.iter_mut().enumerate() {
            let i = off + k;
            let own = Owner {
                x: sys.x[i],
                h: sys.h[i],
                v: sys.v[i],
                rho: sys.rho[i],
                cl: sys.cl[i],
                inv_rho: aux[i].inv_rho,
                sig: cauchy::<D, E>(sys, i),
                art: if art_on { art[i] } else { Matrix::<D>::zeros() },
            };
            let mut s = Sums::<D>::zero();
            let vectorised =
                records && av_row::<D, E>(params, &pg, rec, i, &own, alpha, beta, &mut s);
            if !vectorised {
                let (vi, rhoi, hi, cli, inv_i) = (own.v, own.rho, own.h, own.cl, own.inv_rho);
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
                    let sig = own.sig + cauchy::<D, E>(sys, j);
                    let mut t = sig.dot_vec(&pr.grad) * (inv_i * aj.inv_rho) - pr.grad * pi_ij;
                    if art_on {
                        t += pair_acceleration(1.0, f_art, &own.art, &art[j], &pr.grad);
                    }
                    let mj = sys.m[j];
                    s.acc += t * mj;
                    s.de -= 0.5 * mj * vij.dot(&t);
                    s.div -= aj.vol * vij.dot(&pr.grad);
                    if E::STRENGTH {
                        s.grad_v -= outer(&vij, &pr.grad) * aj.vol;
                    }
                };
                params.nbrs.for_each(i, |e| {
                    let (pr, f_art) = pg.seen_from_i(sys.x, sys.h, &own.x, hi, e);
                    body(&pr, f_art);
                });
            }
            out.acc = s.acc;
            out.de = s.de;
            out.drho = -own.rho * s.div;
            out.rate = if E::STRENGTH {
                equivalent_strain_rate(&s.grad_v)
            } else {
                0.0
            };
            out.ds = if E::STRENGTH {
                deviator_rate(&sys.s[i], &params.materials[sys.mat[i] as usize], &s.grad_v)
            } else {
                Sym3::ZERO
            };
        }
    });
}

/// Writes every particle's neighbour record (`crate::schemes::workspace::Workspace::rec`): what
/// its neighbours' pair loops read of it, exactly the values the portable loop reads
/// (its Cauchy stress as [`cauchy`] gives it).
fn write_records<const D: usize, E: Effects, X: Executor>(
    sys: &System<'_, D>,
    aux: &[Aux],
    art: &[Matrix<D>],
    art_on: bool,
    rec: &mut [Real],
    exec: &X,
) {
    let (at, width) = (RecordAt::of(D), record_len(D));
    for_each_record(exec, rec, width, |i, r| {
        for a in 0..D {
            r[at.x + a] = sys.x[i][a];
            r[at.v + a] = sys.v[i][a];
        }
        r[at.h] = sys.h[i];
        r[at.rho] = sys.rho[i];
        r[at.cl] = sys.cl[i];
        r[at.inv_rho] = aux[i].inv_rho;
        r[at.m] = sys.m[i];
        let sig = cauchy::<D, E>(sys, i);
        for a in 0..D {
            for b in a..D {
                r[at.sig + sym_at(D, a, b)] = sig.get(a, b);
            }
            for b in 0..D {
                r[at.art + a * D + b] = if art_on { art[i][(a, b)] } else { 0.0 };
            }
        }
    });
}

/// Whether [`av_row`] runs at this level with this geometry and these options: AVX2 or
/// AVX-512, the cubic spline or Wendland C2 kernel, every option covered
/// (`lanes::covers`; the caller then writes the neighbour records it reads).
#[inline(always)]
#[allow(unused_variables)]
pub(crate) fn av_rows<const D: usize>(
    params: &crate::schemes::workspace::StepParams<'_, D>,
    pg: &crate::schemes::pairs::PairGeometry<D>,
) -> bool {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if params.simd.vectorised()
        && crate::schemes::pairs::lanes::has_geometry(pg.kernel)
        && super::lanes::covers(&params.options)
    {
        return true;
    }
    false
}

/// The pair sums of particle `i` (`av`; what it brings to its pairs `own`) from its
/// neighbours' records `rec` into `s` by the vectorised loop where [`av_rows`] holds.
/// Returns whether it did them (false: the portable loop does), bitwise as the portable
/// loop of `av`'s rates.
#[inline(always)]
#[allow(clippy::too_many_arguments, unused_variables)]
pub(crate) fn av_row<const D: usize, E: crate::effects::Effects>(
    params: &crate::schemes::workspace::StepParams<'_, D>,
    pg: &crate::schemes::pairs::PairGeometry<D>,
    rec: &[crate::math::Real],
    i: usize,
    own: &Owner<D>,
    alpha: crate::math::Real,
    beta: crate::math::Real,
    s: &mut Sums<D>,
) -> bool {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if av_rows(params, pg) {
        let (row, owned) = (params.nbrs.of(i), params.nbrs.owned(i));
        let lower = row.len() - owned.len();
        // SAFETY: `params.simd` vouches for the instructions (`SimdLevel::assume`) and
        // `av_rows` holds; the row checks its neighbours against `rec`
        unsafe {
            super::lanes::rates_row_at::<D, E>(
                params.simd,
                pg,
                alpha,
                beta,
                rec,
                row,
                lower,
                own,
                s,
            )
        };
        return true;
    }
    false
}
