//! `gsph materials` through the real binary: the library listed, one material printed, a
//! scene's resolved materials with their sources, and one-line errors.
#![cfg(feature = "cli")]

use std::path::Path;
use std::process::{Command, Output};

fn gsph(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gsph"))
        .args(args)
        .current_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join(".."))
        .output()
        .expect("gsph starts")
}

fn stdout(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn materials_lists_the_library() {
    let out = stdout(&gsph(&["materials"]));
    for e in gsph::scene::library::LIBRARY {
        let line = out
            .lines()
            .find(|l| l.split_whitespace().next() == Some(e.name))
            .unwrap_or_else(|| panic!("no line for {}: {out}", e.name));
        assert!(
            line.contains(gsph::scene::library::source_line(e)),
            "{line}"
        );
    }
    assert!(out.contains("mie_gruneisen + johnson_cook"), "{out}");
}

#[test]
fn materials_name_prints_the_file() {
    let out = stdout(&gsph(&["materials", "steel_4340"]));
    assert!(out.contains("# source: Johnson & Cook 1983"), "{out}");
    assert!(out.contains("a = 792.0e6"), "{out}");
    let o = gsph(&["materials", "steel_434"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1));
    assert!(
        err.starts_with("error: `steel_434` is not in the material library (close: steel_4340, connolly2013_steel;"),
        "{err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
}

#[test]
fn materials_scene_prints_resolved_materials_and_sources() {
    let out = stdout(&gsph(&[
        "materials",
        "--scene",
        "cases/hard/spall_plate.toml",
        "--set",
        "materials.0.rho0=8900.0",
    ]));
    assert!(
        out.contains("# materials[0] `copper`: library rublev_murzov_copper, without tensile_strength, with the scene's rho0"),
        "{out}"
    );
    assert!(out.contains("rho0 = 8900.0"), "{out}");
    assert!(
        !out.lines().any(|l| l.starts_with("tensile_strength")),
        "{out}"
    );
    // what it prints is a valid [[materials]] table
    let t: toml::Table = out.parse().expect("TOML");
    assert_eq!(t["materials"].as_array().map(Vec::len), Some(1));
}
