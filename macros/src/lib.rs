//! Procedural macros of gsph (STUB).
