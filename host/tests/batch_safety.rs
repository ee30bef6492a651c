//! Nothing lost, nothing corrupted (issue 17, item 7) and batch runs (item 6), through the
//! real `gsph` binary: refused commands leave an earlier run's results alone; a folder a
//! run holds is refused to a second run; a fresh run removes an older run's checkpoint and
//! a checkpoint never resumes over another run's results; forged checkpoints with a valid
//! checksum are refused; runs too large for memory are refused before allocating; scene
//! names cannot escape out/; plot and study inputs are checked before any work; SIGTERM
//! writes a checkpoint and exits 143; progress lines appear in a batch log; run.log and
//! summary.json say who ran what.

use gsph::checkpoint::{CHECKPOINT_BIN, CHECKPOINT_H5};
use gsph::codec::{fnv1a64, Dec};
use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn case(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../cases")
        .join(name)
        .display()
        .to_string()
}

fn gsph_in(cwd: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gsph"))
        .args(args)
        .current_dir(cwd)
        .output()
        .expect("gsph starts")
}

fn gsph(args: &[&str]) -> Output {
    gsph_in(Path::new("."), args)
}

fn ok(args: &[&str]) -> String {
    let o = gsph(args);
    assert!(
        o.status.success(),
        "gsph {args:?} failed: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Runs `args`, expects failure with one line on stderr containing `expect`; returns it.
fn refused(args: &[&str], expect: &str) -> String {
    let o = gsph(args);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success(), "gsph {args:?} succeeded");
    assert_eq!(err.trim_end().lines().count(), 1, "gsph {args:?}: {err}");
    assert!(
        err.contains(expect),
        "gsph {args:?}: `{err}` lacks `{expect}`"
    );
    err
}

/// Every file of a folder with its bytes (sorted by name).
fn contents(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap())
        // (the lock file names its holder)
        .filter(|e| e.file_type().unwrap().is_file() && e.file_name() != ".gsph.lock")
        .map(|e| {
            (
                e.file_name().to_string_lossy().into_owned(),
                std::fs::read(e.path()).unwrap(),
            )
        })
        .collect();
    v.sort();
    v
}

fn s(p: &Path) -> String {
    p.display().to_string()
}

#[test]
fn refused_commands_leave_earlier_results_alone() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let d = s(&dir);
    let fp = case("flyer_plate.toml");
    ok(&["run", &fp, "--out", &d, "--quiet"]);
    let before = contents(&dir);
    let names: Vec<&str> = before.iter().map(|(n, _)| n.as_str()).collect();
    for f in [
        "summary.json",
        "final.csv",
        "snapshots.h5",
        "snapshots.xdmf",
        "run.log",
    ] {
        assert!(names.contains(&f), "{f} missing: {names:?}");
    }
    let missing = s(&tmp.path().join("nonexistent.toml"));
    refused(&["run", &missing, "--out", &d], "cannot read scene");
    refused(&["run", &fp, "--out", &d, "--set", "t_end=-1"], "t_end");
    refused(&["run", &fp, "--out", &d, "--threads", "0"], "--threads");
    refused(
        &["run", &fp, "--out", &d, "--threads", "100000"],
        "--threads 100000",
    );
    refused(
        &["run", &fp, "--out", &d, "--set", "options=[0.0, 0.0]"],
        "options",
    );
    assert!(
        contents(&dir) == before,
        "a refused command changed the folder"
    );
}

#[test]
fn a_folder_held_by_a_run_is_refused_to_a_second_run() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let fp = case("flyer_plate.toml");
    ok(&["run", &fp, "--out", &s(&dir), "--quiet"]);
    let before = contents(&dir);
    // what a running job holds (the lock is the one `gsph run` takes)
    let held = gsph::outdir::OutLock::acquire(&dir).unwrap();
    refused(
        &["run", &fp, "--out", &s(&dir), "--set", "scheme=av"],
        "another gsph process is writing this folder (pid",
    );
    refused(
        &[
            "study",
            &fp,
            "--out",
            &s(&dir),
            "--schemes",
            "av",
            "--resolutions",
            "1",
        ],
        "another gsph process",
    );
    assert!(
        contents(&dir) == before,
        "the refused run touched the folder"
    );
    drop(held);
    // two real runs at once into a new folder: the second is refused, the first's
    // results are whole
    let both = tmp.path().join("both");
    let run = |out: &str, spawn: bool| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_gsph"));
        c.args(["run", fp.as_str(), "--out", out, "--quiet"])
            .args([
                "--set",
                "resolution_scale=8",
                "--set",
                "output.snapshots=40",
            ])
            .current_dir(tmp.path());
        if spawn {
            c.stderr(Stdio::null());
        }
        c
    };
    assert!(run("alone", false).output().unwrap().status.success());
    let mut first = run("both", true).spawn().unwrap();
    let t0 = Instant::now();
    // run.log is written once the first run holds the lock
    while !std::fs::read_to_string(both.join("run.log")).is_ok_and(|t| t.contains("scene text")) {
        assert!(t0.elapsed() < Duration::from_secs(60));
        std::thread::sleep(Duration::from_millis(5));
    }
    let second = run("both", false).output().unwrap();
    let running = first.try_wait().unwrap().is_none();
    assert!(first.wait().unwrap().success());
    if running {
        let err = String::from_utf8_lossy(&second.stderr);
        assert!(
            !second.status.success() && err.contains("another gsph process"),
            "{err}"
        );
    } else {
        eprintln!("the first run ended before the second started");
    }
    for f in ["final.csv", "series.csv", "snapshots.xdmf"] {
        assert!(
            std::fs::read(both.join(f)).unwrap()
                == std::fs::read(tmp.path().join("alone").join(f)).unwrap(),
            "{f} differs from the run made alone"
        );
    }
}

#[test]
fn a_fresh_run_removes_an_older_checkpoint_and_checkpoints_resume_only_their_run() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    let fp = case("flyer_plate.toml");
    ok(&[
        "run",
        &fp,
        "--out",
        &s(&a),
        "--quiet",
        "--stop-after-steps",
        "20",
    ]);
    assert!(a.join(CHECKPOINT_BIN).exists());
    let old_ck = std::fs::read(a.join(CHECKPOINT_BIN)).unwrap();
    let old_h5 = std::fs::read(a.join(CHECKPOINT_H5)).unwrap();
    // a fresh run into the same folder
    ok(&["run", &fp, "--out", &s(&a), "--quiet", "--set", "scheme=av"]);
    assert!(!a.join(CHECKPOINT_BIN).exists() && !a.join(CHECKPOINT_H5).exists());
    refused(&["run", "--restart", &s(&a)], "cannot read");
    // the older checkpoint put back by hand is refused: another run wrote the results
    std::fs::write(a.join(CHECKPOINT_BIN), &old_ck).unwrap();
    std::fs::write(a.join(CHECKPOINT_H5), &old_h5).unwrap();
    refused(&["run", "--restart", &s(&a)], "summary.json to run");
    // a checkpointed run that finished has nothing to resume
    ok(&[
        "run",
        &fp,
        "--out",
        &s(&b),
        "--quiet",
        "--checkpoint-every-steps",
        "10",
    ]);
    refused(&["run", "--restart", &s(&b)], "has finished");
}

/// Offsets in checkpoint.bin of the driver state and of the simulation's t and step.
struct Layout {
    next_out: usize,
    t: usize,
    step: usize,
}

fn layout(bytes: &[u8]) -> Layout {
    let payload = &bytes[32..];
    let at = |d: &Dec<'_>| 32 + payload.len() - d.remaining();
    let mut d = Dec::new(payload);
    for _ in 0..4 {
        d.get::<String>().unwrap(); // version, run id, origin, text
    }
    d.get::<Vec<String>>().unwrap();
    d.get::<String>().unwrap(); // name
    d.get::<u64>().unwrap(); // policy steps
    d.get::<f64>().unwrap(); // policy seconds
    let next_out = at(&d);
    d.get::<u64>().unwrap(); // next_out
    d.get::<u64>().unwrap(); // next_series
    d.get::<f64>().unwrap(); // kinetic_max
    d.get::<f64>().unwrap(); // energy0
    d.get::<[f64; 3]>().unwrap(); // mom0
    d.get::<u64>().unwrap(); // frames
    d.get::<String>().unwrap(); // series
    d.get::<Vec<f64>>().unwrap(); // monitor
    let t = at(&d);
    Layout {
        next_out,
        t,
        step: t + 8,
    }
}

/// `bytes` with 8 bytes at `at` replaced and the checksum made valid again.
fn forged(bytes: &[u8], at: usize, value: [u8; 8]) -> Vec<u8> {
    let mut b = bytes.to_vec();
    b[at..at + 8].copy_from_slice(&value);
    let sum = fnv1a64(&b[32..]);
    b[24..32].copy_from_slice(&sum.to_le_bytes());
    b
}

#[test]
fn forged_checkpoints_with_a_valid_checksum_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("ck");
    ok(&[
        "run",
        &case("flyer_plate.toml"),
        "--out",
        &s(&dir),
        "--quiet",
        "--stop-after-steps",
        "20",
    ]);
    let good = std::fs::read(dir.join(CHECKPOINT_BIN)).unwrap();
    let l = layout(&good);
    let t_good = f64::from_le_bytes(good[l.t..l.t + 8].try_into().unwrap());
    assert!(t_good > 0.0, "the layout finds t: {t_good}");
    let cases: [(usize, [u8; 8], &str); 5] = [
        (l.t, f64::NAN.to_le_bytes(), "time t = NaN"),
        (l.t, (-1e300f64).to_le_bytes(), "time t = -1e300"),
        (l.step, u64::MAX.to_le_bytes(), "step 18446744073709551615"),
        (l.next_out, 0u64.to_le_bytes(), "next snapshot = 0"),
        (l.t, 1.0f64.to_le_bytes(), "outside [0, t_end"),
    ];
    for (at, value, expect) in cases {
        std::fs::write(dir.join(CHECKPOINT_BIN), forged(&good, at, value)).unwrap();
        refused(&["run", "--restart", &s(&dir)], expect);
    }
    std::fs::write(dir.join(CHECKPOINT_BIN), &good).unwrap();
    ok(&["run", "--restart", &s(&dir), "--quiet"]);
}

#[test]
fn runs_too_large_for_memory_are_refused_before_allocating() {
    let tmp = tempfile::tempdir().unwrap();
    let d = s(&tmp.path().join("big"));
    let fp = case("flyer_plate.toml");
    // 9e7 particles in 1D
    refused(
        &["run", &fp, "--out", &d, "--set", "bodies.0.spacing=5.5e-11"],
        "of memory",
    );
    // the 3D impact at resolution_scale = 10
    refused(
        &[
            "run",
            &case("steel_sic_impact_3d.toml"),
            "--out",
            &d,
            "--set",
            "resolution_scale=10",
        ],
        "available on this machine",
    );
    refused(
        &[
            "check",
            &case("steel_sic_impact_3d.toml"),
            "--set",
            "resolution_scale=10",
        ],
        "available on this machine",
    );
    assert!(
        !tmp.path().join("big").exists(),
        "a refused run made its folder"
    );
}

#[test]
fn scene_names_cannot_escape_out() {
    let tmp = tempfile::tempdir().unwrap();
    let fp = case("flyer_plate.toml");
    for name in ["../../x", "/tmp/gsph_abs", ""] {
        let set = format!("name=\"{name}\"");
        let o = gsph_in(tmp.path(), &["run", &fp, "--set", &set, "--quiet"]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(
            !o.status.success() && err.contains("name: "),
            "{name}: {err}"
        );
    }
    assert!(!Path::new("/tmp/gsph_abs").exists());
    assert!(std::fs::read_dir(tmp.path()).unwrap().next().is_none());
}

#[test]
fn plot_and_study_inputs_are_checked_before_any_work() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let fp = case("flyer_plate.toml");
    ok(&["run", &fp, "--out", &s(&dir), "--quiet"]);
    let series = std::fs::read_to_string(dir.join("series.csv")).unwrap();
    // a truncated last row
    let cut = &series[..series.len() - 20];
    std::fs::write(dir.join("series.csv"), cut).unwrap();
    refused(
        &["plot", "series", &s(&dir), "--columns", "kinetic"],
        "(a truncated file?)",
    );
    for r in ["NaN,1", "0,nan", "1,abc"] {
        refused(&["plot", "particles", &s(&dir), "--range", r], "--range");
    }
    refused(&["plot", "particles", &s(&dir), "--time", "NaN"], "--time");
    // study: an unknown metric is refused before the first run of the grid
    let o = gsph(&[
        "study",
        &fp,
        "--out",
        &s(&tmp.path().join("st")),
        "--metric",
        "no_such_key",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && err.contains("--metric: `no_such_key`"),
        "{err}"
    );
    assert!(!err.contains("study: run 1/"), "a run started: {err}");
    // hugoniot: an --out that is a file is refused before any computation
    let file = tmp.path().join("file");
    std::fs::write(&file, "x").unwrap();
    refused(
        &[
            "hugoniot",
            &case("porous_cu_window.toml"),
            "--out",
            &s(&file),
        ],
        "cannot create",
    );
}

#[test]
fn sigterm_writes_a_checkpoint_and_a_partial_mark_and_exits_143() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    let fp = case("flyer_plate.toml");
    let sets = [
        "--set",
        "resolution_scale=8",
        "--set",
        "output.snapshots=40",
    ];
    let mut args = vec!["run", fp.as_str(), "--out", "", "--quiet"];
    args.extend(sets);
    let sa = s(&a);
    args[3] = &sa;
    ok(&args);
    let sb = s(&b);
    args[3] = &sb;
    let child = Command::new(env!("CARGO_BIN_EXE_gsph"))
        .args(&args)
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    while !std::fs::read_to_string(b.join("run.log")).is_ok_and(|t| t.contains("scene text")) {
        assert!(t0.elapsed() < Duration::from_secs(60));
        std::thread::sleep(Duration::from_millis(5));
    }
    std::thread::sleep(Duration::from_millis(200));
    let killed = Command::new("kill")
        .args(["-TERM", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let o = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    if o.status.success() {
        eprintln!("the run finished before SIGTERM arrived; nothing to check");
        return;
    }
    assert_eq!(o.status.code(), Some(143), "{err}");
    assert!(err.contains("interrupted by SIGTERM"), "{err}");
    assert!(err.contains("--restart"), "{err}");
    let log = std::fs::read_to_string(b.join("run.log")).unwrap();
    assert!(log.contains("INTERRUPTED"), "{log}");
    assert!(b.join(CHECKPOINT_BIN).exists());
    assert!(!b.join("summary.json").exists());
    ok(&["run", "--restart", &sb, "--quiet"]);
    for f in ["final.csv", "series.csv", "snapshots.xdmf"] {
        assert!(
            std::fs::read(a.join(f)).unwrap() == std::fs::read(b.join(f)).unwrap(),
            "{f}: the interrupted and restarted run differs from the whole run"
        );
    }
}

#[test]
fn batch_runs_print_progress_lines_and_record_who_ran_what() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("run");
    let fp = case("flyer_plate.toml");
    let o = Command::new(env!("CARGO_BIN_EXE_gsph"))
        .args(["run", &fp, "--out", &s(&dir)])
        .env("GSPH_PROGRESS_SECONDS", "0.000001")
        .output()
        .unwrap();
    assert!(o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    let lines: Vec<&str> = err
        .lines()
        .filter(|l| l.starts_with("gsph: flyer_plate: step "))
        .collect();
    assert!(lines.len() > 10, "{err}");
    assert!(
        lines[0].contains(" s of 5.000e-7 s (")
            && lines[0].contains("dt = ")
            && lines[0].contains("ETA "),
        "{}",
        lines[0]
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let text = std::fs::read_to_string(&fp).unwrap();
    assert_eq!(summary["gsph_version"], env!("CARGO_PKG_VERSION"));
    assert_eq!(summary["scene_sha256"], gsph::runlog::sha256_hex(&text));
    let log = std::fs::read_to_string(dir.join("run.log")).unwrap();
    assert!(log.starts_with(&format!("gsph {}, run ", env!("CARGO_PKG_VERSION"))));
    assert!(log.contains(&text), "run.log lacks the scene text");
    assert!(
        log.contains("\nfinished ") && log.contains("\nsummary: {"),
        "{log}"
    );
    let id = summary["run_id"].as_str().unwrap();
    assert!(log.contains(&format!("run {id}")));
}

/// A relaxed layout reports itself: progress lines and the result on stderr, the result in
/// run.log; `--quiet` keeps stderr free of them and run.log keeps the result.
#[test]
fn a_relaxed_layout_reports_on_stderr_and_in_the_run_log() {
    let tmp = tempfile::tempdir().unwrap();
    for quiet in [false, true] {
        let dir = tmp.path().join(format!("q{quiet}"));
        let d = s(&dir);
        let mut args = vec![
            "run".to_string(),
            case("ring_breathing.toml"),
            "--out".into(),
            d,
            "--set".into(),
            "max_steps=2".into(),
            "--set".into(),
            "bodies.0.relax_iterations=30".into(),
        ];
        if quiet {
            args.push("--quiet".into());
        }
        let a: Vec<&str> = args.iter().map(|x| x.as_str()).collect();
        let o = gsph(&a);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let err = String::from_utf8_lossy(&o.stderr);
        let done = "bodies[0]: relaxed layout, 2208 particles, 30 iterations in ";
        assert_eq!(
            err.contains("gsph: bodies[0]: relaxing the layout: iteration 1 of 30, imbalance "),
            !quiet,
            "{err}"
        );
        assert_eq!(err.contains(done), !quiet, "{err}");
        let log = std::fs::read_to_string(dir.join("run.log")).unwrap();
        let line = log.lines().find(|l| l.starts_with(done)).expect(&log);
        assert!(
            line.contains("surface roughness 0.301 -> ") && line.contains("nearest pair "),
            "{line}"
        );
    }
}
