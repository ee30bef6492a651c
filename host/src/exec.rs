//! The rayon executor of the core's per-particle loops (in `gsph-kernels`, which compiles
//! the step specialisations for it).

pub use gsph_kernels::Rayon;
