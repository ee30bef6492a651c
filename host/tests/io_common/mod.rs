//! Helpers of the file-safety tests (`io_safety.rs`, `io_limits.rs`): the `gsph` binary
//! started with its output captured (or its peak memory measured), the flyer-plate scene
//! shortened, and small snapshot files made with the library's own writer.

#![allow(dead_code)] // each test file uses some of them

use gsph::output::{Frame, ParticleRow, ParticleTable, RunInfo, SnapshotWriter};
use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

pub fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../cases")
        .join(name)
}

/// Held while this process has an HDF5 file open and while it starts a child: the HDF5
/// library opens files without close-on-exec, so a child started meanwhile (by another
/// test) would inherit the descriptor and hold the file's lock while it runs.
static H5: std::sync::Mutex<()> = std::sync::Mutex::new(());

pub fn h5_lock() -> std::sync::MutexGuard<'static, ()> {
    H5.lock().unwrap_or_else(|e| e.into_inner())
}

/// Starts `cmd` (stdout and stderr piped unless set) and waits for its output.
pub fn output(cmd: &mut Command) -> Output {
    let child = {
        let _h5 = h5_lock();
        cmd.stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("starts")
    };
    child.wait_with_output().unwrap()
}

pub fn gsph(cwd: &Path, args: &[&str]) -> Output {
    output(
        Command::new(env!("CARGO_BIN_EXE_gsph"))
            .args(args)
            .current_dir(cwd),
    )
}

/// Expects failure with one line on stderr, `error: ...`, containing `expect`; returns it.
pub fn refused(cwd: &Path, args: &[&str], expect: &str) -> String {
    let o = gsph(cwd, args);
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(!o.status.success(), "gsph {args:?} succeeded");
    assert_eq!(o.status.code(), Some(1), "gsph {args:?}: {err}");
    assert_eq!(err.trim_end().lines().count(), 1, "gsph {args:?}: {err}");
    assert!(err.starts_with("error: "), "{err}");
    assert!(
        err.contains(expect),
        "gsph {args:?}: `{err}` lacks `{expect}`"
    );
    err
}

pub fn ok(cwd: &Path, args: &[&str]) -> String {
    let o = gsph(cwd, args);
    assert!(
        o.status.success(),
        "gsph {args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// What a command cost: exit status (None: killed by a signal), stderr, peak resident
/// memory of the child (KiB, its own `getrusage`) and wall time.
pub struct Cost {
    pub code: Option<i32>,
    pub stderr: String,
    pub max_rss_kib: u64,
    pub wall: Duration,
}

// the child is reaped by `wait4` (for its own rusage), not by `Child::wait`
#[allow(clippy::zombie_processes)]
pub fn measured(cwd: &Path, args: &[&str]) -> Cost {
    let start = Instant::now();
    let h5 = h5_lock();
    let mut child = Command::new(env!("CARGO_BIN_EXE_gsph"))
        .args(args)
        .current_dir(cwd)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("gsph starts");
    drop(h5);
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut stderr)
        .unwrap();
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: a zeroed rusage is a valid value for wait4 to fill in
    let mut ru: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: waits for our own child, reaped here (never by `child.wait`)
    let r = unsafe { libc::wait4(pid, &mut status, 0, &mut ru) };
    assert_eq!(r, pid);
    let code = libc::WIFEXITED(status).then(|| libc::WEXITSTATUS(status));
    Cost {
        code,
        stderr,
        max_rss_kib: ru.ru_maxrss as u64,
        wall: start.elapsed(),
    }
}

/// A refusal in one line, in under `secs` s and 200 MB.
pub fn refused_cheaply(cwd: &Path, args: &[&str], expect: &str, secs: u64) -> String {
    let c = measured(cwd, args);
    assert_eq!(c.code, Some(1), "gsph {args:?}: {}", c.stderr);
    assert_eq!(c.stderr.trim_end().lines().count(), 1, "{}", c.stderr);
    assert!(c.stderr.contains(expect), "`{}` lacks `{expect}`", c.stderr);
    assert!(
        c.max_rss_kib < 200 * 1024,
        "gsph {args:?}: peak {} MiB",
        c.max_rss_kib / 1024
    );
    assert!(c.wall < Duration::from_secs(secs), "{:?}", c.wall);
    c.stderr
}

/// The flyer plate, shortened, named `flyer`.
pub fn flyer(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(case("flyer_plate.toml")).unwrap();
    let p = dir.join("flyer.toml");
    std::fs::write(&p, text).unwrap();
    p
}

pub const SHORT: [&str; 4] = ["--set", "t_end=2e-8", "--set", "output.snapshots=2"];

pub fn run_args<'a>(scene: &'a str, out: &'a str) -> Vec<&'a str> {
    let mut v = vec!["run", scene, "--out", out, "--quiet"];
    v.extend(SHORT);
    v
}

pub const PARTICLES_1D: &str = r#"dim = 1
scheme = "pm"
t_end = 1e-7
[[materials]]
name = "al"
rho0 = 2700.0
eos = { type = "linear", c0 = 5000.0 }
[[bodies]]
material = "al"
shape = { type = "particles", file = "p.h5" }
"#;

/// A `snapshots.h5` of 10 particles of a 1D bar (one snapshot, step 0) at `path`.
pub fn snapshot_file(dir: &Path, name: &str) -> PathBuf {
    let sub = dir.join(format!("make_{name}"));
    std::fs::create_dir_all(&sub).unwrap();
    let mut t = ParticleTable::default();
    for i in 0..10u32 {
        t.push(&ParticleRow {
            id: i,
            x: (f64::from(i) + 0.5) * 1e-4,
            m: 2700.0 * 1e-4,
            rho: 2700.0,
            h: 1.2e-4,
            ..ParticleRow::default()
        });
    }
    let info = RunInfo {
        materials: vec!["al".into()],
        ..RunInfo::default()
    };
    let _h5 = h5_lock();
    let mut w = SnapshotWriter::create(&sub, 1, &info).unwrap();
    w.append(&Frame {
        time: 0.0,
        step: 0,
        dim: 1,
        table: t,
    })
    .unwrap();
    w.finish().unwrap();
    let p = dir.join(name);
    std::fs::rename(sub.join("snapshots.h5"), &p).unwrap();
    std::fs::remove_dir_all(&sub).unwrap();
    p
}

/// `file` with dataset `rho` of its snapshot made anew by `make` (given the group, the
/// name and the values it held).
pub fn with_rho(file: &Path, make: impl FnOnce(&hdf5::Group, &str, &[f64])) {
    let _h5 = h5_lock();
    let f = hdf5::File::open_rw(file).unwrap();
    let g = f.group("step_000000").unwrap();
    let rho: Vec<f64> = g.dataset("rho").unwrap().read_raw().unwrap();
    g.unlink("rho").unwrap();
    make(&g, "rho", &rho);
    f.close().unwrap();
}

/// A snapshot whose `id` declares `n` values it does not store (contiguous, never
/// written: HDF5 allocates no space for it).
pub fn bomb(dir: &Path, name: &str, n: usize, chunked: bool) -> PathBuf {
    let p = snapshot_file(dir, name);
    let _h5 = h5_lock();
    let f = hdf5::File::open_rw(&p).unwrap();
    let g = f.group("step_000000").unwrap();
    g.unlink("id").unwrap();
    let b = g.new_dataset::<u32>().shape(n);
    if chunked {
        b.chunk(1 << 16).deflate(1).create("id").unwrap();
    } else {
        b.create("id").unwrap();
    }
    f.close().unwrap();
    p
}
