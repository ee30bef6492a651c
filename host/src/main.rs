//! The `gsph` command.
fn main() {}
