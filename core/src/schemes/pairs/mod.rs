//! The pairs every family loops over: their geometry, computed once per step on the side
//! of each pair's owner ([`geometry_pass`], [`PairGeometry`]; its lane twin is
//! [`lanes`], held bitwise equal by `schemes/pairs/lanes_tests.rs`), the pair seen from
//! one particle ([`Pair`], [`for_each_pair`]) and the loop that solves each pair once
//! ([`solve_pair_rows`]).

#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
pub(crate) mod lanes;
#[cfg(all(test, target_arch = "x86_64", not(feature = "f32")))]
mod lanes_tests;

use crate::effects::{EffectSet, Effects};
use crate::exec::{Executor, Rows, Split};
use crate::kernel::Kernel;
use crate::math::{real, Real, Vector};
use crate::neighbors::{Entry, Periodic};
use crate::schemes::workspace::StepParams;
use crate::state::PairGeom;

/// One interacting pair (i, j) as seen from particle i.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Pair<const D: usize> {
    /// Neighbour index.
    pub j: usize,
    /// Distance, m.
    pub r: Real,
    /// Unit vector from i to j (the Riemann axis; seed 004's e_R).
    pub n: Vector<D>,
    /// dW/dr at (r, h_ij), <= 0.
    pub dw: Real,
    /// `grad_i W_ij = (x_i - x_j)/r dW/dr = -n dW/dr`.
    pub grad: Vector<D>,
}

/// The geometry of every pair at the start of a pass sequence, computed once, on the side
/// of its owner: `n` from the owner to the other particle; `r = 0` outside the kernel
/// support. With the effect `artificial_stress`, also each pair's factor `f_ij^n` into
/// `fac` (see [`crate::schemes::artificial_stress`]; empty otherwise). Positions and smoothing
/// lengths must not change while they are in use.
pub(crate) fn geometry_pass<const D: usize, E: Effects, X: Executor>(
    x: &[Vector<D>],
    h: &[Real],
    params: &StepParams<'_, D>,
    geom: &mut [PairGeom<D>],
    fac: &mut [Real],
    exec: &X,
) {
    let nb = params.nbrs;
    let pg = PairGeometry::new::<E>(params);
    let art = pg.art;
    exec.run(
        (
            Rows {
                start: nb.pair_start,
                data: geom,
            },
            Rows {
                start: nb.pair_start,
                data: fac,
            },
        ),
        |off, (mut gs, mut fs): (Rows<'_, PairGeom<D>>, Rows<'_, Real>)| {
            for k in 0..gs.len() {
                let i = off + k;
                let (xi, hi) = (x[i], h[i]);
                let fk: &mut [Real] = if art.is_some() { fs.of(k) } else { &mut [] };
                let (gk, owned) = (gs.of(k), nb.owned(i));
                // the vectorised loop where the CPU and the case allow it (`crate::simd`);
                // this loop whatever it left
                let done = geometry_row::<D>(params.simd, &pg, &xi, hi, x, h, owned, gk, fk);
                for (q, (g, &j)) in gk.iter_mut().zip(owned).enumerate().skip(done) {
                    let (geo, f) = pg.of(&xi, hi, &x[j as usize], h[j as usize]);
                    *g = geo;
                    if art.is_some() {
                        fk[q] = f;
                    }
                }
            }
        },
    );
}

/// The constants of a pair's geometry, and the geometry itself ([`PairGeometry::of`]): one
/// piece of code for the pass that stores it ([`geometry_pass`]) and the loop that
/// computes it in place (`av`).
#[derive(Clone, Copy, Debug)]
pub(crate) struct PairGeometry<const D: usize> {
    pub kernel: Kernel,
    support: Real,
    /// The periodic box with the effect `periodic`.
    pub periodic: Option<Periodic<D>>,
    /// `(1/W_ref shape, n)` with the effect `artificial_stress`.
    pub art: Option<(Real, u32)>,
}

impl<const D: usize> PairGeometry<D> {
    pub fn new<E: Effects>(params: &StepParams<'_, D>) -> Self {
        let kernel = params.kernel;
        let art = params.has::<E>(EffectSet::ARTIFICIAL_STRESS).then(|| {
            (
                crate::schemes::artificial_stress::inverse_reference::<D>(kernel, params.h_factor),
                params.options.artificial_stress_exponent,
            )
        });
        PairGeometry {
            kernel,
            support: kernel.support(),
            periodic: params
                .has::<E>(EffectSet::PERIODIC)
                .then_some(params.periodic),
            art,
        }
    }

    /// The geometry of the pair (i, j) from i's side (`n` from i to j) and its
    /// artificial-stress factor (0 without); zero outside the kernel support. Bitwise the
    /// same from either side but for the sign of `n`: `x_i - x_j = -(x_j - x_i)` and
    /// `h_i + h_j = h_j + h_i` exactly.
    #[inline(always)]
    pub fn of(&self, xi: &Vector<D>, hi: Real, xj: &Vector<D>, hj: Real) -> (PairGeom<D>, Real) {
        match self.inside(xi, hi, xj, hj) {
            Some((n, r, dw, f)) => (PairGeom { n, r, dw }, f),
            None => (PairGeom::default(), 0.0),
        }
    }

    /// `(n, r, dW/dr, factor)` of [`PairGeometry::of`] inside the kernel support.
    #[inline(always)]
    fn inside(
        &self,
        xi: &Vector<D>,
        hi: Real,
        xj: &Vector<D>,
        hj: Real,
    ) -> Option<(Vector<D>, Real, Real, Real)> {
        let mut rij = xi - xj;
        if let Some(p) = &self.periodic {
            rij = p.min_image(rij);
        }
        let r2 = rij.norm_squared();
        let hij = 0.5 * (hi + hj);
        let rmax = self.support * hij;
        if r2 < rmax * rmax && r2 > 0.0 {
            let r = real::sqrt(r2);
            let (shape, dw) = self.kernel.shape_dw::<D>(r, hij);
            let f = match self.art {
                Some((inv_wref, exponent)) => real::powi(shape * inv_wref, exponent),
                None => 0.0,
            };
            Some((rij * (-1.0 / r), r, dw, f))
        } else {
            None
        }
    }

    /// The pair (i, j) seen from i, as [`for_each_pair`] hands over the stored geometry of
    /// [`geometry_pass`] (bitwise), and its artificial-stress factor: computed here.
    #[inline(always)]
    pub fn seen_from_i(
        &self,
        x: &[Vector<D>],
        h: &[Real],
        xi: &Vector<D>,
        hi: Real,
        e: Entry,
    ) -> (Pair<D>, Real) {
        let j = e.j;
        match self.inside(xi, hi, &x[j], h[j]) {
            // i's own side: the owner's n, negated where i does not own the pair, as
            // `seen_from` gives the stored one
            Some((n, r, dw, f)) => (
                Pair {
                    j,
                    r,
                    n,
                    dw,
                    grad: n * (-dw),
                },
                f,
            ),
            None => {
                // the stored zero geometry as `seen_from` gives it: n = -0 on the side
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
}

/// The pair seen from `i` from its cached geometry. A pair outside the support has zero
/// `n`, `r`, `dw` and `grad`, so every sum it enters gets an exact zero: the gathers do not
/// branch on it (a branch on a pattern this irregular costs more than the arithmetic).
#[inline(always)]
fn seen_from<const D: usize>(g: &PairGeom<D>, e: Entry) -> Pair<D> {
    let n = if e.owner { g.n } else { -g.n };
    Pair {
        j: e.j,
        r: g.r,
        n,
        dw: g.dw,
        grad: n * (-g.dw),
    }
}

/// Calls `f` for every neighbour of `i`, in the canonical order of the lists (see
/// [`crate::neighbors`]), with the pair seen from `i` (from the cached geometry of
/// [`geometry_pass`]), the pair's number (its record in a pair buffer) and whether `i`
/// owns it (a record solved with `i` on the left, along `pr.n`; otherwise along `-pr.n`).
/// Pairs outside the kernel support are included with zero geometry (`r = 0`, zero `n`,
/// `dw` and `grad`): `f` must give them zero weight, which every sum weighted by `dw` or
/// `grad` does.
#[inline(always)]
pub(crate) fn for_each_pair<const D: usize>(
    params: &StepParams<'_, D>,
    geom: &[PairGeom<D>],
    i: usize,
    mut f: impl FnMut(&Pair<D>, Entry),
) {
    params
        .nbrs
        .for_each(i, |e| f(&seen_from(&geom[e.pair], e), e));
}

/// Solves every pair once, on the side of its owner: `recs[p] = solve(i, &pair)` for each
/// pair `p` owned by `i` inside the kernel support (`pair` seen from `i`, the left side);
/// pairs outside the support get the default (zero) record. A row solver is tried first:
/// `row(i, geom, owned, out)` may solve the first pairs of `i`'s row itself (a vectorised
/// loop, [`crate::simd`]; their geometry, neighbours and records) and returns how many it
/// did, exactly as `solve` would have; `solve` does the rest.
pub(crate) fn solve_pair_rows<const D: usize, X: Executor, R: Send + Default>(
    params: &StepParams<'_, D>,
    geom: &[PairGeom<D>],
    recs: &mut [R],
    exec: &X,
    row: impl Fn(usize, &[PairGeom<D>], &[u32], &mut [R]) -> usize + Sync,
    solve: impl Fn(usize, &Pair<D>) -> R + Sync,
) {
    let nb = params.nbrs;
    exec.run(
        Rows {
            start: nb.pair_start,
            data: recs,
        },
        |off, mut chunk: Rows<'_, R>| {
            for k in 0..chunk.len() {
                let i = off + k;
                let p0 = nb.pair_start[i] as usize;
                let owned = nb.owned(i);
                let out = chunk.of(k);
                let g = &geom[p0..p0 + out.len()];
                let done = row(i, g, owned, out);
                for (q, (slot, &j)) in out.iter_mut().zip(owned).enumerate().skip(done) {
                    let g = &g[q];
                    *slot = if g.r > 0.0 {
                        let e = Entry {
                            j: j as usize,
                            pair: p0 + q,
                            owner: true,
                        };
                        solve(i, &seen_from(g, e))
                    } else {
                        R::default()
                    };
                }
            }
        },
    );
}

/// The pair geometry of the pairs particle `i` (at `xi`, `hi`) owns, its neighbours
/// `owned`, into `out` (and the artificial-stress factors into `fac`) by the vectorised loop
/// where the level and the case allow it: AVX2 or AVX-512, the cubic spline or Wendland C2
/// kernel. Returns how many of the pairs it did (0: none; the portable loop does the
/// rest), each bitwise as [`PairGeometry::of`](crate::schemes::pairs::PairGeometry)
/// gives it.
#[inline(always)]
#[allow(clippy::too_many_arguments, unused_variables)]
pub(crate) fn geometry_row<const D: usize>(
    level: crate::simd::SimdLevel,
    pg: &PairGeometry<D>,
    xi: &Vector<D>,
    hi: Real,
    x: &[Vector<D>],
    h: &[Real],
    owned: &[u32],
    out: &mut [PairGeom<D>],
    fac: &mut [Real],
) -> usize {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if lanes::has_geometry(pg.kernel) {
        // SAFETY: `level` vouches for the instructions (`SimdLevel::assume`) and the kernel
        // is one the loop computes; it checks the neighbour indices and indexes `out`,
        // `fac` checked
        return unsafe { lanes::geometry_row_at::<D>(level, pg, xi, hi, x, h, owned, out, fac) };
    }
    0
}

/// Whether the vectorised star rows (`ts_star`, `pm_star`) pay for this step's scheme: a
/// first-order star with the acoustic solver is too light for the lanes' loads (measured
/// on the colliding rings: ts1 1.01 to 1.19, pm 1.01 to 1.14 times the portable loop's
/// time), the reconstruction (ts2, tkc) or the two-shock solver is not (the 2D impact's
/// pm: 0.91 to 0.93; docs/performance.md).
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
#[inline(always)]
pub(crate) fn stars_pay<const D: usize, E: crate::effects::Effects>(
    params: &crate::schemes::workspace::StepParams<'_, D>,
) -> bool {
    E::MUSCL || params.options.riemann == crate::schemes::options::RiemannSolver::TwoShock
}
