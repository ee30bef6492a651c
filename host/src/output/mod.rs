//! Output (STUB).
