//! Compile-fail tests: `specialise!` rejects bad input with an error at the user's token.
//! The expected messages are in `tests/ui/*.stderr`; regenerate them with
//! `TRYBUILD=overwrite cargo test -p gsph-macros --test ui` and review the diff.

#[test]
fn ui() {
    trybuild::TestCases::new().compile_fail("tests/ui/*.rs");
}
