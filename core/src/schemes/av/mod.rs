//! `av`: standard SPH with Monaghan artificial viscosity (seed 000 §4; Monaghan & Gingold
//! 1983), integrated with the leap-frog (kick–drift–kick with a predictor for the rates;
//! `core/src/schemes/leapfrog.rs`).
//!
//! Rates of particle i (`sigma = S - P I`, `grad_i W_ij = (x_i - x_j)/r dW/dr`):
//!
//! ```text
//! dv_i/dt   = sum_j m_j [ (sigma_i + sigma_j)/(rho_i rho_j) - Pi_ij I ] . grad_i W_ij
//! de_i/dt   = 1/2 sum_j m_j (v_j - v_i) . [ (sigma_i + sigma_j)/(rho_i rho_j) - Pi_ij I ] . grad_i W_ij
//! drho_i/dt = rho_i sum_j m_j/rho_j (v_i - v_j) . grad_i W_ij               (seed 000 eq 12)
//! Pi_ij     = (-alpha c_ij mu_ij + beta mu_ij²)/rho_ij  if (v_i - v_j).(x_i - x_j) < 0, else 0
//! mu_ij     = h_ij (v_i - v_j).(x_i - x_j) / (r² + 0.01 h_ij²)
//! ```
//!
//! The pair force is antisymmetric, so momentum is conserved to round-off; the energy
//! rate is the exact counterpart of the force, so total energy is conserved up to the
//! time-integration error (leap-frog, second order). With the effect `artificial_stress`
//! the pair force gains `f_ij^n (R_i + R_j) . grad_i W_ij` (see
//! [`super::artificial_stress`]), in the force and so in the energy rate.

#[cfg(all(target_arch = "x86_64", not(feature = "f32")))]
pub(crate) mod lanes;
#[cfg(all(test, target_arch = "x86_64", not(feature = "f32")))]
mod lanes_tests;
mod options;
pub(crate) mod pairs;
pub(crate) mod records;

pub(crate) use options::reads;
use pairs::rates;

use crate::effects::{EffectSet, Effects};
use crate::exec::Executor;
use crate::halo::{Exchange, Fields, Halo};
use crate::schemes::common::halo_exchange;
use crate::schemes::family::SchemeFamily;
use crate::schemes::leapfrog;
use crate::schemes::options::SchemeOptions;
use crate::schemes::scheme::Family;
use crate::schemes::workspace::{Layout, StepParams, Workspace};
use crate::state::{StepError, System};
pub use records::{record_len, AvRates};

/// The halo exchanges of an `av` step (see [`crate::halo`]). The step is: kick and drift
/// (local), then the rate evaluation — the pair geometry (x, h), the per-particle aux
/// (local, from rho), the artificial stress tensors (local), the pair forces (v, rho, h,
/// c_l, the Cauchy stress: S, p and damage) — then the second kick (local). So the one
/// exchange comes before each rate evaluation.
pub const EXCHANGES: [Exchange; 1] = [Exchange {
    before: "rates",
    fields: Fields::STRESS_STATE,
    needs: EffectSet::HYDRO,
    needs_any: EffectSet::HYDRO,
}];

/// The artificial-viscosity family.
#[derive(Clone, Copy, Debug, Default)]
pub struct Av;

impl SchemeFamily for Av {
    const FAMILY: Family = Family::Av;
    const SUPPORTED: EffectSet = EffectSet::STRENGTH
        .union(EffectSet::PLASTICITY)
        .union(EffectSet::DAMAGE)
        .union(EffectSet::HEAT)
        .union(EffectSet::PERIODIC)
        .union(EffectSet::ARTIFICIAL_STRESS);
    const EXCHANGES: &'static [Exchange] = &EXCHANGES;

    fn layout(effects: EffectSet, _options: &SchemeOptions) -> Layout {
        Layout {
            av: true,
            // the pair loop computes the geometry (`pairs.rs`)
            geom: false,
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
        leapfrog::step::<D, E, X, false, false>(sys, ws, params, exec, |sys, ws| {
            halo_exchange!(params, halo, &EXCHANGES[0], sys, ws);
            rates::<D, E, X>(sys, ws, params, exec);
        })
    }
}
