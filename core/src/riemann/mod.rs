//! Riemann solvers for the pair interactions of the Godunov SPH schemes.
//!
//! Every solver works along the pair axis `n`, which points **from particle i (the left
//! side, `l`) to particle j (the right side, `r`)**. Along that axis a side is described by
//! its velocity component `u = v·n` and its normal traction `s = n·sigma·n` (Cauchy stress,
//! **tension positive**), or by its pressure `p = -s` (**positive in compression**) for the
//! hydrodynamic solvers. With this convention two particles approaching each other have
//! `u_l > u_r`, and the star (contact) state of a symmetric collision at `±u` is `u* = 0`,
//! `s* = -rho c u < 0` (compression), as DESIGN §8 requires. The seeds print the acoustic
//! solver with mixed pair-direction conventions; the formulas here are derived from the
//! Riemann problem itself (see [`acoustic`]) and checked by the tests of each module.
//!
//! * [`acoustic`]: the linearised (acoustic) solver, scalar ([`acoustic_star`]), pressure
//!   form ([`pressure_star`]) and the vector form of the Parshikov–Medin / TKC pair with
//!   longitudinal and transverse waves ([`acoustic_star_vector`]).
//! * [`two_shock`]: the two-shock approximate solver of Dukowicz (1985) for a linear
//!   shock-speed relation `Us = c + s up` ([`two_shock_star`]); in the vector problem of
//!   the contact family it solves the longitudinal wave ([`elastic_star_vector`] with the
//!   longitudinal speed `c_l` as the intercept and the EOS's Hugoniot slope), the
//!   transverse waves stay acoustic.
//! * [`low_dissipation`]: the part of a star state that dissipates, and the weight
//!   (`options.dissipation`) that keeps it to compressing pairs (Zhang, Hu & Adams 2017).

pub mod acoustic;
pub mod low_dissipation;
pub mod two_shock;

pub use acoustic::{
    acoustic_star, acoustic_star_vector, elastic_star_vector, pressure_star, AcousticSide,
    PressureSide,
};
pub use low_dissipation::Dissipation;
pub use two_shock::{two_shock_star, ShockSide};
