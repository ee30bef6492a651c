//! The material library: named materials in `cases/materials/` (one TOML file each, the
//! keys of a `[[materials]]` table without `name`), compiled into the binary, and the
//! resolution of a scene's `[[materials]]` tables against it (cases/materials/README.md).
//!
//! In a scene:
//! - a body (or `reference.material`, `monitor.back_face.material`) that names a material
//!   no `[[materials]]` table declares takes the library material of that name;
//! - a `[[materials]]` table with `library = "NAME"` starts from the library material and
//!   its own keys override the library's: a key replaces the library's value, except a
//!   nested table (`eos`, `strength`) with the same `type` (or none), which overrides key
//!   by key; a nested table with another `type` replaces the library's whole;
//! - `include = "FILE.toml"` does the same with a file of the user's (relative to the scene
//!   file's directory), which may itself say `library = ...`;
//! - `unset = ["KEY", ...]` removes keys of the library material (or included file) before
//!   the table's own keys apply (`unset = ["tensile_strength"]`: no pressure cut-off).
//!
//! The library is compiled in (not looked up on disk), so a scene and a `gsph` version
//! determine its materials wherever the scene runs; `gsph materials` lists the library and
//! `gsph materials --scene FILE` prints a scene's resolved materials and where each came
//! from ([`super::Scene::material_sources`]).

use std::path::Path;
use toml::{Table, Value};

/// One library material: its name (the file stem) and the text of its file.
#[derive(Debug, Clone, Copy)]
pub struct Entry {
    /// Name a scene uses (`material = "steel_4340"`, `library = "steel_4340"`).
    pub name: &'static str,
    /// The file, comments (source, units) included.
    pub text: &'static str,
}

macro_rules! library {
    ($($name:literal),* $(,)?) => {
        &[$(Entry {
            name: $name,
            text: include_str!(concat!("../../../cases/materials/", $name, ".toml")),
        }),*]
    };
}

/// The library, in name order (every `cases/materials/*.toml`; a test checks the list).
pub const LIBRARY: &[Entry] = library![
    "al_6061_t6",
    "al_tillotson",
    "beryllium",
    "connolly2013_beryllium",
    "connolly2013_flyer_metal",
    "connolly2013_steel",
    "ofhc_copper",
    "rublev_murzov_copper",
    "rublev_murzov_riemann_aluminium",
    "rublev_murzov_sound_copper",
    "rublev_murzov_verney_aluminium",
    "sic",
    "steel_4340",
    "tungsten_alloy",
];

/// The keys a `[[materials]]` table may have besides those of a material.
pub const RESOLUTION_KEYS: [&str; 3] = ["library", "include", "unset"];

/// How deep `include`s may nest (a file that includes itself stops here).
const MAX_DEPTH: usize = 8;

/// The library material `name`.
pub fn find(name: &str) -> Option<&'static Entry> {
    LIBRARY.iter().find(|e| e.name == name)
}

/// The one-line source of a library material (its `# source:` comment line).
pub fn source_line(e: &Entry) -> &'static str {
    e.text
        .lines()
        .find_map(|l| l.trim_start().strip_prefix("# source:"))
        .map_or("(no source line)", str::trim)
}

/// The table of a library material (its file parsed; files are checked by the tests).
pub fn table_of(e: &Entry) -> Result<Table, String> {
    e.text
        .parse::<Table>()
        .map_err(|err| format!("library material `{}`: malformed TOML: {err}", e.name))
}

/// Library names close to `name` (a word in common, give or take a letter; a few letters
/// apart; or one inside the other), nearest first; at most five.
pub fn close_names(name: &str) -> Vec<&'static str> {
    let lower = name.to_ascii_lowercase();
    let words: Vec<&str> = lower
        .split(['_', '-', ' '])
        .filter(|w| w.len() >= 3)
        .collect();
    let mut hits: Vec<(usize, &'static str)> = LIBRARY
        .iter()
        .filter_map(|e| {
            let d = edit_distance(&lower, e.name);
            let near = d <= (lower.len() / 4).max(2);
            let inside = lower.len() >= 3 && (e.name.contains(&*lower) || lower.contains(e.name));
            let word = words.iter().any(|w| {
                e.name
                    .split('_')
                    .any(|x| edit_distance(w, x) <= usize::from(w.len() >= 5))
            });
            (near || inside || word).then_some((d, e.name))
        })
        .collect();
    hits.sort();
    hits.into_iter().take(5).map(|(_, n)| n).collect()
}

/// Levenshtein distance (bytes; names are ASCII).
fn edit_distance(a: &str, b: &str) -> usize {
    let (a, b) = (a.as_bytes(), b.as_bytes());
    let mut prev: Vec<usize> = (0..=b.len()).collect();
    for (i, &ca) in a.iter().enumerate() {
        let mut cur = vec![i + 1; b.len() + 1];
        for (j, &cb) in b.iter().enumerate() {
            let sub = prev[j] + usize::from(ca != cb);
            cur[j + 1] = sub.min(prev[j + 1] + 1).min(cur[j] + 1);
        }
        prev = cur;
    }
    prev[b.len()]
}

/// `(close: a, b; ...)` for a name that is not in the library.
fn not_in_library(name: &str) -> String {
    let close = close_names(name);
    let all = format!("`gsph materials` lists all {}", LIBRARY.len());
    if close.is_empty() {
        format!("`{name}` is not in the material library ({all})")
    } else {
        format!(
            "`{name}` is not in the material library (close: {}; {all})",
            close.join(", ")
        )
    }
}

/// Resolves the `[[materials]]` tables of a parsed scene in place: `library`, `include`
/// and `unset` are replaced by the material they describe, and a material that a body,
/// `reference.material` or `monitor.back_face.material` names but no table declares is
/// added from the library. Returns where each material of the result came from. `base` is
/// the directory `include` paths are relative to. Errors are one line, `KEY: cause`.
pub fn resolve(scene: &mut Table, base: Option<&Path>) -> Result<Vec<String>, String> {
    let mut sources = Vec::new();
    if let Some(Value::Array(materials)) = scene.get_mut("materials") {
        for (k, m) in materials.iter_mut().enumerate() {
            let key = format!("materials[{k}]");
            let source = match m {
                Value::Table(t) => {
                    let (resolved, source) = resolve_table(std::mem::take(t), &key, base, 0)?;
                    *t = resolved;
                    source
                }
                // not a table: the schema reports it
                _ => "scene".into(),
            };
            sources.push(source);
        }
    }
    for (key, name) in referenced_names(scene) {
        let declared = match scene.get("materials") {
            Some(Value::Array(a)) => a
                .iter()
                .any(|m| m.get("name") == Some(&Value::from(&*name))),
            Some(_) => true, // the schema reports a `materials` that is not an array
            None => false,
        };
        if declared || find(&name).is_none() {
            continue; // an unknown name is reported by the validation, with close names
        }
        let mut t = Table::new();
        t.insert("library".into(), Value::from(&*name));
        let at = format!("{key} -> library");
        let (resolved, source) = resolve_table(t, &at, base, 0)?;
        let materials = scene
            .entry("materials")
            .or_insert_with(|| Value::Array(Vec::new()));
        if let Value::Array(a) = materials {
            a.push(Value::Table(resolved));
            sources.push(format!("{source} (named by {key})"));
        }
    }
    Ok(sources)
}

/// The material names the scene refers to, with the key of each (`bodies[1].material`).
fn referenced_names(scene: &Table) -> Vec<(String, String)> {
    let mut out = Vec::new();
    if let Some(Value::Array(bodies)) = scene.get("bodies") {
        for (k, b) in bodies.iter().enumerate() {
            if let Some(Value::String(n)) = b.get("material") {
                out.push((format!("bodies[{k}].material"), n.clone()));
            }
        }
    }
    if let Some(Value::String(n)) = scene.get("reference").and_then(|r| r.get("material")) {
        out.push(("reference.material".into(), n.clone()));
    }
    let back_face = scene.get("monitor").and_then(|m| m.get("back_face"));
    if let Some(Value::String(n)) = back_face.and_then(|b| b.get("material")) {
        out.push(("monitor.back_face.material".into(), n.clone()));
    }
    out
}

/// One `[[materials]]` table resolved: the material table and its source.
fn resolve_table(
    mut local: Table,
    key: &str,
    base: Option<&Path>,
    depth: usize,
) -> Result<(Table, String), String> {
    let library = local.remove("library");
    let include = local.remove("include");
    let unset = local.remove("unset");
    let (mut table, mut source, default_name) = match (library, include) {
        (Some(_), Some(_)) => {
            return Err(format!(
                "{key}: give `library` or `include`, not both (an included file may say `library`)"
            ))
        }
        (None, None) => {
            if unset.is_some() {
                return Err(format!(
                    "{key}.unset: removes keys of a library material or included file; give `library` or `include`"
                ));
            }
            return Ok((local, "scene".into()));
        }
        (Some(v), None) => {
            let Value::String(name) = v else {
                return Err(format!(
                    "{key}.library: expected the name of a library material (a string), found {}",
                    v.type_str()
                ));
            };
            let e =
                find(&name).ok_or_else(|| format!("{key}.library: {}", not_in_library(&name)))?;
            let mut t = table_of(e).map_err(|m| format!("{key}.library: {m}"))?;
            t.remove("name");
            (t, format!("library {name}"), name)
        }
        (None, Some(v)) => {
            if depth >= MAX_DEPTH {
                return Err(format!(
                    "{key}.include: included files nest more than {MAX_DEPTH} deep (does a file include itself?)"
                ));
            }
            let Value::String(file) = v else {
                return Err(format!(
                    "{key}.include: expected a file name (a string), found {}",
                    v.type_str()
                ));
            };
            crate::output::safe::check_file_name(&file)
                .map_err(|e| format!("{key}.include: {e}"))?;
            let path = match base {
                Some(dir) if Path::new(&file).is_relative() => dir.join(&file),
                _ => Path::new(&file).to_path_buf(),
            };
            let text = read_material_file(&path)
                .map_err(|e| format!("{key}.include: cannot read {}: {e}", path.display()))?;
            let parsed: Table = text.parse().map_err(|e: toml::de::Error| {
                let cause = e.message().split_whitespace().collect::<Vec<_>>().join(" ");
                // (the parser quotes what it found: an excerpt of it)
                let cause = crate::output::safe::shorten_quotes(&cause);
                format!("{key}.include: {}: malformed TOML: {cause}", path.display())
            })?;
            // the file's own `name`, else its stem (not the name of a library material
            // the file starts from)
            let name = match parsed.get("name") {
                Some(Value::String(n)) => n.clone(),
                _ => path
                    .file_stem()
                    .map_or_else(|| file.clone(), |s| s.to_string_lossy().into_owned()),
            };
            let inner_key = format!("{key}.include({file})");
            let (mut t, inner) = resolve_table(parsed, &inner_key, path.parent(), depth + 1)?;
            t.remove("name");
            let source = if inner == "scene" {
                format!("include {file}")
            } else {
                format!("include {file} ({inner})")
            };
            (t, source, name)
        }
    };
    if let Some(u) = unset {
        let removed = apply_unset(&mut table, u, key)?;
        source.push_str(&format!(", without {}", removed.join(", ")));
    }
    let mut changed = Vec::new();
    overlay(&mut table, local, "", &mut changed);
    changed.retain(|k| k != "name");
    if !changed.is_empty() {
        source.push_str(&format!(", with the scene's {}", changed.join(", ")));
    }
    table
        .entry("name")
        .or_insert_with(|| Value::String(default_name));
    Ok((table, source))
}

/// The largest material file `include` reads.
const MAX_FILE: u64 = 1 << 20;

/// The text of an included material file: a regular file of at most [`MAX_FILE`] bytes
/// (not a device or a pipe that never ends).
fn read_material_file(path: &Path) -> Result<String, String> {
    let meta = std::fs::metadata(path).map_err(|e| e.to_string())?;
    if !meta.is_file() {
        return Err("not a regular file".into());
    }
    if meta.len() > MAX_FILE {
        return Err(format!(
            "{} bytes, more than a material file's {MAX_FILE}",
            meta.len()
        ));
    }
    std::fs::read_to_string(path).map_err(|e| e.to_string())
}

/// Removes the (dotted) keys listed in `unset` from `table`; returns them.
fn apply_unset(table: &mut Table, unset: Value, key: &str) -> Result<Vec<String>, String> {
    let wrong = || {
        format!("{key}.unset: expected an array of key names, e.g. unset = [\"tensile_strength\"]")
    };
    let Value::Array(items) = unset else {
        return Err(wrong());
    };
    let mut removed = Vec::new();
    for item in items {
        let Value::String(path) = item else {
            return Err(wrong());
        };
        let parts: Vec<&str> = path.split('.').collect();
        let (last, head) = parts.split_last().expect("split yields one part");
        let mut at = &mut *table;
        for p in head {
            match at.get_mut(*p) {
                Some(Value::Table(t)) => at = t,
                _ => {
                    return Err(format!(
                        "{key}.unset: `{path}` is not a key of the material it names"
                    ))
                }
            }
        }
        if at.remove(*last).is_none() {
            return Err(format!(
                "{key}.unset: `{path}` is not a key of the material it names"
            ));
        }
        removed.push(path);
    }
    Ok(removed)
}

/// Writes `local` over `base`: a nested table over a nested table of the same `type` (or
/// without one) key by key, anything else whole. Records the dotted keys written.
fn overlay(base: &mut Table, local: Table, prefix: &str, changed: &mut Vec<String>) {
    for (k, v) in local {
        let path = format!("{prefix}{k}");
        match (base.get_mut(&k), v) {
            (Some(Value::Table(b)), Value::Table(l))
                if l.get("type").is_none() || l.get("type") == b.get("type") =>
            {
                overlay(b, l, &format!("{path}."), changed);
            }
            (_, v) => {
                base.insert(k, v);
                changed.push(path);
            }
        }
    }
}

/// Adds the resolution keys to serde's list of a material's keys in an unknown-key message
/// (`materials[0].colour: unknown key (known: name, ..., tensile_strength)`).
pub fn explain_unknown_key(msg: String) -> String {
    const LAST: &str = "tensile_strength)";
    if msg.starts_with("materials[") && msg.contains("unknown key (known: name, rho0") {
        msg.replacen(
            LAST,
            &format!("tensile_strength, {})", RESOLUTION_KEYS.join(", ")),
            1,
        )
    } else {
        msg
    }
}

#[path = "library_cmd.rs"]
mod cmd;
pub use cmd::{list, model_summary, scene_report, show, spec_of};

#[cfg(test)]
#[path = "library_tests.rs"]
mod tests;
