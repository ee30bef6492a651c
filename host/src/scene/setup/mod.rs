//! From a checked scene to its initial particles: lattices clipped to shapes (`build`),
//! body-fitted layouts (`relax` against the shapes' signed distances, `sdf`),
//! pores (`pores`), particle files (`import`, CSV and HDF5) and STL solids (`stl`), the
//! periodic lengths against the kernel's reach (`periodic`) and the moving window's geometry
//! (`window`).
//!
//! The scene's loader ([`super::load`]) builds the particles once (`build::check_build`), so
//! that a body holding no particle, a state the EOS cannot reach or a scene too large for
//! memory is refused before any output is written: the loader stands above both the file
//! part of `scene` (its keys, their checks, the material library) and this one, which reads
//! the scene's types and nothing of the loader.

pub mod build;
pub mod import;
pub mod initial;
pub mod periodic;
pub mod pores;
pub mod relax;
#[cfg(test)]
mod relax_tests;
mod sdf;
pub mod stl;
pub mod window;
