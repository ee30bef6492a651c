//! Which `[options]` keys each scheme reads is the core's
//! ([`gsph_core::schemes::options`]: each family answers for its schemes); here the scene's
//! keys are put to it. A scene run as it is gets a one-line error for a key its scheme
//! does not read. The sweeps that change the scheme themselves (`gsph study`,
//! `gsph stability`) instead leave such a key out of the runs of the schemes that do not
//! read it and say so on stderr ([`strip_inapplicable`]).

use super::spec::{OptionsSpec, Scene};
use gsph_core::schemes::options::OptionKey;
use gsph_core::schemes::Scheme;

/// The `[options]` keys set in `o` that scheme `scheme` does not read, each with the
/// reason (`options.KEY`, why), in [`OptionKey::ALL`] order.
pub fn inapplicable(o: &OptionsSpec, scheme: Scheme) -> Vec<(&'static str, String)> {
    let asked = o.asked();
    OptionKey::ALL
        .into_iter()
        .filter(|&k| o.is_set(k))
        .filter_map(|k| {
            let why = scheme.reads(k, asked).err()?;
            Some((k.path(), why.to_string()))
        })
        .collect()
}

/// Removes from `scene` the `[options]` keys its scheme does not read and returns them
/// (`options.KEY` each), for the sweeps that choose the scheme themselves.
pub fn strip_inapplicable(scene: &mut Scene) -> Vec<&'static str> {
    let keys: Vec<&'static str> = inapplicable(&scene.options, scene.scheme)
        .into_iter()
        .map(|(k, _)| k)
        .collect();
    for key in OptionKey::ALL {
        if keys.contains(&key.path()) {
            scene.options.unset(key);
        }
    }
    keys
}

/// The schemes that read `key`, in words: each scheme that reads it as it is, and `pm`
/// with the effects the scene's `options.correction`/`options.muscl` must ask for where
/// plain `pm` does not (from [`Scheme::reads`], so from the options table and the
/// families' answers).
fn readers(key: OptionKey) -> String {
    use gsph_core::effects::EffectSet;
    let mut out: Vec<String> = Scheme::ALL
        .into_iter()
        .filter(|s| s.reads(key, EffectSet::HYDRO).is_ok())
        .map(|s| format!("`{s}`"))
        .collect();
    if Scheme::Pm.reads(key, EffectSet::HYDRO).is_err() {
        let with = [
            (EffectSet::MUSCL, "`muscl`"),
            (EffectSet::CORRECTION, "`correction`"),
            (
                EffectSet::CORRECTION.union(EffectSet::MUSCL),
                "`correction` and `muscl`",
            ),
        ]
        .into_iter()
        .find(|(e, _)| Scheme::Pm.reads(key, *e).is_ok());
        if let Some((_, what)) = with {
            out.push(format!("`pm` with {what}"));
        }
    }
    out.join(", ")
}

/// The default of `key` for the schemes that read it: one value, or each value with its
/// schemes where they differ (`superbee (pm, ts2); minmod (tkc)`).
fn default_of(key: OptionKey) -> String {
    use gsph_core::effects::EffectSet;
    let mut groups: Vec<(String, Vec<&str>)> = Vec::new();
    for s in Scheme::ALL {
        let asked = if s == Scheme::Pm {
            EffectSet::CORRECTION.union(EffectSet::MUSCL)
        } else {
            EffectSet::HYDRO
        };
        if s.reads(key, asked).is_err() {
            continue;
        }
        let v = s.default_options().value(key).to_string();
        match groups.iter_mut().find(|(g, _)| *g == v) {
            Some((_, names)) => names.push(s.name()),
            None => groups.push((v, vec![s.name()])),
        }
    }
    match groups.len() {
        0 => "–".into(),
        1 => format!("`{}`", groups[0].0),
        _ => groups
            .iter()
            .map(|(v, names)| format!("`{v}` ({})", names.join(", ")))
            .collect::<Vec<_>>()
            .join("; "),
    }
}

/// `docs/scene-keys.md`: the reference of the `[options]` keys, generated from the core's
/// options table (`gsph_core::scheme_options!`) and the schemes' answers. The test
/// `host/tests/option_keys.rs` keeps the file equal to it (`GSPH_BLESS=1` rewrites it).
pub fn options_reference() -> String {
    use gsph_core::schemes::options::Range;
    let mut md = String::from(
        "# Scene keys: `[options]`\n\n\
         Generated from the options table (`core/src/schemes/options/mod.rs`, \
         `scheme_options!`) and each scheme's answer for each key; do not edit by hand \
         (`GSPH_BLESS=1 cargo test --release -p gsph --test option_keys` rewrites it). \
         A key a scheme does not read is refused with a one-line error naming the key, \
         the scheme and why (`gsph check`). The other sections of a scene are in \
         [user-guide.md](user-guide.md); which scheme to choose is in \
         [schemes.md](schemes.md).\n\n\
         | key | values | default | unit | read by | what it does |\n\
         | --- | --- | --- | --- | --- | --- |\n",
    );
    for key in OptionKey::ALL {
        let range = match key.range() {
            Range::Any => "",
            Range::Positive => " > 0",
            Range::NonNegative => " ≥ 0",
        };
        let unit = match key.unit() {
            "" => "–",
            u => u,
        };
        md.push_str(&format!(
            "| `{}` | {}{range} | {} | {unit} | {} | {}. |\n",
            key.path(),
            key.values(),
            default_of(key),
            readers(key),
            key.doc(),
        ));
    }
    md
}
