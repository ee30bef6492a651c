//! Explicitly vectorised loops, several pairs per instruction, chosen at run time.
//!
//! A step runs a loop's vectorised version when [`StepParams::simd`](crate::state::StepParams)
//! says the CPU has the instructions. The core cannot ask the CPU (`no_std`): the host
//! detects the level and vouches for it through the `unsafe` [`SimdLevel::assume`]; an
//! embedded caller that never does runs the portable loops, which are the reference the
//! vectorised ones are tested against.
//!
//! **Results are bitwise identical at every level.** Each lane performs exactly the scalar
//! code's IEEE operations in the scalar code's order (no fused multiply-add: Rust never
//! contracts on its own, and the kernels call no FMA instruction), branches become blends
//! of both sides, and nothing is summed across lanes. The tests compare every output bit
//! against the portable loop (`core/src/simd/tests.rs`), and `tests/tests/determinism.rs`
//! compares whole runs.
//!
//! Each loop is written once, generic over the register (`lanes::Lanes`: `__m256d`, four
//! lanes, for AVX2; `__m512d`, eight, for AVX-512F), `#[inline(always)]`, and entered
//! through one function per level compiled for its instructions (`…_avx2`, `…_avx512`).
//! The AVX-512 entries run a row's full groups of eight in `zmm` registers and the rest in
//! `ymm` ones, since a partial group costs as much as a full one.
//!
//! What is vectorised:
//! - the pair geometry (`schemes::common::geometry_pass` of the `pm` and `ts` families,
//!   which store it for their several pair passes; the cubic spline and Wendland C2
//!   kernels, periodic axes by the minimum image), `ops.rs`. (`av`, with one pair loop, computes the
//!   geometry in that loop.)
//! - the star states of `ts1` and `ts2` (MUSCL reconstruction, the acoustic or two-shock
//!   solver; the default time and dissipation options, the superbee and minmod limiters),
//!   `ts_star.rs`: each row's owner broadcast, its neighbours a register at a time, their
//!   fields read from one compact record per particle (`Workspace::rec`, written before the
//!   stars are solved) as `av`'s are (below). A lane the vectorised path does not cover (a
//!   failed particle, an impedance that is not positive and finite, a two-shock answer
//!   that is not finite) is solved again by the portable code.
//! - the star states of `tkc` (and `pm` with MUSCL or the two-shock solver): objective rotation, corrected
//!   traction axis, MUSCL in the pair frame, the acoustic or two-shock solver,
//!   `pm_star.rs`, from records as well; the same fallbacks.
//! - `av`'s pair loop (the cubic spline and Wendland C2 kernels),
//!   `av.rs`. Its neighbours' fields come from one compact record per particle
//!   (`Workspace::rec`, written once per rate evaluation), a register's records loaded four
//!   reals at a time and transposed into lanes; each pair's terms are computed in lanes and
//!   the particle's sums add them in its list's order. (A first version that filled the
//!   lanes from the per-particle arrays, about twenty scalar loads per neighbour, was 27 %
//!   slower than the portable loop: the loop is bound by those loads, not by arithmetic.)

#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
pub(crate) mod av;
#[cfg(all(test, target_arch = "x86_64", not(feature = "f32")))]
mod av_tests;
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
mod lanes;
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
pub(crate) mod ops;
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
mod pm_lanes;
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
pub(crate) mod pm_star;
#[cfg(all(test, target_arch = "x86_64", not(feature = "f32")))]
mod star_tests;
#[cfg(all(test, target_arch = "x86_64", not(feature = "f32")))]
mod tests;

/// The vectorised levels this CPU has, for the tests that compare each with the portable
/// loops (a level it lacks is named on stderr, not tested).
#[cfg(all(test, target_arch = "x86_64", not(feature = "f32")))]
pub(crate) fn tested_levels() -> std::vec::Vec<SimdLevel> {
    extern crate std;
    let mut out = std::vec::Vec::new();
    for (level, has) in [
        (Simd::Avx2, std::is_x86_feature_detected!("avx2")),
        (
            Simd::Avx512,
            std::is_x86_feature_detected!("avx512f") && std::is_x86_feature_detected!("avx2"),
        ),
    ] {
        if has {
            // SAFETY: detected just above
            out.push(unsafe { SimdLevel::assume(level) });
        } else {
            std::eprintln!("this CPU has no {level}: its loops are not tested here");
        }
    }
    out
}
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
pub(crate) mod ts_star;

/// The pair geometry of the pairs particle `i` (at `xi`, `hi`) owns, its neighbours
/// `owned`, into `out` (and the artificial-stress factors into `fac`) by the vectorised loop
/// where the level and the case allow it: AVX2 or AVX-512, the cubic spline or Wendland C2
/// kernel. Returns how many of the pairs it did (0: none; the portable loop does the
/// rest), each bitwise as [`PairGeometry::of`](crate::schemes::common::PairGeometry)
/// gives it.
#[inline(always)]
#[allow(clippy::too_many_arguments, unused_variables)]
pub(crate) fn geometry_row<const D: usize>(
    level: SimdLevel,
    pg: &crate::schemes::common::PairGeometry<D>,
    xi: &crate::math::Vector<D>,
    hi: crate::math::Real,
    x: &[crate::math::Vector<D>],
    h: &[crate::math::Real],
    owned: &[u32],
    out: &mut [crate::state::PairGeom<D>],
    fac: &mut [crate::math::Real],
) -> usize {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if ops::has_geometry(pg.kernel) {
        // SAFETY: `level` vouches for the instructions (`SimdLevel::assume`) and the kernel
        // is one the loop computes; it checks the neighbour indices and indexes `out`,
        // `fac` checked
        match level.get() {
            Simd::Avx512 => unsafe {
                return ops::geometry_row_avx512::<D>(pg, xi, hi, x, h, owned, out, fac);
            },
            Simd::Avx2 => unsafe {
                return ops::geometry_row_avx2::<D>(pg, xi, hi, x, h, owned, out, fac);
            },
            Simd::Baseline => {}
        }
    }
    0
}

/// Whether [`av_row`] runs at this level with this geometry: AVX2 or AVX-512, the cubic
/// spline or Wendland C2 kernel (the caller then writes the neighbour records it reads).
#[inline(always)]
#[allow(unused_variables)]
pub(crate) fn av_rows<const D: usize>(
    level: SimdLevel,
    pg: &crate::schemes::common::PairGeometry<D>,
) -> bool {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if level.vectorised() && ops::has_geometry(pg.kernel) {
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
    params: &crate::state::StepParams<'_, D>,
    pg: &crate::schemes::common::PairGeometry<D>,
    rec: &[crate::math::Real],
    i: usize,
    own: &crate::schemes::av::pairs::Owner<D>,
    alpha: crate::math::Real,
    beta: crate::math::Real,
    s: &mut crate::schemes::av::pairs::Sums<D>,
) -> bool {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if av_rows(params.simd, pg) {
        let (row, owned) = (params.nbrs.of(i), params.nbrs.owned(i));
        let lower = row.len() - owned.len();
        // SAFETY: `params.simd` vouches for the instructions (`SimdLevel::assume`) and
        // `av_rows` holds; the row checks its neighbours against `rec`
        unsafe {
            if params.simd.get() == Simd::Avx512 {
                av::rates_row_avx512::<D, E>(pg, alpha, beta, rec, row, lower, own, s)
            } else {
                av::rates_row_avx2::<D, E>(pg, alpha, beta, rec, row, lower, own, s)
            }
        };
        return true;
    }
    false
}

/// Whether the vectorised star rows (`ts_star`, `pm_star`) pay for this step's scheme: a
/// first-order star with the acoustic solver is too light for the lanes' loads (measured
/// on the colliding rings: ts1 1.01 to 1.19, pm 1.01 to 1.14 times the portable loop's
/// time), the reconstruction (ts2, tkc) or the two-shock solver is not (the 2D impact's
/// pm: 0.91 to 0.93; docs/performance.md).
#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
#[inline(always)]
fn stars_pay<const D: usize, E: crate::effects::Effects>(
    params: &crate::state::StepParams<'_, D>,
) -> bool {
    E::MUSCL || params.options.riemann == crate::state::RiemannSolver::TwoShock
}

/// Writes every particle's neighbour record for [`ts_star_row`] into `rec` where the
/// level and the step's options allow the vectorised row and it pays (AVX2 or AVX-512;
/// `ts_star::covers` and `pays`) and `rec` has the room (`state::record_len`); returns
/// whether it did (false: the rows run the portable loop).
#[inline(always)]
#[allow(unused_variables)]
pub(crate) fn ts_records<const D: usize, E: crate::effects::Effects, X: crate::exec::Executor>(
    sys: &crate::state::System<'_, D>,
    grad: &[crate::state::Gradients<D>],
    params: &crate::state::StepParams<'_, D>,
    rec: &mut [crate::math::Real],
    exec: &X,
) -> bool {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if params.simd.vectorised()
        && ts_star::covers(params)
        && stars_pay::<D, E>(params)
        && rec.len() == sys.x.len() * crate::schemes::ts::record_len(D)
    {
        ts_star::write_records::<D, E, X>(sys, grad, params, rec, exec);
        return true;
    }
    false
}

/// The star states of the pairs particle `i` owns (`ts1`, `ts2`: its neighbours `owned`,
/// their geometry `geom`) into `out` by the vectorised loop, from the neighbour records
/// `rec` [`ts_records`] wrote (call only where it returned true). Returns how many pairs it
/// did (0: none; the portable loop does the rest), each bitwise as
/// [`crate::schemes::ts::pairs::star`] gives it (`p* = 0` unless `with_p`).
#[inline(always)]
#[allow(clippy::too_many_arguments, unused_variables)]
pub(crate) fn ts_star_row<const D: usize, E: crate::effects::Effects>(
    sys: &crate::state::System<'_, D>,
    grad: &[crate::state::Gradients<D>],
    rec: &[crate::math::Real],
    params: &crate::state::StepParams<'_, D>,
    i: usize,
    geom: &[crate::state::PairGeom<D>],
    owned: &[u32],
    out: &mut [crate::state::TsStar],
    with_p: bool,
) -> usize {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if params.simd.vectorised() && ts_star::covers(params) && stars_pay::<D, E>(params) {
        // SAFETY: `params.simd` vouches for the instructions (`SimdLevel::assume`) and
        // `covers` holds
        return unsafe {
            ts_star::star_row_at::<D, E>(
                params.simd,
                sys,
                grad,
                rec,
                params,
                i,
                geom,
                owned,
                out,
                with_p,
            )
        };
    }
    0
}

/// Writes every particle's neighbour record for [`pm_star_row`] into `rec` where the
/// level and the step's options allow the vectorised row and it pays (AVX2 or AVX-512;
/// `pm_star::covers` and `pays`) and `rec` has the room (`state::record_len`); returns
/// whether it did (false: the rows run the portable loop).
#[inline(always)]
#[allow(clippy::too_many_arguments, unused_variables)]
pub(crate) fn pm_records<const D: usize, E: crate::effects::Effects, X: crate::exec::Executor>(
    sys: &crate::state::System<'_, D>,
    aux: &[crate::state::Aux],
    corr: &[crate::state::Correction<D>],
    grad: &[crate::state::Gradients<D>],
    grad_s: &[[crate::math::Vector<D>; 6]],
    params: &crate::state::StepParams<'_, D>,
    rec: &mut [crate::math::Real],
    exec: &X,
) -> bool {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if params.simd.vectorised()
        && pm_star::covers(params)
        && stars_pay::<D, E>(params)
        && rec.len() == sys.x.len() * crate::schemes::pm::record_len(D)
    {
        pm_star::write_records::<D, E, X>(sys, aux, corr, grad, grad_s, params, rec, exec);
        return true;
    }
    false
}

/// The star states of the pairs particle `i` owns (`pm`, `tkc`: its neighbours `owned`,
/// their geometry `geom`) into `out` by the vectorised loop, from the neighbour records
/// `rec` [`pm_records`] wrote (call only where it returned true). Returns how many pairs it
/// did (0: none; the portable loop does the rest), each bitwise as
/// [`crate::schemes::pm::pairs::pair_star`] gives it.
#[inline(always)]
#[allow(clippy::too_many_arguments, unused_variables)]
pub(crate) fn pm_star_row<const D: usize, E: crate::effects::Effects>(
    sys: &crate::state::System<'_, D>,
    aux: &[crate::state::Aux],
    corr: &[crate::state::Correction<D>],
    grad: &[crate::state::Gradients<D>],
    grad_s: &[[crate::math::Vector<D>; 6]],
    rec: &[crate::math::Real],
    params: &crate::state::StepParams<'_, D>,
    i: usize,
    geom: &[crate::state::PairGeom<D>],
    owned: &[u32],
    out: &mut [crate::state::PmStar<D>],
) -> usize {
    #[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
    if params.simd.vectorised() && pm_star::covers(params) && stars_pay::<D, E>(params) {
        // SAFETY: `params.simd` vouches for the instructions (`SimdLevel::assume`) and
        // `covers` holds
        return unsafe {
            pm_star::star_row_at::<D, E>(
                params.simd,
                sys,
                aux,
                corr,
                grad,
                grad_s,
                rec,
                params,
                i,
                geom,
                owned,
                out,
            )
        };
    }
    0
}

/// An instruction-set level of the vectorised loops.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Simd {
    /// The portable loops (x86-64: SSE2, one pair at a time).
    #[default]
    Baseline,
    /// AVX2 (x86-64-v3: Intel since Haswell, AMD since Zen): four `f64` pairs per
    /// instruction.
    Avx2,
    /// AVX-512F (Intel Xeon since Skylake-SP, AMD since Zen 4): eight `f64` pairs per
    /// instruction.
    Avx512,
}

impl Simd {
    /// Every level, lowest first.
    pub const ALL: [Simd; 3] = [Simd::Baseline, Simd::Avx2, Simd::Avx512];

    /// The level's name (`baseline`, `avx2`, `avx512`), as `gsph --simd` and `GSPH_SIMD` take it.
    pub const fn name(self) -> &'static str {
        match self {
            Simd::Baseline => "baseline",
            Simd::Avx2 => "avx2",
            Simd::Avx512 => "avx512",
        }
    }

    /// The level of a name ([`Simd::name`]).
    pub fn from_name(s: &str) -> Option<Simd> {
        Simd::ALL.into_iter().find(|l| l.name() == s)
    }
}

impl core::fmt::Display for Simd {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(self.name())
    }
}

/// A level the CPU is known to have: the only way to reach a vectorised loop.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct SimdLevel(Simd);

impl SimdLevel {
    /// The portable loops (always safe).
    pub const BASELINE: SimdLevel = SimdLevel(Simd::Baseline);

    /// Vouches that the CPU running the steps has `level`'s instructions.
    ///
    /// # Safety
    /// The CPU must have them (x86-64 AVX2 for [`Simd::Avx2`], AVX-512F (which implies
    /// AVX2) for [`Simd::Avx512`]; the host checks with
    /// `is_x86_feature_detected!`). A level the target architecture has no loops for runs
    /// the portable ones.
    pub const unsafe fn assume(level: Simd) -> SimdLevel {
        SimdLevel(level)
    }

    /// The level.
    pub const fn get(self) -> Simd {
        self.0
    }

    /// True when the vectorised loops may run (AVX2 or AVX-512).
    #[inline(always)]
    #[cfg_attr(
        not(all(target_arch = "x86_64", not(feature = "f32"))),
        allow(dead_code)
    )]
    pub(crate) fn vectorised(self) -> bool {
        cfg!(target_arch = "x86_64") && !cfg!(feature = "f32") && self.0 != Simd::Baseline
    }
}
