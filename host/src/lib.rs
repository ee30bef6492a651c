//! # gsph
//!
//! The std host of gsph: scenes, parallel neighbour search, the run driver, output
//! (HDF5 + XDMF, CSV, JSON) and the `gsph` command line.

pub mod output;
