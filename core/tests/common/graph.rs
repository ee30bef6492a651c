//! The import graph of a crate's sources, file by file, and its cycles: shared by the
//! layout tests of the core (`core/tests/layout.rs`) and the host (`host/tests/layout.rs`).
//!
//! A file is named by its module path with `/` (`schemes/pm/pairs` for
//! `src/schemes/pm/pairs.rs`, `schemes/pm` for `src/schemes/pm/mod.rs`). It imports every
//! file that a `crate::…`, `super::…` or `self::…` path in its code names: the longest
//! prefix of the path that is a file (`crate::schemes::pm::pairs::pair_star` names
//! `schemes/pm/pairs`; `crate::schemes::Workspace` names `schemes`, the file of the
//! re-export). Comments and test code are not read: files named `tests.rs` or
//! `*_tests.rs`, and everything from a file's first `#[cfg(test)]` or
//! `#[cfg(all(test, …))]` on.

#![allow(dead_code)] // each test crate uses its part

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// File -> the files it imports.
pub type Graph = BTreeMap<String, BTreeSet<String>>;

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

/// The module path of a source file under `src` (`""` for `lib.rs` and `main.rs`).
pub fn module_of(src: &Path, p: &Path) -> String {
    let rel = p.strip_prefix(src).unwrap().with_extension("");
    let mut parts: Vec<String> = rel
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect();
    if parts.last().is_some_and(|l| l == "mod") {
        parts.pop();
    }
    if parts.len() == 1 && (parts[0] == "lib" || parts[0] == "main") {
        parts.clear();
    }
    parts.join("/")
}

fn is_test_file(p: &Path) -> bool {
    let name = p.file_name().unwrap().to_string_lossy();
    name == "tests.rs" || name.ends_with("_tests.rs")
}

/// The code of a file that the graph reads: without comments and without test code (an
/// item under `#[cfg(test)]` or `#[cfg(all(test, …))]`: a one-line item such as a `use`
/// or `mod x;` is dropped; a `mod tests {` block ends the code, as test modules close a
/// file). Other multi-line test items are read as code: they can only add edges.
pub fn code_of(text: &str) -> String {
    let mut out = Vec::new();
    let mut lines = text.lines().map(|l| match l.find("//") {
        Some(i) => &l[..i],
        None => l,
    });
    while let Some(l) = lines.next() {
        let t = l.trim();
        if t.starts_with("#[cfg(test)]") || t.starts_with("#[cfg(all(test") {
            // the item the attribute is on (further attributes first)
            let mut item = lines.next().unwrap_or("").trim().to_string();
            while item.starts_with("#[") {
                item = lines.next().unwrap_or("").trim().to_string();
            }
            if item.contains("mod ") && item.ends_with('{') {
                break;
            }
            continue;
        }
        out.push(l);
    }
    out.join("\n")
}

fn ident_at(s: &str) -> &str {
    let n = s
        .find(|c: char| !(c.is_ascii_alphanumeric() || c == '_'))
        .unwrap_or(s.len());
    &s[..n]
}

/// The child modules a file declares (`mod x;`, `pub(crate) mod x;`).
pub fn children(code: &str) -> Vec<String> {
    code.lines()
        .filter_map(|l| {
            let t = l.trim();
            let rest = t.split("mod ").nth(1)?;
            let before = &t[..t.len() - rest.len() - "mod ".len()];
            let visibility = before.is_empty() || before.starts_with("pub");
            let name = ident_at(rest);
            (visibility && !name.is_empty() && rest[name.len()..].trim() == ";")
                .then(|| name.to_string())
        })
        .collect()
}

/// The paths `code` names from `crate::`, `super::` and `self::`, and from the file's
/// own child modules (`x::…` where it declares `mod x;`: the head `self` then), as
/// (head, segments); a group `crate::a::{b, c::d}` gives `a::b` and `a::c::d`.
pub fn paths(code: &str) -> Vec<(String, Vec<String>)> {
    let bytes = code.as_bytes();
    let mut out = Vec::new();
    let kids = children(code);
    let heads: Vec<&str> = ["crate", "super", "self"]
        .into_iter()
        .chain(kids.iter().map(String::as_str))
        .collect();
    for head in heads {
        let pat = format!("{head}::");
        for (i, _) in code.match_indices(&pat) {
            let before = if i == 0 { b' ' } else { bytes[i - 1] };
            if before.is_ascii_alphanumeric() || before == b'_' || before == b'$' || before == b':'
            {
                continue;
            }
            let mut rest = &code[i + pat.len()..];
            let mut segs = Vec::new();
            loop {
                let id = ident_at(rest);
                if id.is_empty() {
                    break;
                }
                segs.push(id.to_string());
                rest = &rest[id.len()..];
                match rest.strip_prefix("::") {
                    Some(r) => rest = r,
                    None => break,
                }
            }
            if let Some(group) = rest.strip_prefix('{') {
                for item in group_items(group) {
                    let mut s = segs.clone();
                    s.extend(
                        item.split("::")
                            .map(|x| ident_at(x.trim()).to_string())
                            .take_while(|x| !x.is_empty() && x != "self"),
                    );
                    out.push((head.to_string(), s));
                }
            }
            out.push((head.to_string(), segs));
        }
    }
    // a child module's path is relative to the file's own module
    for p in &mut out {
        if !["crate", "super", "self"].contains(&p.0.as_str()) {
            p.1.insert(0, std::mem::replace(&mut p.0, "self".into()));
        }
    }
    out
}

/// The top-level items of a `{…}` group whose text starts after the `{`.
fn group_items(group: &str) -> Vec<&str> {
    let (mut depth, mut start, mut items) = (0i32, 0, Vec::new());
    for (k, c) in group.char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => {
                items.push(&group[start..k]);
                return items;
            }
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&group[start..k]);
                start = k + 1;
            }
            _ => {}
        }
    }
    items
}

/// The file-level import graph of the crate whose sources are in `src`.
pub fn graph(src: &Path) -> Graph {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let modules: BTreeSet<String> = files.iter().map(|p| module_of(src, p)).collect();
    let mut g = Graph::new();
    for p in &files {
        let m = module_of(src, p);
        if is_test_file(p) || m.is_empty() || m.split('/').any(|s| s == "tests") {
            continue;
        }
        let here: Vec<&str> = m.split('/').collect();
        // `self::` and `super::` are relative to the module the file is
        let code = code_of(&std::fs::read_to_string(p).unwrap());
        let uses = g.entry(m.clone()).or_default();
        for (head, segs) in paths(&code) {
            let mut full: Vec<String> = match head.as_str() {
                "crate" => Vec::new(),
                "self" => here.iter().map(|s| s.to_string()).collect(),
                _ => here[..here.len() - 1]
                    .iter()
                    .map(|s| s.to_string())
                    .collect(),
            };
            full.extend(segs);
            let target = (1..=full.len())
                .rev()
                .map(|k| full[..k].join("/"))
                .find(|t| modules.contains(t));
            if let Some(t) = target {
                if t != m {
                    uses.insert(t);
                }
            }
        }
    }
    g
}

/// The strongly connected components of `g` with more than one file, each sorted
/// (Tarjan).
pub fn cycles(g: &Graph) -> Vec<Vec<String>> {
    struct T<'a> {
        g: &'a Graph,
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
    t.out.sort();
    t.out
}

/// Prints the graph, a line per file (`cargo test --test layout -- --nocapture`).
pub fn print(g: &Graph) {
    for (m, uses) in g {
        let u: Vec<&str> = uses.iter().map(String::as_str).collect();
        println!("{m} -> {}", u.join(" "));
    }
}
