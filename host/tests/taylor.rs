//! The Taylor impact test (cases/taylor_copper.toml, issue 17) at the scene's own spacing
//! D0/10 with tkc: the quarter rod comes to rest on the rigid wall, none of it passes the
//! wall, energy is conserved, and its final length and impact-face diameter are near the
//! measured ones (Wilkins & Guinan 1973, cases/data/taylor_wilkins_guinan_1973.csv).
//! At this coarse spacing tkc reads +6.9 % on the length and -10.2 % on the diameter (-8.9 %
//! before issue 27); at
//! D0/20 and D0/30 (scripts/taylor.sh) +3.0 % and +1.8 % on the length, within the 5 %
//! target (docs/validation.md §4). The bounds below hold today's coarse figures with a few
//! percent to spare, so that a change that moves them by more fails.

use gsph::driver::{run, RunOptions};
use gsph::monitor::rod::read_outline;
use gsph::scene;
use std::path::Path;

fn cases() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases")
}

#[test]
fn the_copper_rod_comes_to_rest_near_the_measured_length_and_face() {
    let text = std::fs::read_to_string(cases().join("taylor_copper.toml")).unwrap();
    let sc = scene::parse(&text, "taylor_copper", &[]).unwrap_or_else(|e| panic!("{e}"));
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("taylor");
    let r = run(
        &sc,
        "taylor_copper",
        &RunOptions {
            out: Some(out.clone()),
            progress: false,
        },
    )
    .unwrap_or_else(|e| panic!("{e}"));
    let num = |k: &str| r.summary.number(k).unwrap_or_else(|| panic!("{k}"));

    // the measured outline: length = its highest point, face = twice its radius at z = 0
    let outline = read_outline(&cases().join("data/taylor_wilkins_guinan_1973.csv")).unwrap();
    let l_exp = outline.iter().map(|p| p.1).fold(0.0, f64::max) * 1e-3;
    let d_exp = 2.0
        * outline
            .iter()
            .filter(|p| p.1 == 0.0)
            .map(|p| p.0)
            .fold(0.0, f64::max)
        * 1e-3;
    assert!((l_exp - 14.7964e-3).abs() < 1e-9 && (d_exp - 16.793e-3).abs() < 1e-9);

    let (l, d) = (num("rod_length"), num("rod_impact_diameter"));
    let (el, ed) = (l / l_exp - 1.0, d / d_exp - 1.0);
    assert!(
        el.abs() < 0.10,
        "final length {l} m: {:+.1} % from {l_exp}",
        100.0 * el
    );
    assert!(
        ed.abs() < 0.15,
        "face diameter {d} m: {:+.1} % from {d_exp}",
        100.0 * ed
    );
    // the rod mushroomed: the face is at least 1.8 times the 7.62 mm it started with
    assert!(d > 1.8 * 7.62e-3, "{d}");
    assert!(
        num("energy_rel_error").abs() < 1e-2,
        "{}",
        num("energy_rel_error")
    );

    // at rest: over the last 30 % of the run the length changes by under 0.5 %
    let series = std::fs::read_to_string(out.join("series.csv")).unwrap();
    let mut lines = series.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let (it, il) = (
        header.iter().position(|h| *h == "t").unwrap(),
        header.iter().position(|h| *h == "rod_length").unwrap(),
    );
    let late: Vec<f64> = lines
        .map(|l| {
            l.split(',')
                .map(|v| v.parse::<f64>().unwrap())
                .collect::<Vec<_>>()
        })
        .filter(|row| row[it] >= 0.7 * sc.t_end)
        .map(|row| row[il])
        .collect();
    assert!(late.len() >= 10, "{} late samples", late.len());
    let (lo, hi) = late
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &v| (a.min(v), b.max(v)));
    assert!(
        (hi - lo) / l < 5e-3,
        "the length still changes: {lo} .. {hi} m"
    );

    // nothing passed the rigid wall z = 0 or the symmetry planes x = 0, y = 0
    let t = &r.table;
    for i in 0..t.len() {
        assert!(
            t.z[i] > 0.0 && t.x[i] > 0.0 && t.y[i] > 0.0,
            "particle {i} crossed a wall"
        );
    }
}

/// `gsph plot rod` refuses a bad outline file or bad arguments on one line, naming the
/// file and line or the flag, and writes no picture.
#[cfg(feature = "plot")]
#[test]
fn plot_rod_refuses_bad_outlines_and_arguments_on_one_line() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let write = |name: &str, text: &str| {
        let p = dir.join(name);
        std::fs::write(&p, text).unwrap();
        p.to_string_lossy().into_owned()
    };
    let header = write("header.csv", "# a comment\nr,z\n1,2\n");
    let row = write("row.csv", "r_mm,z_mm\n1.0,0.0\n2.0,abc\n");
    let short = write("short.csv", "r_mm,z_mm\n1.0,0.0\n");
    let png = dir.join("rod.png").to_string_lossy().into_owned();
    let d = dir.to_string_lossy().into_owned();
    let cases: Vec<(Vec<&str>, String)> = vec![
        (
            vec!["--outline", &header],
            format!("{header} line 2: the header must be `r_mm,z_mm` (got `r,z`)"),
        ),
        (
            vec!["--outline", &row],
            format!("{row} line 3: expected two finite numbers r_mm,z_mm (got `2.0,abc`)"),
        ),
        (
            vec!["--outline", &short],
            format!("{short}: fewer than two outline points"),
        ),
        (
            vec!["--base", "1,2"],
            "--base: expected X,Y,Z (got `1,2`)".into(),
        ),
        (
            vec!["--base", "0,NaN,0"],
            "--base: `NaN` is not a finite number".into(),
        ),
        (
            vec!["--axis", "3"],
            "--axis: must be 0, 1 or 2 (got 3)".into(),
        ),
        (
            vec!["--labels", "a,b"],
            "--labels: 2 labels for 1 directories".into(),
        ),
        (vec![], format!("{d}/final.csv: cannot read")),
    ];
    for (args, want) in cases {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_gsph"))
            .args(["plot", "rod", &d, "--out", &png])
            .args(&args)
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?} succeeded");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(err.contains(&want), "{args:?}: {err} (want {want})");
        assert!(!Path::new(&png).exists(), "{args:?} wrote a picture");
    }
    // a colour range may start with a negative number (not taken for a flag)
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_gsph"))
        .args(["plot", "particles", &d, "--range", "-2e8,NaN"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("--range: expected MIN,MAX (finite numbers, MIN < MAX), got `-2e8,NaN`"),
        "{err}"
    );
    // the side view of `gsph plot particles --axes` takes two different axes
    for axes in ["x,x", "x", "x,w", "x,y,z"] {
        let o = std::process::Command::new(env!("CARGO_BIN_EXE_gsph"))
            .args(["plot", "particles", &d, "--axes", axes])
            .output()
            .unwrap();
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "--axes {axes} succeeded");
        let want = format!("error: --axes: expected two of x, y, z such as `x,z` (got `{axes}`)");
        assert_eq!(err.trim(), want);
    }
}
