//! The host crate's layout (issue 18): no import cycle between its top-level modules, the
//! command-line modules (`cli`, `commands`) used by nothing in the library, and every path
//! that docs/architecture.md names present in the repository.
//!
//! The graph is read from the sources by the core's reader (`core/tests/common/graph.rs`):
//! file by file, and for the top-level modules each file taken to its module. `cargo test
//! --test layout -- --nocapture` prints the module graph.

#[path = "../../core/tests/common/graph.rs"]
mod graph;

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

/// Module -> the modules it uses: the file graph (`graph::graph`) with each file taken
/// to its top-level module (`scene/setup/build` is `scene`); `lib` and `main` left out.
fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let top = |f: &str| f.split('/').next().unwrap().to_string();
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for (file, uses) in graph::graph(&src()) {
        let m = top(&file);
        let entry = g.entry(m.clone()).or_default();
        entry.extend(uses.iter().map(|u| top(u)).filter(|u| *u != m));
    }
    g
}

#[test]
fn host_modules_have_no_import_cycle() {
    let g = graph();
    for (m, uses) in &g {
        let u: Vec<&str> = uses.iter().map(String::as_str).collect();
        println!("{m} -> {}", u.join(" "));
    }
    assert!(
        g.len() > 15,
        "the graph reader found only {} modules",
        g.len()
    );
    assert_eq!(
        graph::cycles(&g),
        Vec::<Vec<String>>::new(),
        "import cycles"
    );
}

#[test]
fn the_cycle_finder_finds_a_cycle() {
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    let edge = |g: &mut BTreeMap<String, BTreeSet<String>>, a: &str, b: &str| {
        g.entry(a.into()).or_default().insert(b.into());
    };
    edge(&mut g, "scene", "sim");
    edge(&mut g, "sim", "checkpoint");
    edge(&mut g, "checkpoint", "scene");
    edge(&mut g, "cli", "scene");
    assert_eq!(graph::cycles(&g), vec![vec!["checkpoint", "scene", "sim"]]);
}

/// No import cycle between the host's files either (issue 44: `output/meta.rs ⇄
/// output/table.rs`, `scene/setup/build.rs ⇄ scene/setup/periodic.rs` and
/// `scene/validate.rs ⇄ scene/validate_parts.rs` were the last). A file's uses of its own
/// ancestors (`crate::scene::Scene` in `scene/setup/build.rs`: a folder's `mod.rs`
/// re-exports what its files define) are left out: the host's folders are entered through
/// their `mod.rs`. (The core is stricter: `core/tests/layout.rs`.)
#[test]
fn host_files_have_no_import_cycle() {
    let mut g = graph::graph(&src());
    assert!(
        g.len() > 80,
        "the graph reader found only {} files",
        g.len()
    );
    for (file, uses) in g.iter_mut() {
        uses.retain(|u| !file.starts_with(&format!("{u}/")));
    }
    assert_eq!(
        graph::cycles(&g),
        Vec::<Vec<String>>::new(),
        "import cycles"
    );
}

#[test]
fn the_command_line_is_used_by_nothing_in_the_library() {
    let g = graph();
    for (m, uses) in &g {
        if m != "cli" {
            assert!(!uses.contains("cli"), "{m} uses cli");
        }
        if m != "cli" && m != "commands" {
            assert!(!uses.contains("commands"), "{m} uses commands");
        }
    }
    // the binary is one call
    let main = std::fs::read_to_string(src().join("main.rs")).unwrap();
    assert!(main.contains("gsph::cli::run("), "{main}");
}

#[test]
fn every_path_architecture_md_names_exists() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let doc = repo.join("docs/architecture.md");
    let text = std::fs::read_to_string(&doc).unwrap();
    // paths are written in backticks: `host/src/sim/mod.rs`, `core/src/material/eos/`
    let mut named = 0;
    for (i, part) in text.split('`').enumerate() {
        let looks_like_path = i % 2 == 1
            && !part.contains(' ')
            && [
                "core/", "host/", "macros/", "cases/", "docs/", "scripts/", "tests/",
            ]
            .iter()
            .any(|p| part.starts_with(p));
        if looks_like_path {
            let path = part
                .split("::")
                .next()
                .unwrap()
                .trim_end_matches(['.', ',', ':']);
            assert!(
                repo.join(path).exists(),
                "docs/architecture.md names `{part}`, which does not exist"
            );
            named += 1;
        }
    }
    assert!(named >= 30, "docs/architecture.md names only {named} paths");
}

/// Every field of the scene's serde structs (a scene key) is named in docs/user-guide.md.
#[test]
fn every_scene_key_is_in_the_user_guide() {
    let repo = Path::new(env!("CARGO_MANIFEST_DIR")).join("..");
    let guide = std::fs::read_to_string(repo.join("docs/user-guide.md")).unwrap();
    let mut keys = BTreeSet::new();
    // the scene's own structs, and the core's types a scene is read into (the equations
    // of state, the strength models; the options below, from their table)
    let core = repo.join("core/src");
    let mut files: Vec<std::path::PathBuf> = [
        "spec.rs",
        "material_spec.rs",
        "walls.rs",
        "window.rs",
        "setup/periodic.rs",
        "setup/pores.rs",
    ]
    .iter()
    .map(|f| src().join("scene").join(f))
    .collect();
    for dir in ["material/eos", "material/strength"] {
        for e in std::fs::read_dir(core.join(dir)).unwrap() {
            let p = e.unwrap().path();
            if p.file_name().is_some_and(|n| n != "mod.rs") {
                files.push(p);
            }
        }
    }
    files.push(core.join("material/mod.rs"));
    for f in files {
        let mut text = std::fs::read_to_string(&f).unwrap();
        if f.starts_with(&core) {
            // the core's files: the structs and enums a scene is read into (those that
            // derive serde's Deserialize; the rest is physics)
            let mut structs = String::new();
            let (mut inside, mut serde) = (false, false);
            for line in text.lines() {
                serde |= line.contains("serde::Deserialize");
                let item = ["pub struct", "pub enum", "    pub enum"];
                if serde && item.iter().any(|i| line.starts_with(i)) {
                    (inside, serde) = (true, false);
                }
                if inside {
                    structs.push_str(line);
                    structs.push('\n');
                }
                inside &= line != "}" && line != "    }";
            }
            text = structs;
        }
        let text = text.split("#[cfg(test)]").next().unwrap();
        let mut skip = false;
        for line in text.lines().map(str::trim) {
            if line.starts_with("#[serde(skip") || line.contains("serde(skip)") {
                skip = true;
                continue;
            }
            // `pub name: Type,` fields and `name: f64,` fields of enum variants
            let field = line.strip_prefix("pub ").unwrap_or(line);
            if let Some((name, rest)) = field.split_once(':') {
                let plain = !name.is_empty()
                    && name
                        .chars()
                        .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
                    && !rest.starts_with(':')
                    && rest.trim_end().ends_with(',');
                if plain && !skip {
                    keys.insert(name.to_string());
                }
            }
            if !line.starts_with("#[") && !line.starts_with("///") {
                skip = false;
            }
        }
    }
    // the resolved window geometry (scene/window.rs `WindowGeometry`) is not read from a
    // scene
    for derived in ["dx", "x_l", "x_r"] {
        keys.remove(derived);
    }
    assert!(keys.len() > 60, "read only {} keys", keys.len());
    let named = |k: &str| {
        [
            format!("`{k}`"),
            format!("{k} ="),
            format!("[{k}]"),
            format!("[[{k}]]"),
        ]
        .iter()
        .any(|form| guide.contains(form.as_str()))
    };
    // the `[options]` keys are the options table's rows (generated: docs/scene-keys.md)
    for key in gsph_core::schemes::options::OptionKey::ALL {
        keys.insert(key.name().to_string());
    }
    let missing: Vec<&String> = keys.iter().filter(|k| !named(k)).collect();
    assert!(
        missing.is_empty(),
        "scene keys missing from docs/user-guide.md: {missing:?}"
    );
}
