//! Strength models: the plastic correction of the trial deviator.
//!
//! Conventions (DESIGN §2): Cauchy stress `sigma = S - P I`, tension positive; the deviator
//! `S` is always the full symmetric 3x3 tensor ([`Sym3`](crate::math::Sym3)), also in 1D (uniaxial strain) and
//! 2D (plane strain), because the out-of-plane components enter the von Mises invariant
//! `sigma_vm = sqrt(3/2 S:S)`. A return mapping takes the elastic trial deviator of one time
//! step and brings it back onto the yield surface, reporting the plastic strain and the
//! plastic work of that step ([`ReturnMap`]).
//!
//! * [`von_mises`]: radial return for elastic–perfectly plastic (and, with the current flow
//!   stress as `yield_stress`, Johnson–Cook) von Mises plasticity.
//! * [`johnson_cook`]: Johnson–Cook flow stress (seed 000 eq 40) with an implicit return at
//!   the updated plastic strain and rate, and adiabatic heating `chi W/(rho c_p)`.
//! * [`jh1`]: Johnson–Holmquist JH1 ceramic model (intact and failed strength curves,
//!   damage from seed 000 eq 41, tensile limit, Algorithm 1's no-tension pressure).

pub mod jh1;
pub mod johnson_cook;
mod return_map;
pub mod von_mises;

pub use jh1::{failed_pair_pressure, Jh1, Jh1Update};
pub use johnson_cook::{JohnsonCook, JohnsonCookReturn};
pub use return_map::ReturnMap;
pub use von_mises::radial_return;
