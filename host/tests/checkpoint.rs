//! Checkpoint and restart through the real `gsph` binary (docs/checkpoint.md): a run
//! stopped after N steps and restarted from its checkpoint writes the same outputs as an
//! uninterrupted run, bitwise; a run killed at random moments while it checkpoints every
//! step leaves a readable checkpoint that restarts to the same result; a damaged
//! checkpoint is refused with one line on stderr.

use gsph::checkpoint::{Checkpoint, CHECKPOINT_BIN, CHECKPOINT_H5};
use gsph::output::{read_frame, read_snapshot_times};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::Instant;

fn case(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../cases")
        .join(name)
        .display()
        .to_string()
}

fn gsph(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_gsph"))
        .args(args)
        .output()
        .expect("gsph starts")
}

fn ok(args: &[&str]) -> String {
    let o = gsph(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "gsph {args:?} failed: {err}");
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// `gsph run SCENE --out DIR` with the scene's overrides and extra flags.
fn run_args<'a>(
    scene: &'a str,
    dir: &'a str,
    sets: &'a [&'a str],
    extra: &[&'a str],
) -> Vec<&'a str> {
    let mut a = vec!["run", scene, "--out", dir, "--quiet"];
    for s in sets {
        a.extend(["--set", s]);
    }
    a.extend_from_slice(extra);
    a
}

fn read(dir: &Path, f: &str) -> Vec<u8> {
    std::fs::read(dir.join(f)).unwrap_or_else(|e| panic!("{}/{f}: {e}", dir.display()))
}

/// summary.json without its wall-time, thread-count and run-id lines (each run has its
/// own id; a restart keeps the id of the run it continues).
fn summary_sans_wall(dir: &Path) -> String {
    String::from_utf8(read(dir, "summary.json"))
        .unwrap()
        .lines()
        .filter(|l| {
            !l.contains("\"wall_") && !l.contains("\"threads\"") && !l.contains("\"run_id\"")
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The outputs of two runs agree: final.csv, series.csv, profile.csv, snapshots.xdmf
/// byte for byte, summary.json but for wall times, every snapshot frame bitwise.
fn assert_same_outputs(a: &Path, b: &Path) {
    for f in ["final.csv", "series.csv", "snapshots.xdmf"] {
        assert!(read(a, f) == read(b, f), "{f} differs");
    }
    // snapshots.h5 byte for byte but for the run id each run's file carries
    let masked = |d: &Path| {
        let id = gsph::outdir::summary_run_id(d)
            .expect("a run id")
            .into_bytes();
        let mut h5 = read(d, "snapshots.h5");
        let at = h5
            .windows(id.len())
            .position(|w| w == id)
            .expect("the run id");
        h5[at..at + id.len()].fill(b'-');
        h5
    };
    assert!(masked(a) == masked(b), "snapshots.h5 differs");
    assert_eq!(
        a.join("profile.csv").exists(),
        b.join("profile.csv").exists()
    );
    if a.join("profile.csv").exists() {
        assert!(read(a, "profile.csv") == read(b, "profile.csv"));
    }
    assert_eq!(summary_sans_wall(a), summary_sans_wall(b));
    let (ha, hb) = (a.join("snapshots.h5"), b.join("snapshots.h5"));
    let times = read_snapshot_times(&ha).unwrap();
    assert_eq!(times, read_snapshot_times(&hb).unwrap());
    assert!(times.len() >= 2);
    for (s, _) in times {
        let (fa, fb) = (
            read_frame(&ha, s, usize::MAX).unwrap(),
            read_frame(&hb, s, usize::MAX).unwrap(),
        );
        // bitwise, NaN included
        let bits = |f: &gsph::output::Frame| {
            f.table
                .float_columns()
                .iter()
                .flat_map(|c| c.iter().map(|v| v.to_bits()))
                .collect::<Vec<u64>>()
        };
        assert_eq!((fa.time.to_bits(), fa.step), (fb.time.to_bits(), fb.step));
        assert_eq!(fa.table.id, fb.table.id);
        assert!(bits(&fa) == bits(&fb), "snapshot of step {s} differs");
    }
}

/// Uninterrupted run vs. run stopped after `stops[0]` steps, restarted and (for each
/// further entry) stopped again, then restarted to the end.
fn restart_matches(scene: &str, sets: &[&str], stops: &[u64]) {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    let (sa, sb) = (a.display().to_string(), b.display().to_string());
    ok(&run_args(scene, &sa, sets, &[]));
    let steps: u64 = serde_json::from_slice::<serde_json::Value>(&read(&a, "summary.json"))
        .unwrap()["steps"]
        .as_u64()
        .unwrap();
    assert!(stops.iter().all(|&s| s < steps), "{steps} steps only");
    let first = stops[0].to_string();
    let o = ok(&run_args(
        scene,
        &sb,
        sets,
        &[
            "--checkpoint-every-steps",
            "3",
            "--stop-after-steps",
            &first,
        ],
    ));
    assert!(o.contains(&format!("stopped after step {first}")), "{o}");
    assert!(b.join(CHECKPOINT_BIN).exists() && !b.join("final.csv").exists());
    for &s in &stops[1..] {
        let n = s.to_string();
        let o = ok(&["run", "--restart", &sb, "--quiet", "--stop-after-steps", &n]);
        assert!(o.contains(&format!("stopped after step {n}")), "{o}");
    }
    ok(&["run", "--restart", &sb, "--quiet", "--threads", "1"]);
    assert_same_outputs(&a, &b);
}

#[test]
fn restart_is_bitwise_for_every_scheme_1d() {
    let fp = case("flyer_plate.toml");
    for scheme in ["av", "pm", "ts2", "tkc"] {
        let set = format!("scheme={scheme}");
        restart_matches(&fp, &[&set, "resolution_scale=2"], &[17]);
    }
}

#[test]
fn restart_is_bitwise_2d_tkc_with_strength_twice_interrupted() {
    restart_matches(
        &case("riemann_al_2d.toml"),
        &["t_end=1.6e-6", "output.snapshots=4", "output.series=40"],
        &[11, 29],
    );
}

#[test]
fn restart_is_bitwise_with_damage_heat_and_a_monitor() {
    // ts2 with JH1 damage, Johnson-Cook heat and the back-face monitor (its running peak
    // is part of the checkpoint)
    restart_matches(
        &case("steel_sic_impact.toml"),
        &["resolution_scale=0.125", "t_end=3e-6", "output.series=50"],
        &[23],
    );
}

#[test]
fn restart_is_bitwise_with_driven_particles_and_a_front_monitor() {
    // tkc with a driven piston and the front monitor, whose fitted speed uses every front
    // sample (those before the interruption come from the checkpoint)
    restart_matches(
        &case("porous_cu_piston.toml"),
        &["resolution_scale=0.5", "t_end=0.05e-6", "output.series=60"],
        &[150],
    );
}

#[test]
fn restart_is_bitwise_with_the_hourglass_stiffness() {
    // its displacement is particle state; with the leap-frog its rate carries over too
    let ring = case("ring_spin.toml");
    for integrator in ["euler", "leapfrog"] {
        let int = format!("options.integrator={integrator}");
        restart_matches(
            &ring,
            &[
                "resolution_scale=0.5",
                "t_end=1e-5",
                "options.hourglass=1",
                "options.dissipation=compression",
                &int,
            ],
            &[19],
        );
    }
}

#[test]
fn restart_is_bitwise_with_the_total_lagrangian_scheme() {
    // tl's reference positions and volumes and its stiffness's energy are particle state;
    // its lists are rebuilt from the reference positions
    restart_matches(
        &case("ring_breathing.toml"),
        &["scheme=tl", "resolution_scale=0.5", "t_end=1e-5"],
        &[19],
    );
}

/// A splitmix64 step: the delays of the kill loop, reproducible.
#[test]
fn restart_is_bitwise_with_walls_a_symmetry_plane_and_friction() {
    // the mirrors are recreated from the owned particles of the checkpoint
    restart_matches(&case("wall_bar.toml"), &["scheme=tkc"], &[23, 41]);
    restart_matches(
        &case("steel_sic_impact.toml"),
        &[
            "resolution_scale=0.25",
            "t_end=3e-6",
            "bodies.0.shape.min=[-0.02, 0.0]",
            "bodies.1.shape.min=[0.0, 0.0]",
            "walls=[{ point = [0.0, 0.0], normal = [0.0, 1.0], type = \"symmetry\" }, { point = [0.03, 0.0], normal = [-1.0, 0.0], friction = 0.2 }]",
        ],
        &[19],
    );
}

fn next(state: &mut u64) -> u64 {
    *state = state.wrapping_add(0x9e37_79b9_7f4a_7c15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

#[test]
fn killed_runs_leave_a_restartable_checkpoint() {
    let scene = case("flyer_plate.toml");
    let sets = ["resolution_scale=6", "output.snapshots=20"];
    let tmp = tempfile::tempdir().unwrap();
    let (a, b, c) = (
        tmp.path().join("a"),
        tmp.path().join("b"),
        tmp.path().join("c"),
    );
    let (sa, sb, sc) = (
        a.display().to_string(),
        b.display().to_string(),
        c.display().to_string(),
    );
    ok(&run_args(&scene, &sa, &sets, &[]));
    // checkpoints every step: the kills land inside checkpoint writes as often as not
    let every = ["--checkpoint-every-steps", "1"];
    let t0 = Instant::now();
    ok(&run_args(&scene, &sc, &sets, &every));
    let full = t0.elapsed();
    // writing checkpoints changes nothing
    assert_same_outputs(&a, &c);
    let mut args = run_args(&scene, &sb, &sets, &every);
    let restart = ["run", "--restart", &sb, "--quiet"];
    let mut seed = 0x5eed_u64;
    let (mut kills, mut found, mut mid_write) = (0, 0, 0);
    let mut last_step = 0;
    for _ in 0..8 {
        let mut child = Command::new(env!("CARGO_BIN_EXE_gsph"))
            .args(&args)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        // somewhere in the first 60 % of a whole checkpointed run
        let wait = full.mul_f64(0.6 * (next(&mut seed) % 1000) as f64 / 1000.0);
        std::thread::sleep(wait);
        if child.try_wait().unwrap().is_some() {
            break; // finished before the kill
        }
        child.kill().unwrap();
        child.wait().unwrap();
        kills += 1;
        // a kill inside a checkpoint write leaves its temp file
        // (`.checkpoint.bin.XXXXXX.tmp`, output::atomic)
        mid_write += std::fs::read_dir(&b)
            .unwrap()
            .filter(|e| {
                let n = e.as_ref().unwrap().file_name();
                let n = n.to_string_lossy();
                n.starts_with(".checkpoint.bin.") && n.ends_with(".tmp")
            })
            .count();
        if b.join(CHECKPOINT_BIN).exists() {
            // never a half-written checkpoint: it reads back and goes forward
            let ck = Checkpoint::read(&b).unwrap_or_else(|e| panic!("after kill {kills}: {e}"));
            assert!(ck.driver.frames >= 1 && b.join(CHECKPOINT_H5).exists());
            assert!(ck.step >= last_step, "{} < {last_step}", ck.step);
            last_step = ck.step;
            found += 1;
            args = restart.to_vec();
        }
    }
    eprintln!(
        "{kills} kills ({mid_write} inside a checkpoint write), {found} checkpoints found, last at step {last_step}"
    );
    assert!(
        kills >= 3 && found >= 2,
        "{kills} kills, {found} checkpoints (a checkpointed run takes {full:?})"
    );
    // summary.json is written last: a kill after final.csv but before it leaves the run
    // unfinished (and its checkpoint in place)
    if !b.join("summary.json").exists() {
        ok(&args);
    }
    assert_same_outputs(&a, &b);
}

/// What a kill between the last step's checkpoint and summary.json leaves (the case the
/// kill test above reaches only by chance): a restart that has no step left to take
/// writes the outputs of the uninterrupted run, summary.json included.
#[test]
fn a_restart_with_no_step_left_matches_the_uninterrupted_run() {
    let scene = case("flyer_plate.toml");
    let sets = ["resolution_scale=2", "output.snapshots=5"];
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    let (sa, sb) = (a.display().to_string(), b.display().to_string());
    ok(&run_args(&scene, &sa, &sets, &[]));
    ok(&run_args(
        &scene,
        &sb,
        &sets,
        &["--checkpoint-every-steps", "1"],
    ));
    std::fs::remove_file(b.join("summary.json")).unwrap();
    let ck = Checkpoint::read(&b).unwrap();
    let steps = serde_json::from_slice::<serde_json::Value>(&read(&a, "summary.json")).unwrap()
        ["steps"]
        .as_u64();
    assert_eq!(Some(ck.step), steps, "the checkpoint is the last step's");
    ok(&["run", "--restart", &sb, "--quiet"]);
    assert_same_outputs(&a, &b);
}

#[test]
fn a_partial_temp_file_does_not_hide_the_last_checkpoint() {
    let scene = case("flyer_plate.toml");
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    let (sa, sb) = (a.display().to_string(), b.display().to_string());
    ok(&run_args(&scene, &sa, &[], &[]));
    ok(&run_args(&scene, &sb, &[], &["--stop-after-steps", "20"]));
    // what a write interrupted before its rename leaves behind
    let full = read(&b, CHECKPOINT_BIN);
    std::fs::write(b.join("checkpoint.bin.tmp"), &full[..full.len() / 3]).unwrap();
    std::fs::write(b.join("checkpoint.h5.tmp"), b"\x89HDF\r\n").unwrap();
    std::fs::write(b.join("snapshots.h5.tmp"), b"partial").unwrap();
    ok(&["run", "--restart", &sb, "--quiet"]);
    assert_same_outputs(&a, &b);
}

fn one_line_error(args: &[&str], expect: &str) {
    let o = gsph(args);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success(), "{args:?} succeeded");
    assert_eq!(o.status.code(), Some(1), "{args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    assert!(
        err.starts_with("error: ") && !err.contains("panicked"),
        "{err}"
    );
    assert!(err.contains(expect), "{args:?}: `{err}` lacks `{expect}`");
}

#[test]
fn damaged_checkpoints_are_refused_on_one_line() {
    let scene = case("flyer_plate.toml");
    let tmp = tempfile::tempdir().unwrap();
    let b = tmp.path().join("b");
    let sb = b.display().to_string();
    ok(&run_args(&scene, &sb, &[], &["--stop-after-steps", "10"]));
    let good = read(&b, CHECKPOINT_BIN);
    let bin = b.join(CHECKPOINT_BIN);
    let restart = ["run", "--restart", sb.as_str(), "--quiet"];
    let n = good.len();
    for cut in [0, 7, 31, 32, n / 2, n - 1] {
        std::fs::write(&bin, &good[..cut]).unwrap();
        let expect = if cut < 32 {
            "truncated"
        } else {
            "truncated or extended"
        };
        one_line_error(&restart, expect);
    }
    for at in [40, n / 2, n - 1] {
        let mut bad = good.clone();
        bad[at] ^= 0x10;
        std::fs::write(&bin, &bad).unwrap();
        one_line_error(&restart, "checksum mismatch");
    }
    let mut bad = good.clone();
    bad[0] = b'X';
    std::fs::write(&bin, &bad).unwrap();
    one_line_error(&restart, "not a gsph checkpoint");
    let mut bad = good.clone();
    bad[8] = 99;
    std::fs::write(&bin, &bad).unwrap();
    one_line_error(&restart, "format version 99");
    std::fs::remove_file(&bin).unwrap();
    one_line_error(&restart, "cannot read");
    // a good checkpoint without the snapshots it needs
    std::fs::write(&bin, &good).unwrap();
    std::fs::write(b.join(CHECKPOINT_H5), b"not hdf5").unwrap();
    one_line_error(&restart, CHECKPOINT_H5);
    std::fs::remove_file(b.join(CHECKPOINT_H5)).unwrap();
    one_line_error(&restart, CHECKPOINT_H5);
}

#[test]
fn checkpoint_options_are_validated() {
    let fp = case("flyer_plate.toml");
    let out = tempfile::tempdir().unwrap();
    let o = out.path().display().to_string();
    one_line_error(
        &["run", &fp, "--out", &o, "--checkpoint-every-steps", "0"],
        "--checkpoint-every-steps",
    );
    one_line_error(
        &["run", &fp, "--out", &o, "--checkpoint-every-seconds", "0"],
        "--checkpoint-every-seconds",
    );
    one_line_error(
        &[
            "run",
            &fp,
            "--out",
            &o,
            "--set",
            "output.checkpoint_steps=0",
        ],
        "output.checkpoint_steps",
    );
    one_line_error(
        &[
            "run",
            &case("porous_cu_window.toml"),
            "--out",
            &o,
            "--checkpoint-every-steps",
            "5",
        ],
        "moving-window",
    );
    // the scene key writes checkpoints too, and the restart continues on it
    let b: PathBuf = out.path().join("k");
    let sb = b.display().to_string();
    ok(&run_args(&fp, &sb, &["output.checkpoint_steps=4"], &[]));
    let ck = Checkpoint::read(&b).unwrap();
    assert_eq!(ck.policy.every_steps, Some(4));
    assert!(b.join("final.csv").exists());
}

/// Every file of a folder, by name, with its bytes.
fn snapshot_of(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut v: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| {
            let e = e.unwrap();
            let name = e.file_name().to_string_lossy().into_owned();
            (name.clone(), read(dir, &name))
        })
        .collect();
    v.sort();
    v
}

/// Issue 45 item 1: run A and run B (B with another dissipation), both stopped with a
/// checkpoint; A's checkpoint.bin copied into B's folder is refused, then A's
/// checkpoint.h5, snapshots and run.log one by one: each time in one line naming both
/// files, and nothing in B's folder changes. With all of A's files it resumes.
#[test]
fn a_restart_never_continues_one_run_with_another_runs_files() {
    let scene = case("flyer_plate.toml");
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a"), tmp.path().join("b"));
    let (sa, sb) = (a.display().to_string(), b.display().to_string());
    let stop = ["--stop-after-steps", "20"];
    ok(&run_args(&scene, &sa, &[], &stop));
    ok(&run_args(
        &scene,
        &sb,
        &["options.dissipation=compression"],
        &stop,
    ));
    // the stop is the log's last line (issue 45: a stopped run's log had no end)
    let log = String::from_utf8(read(&b, "run.log")).unwrap();
    let last = log.lines().last().unwrap();
    assert!(
        last.starts_with("STOPPED ") && last.contains("after step 20"),
        "{last}"
    );
    let restart = ["run", "--restart", sb.as_str(), "--quiet"];
    let mut named = "checkpoint.bin".to_string();
    for f in [
        CHECKPOINT_BIN,
        CHECKPOINT_H5,
        "snapshots.partial.h5",
        "run.log",
    ] {
        std::fs::copy(a.join(f), b.join(f)).unwrap();
        if f == "run.log" {
            break;
        }
        let before = snapshot_of(&b);
        let next = match f {
            CHECKPOINT_BIN => CHECKPOINT_H5,
            CHECKPOINT_H5 => "snapshots.partial.h5",
            _ => "run.log",
        };
        one_line_error(&restart, &format!("{sb}/checkpoint.bin is run "));
        one_line_error(&restart, &format!("but {sb}/{next} is run "));
        assert!(
            snapshot_of(&b) == before,
            "the refused restart wrote into {sb}"
        );
        named = next.to_string();
    }
    assert_eq!(named, "run.log");
    ok(&restart);
    assert_eq!(
        gsph::outdir::summary_run_id(&b),
        Some(Checkpoint::read(&a).unwrap().run_id)
    );
}

/// Issue 45 item 2: a checkpoint whose values break the particle table's ranges (a NaN
/// reference position, a negative mass), checksum recomputed, is refused naming the
/// particle and the field.
#[test]
fn every_value_read_back_is_checked() {
    let scene = case("flyer_plate.toml");
    let tmp = tempfile::tempdir().unwrap();
    let b = tmp.path().join("b");
    let sb = b.display().to_string();
    ok(&run_args(&scene, &sb, &[], &["--stop-after-steps", "10"]));
    let good = read(&b, CHECKPOINT_BIN);
    // the values at step 0 (x0, m) of a particle that moves (its position differs from
    // x0 by step 10): the first copy of their bits in the payload is the field's
    let f0 = read_frame(b.join(CHECKPOINT_H5), 0, usize::MAX).unwrap();
    let col = |c: &str| f0.table.column(c).unwrap();
    let k = col("vx").iter().position(|&v| v != 0.0).unwrap();
    let id = f0.table.id[k];
    for (column, bad, expect) in [
        ("x0", f64::NAN, "`x0` is not finite"),
        ("m", -1.0, "`m` must be positive"),
    ] {
        let bits = col(column)[k].to_le_bytes();
        let mut forged = good.clone();
        let at = 32
            + forged[32..]
                .windows(8)
                .position(|w| w == bits)
                .unwrap_or_else(|| panic!("{column} of particle {id} not in the checkpoint"));
        forged[at..at + 8].copy_from_slice(&bad.to_le_bytes());
        let sum = gsph::codec::fnv1a64(&forged[32..]);
        forged[24..32].copy_from_slice(&sum.to_le_bytes());
        std::fs::write(b.join(CHECKPOINT_BIN), &forged).unwrap();
        one_line_error(&["run", "--restart", &sb, "--quiet"], expect);
        one_line_error(&["run", "--restart", &sb, "--quiet"], "particle ");
    }
    std::fs::write(b.join(CHECKPOINT_BIN), &good).unwrap();
    ok(&["run", "--restart", &sb, "--quiet"]);
}
