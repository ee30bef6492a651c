//! # gsph-core
//!
//! The `no_std`, allocation-free physics core of gsph: smoothing kernels, equations of
//! state, strength models, Riemann solvers, slope limiters, exact solutions, and the pair
//! interactions and time integration of every scheme (AV, PM, TS1/TS2, TKC).
//!
//! State lives in caller-provided slices (structure of arrays, see [`state::System`]);
//! neighbour lists have a fixed capacity and overflow is an error value
//! ([`neighbors::NeighborError`]). The host crate `gsph` adds parallel neighbour search,
//! I/O and the command line; a firmware-style runner can step a case with this crate alone
//! (see `examples/firmware_flyer.rs`).
#![no_std]
#![deny(missing_docs)]
#![warn(clippy::std_instead_of_core)]

#[cfg(test)]
extern crate std;

pub mod dispatch;
pub mod effects;
pub mod exact;
pub mod exec;
pub mod halo;
pub mod kernel;
pub mod limiter;
pub mod material;
pub mod math;
pub mod named;
pub mod neighbors;
pub mod particles;
pub mod riemann;
pub mod schemes;
pub mod simd;
pub mod state;

pub use effects::{EffectSet, Effects};
pub use math::{Real, Sym3, Vector};
