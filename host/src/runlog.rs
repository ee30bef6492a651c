//! `run.log` in the output folder: who ran what and how it ended, for batch jobs and for
//! a referee reading the folder later. Written when the run has been validated and holds
//! the folder's lock; a restart appends to the log of the run it continues.
//!
//! ```text
//! gsph 0.1.0, run 3f2a9c0d41e7b655, started 2026-12-02 21:40:01 UTC
//! command: gsph run cases/flyer_plate.toml --out out/flyer
//! threads: 2, MPI ranks: 1, SIMD: avx2
//! scene: cases/flyer_plate.toml, sha256 9b1c…
//! overrides: t_end=1e-6
//! ----- scene text -----
//! …
//! ----- end of scene text -----
//! finished 2026-12-02 21:40:13 UTC: 520 steps, t = 5.000e-7 s, wall 11.8 s
//! summary: {…}
//! ```

use crate::output::safe::open_nofollow;
use sha2::{Digest, Sha256};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

/// File name of the log in the output folder.
pub const RUN_LOG: &str = "run.log";

/// SHA-256 of `text`, as 64 hex digits.
pub fn sha256_hex(text: &str) -> String {
    Sha256::digest(text.as_bytes())
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// `YYYY-MM-DD hh:mm:ss UTC` of the system clock.
pub fn utc_now() -> String {
    let secs = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    utc(secs)
}

/// `YYYY-MM-DD hh:mm:ss UTC` of `secs` since 1970 (civil-from-days, H. Hinnant).
pub fn utc(secs: u64) -> String {
    let days = (secs / 86_400) as i64;
    let rem = secs % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02} {:02}:{:02}:{:02} UTC",
        rem / 3600,
        rem / 60 % 60,
        rem % 60
    )
}

/// What run.log records about the scene.
#[derive(Debug, Clone, Default)]
pub struct SceneInfo<'a> {
    /// Where the scene came from.
    pub origin: &'a str,
    /// The scene text.
    pub text: &'a str,
    /// `--set`/`--unset` overrides, in order.
    pub overrides: &'a [String],
}

/// The run `dir/run.log` belongs to: the id on its first line (`gsph V, run ID, started
/// …`), `Ok(None)` when there is no run.log. A restart compares it with its checkpoint's
/// (a log is never continued by another run).
pub fn run_id_of(dir: &Path) -> Result<Option<String>, String> {
    use std::io::BufRead;
    let path = dir.join(RUN_LOG);
    match std::fs::symlink_metadata(&path) {
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(format!("{}: {e}", path.display())),
        Ok(m) if m.file_type().is_symlink() => {
            return Err(format!("{}: is a symbolic link", path.display()))
        }
        Ok(m) if !m.file_type().is_file() => {
            return Err(format!("{}: not a regular file", path.display()))
        }
        Ok(_) => {}
    }
    let f = std::fs::File::open(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    // the first line only, and at most 4 KiB of it
    let mut first = Vec::new();
    std::io::BufReader::new(f)
        .take(4096)
        .read_until(b'\n', &mut first)
        .map_err(|e| format!("{}: {e}", path.display()))?;
    let first = String::from_utf8_lossy(&first);
    let id = first
        .strip_prefix("gsph ")
        .and_then(|rest| rest.split(", ").nth(1))
        .and_then(|w| w.strip_prefix("run "))
        .filter(|id| !id.is_empty() && id.chars().all(|c| c.is_ascii_alphanumeric()));
    match id {
        Some(id) => Ok(Some(id.to_owned())),
        None => Err(format!(
            "{}: its first line names no run (`gsph VERSION, run ID, …`)",
            path.display()
        )),
    }
}

/// An open run.log.
#[derive(Debug)]
pub struct RunLog {
    path: PathBuf,
}

impl RunLog {
    /// Starts `dir/run.log` (a fresh run truncates it; a restart, `resumed_at = Some(step)`,
    /// appends) with the header: version, run id, command, scene and its hash.
    pub fn start(
        dir: &Path,
        run_id: &str,
        scene: &SceneInfo<'_>,
        resumed_at: Option<u64>,
    ) -> std::io::Result<RunLog> {
        let path = dir.join(RUN_LOG);
        // never through a link planted in the folder (output::safe)
        let mut f = open_nofollow(
            std::fs::OpenOptions::new()
                .create(true)
                .write(true)
                .append(resumed_at.is_some())
                .truncate(resumed_at.is_none()),
            &path,
        )?;
        let mut head = String::new();
        let verb = match resumed_at {
            Some(step) => format!("restarted from the checkpoint at step {step}"),
            None => "started".into(),
        };
        head.push_str(&format!(
            "gsph {}, run {run_id}, {verb} {}\n",
            env!("CARGO_PKG_VERSION"),
            utc_now()
        ));
        head.push_str(&format!(
            "command: {}\n",
            std::env::args().collect::<Vec<_>>().join(" ")
        ));
        head.push_str(&format!(
            "threads: {}, MPI ranks: {}, SIMD: {}\n",
            rayon::current_num_threads(),
            crate::dist_size(),
            crate::exec::simd().map_or("?", |l| l.get().name())
        ));
        if resumed_at.is_none() {
            head.push_str(&format!(
                "scene: {}, sha256 {}\n",
                scene.origin,
                sha256_hex(scene.text)
            ));
            if !scene.overrides.is_empty() {
                head.push_str(&format!("overrides: {}\n", scene.overrides.join(" ")));
            }
            head.push_str("----- scene text -----\n");
            head.push_str(scene.text);
            if !scene.text.ends_with('\n') {
                head.push('\n');
            }
            head.push_str("----- end of scene text -----\n");
        }
        f.write_all(head.as_bytes())?;
        f.sync_data()?;
        Ok(RunLog { path })
    }

    /// Appends `text` (a line or more), best effort: the log never fails a run.
    pub fn append(&self, text: &str) {
        if let Ok(mut f) = open_nofollow(std::fs::OpenOptions::new().append(true), &self.path) {
            let mut t = text.to_owned();
            if !t.ends_with('\n') {
                t.push('\n');
            }
            let _ = f.write_all(t.as_bytes());
            let _ = f.sync_data();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn utc_dates_are_civil() {
        assert_eq!(utc(0), "1970-01-01 00:00:00 UTC");
        assert_eq!(utc(951_782_400), "2000-02-29 00:00:00 UTC");
        assert_eq!(utc(1_796_246_461), "2026-12-02 21:21:01 UTC");
    }

    #[test]
    fn sha256_of_a_known_text() {
        assert_eq!(
            sha256_hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_linked_run_log_is_never_written_through() {
        let d = tempfile::tempdir().unwrap();
        let target = d.path().join("victim");
        std::fs::write(&target, "keep").unwrap();
        std::os::unix::fs::symlink(&target, d.path().join(RUN_LOG)).unwrap();
        for resumed in [None, Some(3)] {
            let e = RunLog::start(d.path(), "a", &SceneInfo::default(), resumed).unwrap_err();
            assert!(e.to_string().contains("is a symbolic link"), "{e}");
        }
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
    }

    #[test]
    fn a_restart_appends_and_a_fresh_run_truncates() {
        let d = tempfile::tempdir().unwrap();
        let sc = SceneInfo {
            origin: "s.toml",
            text: "dim = 1",
            overrides: &["t_end=1".into()],
        };
        RunLog::start(d.path(), "a", &sc, None)
            .unwrap()
            .append("finished");
        RunLog::start(d.path(), "a", &sc, Some(7)).unwrap();
        let t = std::fs::read_to_string(d.path().join(RUN_LOG)).unwrap();
        assert!(t.contains("run a, started"), "{t}");
        assert!(t.contains("overrides: t_end=1\n----- scene text -----\ndim = 1\n"));
        assert!(t.contains("finished\ngsph "), "{t}");
        assert!(t.contains("restarted from the checkpoint at step 7"), "{t}");
        assert_eq!(run_id_of(d.path()), Ok(Some("a".into())));
        RunLog::start(d.path(), "b", &sc, None).unwrap();
        let t = std::fs::read_to_string(d.path().join(RUN_LOG)).unwrap();
        assert!(!t.contains("run a"), "{t}");
        assert_eq!(run_id_of(d.path()), Ok(Some("b".into())));
        std::fs::write(d.path().join(RUN_LOG), "not a log\n").unwrap();
        assert!(run_id_of(d.path()).unwrap_err().contains("names no run"));
        std::fs::remove_file(d.path().join(RUN_LOG)).unwrap();
        assert_eq!(run_id_of(d.path()), Ok(None));
    }
}
