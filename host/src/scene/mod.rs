//! Scene files: TOML descriptions of a case (DESIGN §6).
//!
//! A scene names its materials, bodies (shapes filled with a particle lattice), initial
//! fields, scheme and run controls. Unknown keys are errors. `--set KEY=VALUE` overrides
//! any key by dotted path before the scene is interpreted (see [`apply_override`]).
//! Every error is one line naming the file, the key and the cause.

pub mod applies;
mod checks;
mod de;
pub mod library;
mod material_spec;
pub mod materials;
pub mod setup;
mod spec;
mod validate;
mod validate_parts;
pub mod walls;
mod window;

pub use setup::build::{
    build_particles, build_particles_reporting, check_particles, InitialParticles, MAX_PARTICLES,
};
pub use setup::window::WindowGeometry;
use setup::{build, periodic};
pub use setup::{import, pores, stl};
pub use spec::*;
pub use walls::WallSpec;
pub use window::WindowSpec;

use crate::output::safe::{excerpt, excerpt_to, shorten_quotes};
use std::path::Path;

/// Scene name: the `name` key or the file stem of `path`.
pub fn scene_name(scene: &Scene, path: &Path) -> String {
    scene.name.clone().unwrap_or_else(|| {
        path.file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_default()
    })
}

/// A scene error: one line naming the key (or position) and the cause.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneError(pub String);

impl std::fmt::Display for SceneError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for SceneError {}

fn err<T>(msg: impl Into<String>) -> Result<T, SceneError> {
    Err(SceneError(msg.into()))
}

/// The largest scene file read (far above any scene written by hand or by a script).
pub const MAX_SCENE: u64 = 1 << 26;

/// The text of a scene file: a regular file (not a directory, a pipe or a device) of at most
/// [`MAX_SCENE`] bytes.
pub fn read_scene(path: &Path) -> Result<String, SceneError> {
    crate::output::safe::read_text(path, MAX_SCENE).map_err(|e| {
        let cause = e.strip_prefix("cannot read: ").unwrap_or(&e);
        SceneError(format!("{}: cannot read scene: {cause}", path.display()))
    })
}

/// Reads and validates a scene file, applying `overrides` (`KEY=VALUE`) first.
pub fn load(path: &Path, overrides: &[String]) -> Result<Scene, SceneError> {
    let text = read_scene(path)?;
    parse(&text, &path.display().to_string(), overrides)
}

/// Parses and validates scene text. `origin` names the source in messages.
///
/// Beyond the schema and the semantic checks of `validate`, this builds the particles once, so a
/// body that holds no particle, an initial state the EOS cannot reach, or a scene too large
/// for memory is reported here, before any output is written.
pub fn parse(text: &str, origin: &str, overrides: &[String]) -> Result<Scene, SceneError> {
    parse_inner(text, origin, overrides, Mode::Bodies).map(|(s, _)| s)
}

/// Parses and validates the settings of a scene whose particles the caller gives (the
/// library's `Simulation::from_particles`): scene text without `bodies`. The particles
/// are checked with [`build::check_particles`] once they are known.
pub fn parse_settings(text: &str, origin: &str, overrides: &[String]) -> Result<Scene, SceneError> {
    parse_inner(text, origin, overrides, Mode::Settings).map(|(s, _)| s)
}

/// What [`parse_inner`] checks.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Mode {
    /// A whole scene.
    Bodies,
    /// A whole scene whose inapplicable `[options]` keys are dropped.
    Strip,
    /// A scene without bodies.
    Settings,
}

/// Reads a scene for a sweep that sets the scheme itself (`gsph study`, `gsph stability`):
/// as [`load`] with `scheme=NAME` appended to `overrides`, but the `[options]` keys that
/// scheme does not read are left out (and returned, `options.KEY` each) instead of refused.
pub fn load_for_scheme(
    path: &Path,
    overrides: &[String],
    scheme: &str,
) -> Result<(Scene, Vec<&'static str>), SceneError> {
    let text = read_scene(path)?;
    let mut set = overrides.to_vec();
    set.push(format!("scheme={scheme}"));
    parse_inner(&text, &path.display().to_string(), &set, Mode::Strip)
}

fn parse_inner(
    text: &str,
    origin: &str,
    overrides: &[String],
    mode: Mode,
) -> Result<(Scene, Vec<&'static str>), SceneError> {
    let mut value: toml::Table = text
        .parse::<toml::Table>()
        .map_err(|e| SceneError(toml_error(text, origin, &e)))?;
    for o in overrides {
        match o.strip_prefix(UNSET) {
            Some(key) => remove_key(&mut value, key)
                .map_err(|e| SceneError(format!("--unset {}: {}", excerpt(key), e.0)))?,
            None => apply_override(&mut value, o)
                .map_err(|e| SceneError(format!("--set {}: {}", shown_override(o), e.0)))?,
        }
    }
    if mode == Mode::Settings {
        // the caller gives the particles: no bodies (validate_settings refuses any)
        value
            .entry("bodies")
            .or_insert_with(|| toml::Value::Array(Vec::new()));
    }
    let blame = |msg: String, up: bool| {
        SceneError(format!("{}: {msg}", source_of(&msg, up, origin, overrides)))
    };
    // `include` paths are relative to the scene file's directory (to the working directory
    // for scene text that does not come from a file)
    let file = Path::new(origin);
    let base = file.parent().filter(|_| file.is_file());
    let sources = library::resolve(&mut value, base).map_err(|e| blame(e, true))?;
    let mut scene = Scene::deserialize_table(value)
        .map_err(|e| blame(library::explain_unknown_key(e), true))?;
    scene.material_sources = sources;
    // particle and STL files, like included material files, are relative to the scene file
    import::resolve_files(&mut scene, base);
    let dropped = if mode == Mode::Strip {
        applies::strip_inapplicable(&mut scene)
    } else {
        Vec::new()
    };
    if mode == Mode::Settings {
        validate::validate_settings(&scene).map_err(|e| blame(e.0, false))?;
    } else {
        validate::validate(&scene).map_err(|e| blame(e.0, false))?;
    }
    periodic::check_length(&scene).map_err(|e| blame(e.0, false))?;
    validate::resolve_poisson(&mut scene).map_err(|e| blame(e.0, false))?;
    if mode != Mode::Settings {
        build::check_build(&scene).map_err(|e| blame(e.0, false))?;
    }
    Ok((scene, dropped))
}

/// `origin:line:col: malformed TOML: cause` on one line.
fn toml_error(text: &str, origin: &str, e: &toml::de::Error) -> String {
    let cause: Vec<&str> = e
        .message()
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    let at = match e.span() {
        Some(s) => {
            let before = text.get(..s.start.min(text.len())).unwrap_or(text);
            let line = before.matches('\n').count() + 1;
            let line_start = before.rfind('\n').map_or(0, |p| p + 1);
            let col = before[line_start..].chars().count() + 1;
            format!(":{line}:{col}")
        }
        None => String::new(),
    };
    // (the parser quotes what it found: an excerpt of it); where it gives no reason (a
    // NUL in a comment), the character it stopped at
    let mut why = shorten_quotes(&cause.join("; "));
    if why.is_empty() {
        let found = e
            .span()
            .and_then(|s| text.get(s.start.min(text.len())..))
            .and_then(|rest| rest.chars().next());
        why = match found {
            Some(c) if c.is_control() => format!(
                "the control character U+{:04X}, which TOML allows nowhere (not even in a comment)",
                c as u32
            ),
            _ => "the parser gives no reason".into(),
        };
    }
    format!("{origin}{at}: malformed TOML: {why}")
}

/// `KEY=VALUE` of a `--set` as a message shows it: whole up to 120 characters (an inline
/// table), else an excerpt; control characters escaped.
fn shown_override(o: &str) -> String {
    excerpt_to(o, 120)
}

/// Where the value behind an error came from: the last `--set` that wrote the key the message
/// starts with or a table holding it (with `up`, also a key inside it), else `origin`.
fn source_of(msg: &str, up: bool, origin: &str, overrides: &[String]) -> String {
    let key = msg.split(": ").next().unwrap_or("");
    let inside = |inner: &str, outer: &str| {
        inner
            .strip_prefix(outer)
            .is_some_and(|rest| rest.is_empty() || rest.starts_with('.') || rest.starts_with('['))
    };
    let hit = |set: &str| inside(key, set) || (up && inside(set, key));
    overrides
        .iter()
        .rev()
        .find(|o| {
            o.split_once('=')
                .is_some_and(|(k, _)| hit(&bracketed(k.trim())))
        })
        .map_or_else(
            || origin.to_string(),
            |o| format!("--set {}", shown_override(o)),
        )
}

/// `bodies.0.spacing` -> `bodies[0].spacing` (the form messages use).
fn bracketed(dotted: &str) -> String {
    let mut s = String::new();
    for part in dotted.split('.') {
        if !s.is_empty() && part.parse::<usize>().is_ok() {
            s.push_str(&format!("[{part}]"));
        } else {
            if !s.is_empty() {
                s.push('.');
            }
            s.push_str(part);
        }
    }
    s
}

/// The prefix that marks an override as a removal (`--unset KEY` is `unset:KEY` among the
/// overrides, so that checkpoints and messages keep it in order with the `--set`s).
pub const UNSET: &str = "unset:";

/// `set` followed by the removals `unset` (each `KEY`, encoded as [`UNSET`]`KEY`).
pub fn with_unsets(mut set: Vec<String>, unset: &[String]) -> Vec<String> {
    set.extend(unset.iter().map(|k| format!("{UNSET}{k}")));
    set
}

/// Removes the key at dotted path `key` from a parsed scene table; an error if it is not
/// there (a removal that removes nothing is a typo).
fn remove_key(table: &mut toml::Table, key: &str) -> Result<(), SceneError> {
    fn walk(v: &mut toml::Value, parts: &[&str]) -> bool {
        let Some((first, rest)) = parts.split_first() else {
            return false;
        };
        match v {
            toml::Value::Table(t) if rest.is_empty() => t.remove(*first).is_some(),
            toml::Value::Table(t) => t.get_mut(*first).is_some_and(|c| walk(c, rest)),
            toml::Value::Array(a) if !rest.is_empty() => first
                .parse::<usize>()
                .ok()
                .and_then(|i| a.get_mut(i))
                .is_some_and(|c| walk(c, rest)),
            _ => false,
        }
    }
    let parts: Vec<&str> = key.trim().split('.').map(str::trim).collect();
    if parts.iter().any(|p| p.is_empty()) {
        return err(format!("`{key}` has an empty part"));
    }
    let mut root = toml::Value::Table(std::mem::take(table));
    let found = walk(&mut root, &parts);
    if let toml::Value::Table(t) = root {
        *table = t;
    }
    if found {
        Ok(())
    } else {
        err(format!("`{}` is not in the scene", key.trim()))
    }
}

/// Parses the value of an override: a TOML value, or else the text as a string.
fn override_value(raw: &str) -> toml::Value {
    use serde::Deserialize;
    toml::Value::deserialize(toml::de::ValueDeserializer::new(raw))
        .unwrap_or_else(|_| toml::Value::String(raw.to_string()))
}

/// Applies one `KEY=VALUE` override to a parsed scene table. `KEY` is a dotted path; array
/// elements are addressed by index (`bodies.0.spacing`). `VALUE` is parsed as a TOML value
/// (`1e-3`, `true`, `[1.0, 2.0]`, `"text"`); a bare word that is not valid TOML is taken as
/// a string (`scheme=ts2`). Missing tables on the path are created; array indices must exist.
pub fn apply_override(table: &mut toml::Table, assignment: &str) -> Result<(), SceneError> {
    let (key, raw) = assignment
        .split_once('=')
        .ok_or_else(|| SceneError("expected KEY=VALUE".into()))?;
    let key = key.trim();
    if key.is_empty() {
        return err("empty key");
    }
    let value = override_value(raw.trim());
    let parts: Vec<&str> = key.split('.').map(str::trim).collect();
    if parts.iter().any(|p| p.is_empty()) {
        return err(format!("`{key}` has an empty part"));
    }
    let mut cur = TomlSlot::Table(table);
    for (k, part) in parts.iter().enumerate() {
        let last = k + 1 == parts.len();
        cur = match cur {
            TomlSlot::Table(t) => {
                if last {
                    t.insert(part.to_string(), value);
                    return Ok(());
                }
                let entry = t
                    .entry(part.to_string())
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()));
                TomlSlot::from_value(entry, &parts[..=k])?
            }
            TomlSlot::Array(a) => {
                let idx: usize = part.parse().map_err(|_| {
                    SceneError(format!(
                        "`{}` is an array: expected an index, got `{part}`",
                        parts[..k].join(".")
                    ))
                })?;
                let len = a.len();
                let slot = a.get_mut(idx).ok_or_else(|| {
                    SceneError(format!(
                        "`{}` has {len} elements, index {idx} is out of range",
                        parts[..k].join(".")
                    ))
                })?;
                if last {
                    *slot = value;
                    return Ok(());
                }
                TomlSlot::from_value(slot, &parts[..=k])?
            }
        };
    }
    Ok(())
}

enum TomlSlot<'a> {
    Table(&'a mut toml::Table),
    Array(&'a mut Vec<toml::Value>),
}

impl<'a> TomlSlot<'a> {
    fn from_value(v: &'a mut toml::Value, path: &[&str]) -> Result<Self, SceneError> {
        match v {
            toml::Value::Table(t) => Ok(TomlSlot::Table(t)),
            toml::Value::Array(a) => Ok(TomlSlot::Array(a)),
            _ => err(format!(
                "`{}` is a value, not a table or array",
                path.join(".")
            )),
        }
    }
}

#[cfg(test)]
mod tests;
