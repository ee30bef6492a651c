//! The host crate's layout (issue 18): no import cycle between its top-level modules, the
//! command-line modules (`cli`, `commands`) used by nothing in the library, and every path
//! that docs/architecture.md names present in the repository.
//!
//! The module graph is read from the sources: an edge `a -> b` for each `crate::b` that a
//! file of module `a` (host/src/a.rs or host/src/a/...) names outside comments and test
//! code (`#[cfg(test)]` and after, files named `tests.rs` or `*_tests.rs`). `cargo test
//! --test layout -- --nocapture` prints the graph.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    for e in std::fs::read_dir(dir).unwrap() {
        let p = e.unwrap().path();
        if p.is_dir() {
            rust_files(&p, out);
        } else if p.extension().is_some_and(|x| x == "rs") {
            out.push(p);
        }
    }
}

/// The identifiers after each `crate::` in `code` (for `crate::{a, b::c}` each of a, b).
fn crate_refs(code: &str) -> Vec<String> {
    let ident = |s: &str| -> String {
        s.chars()
            .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
            .collect()
    };
    let mut refs = Vec::new();
    for (i, _) in code.match_indices("crate::") {
        let rest = &code[i + "crate::".len()..];
        if let Some(group) = rest.strip_prefix('{') {
            // the group ends at its matching brace
            let mut depth = 0i32;
            let end = group
                .char_indices()
                .find(|&(_, c)| {
                    match c {
                        '{' => depth += 1,
                        '}' => depth -= 1,
                        _ => {}
                    }
                    depth < 0
                })
                .map_or(group.len(), |(k, _)| k);
            // top-level items of the group: split on commas outside nested braces
            let (mut depth, mut start) = (0, 0);
            let g = &group[..end];
            for (k, c) in g.char_indices() {
                match c {
                    '{' => depth += 1,
                    '}' => depth -= 1,
                    ',' if depth == 0 => {
                        refs.push(ident(g[start..k].trim()));
                        start = k + 1;
                    }
                    _ => {}
                }
            }
            refs.push(ident(g[start..].trim()));
        } else {
            refs.push(ident(rest));
        }
    }
    refs.retain(|r| !r.is_empty());
    refs
}

/// Module -> the modules it uses.
fn graph() -> BTreeMap<String, BTreeSet<String>> {
    let root = src();
    let mut files = Vec::new();
    rust_files(&root, &mut files);
    let module_of = |p: &Path| -> String {
        let rel = p.strip_prefix(&root).unwrap();
        let first = rel
            .components()
            .next()
            .unwrap()
            .as_os_str()
            .to_string_lossy();
        first.trim_end_matches(".rs").to_string()
    };
    let modules: BTreeSet<String> = files.iter().map(|p| module_of(p)).collect();
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for p in &files {
        let name = p.file_name().unwrap().to_string_lossy();
        let m = module_of(p);
        if name == "tests.rs" || name.ends_with("_tests.rs") || m == "lib" || m == "main" {
            continue;
        }
        let text = std::fs::read_to_string(p).unwrap();
        let text = match text.find("#[cfg(test)]") {
            Some(i) => &text[..i],
            None => &text[..],
        };
        let code: String = text
            .lines()
            .map(|l| match l.find("//") {
                Some(i) => &l[..i],
                None => l,
            })
            .collect::<Vec<_>>()
            .join("\n");
        let uses = g.entry(m.clone()).or_default();
        for r in crate_refs(&code) {
            if r != m && modules.contains(&r) {
                uses.insert(r);
            }
        }
    }
    g
}

/// The strongly connected components with more than one module (Tarjan).
fn cycles(g: &BTreeMap<String, BTreeSet<String>>) -> Vec<Vec<String>> {
    struct T<'a> {
        g: &'a BTreeMap<String, BTreeSet<String>>,
        index: BTreeMap<&'a str, usize>,
        low: BTreeMap<&'a str, usize>,
        stack: Vec<&'a str>,
        on: BTreeSet<&'a str>,
        out: Vec<Vec<String>>,
    }
    fn visit<'a>(t: &mut T<'a>, v: &'a str) {
        let n = t.index.len();
        t.index.insert(v, n);
        t.low.insert(v, n);
        t.stack.push(v);
        t.on.insert(v);
        if let Some(ws) = t.g.get(v) {
            for w in ws {
                let w = w.as_str();
                if !t.index.contains_key(w) {
                    visit(t, w);
                    let lw = t.low[w];
                    let lv = t.low.get_mut(v).unwrap();
                    *lv = (*lv).min(lw);
                } else if t.on.contains(w) {
                    let iw = t.index[w];
                    let lv = t.low.get_mut(v).unwrap();
                    *lv = (*lv).min(iw);
                }
            }
        }
        if t.low[v] == t.index[v] {
            let mut comp = Vec::new();
            loop {
                let w = t.stack.pop().unwrap();
                t.on.remove(w);
                comp.push(w.to_string());
                if w == v {
                    break;
                }
            }
            if comp.len() > 1 {
                comp.sort();
                t.out.push(comp);
            }
        }
    }
    let mut t = T {
        g,
        index: BTreeMap::new(),
        low: BTreeMap::new(),
        stack: Vec::new(),
        on: BTreeSet::new(),
        out: Vec::new(),
    };
    for v in g.keys() {
        if !t.index.contains_key(v.as_str()) {
            visit(&mut t, v);
        }
    }
    t.out
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
    assert_eq!(cycles(&g), Vec::<Vec<String>>::new(), "import cycles");
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
    assert_eq!(cycles(&g), vec![vec!["checkpoint", "scene", "sim"]]);
    assert_eq!(
        crate_refs("use crate::{scene::{self, Scene}, sim};\nlet x = crate::output::read(a);"),
        ["scene", "sim", "output"]
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
