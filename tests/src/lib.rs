//! Helpers for the validation tests in `tests/tests/`: run a bundled scene in-process and
//! read its summary.

use gsph::driver::{run, RunOptions};
use std::path::PathBuf;

/// Path of a bundled scene (`cases/<name>.toml`).
pub fn case(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("..")
        .join("cases")
        .join(format!("{name}.toml"))
}

/// Runs a bundled scene with overrides, in memory, and returns its summary as
/// summary.json's object (every key by name).
pub fn run_case(name: &str, overrides: &[&str]) -> serde_json::Map<String, serde_json::Value> {
    run_case_table(name, overrides).1
}

/// Runs a bundled scene with overrides, in memory, and returns its final particle table
/// (rows in id order) and its summary.
pub fn run_case_table(
    name: &str,
    overrides: &[&str],
) -> (
    gsph::output::ParticleTable,
    serde_json::Map<String, serde_json::Value>,
) {
    let path = case(name);
    let set: Vec<String> = overrides.iter().map(|s| s.to_string()).collect();
    let scene = gsph::scene::load(&path, &set).unwrap_or_else(|e| panic!("{e}"));
    let opts = RunOptions {
        out: None,
        progress: false,
    };
    let r = run(&scene, name, &opts).unwrap_or_else(|e| panic!("{name} {overrides:?}: {e}"));
    (r.table, r.summary.to_map())
}

/// A number from a summary.
pub fn num(s: &serde_json::Map<String, serde_json::Value>, key: &str) -> f64 {
    s.get(key)
        .and_then(|v| v.as_f64())
        .unwrap_or_else(|| panic!("summary has no number `{key}`"))
}
