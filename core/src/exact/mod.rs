//! Exact and analytic reference solutions for the validation cases (DESIGN §7).
//!
//! * [`ElasticPlasticRiemann`]: the four-wave elastic–plastic Riemann problem of seed 004
//!   §2.1.1 (log EOS, Wilkins elastic–perfectly-plastic), with the rarefactions as centred
//!   fans (DESIGN §8).
//! * [`FlyerPlate`]: the symmetric flyer-plate impact of seed 000 §4.1 (elastic precursor
//!   and plastic shock in each plate).
//! * [`SoundPulse`]: the linear longitudinal sound pulse of seed 004 §2.1.2.
//! * [`ShellCollapse`]: the incompressible rigid-plastic collapse of a cylindrical shell,
//!   reference of the beryllium ring (seed 000 §4.2) and the Verney cylinder (seed 004 §2.1.3).
//!
//! Conventions (DESIGN §2): SI units, Cauchy stress tension positive, pressure positive in
//! compression, 1D = uniaxial strain with `S_xx = -2 S_yy = -2 S_zz`, so that
//! `|S_xx| <= 2Y/3` at yield. Every solver here is allocation-free and `no_std`.

mod elastic_plastic_riemann;
mod error;
mod flyer_plate;
pub(crate) mod root;
mod shell_collapse;
mod sound_wave;

pub use elastic_plastic_riemann::{ElasticPlasticRiemann, EpRiemannParams, EpState, EpWaves};
pub use error::ExactError;
pub use flyer_plate::{FlyerPlate, FlyerPlateParams};
pub use shell_collapse::{ShellCollapse, ShellParams};
pub use sound_wave::{SoundPulse, SoundPulseParams};
