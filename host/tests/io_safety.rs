//! Files in and out under hostile and careless input (issue 25, items 2, 3 and 7), through
//! the real `gsph` binary: nothing is written through a symbolic link in an output folder;
//! HDF5 files that would pull data from elsewhere (external storage, virtual datasets,
//! external links) or need a filter plugin are refused naming the dataset; messages quote
//! no more than a short excerpt of a file and files that are not regular are refused; a
//! file declaring more than it holds is refused in bounded memory and time; result files
//! follow the umask.

use gsph::output::{Frame, ParticleRow, ParticleTable, RunInfo, SnapshotWriter};
use std::io::Read;
use std::os::unix::fs::{symlink, PermissionsExt};
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

fn case(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../cases")
        .join(name)
}

/// Held while this process has an HDF5 file open and while it starts a child: the HDF5
/// library opens files without close-on-exec, so a child started meanwhile (by another
/// test) would inherit the descriptor and hold the file's lock while it runs.
static H5: std::sync::Mutex<()> = std::sync::Mutex::new(());

fn h5_lock() -> std::sync::MutexGuard<'static, ()> {
    H5.lock().unwrap_or_else(|e| e.into_inner())
}

/// Starts `cmd` (stdout and stderr piped unless set) and waits for its output.
fn output(cmd: &mut Command) -> Output {
    let child = {
        let _h5 = h5_lock();
        cmd.stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .expect("starts")
    };
    child.wait_with_output().unwrap()
}

fn gsph(cwd: &Path, args: &[&str]) -> Output {
    output(
        Command::new(env!("CARGO_BIN_EXE_gsph"))
            .args(args)
            .current_dir(cwd),
    )
}

/// Expects failure with one line on stderr, `error: ...`, containing `expect`; returns it.
fn refused(cwd: &Path, args: &[&str], expect: &str) -> String {
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

fn ok(cwd: &Path, args: &[&str]) -> String {
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
struct Cost {
    code: Option<i32>,
    stderr: String,
    max_rss_kib: u64,
    wall: Duration,
}

// the child is reaped by `wait4` (for its own rusage), not by `Child::wait`
#[allow(clippy::zombie_processes)]
fn measured(cwd: &Path, args: &[&str]) -> Cost {
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
fn refused_cheaply(cwd: &Path, args: &[&str], expect: &str, secs: u64) -> String {
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
fn flyer(dir: &Path) -> PathBuf {
    let text = std::fs::read_to_string(case("flyer_plate.toml")).unwrap();
    let p = dir.join("flyer.toml");
    std::fs::write(&p, text).unwrap();
    p
}

const SHORT: [&str; 4] = ["--set", "t_end=2e-8", "--set", "output.snapshots=2"];

fn run_args<'a>(scene: &'a str, out: &'a str) -> Vec<&'a str> {
    let mut v = vec!["run", scene, "--out", out, "--quiet"];
    v.extend(SHORT);
    v
}

// ----- item 2: no file written through a link --------------------------------------

#[test]
fn links_in_an_output_folder_are_refused_and_never_followed() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scene = flyer(d);
    let scene = scene.to_str().unwrap();
    let victim = d.join("victim.txt");
    for name in [
        "run.log",
        ".gsph.lock",
        "checkpoint.h5.tmp",
        "summary.json",
        "snapshots.partial.h5",
        "final.csv",
    ] {
        std::fs::write(&victim, "precious").unwrap();
        let out = d.join(format!("out_{}", name.replace('.', "_")));
        std::fs::create_dir(&out).unwrap();
        symlink(&victim, out.join(name)).unwrap();
        let e = refused(
            d,
            &run_args(scene, out.to_str().unwrap()),
            "is a symbolic link",
        );
        assert!(
            e.trim_end().ends_with(&format!(
                ": {}: is a symbolic link; gsph writes no file through a link (remove it or choose another --out)",
                out.join(name).display()
            )),
            "{e}"
        );
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
        // the folder is as it was: the link alone
        let names: Vec<_> = std::fs::read_dir(&out).unwrap().collect();
        assert_eq!(names.len(), 1, "{name}: {names:?}");
    }
    // a dangling link is refused too (it would create its target)
    let out = d.join("dangling");
    std::fs::create_dir(&out).unwrap();
    symlink(d.join("nowhere.txt"), out.join("series.csv")).unwrap();
    refused(
        d,
        &run_args(scene, out.to_str().unwrap()),
        "series.csv: is a symbolic link",
    );
    assert!(!d.join("nowhere.txt").exists());
    // the folder named by --out may itself be a link: the user named it
    let real = d.join("real");
    std::fs::create_dir(&real).unwrap();
    symlink(&real, d.join("via_link")).unwrap();
    ok(d, &run_args(scene, "via_link"));
    assert!(real.join("summary.json").is_file());
    // the default folder out/<name> is gsph's choice: a link there is refused
    std::fs::create_dir(d.join("out")).unwrap();
    symlink(&real, d.join("out/flyer_plate")).unwrap();
    let mut args = vec!["run", scene, "--quiet"];
    args.extend(SHORT);
    refused(d, &args, "out/flyer_plate: is a symbolic link");
}

#[test]
fn a_restart_refuses_a_link_planted_in_its_folder() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scene = flyer(d);
    let mut args = run_args(scene.to_str().unwrap(), "ck");
    args.extend(["--stop-after-steps", "3"]);
    ok(d, &args);
    let victim = d.join("victim.txt");
    std::fs::write(&victim, "precious").unwrap();
    symlink(&victim, d.join("ck/run.log.tmp")).unwrap();
    // (run.log.tmp is not a name gsph writes: allowed)
    std::fs::remove_file(d.join("ck/run.log.tmp")).unwrap();
    std::fs::remove_file(d.join("ck/run.log")).unwrap();
    symlink(&victim, d.join("ck/run.log")).unwrap();
    refused(
        d,
        &["run", "--restart", "ck", "--quiet"],
        "ck/run.log: is a symbolic link",
    );
    assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
}

#[test]
fn a_plot_replaces_a_link_at_its_path_instead_of_writing_through_it() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scene = flyer(d);
    ok(d, &run_args(scene.to_str().unwrap(), "r"));
    for ext in ["png", "svg"] {
        let victim = d.join(format!("victim.{ext}"));
        std::fs::write(&victim, "precious").unwrap();
        let link = d.join(format!("plot.{ext}"));
        symlink(&victim, &link).unwrap();
        ok(
            d,
            &[
                "plot",
                "series",
                "r",
                "--columns",
                "kinetic",
                "--out",
                link.to_str().unwrap(),
            ],
        );
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "precious");
        let meta = std::fs::symlink_metadata(&link).unwrap();
        assert!(meta.is_file() && meta.len() > 100, "{ext}");
    }
}

// ----- item 2: HDF5 files read only from themselves --------------------------------

const PARTICLES_1D: &str = r#"dim = 1
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
fn snapshot_file(dir: &Path, name: &str) -> PathBuf {
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
fn with_rho(file: &Path, make: impl FnOnce(&hdf5::Group, &str, &[f64])) {
    let _h5 = h5_lock();
    let f = hdf5::File::open_rw(file).unwrap();
    let g = f.group("step_000000").unwrap();
    let rho: Vec<f64> = g.dataset("rho").unwrap().read_raw().unwrap();
    g.unlink("rho").unwrap();
    make(&g, "rho", &rho);
    f.close().unwrap();
}

#[test]
fn hdf5_data_from_outside_the_file_or_through_a_plugin_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("scene.toml"), PARTICLES_1D).unwrap();
    // the control: the file as written reads
    std::fs::copy(snapshot_file(d, "good.h5"), d.join("p.h5")).unwrap();
    assert!(ok(d, &["check", "scene.toml"]).contains("particles 10"));

    // external storage: the values of `rho` in another file (a secret of the user's)
    let secret = d.join("secret.bin");
    let bytes: Vec<u8> = (0..10).flat_map(|_| 2700.0f64.to_le_bytes()).collect();
    std::fs::write(&secret, &bytes).unwrap();
    let p = snapshot_file(d, "p.h5");
    with_rho(&p, |g, name, _| {
        g.new_dataset::<f64>()
            .shape(10)
            .external(secret.to_str().unwrap(), 0, 80)
            .create(name)
            .unwrap();
    });
    refused(
        d,
        &["check", "scene.toml"],
        "/step_000000/rho: stored in an external file; gsph reads data stored in the file itself",
    );

    // a virtual dataset mapping another file's dataset
    let src = snapshot_file(d, "src.h5");
    let p = snapshot_file(d, "p.h5");
    with_rho(&p, |g, name, _| {
        g.new_dataset::<f64>()
            .shape(10)
            .virtual_map(src.to_str().unwrap(), "/step_000000/rho", 10, .., 10, ..)
            .create(name)
            .unwrap();
    });
    refused(
        d,
        &["check", "scene.toml"],
        "/step_000000/rho: a virtual dataset",
    );

    // a filter other than deflate and shuffle
    let p = snapshot_file(d, "p.h5");
    with_rho(&p, |g, name, rho| {
        g.new_dataset_builder()
            .with_data(rho)
            .chunk(10)
            .fletcher32()
            .create(name)
            .unwrap();
    });
    refused(
        d,
        &["check", "scene.toml"],
        "/step_000000/rho: filter fletcher32 (id 3); gsph reads data compressed with deflate (gzip) and shuffle only",
    );

    // a filter no library has: HDF5 would look for a plugin to decode it
    let p = snapshot_file(d, "p.h5");
    with_rho(&p, |g, name, _| optional_unknown_filter(g, name, 10));
    refused(
        d,
        &["check", "scene.toml"],
        "/step_000000/rho: filter (a plugin) (id 32100)",
    );

    // an external link in place of the snapshot's group
    let p = snapshot_file(d, "p.h5");
    {
        let _h5 = h5_lock();
        let f = hdf5::File::open_rw(&p).unwrap();
        f.unlink("step_000000").unwrap();
        f.link_external(src.to_str().unwrap(), "step_000000", "step_000000")
            .unwrap();
    }
    refused(
        d,
        &["check", "scene.toml"],
        "/step_000000: a link to another file",
    );

    // gsph plot particles reads the same way
    let run = d.join("run");
    std::fs::create_dir(&run).unwrap();
    std::fs::copy(d.join("p.h5"), run.join("snapshots.h5")).unwrap();
    refused(
        d,
        &["plot", "particles", "run", "--field", "rho"],
        "a link to another file",
    );
}

/// Dataset `name` of `n` f64 in `g`, chunked, with the optional filter 32100 (which no
/// library registers; HDF5 accepts an optional filter it cannot apply).
fn optional_unknown_filter(g: &hdf5::Group, name: &str, n: usize) {
    use hdf5_sys::{h5d, h5p, h5z};
    let dcpl = hdf5::plist::DatasetCreate::build()
        .chunk(n)
        .finish()
        .unwrap();
    let space = hdf5::Dataspace::try_new(n).unwrap();
    let dtype = hdf5::Datatype::from_type::<f64>().unwrap();
    let cname = std::ffi::CString::new(name).unwrap();
    // SAFETY: valid identifiers of live objects; the dataset id is closed at once
    unsafe {
        assert!(
            h5p::H5Pset_filter(
                dcpl.id(),
                32100,
                h5z::H5Z_FLAG_OPTIONAL,
                0,
                std::ptr::null()
            ) >= 0
        );
        let ds = h5d::H5Dcreate2(
            g.id(),
            cname.as_ptr(),
            dtype.id(),
            space.id(),
            h5p::H5P_DEFAULT,
            dcpl.id(),
            h5p::H5P_DEFAULT,
        );
        assert!(ds >= 0);
        h5d::H5Dclose(ds);
    }
}

// ----- item 3: bounded memory on any input -----------------------------------------

/// A snapshot whose `id` declares `n` values it does not store (contiguous, never
/// written: HDF5 allocates no space for it).
fn bomb(dir: &Path, name: &str, n: usize, chunked: bool) -> PathBuf {
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

#[test]
fn hdf5_files_declaring_more_than_they_hold_are_refused_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::write(d.join("scene.toml"), PARTICLES_1D).unwrap();
    let p = bomb(d, "p.h5", 1 << 33, false);
    assert!(std::fs::metadata(&p).unwrap().len() < 1 << 20);
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "/step_000000/id: 8589934592 particles, more than the limit 1e8 of a scene",
        10,
    );
    // under the particle limit, but not in the file
    bomb(d, "p.h5", 50_000_000, false);
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "/step_000000/id: declares 50000000 values (200000000 bytes), more than the file holds for it",
        10,
    );
    bomb(d, "p.h5", 50_000_000, true);
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "more than the file holds for it",
        10,
    );
    // gsph plot particles
    let run = d.join("run");
    std::fs::create_dir(&run).unwrap();
    std::fs::rename(bomb(d, "b.h5", 1 << 33, false), run.join("snapshots.h5")).unwrap();
    refused_cheaply(
        d,
        &["plot", "particles", "run", "--field", "rho"],
        "8589934592 particles, more than the limit",
        10,
    );
    // a restart (its checkpoint.h5 replaced)
    let scene = flyer(d);
    let mut args = run_args(scene.to_str().unwrap(), "ck");
    args.extend(["--stop-after-steps", "3"]);
    ok(d, &args);
    std::fs::rename(bomb(d, "c.h5", 1 << 33, false), d.join("ck/checkpoint.h5")).unwrap();
    refused_cheaply(
        d,
        &["run", "--restart", "ck", "--quiet"],
        "8589934592 particles, more than the limit",
        10,
    );
}

#[test]
fn a_huge_csv_without_line_breaks_is_refused_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let mut text = PARTICLES_1D.replace("p.h5", "big.csv");
    text.push_str("spacing = 1e-4\n");
    std::fs::write(d.join("scene.toml"), text).unwrap();
    // 12 GB, sparse: "x,m," then zeros, no line break
    let f = std::fs::File::create(d.join("big.csv")).unwrap();
    std::io::Write::write_all(&mut &f, b"x,m,").unwrap();
    f.set_len(12 << 30).unwrap();
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "big.csv: line 1: longer than 65536 bytes",
        10,
    );
}

#[test]
fn huge_stl_files_are_refused_in_bounded_memory() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scene = "dim = 3\nscheme = \"pm\"\nt_end = 1e-7\n[[materials]]\nname = \"al\"\nrho0 = 2700.0\neos = { type = \"linear\", c0 = 5000.0 }\n[[bodies]]\nmaterial = \"al\"\nshape = { type = \"stl\", file = \"big.stl\" }\nspacing = 1e-4\n";
    std::fs::write(d.join("scene.toml"), scene).unwrap();
    // ASCII: a first line of 12 GB
    let f = std::fs::File::create(d.join("big.stl")).unwrap();
    std::io::Write::write_all(&mut &f, b"solid big ").unwrap();
    f.set_len(12 << 30).unwrap();
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "big.stl: line 1: longer than 65536 bytes",
        10,
    );
    // ASCII: a facet line of 12 GB
    let f = std::fs::File::create(d.join("big.stl")).unwrap();
    std::io::Write::write_all(&mut &f, b"solid big\nfacet normal 0 0 0").unwrap();
    f.set_len(12 << 30).unwrap();
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "facet 0: line 2: longer than 65536 bytes",
        10,
    );
    // binary: a header declaring 4e9 facets
    let mut head = vec![0u8; 84];
    head[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
    std::fs::write(d.join("big.stl"), &head).unwrap();
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "big.stl: the header declares 4294967295 facets, more than the limit 1e8",
        10,
    );
    // binary, 12 GB of facets streamed: the first one is refused
    let f = std::fs::File::create(d.join("big.stl")).unwrap();
    head[80..84].copy_from_slice(&100_000_000u32.to_le_bytes());
    std::io::Write::write_all(&mut &f, &head).unwrap();
    f.set_len(12 << 30).unwrap();
    refused_cheaply(
        d,
        &["check", "scene.toml"],
        "big.stl: facet 0: zero area",
        10,
    );
}

// ----- item 2: excerpts, and regular files only -------------------------------------

#[test]
fn messages_quote_short_excerpts_and_only_regular_files_are_read() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // what a message may not quote: a long value whose end is marked
    let secret = format!("TOPSECRET{}-END", "0123456789".repeat(10));
    let scene = |file: &str| PARTICLES_1D.replace("p.h5", file) + "spacing = 1e-4\n";
    let check = |text: &str| {
        std::fs::write(d.join("scene.toml"), text).unwrap();
        let o = output(
            Command::new(env!("CARGO_BIN_EXE_gsph"))
                .args(["check", "scene.toml"])
                .current_dir(d)
                .env("GSPH_TEST_SECRET", &secret),
        );
        let err = String::from_utf8_lossy(&o.stderr).into_owned();
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(!err.contains("-END"), "{err}");
        assert!(!err.chars().any(|c| c.is_control() && c != '\n'), "{err:?}");
        err
    };
    // the environment as a particle file: an excerpt of its first field, no more
    let e = check(&scene("/proc/self/environ"));
    assert!(e.len() < 400, "{} bytes: {e}", e.len());
    assert!(e.contains("/proc/self/environ: line 1"), "{e}");
    // a particle file whose header is one long secret
    std::fs::write(d.join("s.csv"), format!("x,{secret}\n0,1\n")).unwrap();
    let e = check(&scene("s.csv"));
    assert!(
        e.contains("unknown column `TOPSECRET") && e.contains("…`"),
        "{e}"
    );
    // a value in the scene
    let e = check(&PARTICLES_1D.replace("rho0 = 2700.0", &format!("rho0 = \"{secret}\"")));
    assert!(
        e.contains("materials[0].rho0: invalid type: string \"TOPSECRET"),
        "{e}"
    );
    // a duplicate key in the scene (the TOML parser quotes it)
    let e = check(&format!("{PARTICLES_1D}{secret} = 1\n{secret} = 2\n"));
    assert!(e.contains("malformed TOML"), "{e}");
    // files that are not regular files
    let e = check(&scene("/dev/zero"));
    assert!(
        e.ends_with("bodies[0].shape.file: /dev/zero: not a regular file\n"),
        "{e}"
    );
    let e = check(&scene("."));
    assert!(e.ends_with(": not a regular file\n"), "{e}");
    let fifo = d.join("fifo.csv");
    let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
    // SAFETY: a valid NUL-terminated path
    assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
    let e = check(&scene("fifo.csv"));
    assert!(e.ends_with("fifo.csv: not a regular file\n"), "{e}");
    let e = check(
        &scene("fifo.csv")
            .replace("particles", "stl")
            .replace("dim = 1", "dim = 3"),
    );
    assert!(e.contains("fifo.csv: not a regular file"), "{e}");
    // the scene itself
    for bad in ["/dev/zero", "fifo.csv", "."] {
        refused(
            d,
            &["check", bad],
            &format!("{bad}: cannot read scene: not a regular file"),
        );
    }
    // a file name of a megabyte
    let e = check(&scene(&"n".repeat(1 << 20)));
    assert!(e.len() < 300 && e.contains("is not a file name"), "{e}");
}

// ----- item 7: result files follow the umask ----------------------------------------

#[test]
fn result_files_follow_the_umask() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let scene = flyer(d);
    for (umask, want) in [("002", 0o664), ("077", 0o600), ("022", 0o644)] {
        let out = format!("u{umask}");
        let mut args = vec![
            "-c".to_string(),
            format!("umask {umask} && exec \"$0\" \"$@\""),
            env!("CARGO_BIN_EXE_gsph").to_string(),
        ];
        args.extend(
            run_args(scene.to_str().unwrap(), &out)
                .iter()
                .map(|s| s.to_string()),
        );
        let o = output(Command::new("sh").args(&args).current_dir(d));
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        for f in [
            "summary.json",
            "final.csv",
            "series.csv",
            "snapshots.h5",
            "snapshots.xdmf",
            "run.log",
        ] {
            let mode = std::fs::metadata(d.join(&out).join(f))
                .unwrap()
                .permissions()
                .mode()
                & 0o777;
            assert_eq!(mode, want, "umask {umask}: {f} is {mode:o}");
        }
    }
}
