//! The scene parser on arbitrary UTF-8: `gsph::scene::parse` must return `Ok` or an error
//! of one line, and never panic. The input is the scene text, optionally followed by a
//! line `%%` and `--set` assignments, one per line.
#![no_main]
use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    let (scene, sets) = match text.split_once("\n%%\n") {
        Some((a, b)) => (a, b.lines().map(str::to_owned).collect::<Vec<_>>()),
        None => (text, Vec::new()),
    };
    if let Err(e) = gsph::scene::parse(scene, "fuzz.toml", &sets) {
        assert!(
            !e.0.contains('\n') && !e.0.is_empty(),
            "error is not one line: {:?}",
            e.0
        );
    }
});
