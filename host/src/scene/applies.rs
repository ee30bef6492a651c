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
