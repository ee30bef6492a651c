//! Exact and analytic reference solutions (STUB).
