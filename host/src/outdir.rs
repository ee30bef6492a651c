//! The output folder of a run: a default folder name that cannot escape `out/`, an
//! exclusive lock held for the run's lifetime, and the identity of the run that wrote it.
//!
//! Order of events in `gsph run` (and `hugoniot`, `study`): everything is validated and
//! the particles are built first; then the folder is locked ([`OutLock::acquire`]); only
//! then are an earlier run's results removed and the new ones written. So a refused
//! command never touches the folder, and a second run into a folder that a running job
//! holds is refused in one line before it writes anything.
//!
//! No file is written through a symbolic link ([`crate::output::safe`]): before the lock
//! is taken, every entry the command will write or remove in the folder is checked
//! ([`OutLock::acquire_for`]) and a link among them refused in one line naming it; the lock
//! file is opened with `O_NOFOLLOW`. The folder itself may be a link when the user named it
//! (`--out`); the default folder `out/<name>`, which gsph chooses, may not ([`default_dir`]).

use crate::output::safe;
use std::fs::{File, OpenOptions, TryLockError};
use std::io::{Read, Seek, Write};
use std::path::{Path, PathBuf};

/// Name of the lock file in an output folder (kept after the run: removing a lock file is
/// racy; an unlocked file is free).
pub const LOCK_FILE: &str = ".gsph.lock";

/// Checks that a scene name can be a folder name under `out/`: not empty, no path
/// separator, not `.` or `..`, no leading dot, no control character.
pub fn check_name(name: &str) -> Result<(), String> {
    let bad = if name.is_empty() {
        Some("is empty")
    } else if name.contains(['/', '\\']) {
        Some("contains a path separator")
    } else if name.starts_with('.') {
        Some("starts with a dot")
    } else if name.chars().any(char::is_control) {
        Some("contains a control character")
    } else if name.len() > 200 {
        Some("is longer than 200 bytes")
    } else {
        None
    };
    match bad {
        Some(why) => Err(format!(
            "name: `{}` {why}; the scene name is the default output folder out/<name>: give a plain name or --out",
            name.escape_default()
        )),
        None => Ok(()),
    }
}

/// The default output folder `out/<name><suffix>` of a scene (see [`check_name`]); refused
/// if it is a symbolic link (gsph chose it, the user did not: `out` itself may be one).
pub fn default_dir(name: &str, suffix: &str) -> Result<PathBuf, String> {
    check_name(name)?;
    let dir = PathBuf::from("out").join(format!("{name}{suffix}"));
    crate::output::safe::refuse_link(&dir)?;
    Ok(dir)
}

/// An exclusive lock on an output folder, released when dropped (or when the process
/// ends, however it ends: the operating system drops the lock with the file).
#[derive(Debug)]
pub struct OutLock {
    _file: File,
    dir: PathBuf,
}

impl OutLock {
    /// Creates `dir` if needed and locks it; refuses in one line when another process
    /// holds it, naming that process, or when its lock file is a symbolic link.
    pub fn acquire(dir: &Path) -> Result<OutLock, String> {
        Self::acquire_for(dir, &[] as &[&str])
    }

    /// [`OutLock::acquire`] for a command that writes or removes the entries `names` of
    /// `dir`: refuses first, before anything is created, if any of them (or the lock file)
    /// is a symbolic link.
    pub fn acquire_for<S: AsRef<str>>(dir: &Path, names: &[S]) -> Result<OutLock, String> {
        let shown = dir.display();
        safe::check_entries(dir, &[LOCK_FILE])?;
        safe::check_entries(dir, names)?;
        std::fs::create_dir_all(dir).map_err(|e| format!("{shown}: cannot create: {e}"))?;
        let path = dir.join(LOCK_FILE);
        let mut opts = OpenOptions::new();
        opts.read(true).write(true).create(true).truncate(false);
        let mut file =
            safe::open_nofollow(&opts, &path).map_err(|e| safe::io_message(&path, "open", &e))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                // what the holder wrote (its pid and command line), bounded and quoted
                // printable: a lock file is a file of the folder like any other
                let mut holder = String::new();
                let _ = (&mut file).take(4096).read_to_string(&mut holder);
                let holder = safe::excerpt_to(&holder.trim().replace('\n', "; "), 400);
                let who = if holder.is_empty() {
                    String::new()
                } else {
                    format!(" ({holder})")
                };
                return Err(format!(
                    "{shown}: another gsph process is writing this folder{who}; wait for it to end or choose another --out"
                ));
            }
            Err(TryLockError::Error(e)) => {
                return Err(format!("{}: cannot lock: {e}", path.display()))
            }
        }
        let me = format!(
            "pid {}, {}",
            std::process::id(),
            std::env::args().collect::<Vec<_>>().join(" ")
        );
        let _ = file.set_len(0);
        let _ = file.rewind();
        let _ = file.write_all(me.as_bytes());
        let _ = file.flush();
        Ok(OutLock {
            _file: file,
            dir: dir.to_path_buf(),
        })
    }

    /// The locked folder.
    pub fn dir(&self) -> &Path {
        &self.dir
    }
}

/// A fresh identifier for a run (16 hex digits): binds its checkpoints to its results.
pub fn new_run_id() -> String {
    use std::hash::{BuildHasher, Hasher};
    // RandomState is seeded from the operating system's randomness per process
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u128(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map_or(0, |d| d.as_nanos()),
    );
    h.write_u32(std::process::id());
    format!("{:016x}", h.finish())
}

/// The `run_id` recorded in `dir/summary.json`, if that file exists and has one.
pub fn summary_run_id(dir: &Path) -> Option<String> {
    // a regular file of bounded size (a pipe there would block the restart)
    let text = safe::read_text(&dir.join("summary.json"), 1 << 26).ok()?;
    let v: serde_json::Value = serde_json::from_str(&text).ok()?;
    v.get("run_id")?.as_str().map(str::to_owned)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_that_would_escape_out_are_refused() {
        for bad in [
            "",
            "../../x",
            "/abs/path",
            "a/b",
            "a\\b",
            ".",
            "..",
            ".hidden",
            "a\nb",
        ] {
            let e = check_name(bad).unwrap_err();
            assert!(e.starts_with("name: "), "{bad:?}: {e}");
        }
        for good in ["flyer_plate", "ring collapse", "Cu-2.5", "ü"] {
            check_name(good).unwrap();
        }
        assert_eq!(
            default_dir("flyer", "_study").unwrap(),
            PathBuf::from("out/flyer_study")
        );
    }

    #[test]
    fn a_locked_folder_is_refused_and_freed_on_drop() {
        let d = tempfile::tempdir().unwrap();
        let first = OutLock::acquire(d.path()).unwrap();
        // a second handle in the same process conflicts like a second process does
        let e = OutLock::acquire(d.path()).unwrap_err();
        assert!(
            e.contains("another gsph process is writing this folder (pid"),
            "{e}"
        );
        drop(first);
        OutLock::acquire(d.path()).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_linked_lock_file_or_entry_is_refused_before_anything_is_written() {
        let d = tempfile::tempdir().unwrap();
        let target = d.path().join("elsewhere");
        std::fs::write(&target, "keep").unwrap();
        let out = d.path().join("out");
        std::fs::create_dir(&out).unwrap();
        std::os::unix::fs::symlink(&target, out.join(LOCK_FILE)).unwrap();
        let e = OutLock::acquire(&out).unwrap_err();
        assert!(e.ends_with(".gsph.lock: is a symbolic link; gsph writes no file through a link (remove it or choose another --out)"), "{e}");
        std::fs::remove_file(out.join(LOCK_FILE)).unwrap();
        std::os::unix::fs::symlink(&target, out.join("run.log")).unwrap();
        let e = OutLock::acquire_for(&out, &["summary.json", "run.log"]).unwrap_err();
        assert!(e.contains("run.log: is a symbolic link"), "{e}");
        assert!(
            !out.join(LOCK_FILE).exists(),
            "nothing created before the check"
        );
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
    }

    #[test]
    fn run_ids_differ() {
        assert_ne!(new_run_id(), new_run_id());
        assert_eq!(new_run_id().len(), 16);
    }
}
