//! `tl`: total-Lagrangian Godunov SPH for solids (issue 47; after Lee, Gil, Ghavamian &
//! Bonet, CMAME 344 (2019) 209, in the rate form of gsph's strength models).
//!
//! Kernel, neighbours and gradient correction live in the **reference configuration**
//! (the particle fields `xr`, `vr`: positions and volumes at the start): no neighbour
//! search runs while the body deforms, so there is no tensile instability and no
//! neighbour enters or leaves a particle's support. With `u = x - X`, `g_ij = C_i grad_i
//! W(X_i - X_j)` and `C_i = (sum_j V0_j (X_j - X_i) ⊗ grad_i W_ij)^-1`:
//!
//! ```text
//! F_i    = I + H_i,  H_i = sum_j V0_j (u_j - u_i) ⊗ g_ij        (exact for every affine motion)
//! dF_i/dt = sum_j V0_j (v_j - v_i) ⊗ g_ij
//! m_i dv_i/dt = sum_j V0_i V0_j (P~_i C_i + P~_j C_j) grad_i W_ij + sum_j (k_ji e_ji - k_ij e_ij) + f^R_i  (Riemann)
//! P~_i  = P_i + A_i/V0_i,  P_i = J_i sigma_i F_i^-T (first Piola–Kirchhoff)
//! ```
//!
//! **Stress.** An elastic material's deviator is hyperelastic, a function of F: the
//! compressible neo-Hookean `G J^(-5/3) dev(F F^T)` (`pairs::neo_hookean_deviator`,
//! Hooke's law at small strain; the rate form's Jaumann integration let the twisting
//! column's corners invert at four times its rate). The plastic models (von Mises,
//! Johnson–Cook, JH1 with damage) are in rate form: the spatial velocity gradient `L =
//! dF/dt F^-1` (F at mid-step) advances the deviator with Hooke's law, the Jaumann terms
//! and the plastic return (`common::advance_deviator`). The density is `rho0/det F`, and
//! the pressure comes from the equation of state. The internal energy gains the stress power: the
//! exact volume change `-p (1/rho^{n+1} - 1/rho^n)` (trapezoidal in p) and `S:D dt/rho`
//! (trapezoidal in S). The force is the exact adjoint of `dF/dt` (its power is `-sum V0
//! P:dF/dt`); it conserves linear momentum to round-off, and angular momentum where `P_i
//! F_i^T` is symmetric — which it is, since F is computed from the positions (not
//! integrated), so the torque `-sum V0_i skew(P_i F_i^T)` vanishes to round-off.
//!
//! **Hourglass stiffness** (the rank-deficient modes a collocated gradient leaves, which
//! no amount of correction removes): a potential on each pair's error of the F-predicted
//! separation, `e_ij = F_i dX_ij - dx_ij` (Ganzenmüller's error term, CMAME 286 (2015) 87),
//!
//! ```text
//! Phi = sum_i sum_j k_ij |e_ij|^2 / 2,   k_ij = kappa_i V0_j omega_ij,   kappa_i = xi G_i (1 - D_i) V0_i / h_i^2,
//! omega_ij = r_ij |W'(r_ij)| / D   (sum_j V0_j omega_ij is about 1)
//! ```
//!
//! with F_i the position-computed one, so `Phi` is a function of the positions alone
//! and its force is exactly `-dPhi/dx`: the pair term above and the stress-like `A_i =
//! sum_j k_ij e_ij ⊗ dX_ij = kappa_i (H_i M_i - N_i)` (`M_i = sum_j V0_j omega_ij dX ⊗ dX`,
//! `N_i = sum_j V0_j omega_ij du ⊗ dX`: one pass) that enters the force as a stress. It
//! vanishes for every affine motion (rigid rotations included), is invariant under
//! rotation (so it conserves angular momentum), and conserves linear momentum. Unlike
//! Ganzenmüller's force, which is not the gradient of an energy, its work is exactly the
//! change of `Phi`: each step books `Phi_i^{n+1} - Phi_i^n` into particle i's internal
//! energy (the field `phi` keeps `Phi_i`), so total energy is what the time integration
//! makes it and the monitor counts `Phi` with the strain energy. `options.hourglass =
//! xi` (default 1).
//!
//! **Riemann dissipation.** The longitudinal acoustic Riemann problem of the (p, F)
//! system (Lee et al. 2019) at each pair's interface: the traction jump `Z [v*].n n`
//! with the pair's impedance `Z = Z_i Z_j/(Z_i + Z_j)` (`Z = rho0 c_l`) on the reference
//! interface area `|V0_i V0_j (C_i + C_j) grad_i W_ij|`, `n` the pair's current
//! direction. The jump `[v*].n` is the reconstructed one: each side extrapolates its
//! velocity to the midpoint with its own `dF/dt` (a reference gradient), bounded by half
//! the pair's jump ([`crate::limiter::bounded_extrapolation`]), so the dissipation is
//! one-signed (its power is `-Z [v*].n [v].n <= 0`) and vanishes for every affine
//! velocity field (a rigid rotation is not dissipated). With `options.dissipation =
//! "compression"` it acts only on approaching pairs, weighted by the approach Mach
//! number. Its heat goes half to each particle's internal energy. The force is central,
//! so angular momentum is conserved to round-off without a projection: the transverse
//! Riemann problem Lee et al. also solve was measured and left out (a spinning ring's
//! angular momentum changed by −1.2e-3 over one turn with it, −3e-15 without; the
//! breathing ring kept 0.982 with it, 0.986 without; the hourglass stiffness, not the
//! transverse dissipation, holds the zero-energy modes).
//!
//! **Time integration** (velocity Verlet, second order): `v += a dt/2` with the
//! acceleration the previous step left (`AvRates::acc`, state that checkpoints carry;
//! the first step of a run computes it from the state); `x += v dt`; F from the new
//! positions and dF/dt from the half-step velocities (`F^{n+1} - F^n = dt dF/dt`
//! exactly); density, deviator (with `F` at mid-step), pressure and energy; the forces of
//! the new state, their Riemann dissipation from the half-step velocities and slopes;
//! `v += a dt/2`.
//!
//! What the step keeps where (`PairSums` and the `Hourglass` records): see the module
//! `pairs`. The host runs it with symmetry planes and on any number of MPI ranks; it
//! refuses rigid walls, periodic boundaries, the moving window and bodies that share no
//! pair at the start, and updates the reference on `options.reference_update`.

mod options;
pub(crate) mod pairs;
#[cfg(test)]
mod tests;

pub(crate) use options::{defaults, reads};

use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::halo::{Exchange, Fields, Halo};
use crate::schemes::common::halo_exchange;
use crate::schemes::family::SchemeFamily;
use crate::schemes::options::SchemeOptions;
use crate::schemes::pairs::geometry_pass;
use crate::schemes::scheme::Family;
use crate::schemes::workspace::{Layout, StepParams, Workspace};
use crate::state::{StepError, System};

/// The halo exchanges of a `tl` step, in order (see [`crate::halo`]).
///
/// 1. Before the deformation pass, after the drift: x and v (the reference positions and
///    volumes do not change during a run).
/// 2. Before the force pass: the records of the deformation pass and the local update
///    (correction, H, dF/dt, the stress, the stiffness factor and the impedance).
pub const EXCHANGES: [Exchange; 2] = [
    Exchange {
        before: "deformation",
        fields: Fields::X.with(Fields::V),
        needs: EffectSet::HYDRO,
        needs_any: EffectSet::HYDRO,
    },
    Exchange {
        before: "forces",
        fields: Fields::HOURGLASS,
        needs: EffectSet::HYDRO,
        needs_any: EffectSet::HYDRO,
    },
];

/// The total-Lagrangian family (`tl`).
#[derive(Clone, Copy, Debug, Default)]
pub struct Tl;

impl SchemeFamily for Tl {
    const FAMILY: Family = Family::Tl;
    const SUPPORTED: EffectSet = EffectSet::STRENGTH
        .union(EffectSet::PLASTICITY)
        .union(EffectSet::DAMAGE)
        .union(EffectSet::HEAT)
        .union(EffectSet::REFERENCE);
    const EXCHANGES: &'static [Exchange] = &EXCHANGES;

    fn layout(effects: EffectSet, _options: &SchemeOptions) -> Layout {
        Layout {
            // the per-particle records of the force pass
            hg: true,
            // the acceleration carried from one step into the next (velocity Verlet)
            av: true,
            // no MUSCL gradients, kernel-correction records or artificial stress: the
            // records carry what the passes need
            grad: false,
            corr: false,
            art: false,
            ..Layout::base(effects)
        }
    }

    fn step<const D: usize, E: Effects, X: Executor>(
        sys: &mut System<'_, D>,
        ws: &mut Workspace<'_, D>,
        params: &StepParams<'_, D>,
        exec: &X,
        halo: &mut dyn Halo<D>,
    ) -> Result<(), StepError> {
        let dt = params.dt;
        // the pair geometry of the reference configuration (fixed during a run)
        geometry_pass::<D, E, X>(sys.xr, sys.h, params, ws.geom, &mut [], exec);
        if !ws.primed {
            // the acceleration of the state as it is
            halo_exchange!(params, halo, &EXCHANGES[0], sys, ws);
            pairs::deformation::<D, X>(sys, ws.geom, ws.hg, params, exec);
            pairs::stress_records::<D, E, X>(sys, ws.hg, exec);
            halo_exchange!(params, halo, &EXCHANGES[1], sys, ws);
            pairs::forces::<D, X>(sys, ws.geom, ws.hg, ws.sums, params, exec);
            pairs::prime(ws.sums, ws.av, exec);
            ws.primed = true;
        }
        pairs::half_kick(sys, ws.av, dt, exec);
        pairs::drift(sys, dt, exec);
        halo_exchange!(params, halo, &EXCHANGES[0], sys, ws);
        pairs::deformation::<D, X>(sys, ws.geom, ws.hg, params, exec);
        pairs::constitutive::<D, E, X>(sys, ws.hg, params, exec);
        halo_exchange!(params, halo, &EXCHANGES[1], sys, ws);
        pairs::forces::<D, X>(sys, ws.geom, ws.hg, ws.sums, params, exec);
        pairs::kick(sys, ws.sums, ws.av, params, exec);
        Ok(())
    }
}
