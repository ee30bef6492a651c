//! Validation tests of gsph live in `tests/tests/`.
