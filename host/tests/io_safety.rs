//! Files in and out under hostile and careless input (issue 25, items 2 and 7), through the
//! real `gsph` binary: nothing is written through a symbolic link in an output folder;
//! messages quote no more than a short excerpt of a file and files that are not regular
//! are refused; result files follow the umask. (HDF5 indirection and bounded memory:
//! `io_limits.rs`.)

mod io_common;

use io_common::*;
use std::os::unix::fs::{symlink, PermissionsExt};
use std::process::Command;

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
    // the environment as a particle file: refused before anything is read (issue 45)
    let e = check(&scene("/proc/self/environ"));
    assert!(e.len() < 400, "{} bytes: {e}", e.len());
    assert!(
        e.contains("/proc/self/environ: a file of the kernel's /proc (procfs)"),
        "{e}"
    );
    // a particle file whose header is one long secret: its line and column, nothing of it
    std::fs::write(d.join("s.csv"), format!("x,{secret}\n0,1\n")).unwrap();
    let e = check(&scene("s.csv"));
    assert!(
        e.contains("s.csv: line 1, column 2: not a column name gsph knows")
            && !e.contains("TOPSECRET"),
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
