//! Quantities derived from the particle state for output and the library API, one function
//! per row of the core's [`gsph_core::derived_fields!`] table, named after it: each takes
//! the simulation and returns one value per particle in memory order. They are computed
//! when a table is written or a caller reads them, never by a step.
