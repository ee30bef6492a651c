#![cfg(target_os = "linux")]

//! A signal during the set-up of `gsph run` (issue 25): before the run touches its output
//! folder, SIGTERM and SIGINT end the process at once with 128 + the signal's number, and
//! leave that folder as it was. Before, the handler only set a flag that the first step
//! read, so a long set-up (20 parallel walls: 12 minutes) ignored SIGTERM, and the run then
//! replaced the folder's earlier results before stopping.

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

/// Waits until process `pid` catches SIGINT and SIGTERM (`SigCgt` in `/proc/PID/status`).
fn handlers_installed(pid: u32) {
    let t0 = Instant::now();
    loop {
        let status = std::fs::read_to_string(format!("/proc/{pid}/status")).unwrap_or_default();
        let caught = status
            .lines()
            .find_map(|l| l.strip_prefix("SigCgt:"))
            .and_then(|m| u64::from_str_radix(m.trim(), 16).ok())
            .unwrap_or(0);
        // bit n - 1 is signal n: SIGINT 2, SIGTERM 15
        if caught & (1 << 1) != 0 && caught & (1 << 14) != 0 {
            return;
        }
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "gsph run installed no handlers within 60 s"
        );
        std::thread::sleep(Duration::from_millis(5));
    }
}

#[test]
fn a_signal_during_set_up_ends_the_run_at_once_and_touches_nothing() {
    let scene = Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/steel_sic_impact.toml");
    for (signal, code) in [("-TERM", 143), ("-INT", 130)] {
        let tmp = tempfile::tempdir().unwrap();
        let out = tmp.path().join("out");
        std::fs::create_dir(&out).unwrap();
        std::fs::write(out.join("summary.json"), "{\"earlier\": true}").unwrap();
        // about 470,000 particles: a set-up of seconds (the lattice, the overlap check,
        // the neighbour lists), far longer than the signal's delay
        let child = Command::new(env!("CARGO_BIN_EXE_gsph"))
            .args(["run", &scene.display().to_string(), "--out"])
            .arg(&out)
            .args(["--quiet", "--set", "resolution_scale=3"])
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        // wait until the run has installed its handlers (a fixed delay raced with a
        // loaded CI machine: the signal then arrived first and killed the process)
        handlers_installed(child.id());
        let t0 = Instant::now();
        let sent = Command::new("kill")
            .args([signal, &child.id().to_string()])
            .status()
            .unwrap();
        assert!(sent.success());
        let o = child.wait_with_output().unwrap();
        eprintln!(
            "{signal}: exit {:?} {:.3} s after the signal",
            o.status.code(),
            t0.elapsed().as_secs_f64()
        );
        assert_eq!(
            o.status.code(),
            Some(code),
            "{}",
            String::from_utf8_lossy(&o.stderr)
        );
        let mut names: Vec<String> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(names, ["summary.json"], "the folder was touched");
        assert_eq!(
            std::fs::read_to_string(out.join("summary.json")).unwrap(),
            "{\"earlier\": true}"
        );
    }
}
