//! `gsph materials`: the library listed, one material printed, a scene's resolved materials.

use super::{find, not_in_library, source_line, table_of, Entry, LIBRARY};
use crate::scene::MaterialSpec;
use std::path::Path;
use toml::Value;

/// A library material read as a scene material (named after its file).
pub fn spec_of(e: &Entry) -> Result<MaterialSpec, String> {
    let mut t = table_of(e)?;
    t.insert("name".into(), Value::from(e.name));
    crate::scene::de::from_table(t).map_err(|err| format!("library material `{}`: {err}", e.name))
}

/// `EOS + strength [+ pressure cut-off]`, e.g. `mie_gruneisen + johnson_cook`.
pub fn model_summary(m: &MaterialSpec) -> String {
    let eos = m.eos.name();
    let strength = match &m.strength {
        Some(strength) => strength.name(),
        None if m.shear_modulus > 0.0 || m.poisson_ratio.is_some() => "elastic",
        None => "fluid",
    };
    let cut = if m.tensile_strength.is_some() {
        " + tensile cut-off"
    } else {
        ""
    };
    format!("{eos} + {strength}{cut}")
}

/// `gsph materials`: one line per library material (name, density, models, source).
pub fn list() -> Result<String, String> {
    let mut out = format!(
        "{:<32} {:>8}  {:<42} source\n",
        "name", "rho0", "EOS + strength"
    );
    for e in LIBRARY {
        let m = spec_of(e)?;
        out.push_str(&format!(
            "{:<32} {:>8}  {:<42} {}\n",
            e.name,
            m.rho0,
            model_summary(&m),
            source_line(e)
        ));
    }
    out.push_str(&format!(
        "{} materials (cases/materials/, compiled in); `gsph materials NAME` prints one\n",
        LIBRARY.len()
    ));
    Ok(out)
}

/// `gsph materials NAME`: the library file, comments (source, units) included.
pub fn show(name: &str) -> Result<String, String> {
    find(name)
        .map(|e| e.text.to_string())
        .ok_or_else(|| not_in_library(name))
}

/// `gsph materials --scene FILE`: each material of the scene as the run uses it (library,
/// includes and overrides resolved, `poisson_ratio` turned into `shear_modulus`) with
/// where it came from.
pub fn scene_report(path: &Path, overrides: &[String]) -> Result<String, String> {
    let sc = crate::scene::load(path, overrides).map_err(|e| e.to_string())?;
    let mut out = format!(
        "# {}: {} material{}, as the run uses them\n",
        path.display(),
        sc.materials.len(),
        if sc.materials.len() == 1 { "" } else { "s" }
    );
    for (k, m) in sc.materials.iter().enumerate() {
        let source = sc.material_sources.get(k).map_or("scene", String::as_str);
        out.push_str(&format!("\n# materials[{k}] `{}`: {source}\n", m.name));
        // a struct, not a toml::Table, keeps the keys in the schema's order
        #[derive(serde::Serialize)]
        struct One<'a> {
            materials: [&'a MaterialSpec; 1],
        }
        let text =
            toml::to_string(&One { materials: [m] }).map_err(|e| format!("materials[{k}]: {e}"))?;
        out.push_str(&text);
    }
    Ok(out)
}
