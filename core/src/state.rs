//! Particle state as structure-of-arrays over caller-provided slices, the per-step
//! workspace, step parameters and errors.
//!
//! Optional fields (deviator, plastic strain, damage, temperature, and every workspace
//! array an effect needs) are empty slices when their effect is absent: a hydro-only run
//! allocates no storage for strength, damage, heat, gradients or kernel correction.
//! [`Layout`] tells the caller which arrays a given scheme family and effect set needs.

use crate::effects::{EffectSet, Effects};
use crate::exec::{split_opt, Split};
use crate::kernel::Kernel;
use crate::limiter::Limiter;
use crate::material::Material;
use crate::math::{real, Matrix, Real, Sym3, Vector};
use crate::neighbors::{Neighbors, Periodic};
use crate::schemes::artificial_stress::ArtificialStress;

/// The slice type of a field of [`System`]: `&'a mut [T]` or `&'a [T]`.
macro_rules! slice_of {
    (mut, $a:lifetime, $t:ty) => { &$a mut [$t] };
    (ref, $a:lifetime, $t:ty) => { &$a [$t] };
}

/// The doc of a field's unit.
macro_rules! unit_doc {
    ("") => {
        "."
    };
    ("1") => {
        " (dimensionless)."
    };
    ($unit:literal) => {
        concat!(", ", $unit, ".")
    };
}

/// The doc of a field's storage.
macro_rules! storage_doc {
    (HYDRO) => {
        ""
    };
    ($when:ident) => {
        concat!(" Empty without the effect `", stringify!($when), "`.")
    };
}

/// Splits a field's slice at `mid` (an empty optional field into two empty halves).
macro_rules! split_field {
    (mut, HYDRO, $v:expr, $mid:expr) => {
        $v.split_at_mut($mid)
    };
    (ref, HYDRO, $v:expr, $mid:expr) => {
        $v.split_at($mid)
    };
    (mut, $when:ident, $v:expr, $mid:expr) => {
        split_opt($v, $mid)
    };
}

/// [`System`], its reborrow, storage check and split, from the table of
/// [`crate::particle_fields!`].
macro_rules! system_from_fields {
    (() $($name:ident: $ty:ty, $kind:ident, $when:ident, $acc:ident, $unit:literal, $doc:literal, $io:tt;)*) => {
        /// The particles of a run (structure of arrays), one slice per field of
        /// [`crate::particle_fields!`]. All slices have the same length `n`, except
        /// optional fields, which are empty when their effect is absent.
        #[derive(Debug)]
        pub struct System<'a, const D: usize> {
            $(
                #[doc = concat!($doc, unit_doc!($unit), storage_doc!($when))]
                pub $name: slice_of!($acc, 'a, $ty),
            )*
        }

        impl<'a, const D: usize> System<'a, D> {
            /// Reborrows with a shorter lifetime (to split or hand to an executor).
            pub fn reborrow(&mut self) -> System<'_, D> {
                System { $($name: self.$name,)* }
            }
            /// Checks that every slice has the length its effect set requires.
            pub fn check_storage(&self, effects: EffectSet) -> Result<(), StepError> {
                let n = self.len();
                $(
                    let want = if effects.contains(EffectSet::$when) { n } else { 0 };
                    if self.$name.len() != want {
                        return Err(StepError::Storage { field: stringify!($name) });
                    }
                )*
                Ok(())
            }
        }

        impl<const D: usize> Split for System<'_, D> {
            fn len(&self) -> usize {
                self.x.len()
            }
            fn split_at(self, mid: usize) -> (Self, Self) {
                $(let $name = split_field!($acc, $when, self.$name, mid);)*
                (System { $($name: $name.0,)* }, System { $($name: $name.1,)* })
            }
        }
    };
}

crate::particle_fields!(step system_from_fields {});

impl<'a, const D: usize> System<'a, D> {
    /// Number of particles.
    #[inline]
    pub fn len(&self) -> usize {
        self.x.len()
    }
    /// True if there are no particles.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.x.is_empty()
    }
    /// The run-time effect `plasticity` ([`EffectSet::PLASTICITY`]) in a step of `E`: a
    /// run stores plastic strains exactly when it has the effect (absent effects get no
    /// storage).
    #[inline(always)]
    pub fn has_plasticity<E: Effects>(&self) -> bool {
        E::RUNTIME.contains(EffectSet::PLASTICITY) && !self.eps_p.is_empty()
    }
    /// The run-time effect `damage` ([`EffectSet::DAMAGE`]): damage is stored exactly when
    /// the run has the effect.
    #[inline(always)]
    pub fn has_damage<E: Effects>(&self) -> bool {
        E::RUNTIME.contains(EffectSet::DAMAGE) && !self.damage.is_empty()
    }
    /// The run-time effect `heat` ([`EffectSet::HEAT`]): temperatures are stored exactly
    /// when the run has the effect.
    #[inline(always)]
    pub fn has_heat<E: Effects>(&self) -> bool {
        E::RUNTIME.contains(EffectSet::HEAT) && !self.temp.is_empty()
    }
}

/// What one pass over the pairs accumulates for particle i (per unit mass where it is a
/// rate of a specific quantity).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairSums<const D: usize> {
    /// Acceleration, m/s².
    pub acc: Vector<D>,
    /// Power per unit mass at the pair contacts (scheme-specific, see each scheme), W/kg.
    pub power: Real,
    /// Velocity divergence, 1/s. Before the pass that sums it, it holds the surface flag
    /// ([`PairSums::set_surface`]).
    pub div: Real,
    /// Velocity gradient `L_ab = dv_a/dx_b`, 1/s (only with `strength`).
    pub grad_v: Matrix<D>,
    /// Velocity at the start of the step (time-centred position update), m/s.
    pub v0: Vector<D>,
}

impl<const D: usize> PairSums<D> {
    /// Marks a particle at or near a free surface, in the step's first passes, for a later
    /// pass of the same step: `ts` takes its consistent divergence there, `pm` (`tkc`) its
    /// uncorrected kernel gradient (`L = I`). The flag lives in `div`, which is free until
    /// the pass that sums the divergence overwrites it: a separate `bool` field made the
    /// struct a word longer and the tkc impact 3 % slower (measured, issue 26).
    #[inline(always)]
    pub fn set_surface(&mut self, on: bool) {
        self.div = if on { 1.0 } else { 0.0 };
    }
    /// The flag of [`PairSums::set_surface`] (valid until the divergence is summed).
    #[inline(always)]
    pub fn surface(&self) -> bool {
        self.div != 0.0
    }
}

impl<const D: usize> Default for PairSums<D> {
    fn default() -> Self {
        PairSums {
            acc: Vector::<D>::zeros(),
            power: 0.0,
            div: 0.0,
            grad_v: Matrix::<D>::zeros(),
            v0: Vector::<D>::zeros(),
        }
    }
}

/// Gradients used by MUSCL reconstruction (`ts2`, `tkc`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Gradients<const D: usize> {
    /// grad rho.
    pub rho: Vector<D>,
    /// grad P (the contact family computes it only without strength, where the pressure's
    /// slope reconstructs the traction; with strength it stays zero).
    pub p: Vector<D>,
    /// Velocity gradient `dv_a/dx_b`.
    pub v: Matrix<D>,
    /// grad c_l (tkc).
    pub cl: Vector<D>,
    /// grad c_t (tkc).
    pub ct: Vector<D>,
    /// The spin `W = (G - G^T)/2` of the velocity gradient `G` corrected with the full
    /// `L^-1` (no free-surface switch; exact for an affine velocity field wherever `L` is
    /// invertible): the rigid rotation the contact family's transverse Riemann problems
    /// leave out with `options.objective` (`pm`, `tkc`).
    pub w: Matrix<D>,
    /// The gradient of the specific volume `1/rho` from the plain kernel sum,
    /// `-(1/rho^2) sum_j m_j grad W_ij`, with `options.specific_volume = "interpolated"`
    /// (`pm`, `tkc`; `schemes::pm::volume`).
    pub sv: Vector<D>,
}

impl<const D: usize> Default for Gradients<D> {
    fn default() -> Self {
        Gradients {
            rho: Vector::<D>::zeros(),
            p: Vector::<D>::zeros(),
            v: Matrix::<D>::zeros(),
            cl: Vector::<D>::zeros(),
            ct: Vector::<D>::zeros(),
            w: Matrix::<D>::zeros(),
            sv: Vector::<D>::zeros(),
        }
    }
}

/// Kernel gradient correction of one particle (`tkc`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Correction<const D: usize> {
    /// The matrix `L^-1` applied to kernel gradients (identity near free surfaces).
    pub l_inv: Matrix<D>,
    /// Smallest eigenvalue of L (free-surface indicator).
    pub lambda_min: Real,
    /// 0 interior, 1 near a boundary particle, 2 boundary particle.
    pub boundary: u8,
}

impl<const D: usize> Default for Correction<D> {
    fn default() -> Self {
        Correction {
            l_inv: Matrix::<D>::identity(),
            lambda_min: 1.0,
            boundary: 0,
        }
    }
}

/// Per-particle quantities that the pair loops read from neighbours, computed once per
/// particle (not once per pair) whenever the density changes.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Aux {
    /// `1 / rho`, m³/kg.
    pub inv_rho: Real,
    /// Volume `m / rho`, m³ (in 2D per unit length out of the plane, m²; in 1D per unit
    /// cross-section area, m).
    pub vol: Real,
    /// Transverse sound speed `sqrt(G / rho)`, m/s (`pm` family; 0 otherwise).
    pub ct: Real,
}

/// The geometry of one pair, computed once per step on the side of its owner (see
/// [`crate::neighbors`]); `r = 0` marks a pair outside the kernel support.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairGeom<const D: usize> {
    /// Unit vector from the owner to the other particle.
    pub n: Vector<D>,
    /// Distance, m (0: outside the support).
    pub r: Real,
    /// dW/dr at (r, h_ij), m^-(D+1).
    pub dw: Real,
}

impl<const D: usize> Default for PairGeom<D> {
    fn default() -> Self {
        PairGeom {
            n: Vector::<D>::zeros(),
            r: 0.0,
            dw: 0.0,
        }
    }
}

pub use crate::schemes::av::AvRates;

/// The reals per particle of [`Workspace::rec`] for a family in `d` dimensions.
pub const fn record_len(family: Family, d: usize) -> usize {
    match family {
        Family::Av => crate::schemes::av::record_len(d),
        Family::Ts => crate::schemes::ts::record_len(d),
        Family::Pm => crate::schemes::pm::record_len(d),
    }
}
pub use crate::schemes::pm::PmStar;
pub use crate::schemes::ts::TsStar;

/// Per-step scratch and scheme state owned by the caller. Arrays a family or effect set
/// does not use are empty (see [`Layout`]).
#[derive(Debug)]
pub struct Workspace<'a, const D: usize> {
    /// Pair sums (all schemes).
    pub sums: &'a mut [PairSums<D>],
    /// MUSCL gradients.
    pub grad: &'a mut [Gradients<D>],
    /// Gradients of the stress components in Voigt order (`tkc` with strength; only those
    /// the pairs read: in 2D xx, yy and xy, the others zero).
    pub grad_stress: &'a mut [[Vector<D>; 6]],
    /// Kernel correction.
    pub corr: &'a mut [Correction<D>],
    /// Leap-frog rates (`av`); persistent between steps.
    pub av: &'a mut [AvRates<D>],
    /// Artificial stress tensors `R_i` (effect `artificial_stress`).
    pub art: &'a mut [Matrix<D>],
    /// Neighbour records of the vectorised pair loops (`crate::simd`; every family),
    /// [`record_len`]`(family, D)` reals per particle: what each particle gives its
    /// neighbours' pairs, in one place. Scratch, written by the step where a vectorised
    /// loop reads it; optional: empty (or another length), the portable loops run.
    pub rec: &'a mut [Real],
    /// Pair geometry (all schemes), one per unordered pair of the lists.
    pub geom: &'a mut [PairGeom<D>],
    /// The artificial stress factor `f_ij^n` of each pair (effect `artificial_stress`).
    pub fac: &'a mut [Real],
    /// Per-particle quantities the pair loops read from neighbours (all schemes).
    pub aux: &'a mut [Aux],
    /// Star states of the pairs (`ts` family), one per unordered pair of the lists.
    pub ts_star: &'a mut [TsStar],
    /// Star states of the pairs (`pm` family), one per unordered pair of the lists.
    pub pm_star: &'a mut [PmStar<D>],
    /// True once `av` holds the rates of the current state (set by the first `av` step).
    pub primed: bool,
}

/// Which workspace arrays a family and effect set need.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Layout {
    /// [`Workspace::grad`].
    pub grad: bool,
    /// [`Workspace::grad_stress`].
    pub grad_stress: bool,
    /// [`Workspace::corr`].
    pub corr: bool,
    /// [`Workspace::av`].
    pub av: bool,
    /// [`Workspace::geom`] (one per unordered pair), and [`Workspace::fac`] with `art`: the
    /// pair geometry stored by the geometry pass. `av` computes it in its one pair loop
    /// instead.
    pub geom: bool,
    /// [`Workspace::art`], and [`Workspace::fac`] (one per unordered pair) with `geom`.
    pub art: bool,
    /// [`Workspace::ts_star`] (one record per unordered pair).
    pub ts_star: bool,
    /// [`Workspace::pm_star`] (one record per unordered pair).
    pub pm_star: bool,
}

impl Layout {
    /// The arrays the effects ask for whatever the family: MUSCL gradients, kernel
    /// corrections, artificial stress; a family's [`layout`](crate::schemes::SchemeFamily::layout)
    /// adds its own.
    pub const fn base(effects: EffectSet) -> Layout {
        Layout {
            grad: effects.contains(EffectSet::MUSCL),
            grad_stress: false,
            corr: effects.contains(EffectSet::CORRECTION),
            av: false,
            geom: true,
            art: effects.contains(EffectSet::ARTIFICIAL_STRESS),
            ts_star: false,
            pm_star: false,
        }
    }
}

impl<const D: usize> Workspace<'_, D> {
    /// Checks that the arrays `layout` asks for have their lengths: one per particle (`n`)
    /// or per unordered pair (`pairs`); the sums, geometry and `aux` every step uses.
    /// Arrays the layout does not ask for are not read and not checked.
    pub fn check(&self, layout: &Layout, n: usize, pairs: usize) -> Result<(), StepError> {
        let wrong = [
            ("sums", true, self.sums.len(), n),
            ("aux", true, self.aux.len(), n),
            ("geom", layout.geom, self.geom.len(), pairs),
            ("grad", layout.grad, self.grad.len(), n),
            ("grad_stress", layout.grad_stress, self.grad_stress.len(), n),
            ("corr", layout.corr, self.corr.len(), n),
            ("av", layout.av, self.av.len(), n),
            ("art", layout.art, self.art.len(), n),
            ("fac", layout.art && layout.geom, self.fac.len(), pairs),
            ("ts_star", layout.ts_star, self.ts_star.len(), pairs),
            ("pm_star", layout.pm_star, self.pm_star.len(), pairs),
        ]
        .into_iter()
        .find(|&(_, needed, len, want)| needed && len != want);
        match wrong {
            Some((field, ..)) => Err(StepError::Storage { field }),
            None => Ok(()),
        }
    }
}

/// Scheme families. `tkc` is the `pm` family with correction and MUSCL; `ts2` is `ts`
/// with MUSCL.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Family {
    /// Standard SPH with Monaghan artificial viscosity, leap-frog.
    Av,
    /// Contact (Parshikov–Medin) Godunov SPH: full stress Riemann problem per pair.
    Pm,
    /// Time-split Godunov SPH: deviatoric step, then hydrodynamic Riemann step.
    Ts,
}

/// `NAMES`, `name`, `from_name` and `Display` (the scene name) of an enum chosen by name
/// in a scene's `[options]`.
macro_rules! scene_names {
    ($t:ident { $($v:ident => $s:literal),+ $(,)? }) => {
        impl $t {
            /// The scene names, in the order messages list them.
            pub const NAMES: [&'static str; [$($s),+].len()] = [$($s),+];

            /// The scene name.
            pub const fn name(self) -> &'static str {
                match self {
                    $($t::$v => $s),+
                }
            }

            /// The choice of a scene name.
            pub fn from_name(name: &str) -> Option<$t> {
                match name {
                    $($s => Some($t::$v),)+
                    _ => None,
                }
            }
        }

        /// The scene name.
        impl core::fmt::Display for $t {
            fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
                f.write_str(self.name())
            }
        }
    };
}

/// Riemann solver of the hydrodynamic step of `ts`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RiemannSolver {
    /// Linearised acoustic solver.
    Acoustic,
    /// Two-shock approximate solver (Dukowicz 1985).
    TwoShock,
}

/// The time dimension of the MUSCL reconstruction of `ts2`. Seed 000 eq 23 multiplies the
/// slope by `[1 - c_i dt]`, which has units of length: see `schemes::ts` for the choice.
/// Whatever is chosen applies to every use of the pair's star state (continuity, momentum
/// and energy), as seed 000 eqs 22 and 34 use the same contact velocity.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MusclTime {
    /// MUSCL–Hancock predictor: the particle's state is advanced half a step with the
    /// Lagrangian acoustic equations before the spatial reconstruction.
    Predictor,
    /// The seed's factor made dimensionless: slopes scaled by `max(0, 1 - c_i dt / r_ij)`.
    CourantFactor,
    /// Spatial reconstruction only (default).
    None,
}

/// The scene name.
impl core::fmt::Display for MusclTime {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str(match self {
            MusclTime::Predictor => "predictor",
            MusclTime::CourantFactor => "courant",
            MusclTime::None => "none",
        })
    }
}

impl MusclTime {
    /// The scene names, in the order messages list them.
    pub const NAMES: [&'static str; 3] = ["predictor", "courant", "none"];

    /// The time treatment of a scene name.
    pub fn from_name(name: &str) -> Option<MusclTime> {
        match name {
            "predictor" => Some(MusclTime::Predictor),
            "courant" => Some(MusclTime::CourantFactor),
            "none" => Some(MusclTime::None),
            _ => None,
        }
    }
}

scene_names!(RiemannSolver { Acoustic => "acoustic", TwoShock => "two_shock" });

/// How the contact family (`pm`, `tkc`) advances in time (`options.integrator`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Integrator {
    /// The seeds': every rate from the state at the start of the step (pm, explicit
    /// Euler), or with MUSCL density and deviator first and the forces from the new
    /// stresses (tkc, symplectic Euler). First order in time.
    Euler,
    /// The predictor–corrector leap-frog of `av` (kick, drift, predict, one rate
    /// evaluation at the predicted end state, kick): second order in time, one pair
    /// pass per step; with tkc's total-energy equation, energy stays exact.
    Leapfrog,
}

scene_names!(Integrator { Euler => "euler", Leapfrog => "leapfrog" });

/// The specific volumes a pair force of the contact family (`pm`, `tkc`) carries
/// (`options.specific_volume`).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SpecificVolume {
    /// The seeds': `1/(rho_i rho_j)`.
    Product,
    /// Sugiura & Inutsuka (2016, 2017): `1/rho` interpolated along the pair, linear
    /// through both values where the pair is compressed and cubic through the values and
    /// the slopes of the plain kernel sum where it is stretched, and its square averaged
    /// over the pair's kernel product (Inutsuka 2002; `schemes::pm::volume`).
    Interpolated,
}

scene_names!(SpecificVolume { Product => "product", Interpolated => "interpolated" });

/// Scheme options (with the defaults of the seeds).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SchemeOptions {
    /// Monaghan viscosity alpha (`av`).
    pub av_alpha: Real,
    /// Monaghan viscosity beta (`av`).
    pub av_beta: Real,
    /// Slope limiter of `ts2`.
    pub limiter: Limiter,
    /// Riemann solver of `ts`.
    pub riemann: RiemannSolver,
    /// Where the Riemann solver's dissipation acts (every Godunov scheme;
    /// [`crate::riemann::low_dissipation`]).
    pub dissipation: crate::riemann::Dissipation,
    /// Where the transverse Riemann problems' dissipation acts (`pm`, `tkc`), on top of
    /// `dissipation`.
    pub transverse_dissipation: crate::riemann::Dissipation,
    /// The transverse Riemann problems of `pm` and `tkc` see the velocity jump of a pair
    /// less its rigid rotation (the pair's mean spin times its separation): a rigid
    /// rotation is not dissipated (`schemes::pm`).
    pub objective: bool,
    /// The MUSCL slopes of a free-surface particle (`L = I` there) corrected with its full
    /// `L^-1` where `L` is invertible, so that they are exact for linear fields at the
    /// surface as inside (`tkc`, `pm` with correction and MUSCL); the forces keep the
    /// surface rule. Off: seed 004's `L = I` for the slopes too.
    pub corrected_slopes: bool,
    /// The time integration of `pm` and `tkc`.
    pub integrator: Integrator,
    /// How `ts2` accounts for the time step when it reconstructs the contact states (seed
    /// 000 eq 23; one choice for continuity, momentum and energy, see `schemes::ts`).
    pub muscl_time: MusclTime,
    /// Threshold on the smallest eigenvalue of L below which a particle is a free-surface
    /// particle (`tkc`: L = I there; `ts`: consistent divergence there).
    pub surface_lambda: Real,
    /// A particle below `surface_lambda` is a free-surface particle only if its
    /// neighbourhood is open by the umbrella scan (`tkc`, `pm` with correction; see
    /// `open_neighbourhood` in the schemes' common module); `false` (default): seed 004's
    /// eigenvalue test alone. Off by default: the particles it keeps corrected at
    /// compacting pore surfaces break momentum conservation (docs/elastic.md).
    pub surface_scan: bool,
    /// L is not inverted where det L is below this (`tkc`, `ts`).
    pub det_epsilon: Real,
    /// The specific volumes of the contact family's pair force (`pm`, `tkc`).
    pub specific_volume: SpecificVolume,
    /// Artificial stress (read with the effect `artificial_stress`).
    pub artificial_stress: ArtificialStress,
    /// Keep every particle's smoothing length as it starts (the peers' colliding rings,
    /// and codes with a fixed h); otherwise `h = h_factor (m/rho)^(1/D)` after each step.
    pub constant_h: bool,
}

impl Default for SchemeOptions {
    fn default() -> Self {
        SchemeOptions {
            av_alpha: 1.0,
            av_beta: 1.0,
            limiter: Limiter::Superbee,
            riemann: RiemannSolver::Acoustic,
            dissipation: crate::riemann::Dissipation::Full,
            transverse_dissipation: crate::riemann::Dissipation::Full,
            objective: true,
            corrected_slopes: false,
            integrator: Integrator::Euler,
            muscl_time: MusclTime::None,
            specific_volume: SpecificVolume::Product,
            surface_lambda: 0.75,
            surface_scan: false,
            det_epsilon: 0.05,
            artificial_stress: ArtificialStress::default(),
            constant_h: false,
        }
    }
}

/// Everything a step needs besides the particles.
#[derive(Clone, Copy, Debug)]
pub struct StepParams<'a, const D: usize> {
    /// Time step, s.
    pub dt: Real,
    /// Materials, indexed by [`System::mat`].
    pub materials: &'a [Material],
    /// Smoothing kernel.
    pub kernel: Kernel,
    /// `h = h_factor (m/rho)^(1/D)`.
    pub h_factor: Real,
    /// Periodic boundaries.
    pub periodic: Periodic<D>,
    /// Neighbour lists (sorted; see [`crate::neighbors`]).
    pub nbrs: Neighbors<'a>,
    /// Scheme options.
    pub options: SchemeOptions,
    /// The run's whole effect set (closed). The step is compiled for its
    /// [`EffectSet::kernel_part`]; it reads the run-time effects periodic and
    /// artificial stress from here ([`Self::has`]), and plasticity, damage and heat from
    /// their storage ([`System::has_plasticity`] …), which the caller sizes by this set.
    pub effects: EffectSet,
    /// The instruction-set level of the vectorised loops ([`crate::simd`]; results are
    /// bitwise the same at every level).
    pub simd: crate::simd::SimdLevel,
}

impl<const D: usize> StepParams<'_, D> {
    /// True if the run has every effect of `e`: a run-time flag of a step of `E` (false
    /// where `E` compiles the flag out, [`Effects::RUNTIME`]).
    #[inline(always)]
    pub fn has<E: Effects>(&self, e: EffectSet) -> bool {
        E::RUNTIME.contains(e) && self.effects.contains(e)
    }
}

/// A step that cannot continue.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum StepError {
    /// A field became NaN or infinite.
    NonFinite {
        /// Particle index.
        particle: usize,
        /// Field name.
        field: &'static str,
    },
    /// Density became zero or negative.
    NonPositiveDensity {
        /// Particle index.
        particle: usize,
    },
    /// A slice has the wrong length for the effect set.
    Storage {
        /// Field name.
        field: &'static str,
    },
    /// The requested specialisation is not compiled into this build.
    NotCompiled,
}

impl core::fmt::Display for StepError {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        match self {
            StepError::NonFinite { particle, field } => {
                write!(f, "{field} of particle {particle} is not finite")
            }
            StepError::NonPositiveDensity { particle } => {
                write!(f, "density of particle {particle} is not positive")
            }
            StepError::Storage { field } => write!(
                f,
                "storage for `{field}` has the wrong length for this effect set"
            ),
            StepError::NotCompiled => {
                f.write_str("this specialisation is not compiled into this build")
            }
        }
    }
}

/// Checks every particle for NaN/inf and non-positive density (first offender reported).
/// Plastic strain, damage and temperature are checked where their effect is present (their
/// slices are empty otherwise).
pub fn check_finite<const D: usize>(sys: &System<'_, D>) -> Result<(), StepError> {
    for i in 0..sys.len() {
        check_finite_one(sys, i)?;
    }
    Ok(())
}

/// [`check_finite`] of particle `i` alone.
#[inline]
pub fn check_finite_one<const D: usize>(sys: &System<'_, D>, i: usize) -> Result<(), StepError> {
    let bad = |field| Err(StepError::NonFinite { particle: i, field });
    if !sys.x[i].iter().all(|c| c.is_finite()) {
        return bad("position");
    }
    if !sys.v[i].iter().all(|c| c.is_finite()) {
        return bad("velocity");
    }
    if !sys.rho[i].is_finite() {
        return bad("density");
    }
    if sys.rho[i] <= 0.0 {
        return Err(StepError::NonPositiveDensity { particle: i });
    }
    if !sys.e[i].is_finite() {
        return bad("internal energy");
    }
    if !sys.p[i].is_finite() {
        return bad("pressure");
    }
    if !sys.s.is_empty() && !sys.s[i].is_finite() {
        return bad("stress deviator");
    }
    let bad_opt = |v: &[Real]| v.get(i).is_some_and(|x| !x.is_finite());
    if bad_opt(sys.eps_p) {
        return bad("plastic strain");
    }
    if bad_opt(sys.damage) {
        return bad("damage");
    }
    if bad_opt(sys.temp) {
        return bad("temperature");
    }
    Ok(())
}

/// Total energy `sum m (v²/2 + e)`, J (J/m per unit length in 2D, J/m² per unit area in 1D).
pub fn total_energy<const D: usize>(sys: &System<'_, D>) -> Real {
    let mut s = 0.0;
    for i in 0..sys.len() {
        s += sys.m[i] * (0.5 * sys.v[i].norm_squared() + sys.e[i]);
    }
    s
}

/// Kinetic energy, J.
pub fn kinetic_energy<const D: usize>(sys: &System<'_, D>) -> Real {
    let mut s = 0.0;
    for i in 0..sys.len() {
        s += sys.m[i] * 0.5 * sys.v[i].norm_squared();
    }
    s
}

/// Total momentum, kg m/s.
pub fn total_momentum<const D: usize>(sys: &System<'_, D>) -> Vector<D> {
    let mut s = Vector::<D>::zeros();
    for i in 0..sys.len() {
        s += sys.v[i] * sys.m[i];
    }
    s
}

/// Largest stable time step `cfl * min h / (c_l + |v|)`.
pub fn stable_dt<const D: usize>(sys: &System<'_, D>, cfl: Real) -> Real {
    let mut dt = Real::INFINITY;
    for i in 0..sys.len() {
        let speed = sys.cl[i] + real::sqrt(sys.v[i].norm_squared());
        if speed > 0.0 {
            dt = real::min(dt, sys.h[i] / speed);
        }
    }
    cfl * dt
}

/// Smoothing length of a particle: `h_factor (m/rho)^(1/D)`.
#[inline]
pub fn smoothing_length<const D: usize>(h_factor: Real, m: Real, rho: Real) -> Real {
    let vol = m / rho;
    h_factor
        * match D {
            1 => vol,
            2 => real::sqrt(vol),
            _ => real::cbrt(vol),
        }
}

#[cfg(test)]
mod tests;
