//! Particle state as structure-of-arrays over caller-provided slices, the per-particle
//! records the pair passes share (sums, gradients, corrections, pair geometry) and the
//! errors of a step. Below every scheme: the step's parameters and workspace are the
//! schemes' side ([`crate::schemes::workspace`]).
//!
//! Optional fields (deviator, plastic strain, damage, temperature, and every workspace
//! array an effect needs) are empty slices when their effect is absent: a hydro-only run
//! allocates no storage for strength, damage, heat, gradients or kernel correction.
//! [`Layout`](crate::schemes::workspace::Layout) tells the caller which arrays a given
//! scheme family and effect set needs.

use crate::effects::{EffectSet, Effects};
use crate::exec::{split_opt, split_opt_ref, Split};
use crate::math::{real, Matrix, Real, Sym3, Vector};

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
    (ref, $when:ident, $v:expr, $mid:expr) => {
        split_opt_ref($v, $mid)
    };
}

/// A field given to a [`SystemBuilder`]: required where every run stores it, else empty
/// unless given.
macro_rules! given_field {
    ($acc:ident, HYDRO, $v:expr, $name:expr) => {
        $v.ok_or(StepError::Storage { field: $name })
    };
    (mut, $when:ident, $v:expr, $name:expr) => {
        Ok::<_, StepError>($v.unwrap_or(&mut []))
    };
    (ref, $when:ident, $v:expr, $name:expr) => {
        Ok::<_, StepError>($v.unwrap_or(&[]))
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

        /// A [`System`] built field by field ([`System::builder`]): the fields every run
        /// stores must be given, the others are empty unless given. Code that builds a
        /// system by hand (the firmware example, tests) names only what it has, so a field
        /// added to the table reaches it as an empty slice or, if every run stores it, as
        /// the error of [`SystemBuilder::build`] naming it.
        #[derive(Debug)]
        pub struct SystemBuilder<'a, const D: usize> {
            $($name: Option<slice_of!($acc, 'a, $ty)>,)*
        }

        impl<'a, const D: usize> System<'a, D> {
            /// A builder with no field given.
            pub fn builder() -> SystemBuilder<'a, D> {
                SystemBuilder { $($name: None,)* }
            }
        }

        impl<'a, const D: usize> SystemBuilder<'a, D> {
            $(
                #[doc = concat!("Gives `", stringify!($name), "`: ", $doc, unit_doc!($unit))]
                pub fn $name(mut self, v: slice_of!($acc, 'a, $ty)) -> Self {
                    self.$name = Some(v);
                    self
                }
            )*
            /// The system: [`StepError::Storage`] names the first field every run stores
            /// that was not given (check the lengths with [`System::check_storage`]).
            pub fn build(self) -> Result<System<'a, D>, StepError> {
                Ok(System {
                    $($name: given_field!($acc, $when, self.$name, stringify!($name))?,)*
                })
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

/// Calls `$cb! { ($($args)*) RECORDS }` with the table of the per-particle scratch
/// records the pair passes share (computed by a step, read by later passes of the same
/// step or, through a halo or a wall's mirror, by neighbours), a record each:
///
/// ```text
/// Name "doc" { field: Type = default, kind, "doc"; ... }
/// ```
///
/// `kind` says how a field maps under a reflection (a wall's mirror): `vector` (a
/// vector), `matrix` (a `D x D` tensor, `R M R`), `scalar` or `flag` (unchanged).
/// Generated from it: the structs and their defaults (here), and in the host the
/// checkpoint codec, the MPI words and the wall mirrors' reflection. The order of the
/// fields is the order of the codec and the words.
#[macro_export]
macro_rules! scratch_records {
    ($cb:ident { $($args:tt)* }) => {
        $cb! {
            ($($args)*)
            PairSums "What one pass over the pairs accumulates for particle i (per unit mass where it is a rate of a specific quantity)" {
                acc: Vector<D> = Vector::<D>::zeros(), vector, "Acceleration, m/s²";
                power: Real = 0.0, scalar, "Power per unit mass at the pair contacts (scheme-specific, see each scheme), W/kg";
                div: Real = 0.0, scalar, "Velocity divergence, 1/s. Before the pass that sums it, it holds the surface flag ([`PairSums::set_surface`])";
                grad_v: Matrix<D> = Matrix::<D>::zeros(), matrix, "Velocity gradient `L_ab = dv_a/dx_b`, 1/s (only with `strength`)";
                v0: Vector<D> = Vector::<D>::zeros(), vector, "Velocity at the start of the step (time-centred position update), m/s";
            }
            Gradients "Gradients used by MUSCL reconstruction (`ts2`, `tkc`)" {
                rho: Vector<D> = Vector::<D>::zeros(), vector, "grad rho";
                p: Vector<D> = Vector::<D>::zeros(), vector, "grad P (the contact family computes it only without strength, where the pressure's slope reconstructs the traction; with strength it stays zero)";
                v: Matrix<D> = Matrix::<D>::zeros(), matrix, "Velocity gradient `dv_a/dx_b`";
                cl: Vector<D> = Vector::<D>::zeros(), vector, "grad c_l (tkc)";
                ct: Vector<D> = Vector::<D>::zeros(), vector, "grad c_t (tkc)";
                w: Matrix<D> = Matrix::<D>::zeros(), matrix, "The spin `W = (G - G^T)/2` of the velocity gradient `G` corrected with the full `L^-1` (no free-surface switch; exact for an affine velocity field wherever `L` is invertible): the rigid rotation the contact family's transverse Riemann problems leave out with `options.objective` (`pm`, `tkc`)";
                sv: Vector<D> = Vector::<D>::zeros(), vector, "The gradient of the specific volume `1/rho` from the plain kernel sum, `-(1/rho^2) sum_j m_j grad W_ij`, with `options.specific_volume = \"interpolated\"` (`pm`, `tkc`; `schemes::pm::volume`)";
            }
            Hourglass "What the hourglass stiffness's force pass reads of a particle and its neighbours (`schemes::hourglass`; the total-Lagrangian scheme `tl` keeps its per-particle record here too, with the meanings its fields' docs give after `tl:`)" {
                q: Vector<D> = Vector::<D>::zeros(), vector, "The restoring force `k_i d_i` of the particle's hourglass displacement, N (per unit length in 2D). tl: unused (zero)";
                t: Matrix<D> = Matrix::<D>::zeros(), matrix, "`(q_i ⊗ y_i) C_i`: the first moment `y_i` of the particle's neighbour weights and its gradient correction `C_i`, the tensor of the force that the affine part of the rate brings, N. tl: the displacement gradient `H_i = F_i - I` (reference configuration)";
                vol: Real = 0.0, scalar, "The volume `m/rho` the rate was summed with (the force pass uses the same), m³. tl: the reference volume `V0_i`";
                c: Matrix<D> = Matrix::<D>::identity(), matrix, "The kernel gradient correction `C_i` of the rate (the identity where `det C_i^-1 < det_epsilon`). tl: the same in the reference configuration";
                l: Matrix<D> = Matrix::<D>::zeros(), matrix, "The corrected velocity gradient `L_i` the rate was summed with, 1/s (`ts` advances its deviator with it). tl: the rate `dF_i/dt`, the velocity gradient in the reference configuration (the slopes of its reconstruction)";
                p: Matrix<D> = Matrix::<D>::zeros(), matrix, "`S_i C_i - t/V_i` with the advanced deviator: the one tensor of `ts`'s fused deviatoric and stiffness force (`schemes::hourglass::stress_forces`), Pa. tl: `P_i + A_i/V0_i`, the first Piola–Kirchhoff stress and the hourglass stiffness's stress of the force pass";
                k: Real = 0.0, scalar, "tl: the stiffness factor `kappa_i = xi G (1 - damage) V0_i / h_i^2` of the particle's pairs (`k_ij = kappa_i V0_j omega_ij`), N/m^(D+1)";
                zp: Real = 0.0, scalar, "tl: the longitudinal impedance `rho0 c_l` of the pairs' acoustic Riemann problems, kg/(m² s)";
            }
            Correction "Kernel gradient correction of one particle (`tkc`)" {
                l_inv: Matrix<D> = Matrix::<D>::identity(), matrix, "The matrix `L^-1` applied to kernel gradients (identity near free surfaces)";
                lambda_min: Real = 1.0, scalar, "Smallest eigenvalue of L (free-surface indicator)";
                boundary: u8 = 0, flag, "0 interior, 1 near a boundary particle, 2 boundary particle";
            }
        }
    };
}

/// The structs of [`scratch_records!`](crate::scratch_records) and their defaults.
macro_rules! records_from_table {
    (() $($rec:ident $rdoc:literal { $($f:ident: $ty:ty = $default:expr, $kind:ident, $doc:literal;)* })*) => {
        $(
            #[doc = concat!($rdoc, ".")]
            #[derive(Clone, Copy, Debug, PartialEq)]
            pub struct $rec<const D: usize> {
                $(
                    #[doc = concat!($doc, ".")]
                    pub $f: $ty,
                )*
            }

            impl<const D: usize> Default for $rec<D> {
                fn default() -> Self {
                    $rec { $($f: $default,)* }
                }
            }
        )*
    };
}

crate::scratch_records!(records_from_table {});

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
