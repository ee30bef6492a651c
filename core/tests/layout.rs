//! The core's modules form a ladder (issue 44): no import cycle among its source files
//! except inside one folder under `schemes/` (a scheme's portable pair arithmetic and its
//! lane twin name each other), the particles (`state.rs`) know nothing of schemes, and the
//! vectorised primitives (`simd/`) nothing of any scheme.
//!
//! The graph is read from the sources (`common/graph.rs`); `cargo test -p gsph-core --test
//! layout -- --nocapture` prints it.

#[path = "common/graph.rs"]
mod graph;

use std::path::{Path, PathBuf};

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// The scheme folder a file is in (`schemes/pm` for `schemes/pm/pairs`), if any.
fn scheme_folder(file: &str) -> Option<String> {
    let parts: Vec<&str> = file.split('/').collect();
    (parts.len() >= 2 && parts[0] == "schemes").then(|| parts[..2].join("/"))
}

/// The cycles the ladder forbids: those not inside one scheme folder.
fn forbidden(cycles: Vec<Vec<String>>) -> Vec<Vec<String>> {
    cycles
        .into_iter()
        .filter(|c| {
            let folder = scheme_folder(&c[0]);
            folder.is_none() || c.iter().any(|f| scheme_folder(f) != folder)
        })
        .collect()
}

#[test]
fn core_files_form_a_ladder() {
    let g = graph::graph(&src());
    graph::print(&g);
    assert!(
        g.len() > 60,
        "the graph reader found only {} files",
        g.len()
    );
    // the reader sees the edges the ladder is built on
    assert!(g["schemes/pm/pairs"].contains("schemes/common"));
    assert!(g["schemes/pm/lanes"].contains("simd/riemann"));
    assert_eq!(forbidden(graph::cycles(&g)), Vec::<Vec<String>>::new());
}

#[test]
fn the_particles_and_the_lane_primitives_know_no_scheme() {
    let g = graph::graph(&src());
    for (file, uses) in &g {
        if file == "state" || file.starts_with("simd") || file == "halo" {
            let schemes: Vec<&String> = uses.iter().filter(|u| u.starts_with("schemes")).collect();
            assert!(schemes.is_empty(), "{file} imports {schemes:?}");
        }
    }
}

#[test]
fn the_ladder_test_finds_a_cycle_across_folders_and_allows_one_inside() {
    let mut g = graph::Graph::new();
    let mut edge = |a: &str, b: &str| {
        g.entry(a.into()).or_default().insert(b.into());
    };
    edge("schemes/pm/pairs", "schemes/pm/lanes");
    edge("schemes/pm/lanes", "schemes/pm/pairs");
    edge("state", "schemes/workspace");
    edge("schemes/workspace", "state");
    let cycles = graph::cycles(&g);
    assert_eq!(cycles.len(), 2);
    assert_eq!(
        forbidden(cycles),
        vec![vec!["schemes/workspace".to_string(), "state".to_string()]]
    );
    // the reader: groups (a nested one names its module), `super::` and `self::`
    let p = graph::paths("use crate::{a::{self, B}, c::D};\nlet x = super::d::e(1);");
    assert!(p.contains(&("crate".into(), vec!["a".into()])));
    assert!(p.contains(&("crate".into(), vec!["c".into(), "D".into()])));
    assert!(p.contains(&("super".into(), vec!["d".into(), "e".into()])));
    assert!(graph::paths("pub(super) fn f() {}").is_empty());
    // a child module's path: relative to the file's module
    let p = graph::paths("mod lanes;\nfn f() { lanes::row(); x::lanes::y(); }");
    assert_eq!(
        p,
        vec![("self".to_string(), vec!["lanes".into(), "row".into()])]
    );
    assert_eq!(
        graph::code_of("use crate::a; // crate::b\n#[cfg(test)]\nuse crate::c;\nuse crate::d;"),
        "use crate::a; \nuse crate::d;"
    );
    assert_eq!(
        graph::code_of("use crate::a;\n#[cfg(test)]\nmod tests {\n    use crate::c;\n}"),
        "use crate::a;"
    );
}
