//! Which `[options]` keys each scheme reads (promise 3: a key either changes the result or
//! is refused, naming the key and the scheme).
//!
//! | key | read by |
//! | --- | --- |
//! | `av_alpha`, `av_beta` | `av` |
//! | `limiter` | the schemes with MUSCL: `ts2`, `tkc`, `pm` with `muscl = true` |
//! | `riemann` | every Godunov scheme: `pm`, `tkc` (longitudinal wave), `ts1`, `ts2` |
//! | `muscl_time` | `ts2` |
//! | `surface_lambda`, `det_epsilon` | `ts1`, `ts2` (free-surface divergence), `tkc`, `pm` with `correction = true` |
//! | `correction`, `muscl` | `pm` (tkc always has both) |
//!
//! A scene run as it is gets a one-line error for a key its scheme does not read. The
//! sweeps that change the scheme themselves (`gsph study`, `gsph stability`) instead leave
//! such a key out of the runs of the schemes that do not read it and say so on stderr
//! ([`strip_inapplicable`]).

use super::spec::{OptionsSpec, Scene};

/// The `[options]` keys set in `o` that scheme `scheme` does not read, each with the
/// reason (`options.KEY`, why).
pub fn inapplicable(o: &OptionsSpec, scheme: &str) -> Vec<(&'static str, String)> {
    let pm_muscl = scheme == "pm" && o.muscl == Some(true);
    let pm_corr = scheme == "pm" && o.correction == Some(true);
    let muscl = scheme == "ts2" || scheme == "tkc" || pm_muscl;
    let surface = matches!(scheme, "ts1" | "ts2" | "tkc") || pm_corr;
    let mut out = Vec::new();
    let mut no = |set: bool, key: &'static str, why: &str| {
        if set {
            out.push((key, format!("not read by scheme {scheme} ({why})")));
        }
    };
    no(
        o.av_alpha.is_some() && scheme != "av",
        "options.av_alpha",
        "artificial viscosity is scheme av's",
    );
    no(
        o.av_beta.is_some() && scheme != "av",
        "options.av_beta",
        "artificial viscosity is scheme av's",
    );
    no(
        o.limiter.is_some() && !muscl,
        "options.limiter",
        "it has no MUSCL reconstruction; ts2, tkc and pm with options.muscl have",
    );
    no(
        o.riemann.is_some() && scheme == "av",
        "options.riemann",
        "it solves no Riemann problem",
    );
    no(
        o.muscl_time.is_some() && scheme != "ts2",
        "options.muscl_time",
        "only ts2's reconstruction has a time treatment",
    );
    for (set, key) in [
        (o.surface_lambda.is_some(), "options.surface_lambda"),
        (o.det_epsilon.is_some(), "options.det_epsilon"),
    ] {
        no(
            set && !surface,
            key,
            "it has no free-surface rule; ts1, ts2, tkc and pm with options.correction have",
        );
    }
    for (set, key, what) in [
        (o.correction.is_some(), "options.correction", "correction"),
        (o.muscl.is_some(), "options.muscl", "MUSCL"),
    ] {
        if set && scheme == "tkc" {
            out.push((
                key,
                format!("scheme tkc always has {what}; choose it for scheme pm"),
            ));
        } else if set && scheme != "pm" {
            out.push((key, format!("only with scheme pm (scheme is {scheme})")));
        }
    }
    out
}

/// Removes from `scene` the `[options]` keys its scheme does not read and returns them
/// (`options.KEY` each), for the sweeps that choose the scheme themselves.
pub fn strip_inapplicable(scene: &mut Scene) -> Vec<&'static str> {
    let keys: Vec<&'static str> = inapplicable(&scene.options, &scene.scheme)
        .into_iter()
        .map(|(k, _)| k)
        .collect();
    let o = &mut scene.options;
    for k in &keys {
        match *k {
            "options.av_alpha" => o.av_alpha = None,
            "options.av_beta" => o.av_beta = None,
            "options.limiter" => o.limiter = None,
            "options.riemann" => o.riemann = None,
            "options.muscl_time" => o.muscl_time = None,
            "options.surface_lambda" => o.surface_lambda = None,
            "options.det_epsilon" => o.det_epsilon = None,
            "options.correction" => o.correction = None,
            "options.muscl" => o.muscl = None,
            _ => unreachable!("inapplicable() names only these keys"),
        }
    }
    keys
}
