//! Files in and out without surprises (issue 25): nothing written through a symbolic link,
//! nothing read from something that is not a regular file, no file's contents quoted at
//! length in a message.
//!
//! Writing. A run writes only into the folder it was given, and never through a link in
//! it: a link planted there (or unpacked from a results tarball) would make a plain
//! `open` overwrite its target. So [`check_entries`] refuses, before a command touches its
//! folder, any entry it would write or remove that is a symbolic link (one line naming
//! it, [`refuse_link`]); files opened in place ([`open_nofollow`]: the lock, run.log) are
//! opened with `O_NOFOLLOW`, so a link planted after the check fails the open instead of
//! being followed; files written whole go through a temp file created with `O_EXCL` and a
//! rename, which replaces a link rather than following it ([`super::atomic`]). The folder
//! named by `--out` may itself be a link (the user named it); a folder gsph creates inside
//! another ([`create_dir_in`]) may not.
//!
//! Permissions. Result files are created as the umask says (mode `0o666` less the
//! umask, as `open` makes them), not `0o600`: on a shared cluster folder a group reads
//! them ([`FILE_MODE`]).
//!
//! Reading. Where a file is expected it must be a regular file ([`regular_file`]: not a
//! directory, a FIFO that never ends, `/dev/zero` or a socket), and text files are read
//! up to a bound ([`read_text`]). `/proc` files report as regular files, which is why
//! messages quote at most a short excerpt of a file's contents ([`excerpt`],
//! [`shorten_quotes`]): `file = "/proc/self/environ"` must not print the environment.

use std::fs::{File, OpenOptions};
use std::io::{self, BufRead, Read};
use std::path::Path;

/// The mode files are created with before the umask applies (`open(2)` applies it).
pub const FILE_MODE: u32 = 0o666;

/// Most bytes a table gsph wrote and reads back whole is read of (series.csv, profile.csv,
/// hugoniot.csv, a measured outline): far above any such file, a bound for a `/proc` file
/// named in their place.
pub const MAX_TABLE: u64 = 1 << 30;

/// Longest line of a text file read line by line (a particle CSV file, an ASCII STL):
/// far above any row such a file has, short enough that a file without line breaks is
/// refused after reading this much of it.
pub const MAX_LINE: usize = 1 << 16;

/// Most characters of a file's contents a message quotes ([`excerpt`]).
pub const EXCERPT_CHARS: usize = 40;

/// At most [`EXCERPT_CHARS`] characters of `s`, control characters escaped (`\n`,
/// `\u{0}`), a cut marked with `…`. What a message may quote of a file's contents.
pub fn excerpt(s: &str) -> String {
    excerpt_to(s, EXCERPT_CHARS)
}

/// [`excerpt`] of at most `chars` characters (for what the user typed, such as a `--set`,
/// which may be longer than a file's excerpt but not unbounded: a restart replays the
/// overrides stored in a checkpoint file).
pub fn excerpt_to(s: &str, chars: usize) -> String {
    let mut out = String::new();
    for (shown, c) in s.chars().enumerate() {
        if shown == chars {
            out.push('…');
            return out;
        }
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// Names read from a file (a header's columns), listed for a message: each an [`excerpt`],
/// at most 12 of them (`…, and N more`).
pub fn shorten_list(names: &[&str]) -> String {
    let mut v: Vec<String> = names.iter().take(12).map(|n| excerpt(n)).collect();
    if names.len() > 12 {
        v.push(format!("… and {} more", names.len() - 12));
    }
    v.join(", ")
}

/// `msg` with every quoted span (between backticks or double quotes) cut to an
/// [`excerpt`], and control characters escaped everywhere: for messages of other crates
/// (TOML, STL, serde) that quote a file's contents whole.
pub fn shorten_quotes(msg: &str) -> String {
    let mut out = String::with_capacity(msg.len().min(512));
    let mut rest = msg;
    while let Some(open) = rest.find(['`', '"']) {
        let q = rest.as_bytes()[open] as char;
        out.push_str(&escape_controls(&rest[..open]));
        let after = &rest[open + 1..];
        match after.find(q) {
            Some(close) => {
                out.push(q);
                out.push_str(&excerpt(&after[..close]));
                out.push(q);
                rest = &after[close + 1..];
            }
            None => {
                // an unclosed quote: what follows is quoted to the end
                out.push(q);
                out.push_str(&excerpt(after));
                return out;
            }
        }
    }
    out.push_str(&escape_controls(rest));
    out
}

fn escape_controls(s: &str) -> String {
    s.chars()
        .flat_map(|c| {
            let e: Vec<char> = if c.is_control() {
                c.escape_default().collect()
            } else {
                vec![c]
            };
            e
        })
        .collect()
}

/// One line for an entry of an output folder that is a symbolic link.
pub fn link_message(path: &Path) -> String {
    format!(
        "{}: is a symbolic link; gsph writes no file through a link (remove it or choose another --out)",
        path.display()
    )
}

/// Refuses `path` if it is a symbolic link (whatever it points to, dangling or not).
pub fn refuse_link(path: &Path) -> Result<(), String> {
    match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => Err(link_message(path)),
        _ => Ok(()),
    }
}

/// Refuses the first of `names` in `dir` that is a symbolic link: the entries a command
/// will write or remove, checked before it touches the folder.
pub fn check_entries<S: AsRef<str>>(dir: &Path, names: &[S]) -> Result<(), String> {
    names
        .iter()
        .try_for_each(|n| refuse_link(&dir.join(n.as_ref())))
}

/// `opts` set not to follow a symbolic link at the last component of the path
/// (`O_NOFOLLOW`; the open fails with `ELOOP` on a link). Elsewhere than Unix a check
/// with [`refuse_link`] before the open has to do.
pub fn nofollow(opts: &mut OpenOptions) -> &mut OpenOptions {
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        opts.custom_flags(libc::O_NOFOLLOW);
    }
    opts
}

/// The error of [`open_nofollow`] at a symbolic link (inside an `io::Error`; its
/// `Display` is [`link_message`]).
#[derive(Debug)]
pub struct LinkRefused(pub String);

impl std::fmt::Display for LinkRefused {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for LinkRefused {}

/// One line for an error of opening or writing `path`: the [`LinkRefused`] line as it is,
/// else `PATH: cannot VERB: cause`.
pub fn io_message(path: &Path, verb: &str, e: &io::Error) -> String {
    match e.get_ref().and_then(|i| i.downcast_ref::<LinkRefused>()) {
        Some(l) => l.0.clone(),
        None => format!("{}: cannot {verb}: {e}", path.display()),
    }
}

/// Opens `path` with `opts` without following a link there; a link is refused
/// ([`LinkRefused`], one line naming it).
pub fn open_nofollow(opts: &OpenOptions, path: &Path) -> io::Result<File> {
    let refused = || io::Error::other(LinkRefused(link_message(path)));
    if refuse_link(path).is_err() {
        return Err(refused());
    }
    let mut o = opts.clone();
    match nofollow(&mut o).open(path) {
        #[cfg(unix)]
        Err(e) if e.raw_os_error() == Some(libc::ELOOP) => Err(refused()),
        r => r,
    }
}

/// Creates the folder `name` inside `parent` (which exists or is created: the user named
/// it) unless it exists; refuses it if it is a symbolic link. For folders gsph chooses
/// itself.
pub fn create_dir_in(parent: &Path, name: &str) -> Result<std::path::PathBuf, String> {
    let dir = parent.join(name);
    refuse_link(&dir)?;
    std::fs::create_dir_all(&dir).map_err(|e| format!("{}: cannot create: {e}", dir.display()))?;
    refuse_link(&dir)?;
    Ok(dir)
}

/// Checks that a file name given in a scene can be one: at most 4096 bytes (`PATH_MAX`),
/// no control character. Else a message quotes an excerpt of it, not the whole value.
pub fn check_file_name(name: &str) -> Result<(), String> {
    if name.len() > 4096 || name.chars().any(char::is_control) {
        return Err(format!(
            "`{}` is not a file name (longer than 4096 bytes or with control characters)",
            excerpt(name)
        ));
    }
    Ok(())
}

/// Checks that `path` is a regular file (following links: the user named it); returns its
/// length. `Err` is the cause alone (`not a regular file`, `cannot read: ...`), for the
/// caller to prefix with the key and file.
pub fn regular_file(path: &Path) -> Result<u64, String> {
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot read: {e}"))?;
    if !meta.is_file() {
        return Err("not a regular file".into());
    }
    if let Some(fs) = pseudo_file_system(path) {
        return Err(format!(
            "a file of the kernel's {fs}, not a data file (nothing of it is read)"
        ));
    }
    Ok(meta.len())
}

/// The kernel file system `path` lies on when it is one whose files are made up on
/// reading (procfs, sysfs, …: a "regular file" of length 0 that yields the process's
/// environment, say), by the file system's magic number on Linux and the path elsewhere.
fn pseudo_file_system(path: &Path) -> Option<&'static str> {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::ffi::OsStrExt;
        let c = std::ffi::CString::new(path.as_os_str().as_bytes()).ok()?;
        let mut st: libc::statfs = unsafe { std::mem::zeroed() };
        // SAFETY: `c` is a NUL-terminated path and `st` a writable statfs
        if unsafe { libc::statfs(c.as_ptr(), &mut st) } == 0 {
            // <linux/magic.h>
            return match (st.f_type as i64) & 0xffff_ffff {
                0x9fa0 => Some("/proc (procfs)"),
                0x6265_6572 => Some("/sys (sysfs)"),
                0x6462_6720 => Some("debugfs"),
                0x7472_6163 => Some("tracefs"),
                0x2738_6c73 => Some("cgroup2fs"),
                0x0027_e0eb => Some("cgroupfs"),
                0x1cd1 => Some("devpts"),
                0x6e73_6673 => Some("nsfs"),
                0x7363_6673 => Some("securityfs"),
                0xcafe_4a11 => Some("bpf"),
                _ => None,
            };
        }
        None
    }
    #[cfg(not(target_os = "linux"))]
    {
        let real = std::fs::canonicalize(path).ok()?;
        ["/proc", "/sys", "/dev"]
            .into_iter()
            .find(|d| real.starts_with(d))
    }
}

/// The text of a regular file of at most `max` bytes (read with a bound, so that a
/// `/proc` file reporting length 0 cannot grow past it either). `Err` is the cause alone.
pub fn read_text(path: &Path, max: u64) -> Result<String, String> {
    let len = regular_file(path)?;
    if len > max {
        return Err(format!(
            "{len} bytes, more than the {max} read of such a file"
        ));
    }
    let mut bytes = Vec::new();
    File::open(path)
        .and_then(|f| f.take(max.saturating_add(1)).read_to_end(&mut bytes))
        .map_err(|e| format!("cannot read: {e}"))?;
    if bytes.len() as u64 > max {
        return Err(format!("more than the {max} bytes read of such a file"));
    }
    String::from_utf8(bytes).map_err(|e| {
        format!(
            "not UTF-8 text (byte {} is not; is this the right file?)",
            e.utf8_error().valid_up_to()
        )
    })
}

/// The lines of `r` (without their line breaks, a CR before one dropped), each at most
/// [`MAX_LINE`] bytes: a longer one ends the iteration with an error naming it, read no
/// further. `Err` is `line N: cause`.
pub fn lines<R: io::BufRead>(mut r: R) -> impl Iterator<Item = Result<String, String>> {
    let mut lineno = 0usize;
    let mut done = false;
    std::iter::from_fn(move || {
        if done {
            return None;
        }
        lineno += 1;
        let mut line = Vec::new();
        let got = (&mut r)
            .take(MAX_LINE as u64 + 1)
            .read_until(b'\n', &mut line);
        let mut fail = |msg: String| {
            done = true;
            Some(Err(format!("line {lineno}: {msg}")))
        };
        match got {
            Err(e) => return fail(format!("cannot read: {e}")),
            Ok(0) => {
                done = true;
                return None;
            }
            Ok(_) => {}
        }
        if line.last() == Some(&b'\n') {
            line.pop();
            if line.last() == Some(&b'\r') {
                line.pop();
            }
        } else if line.len() > MAX_LINE {
            return fail(format!(
                "longer than {MAX_LINE} bytes (no line break: is this the right file?)"
            ));
        }
        match String::from_utf8(line) {
            Ok(l) => Some(Ok(l)),
            Err(_) => fail("not UTF-8 text".into()),
        }
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn excerpts_are_short_and_printable() {
        assert_eq!(excerpt("abc"), "abc");
        let long = "x".repeat(100);
        let e = excerpt(&long);
        assert_eq!(e.chars().count(), EXCERPT_CHARS + 1);
        assert!(e.ends_with('…'));
        assert_eq!(excerpt("a\nb\0c"), "a\\nb\\u{0}c");
        let env = format!(
            "`{}` is not a column; \"{}\"",
            "A=1\0".repeat(50),
            "q".repeat(60)
        );
        let s = shorten_quotes(&env);
        assert!(s.len() < 200, "{s}");
        assert!(!s.chars().any(char::is_control), "{s}");
        assert!(s.contains("` is not a column; \""), "{s}");
        assert_eq!(shorten_quotes("plain, no quotes"), "plain, no quotes");
        assert!(shorten_quotes(&format!("open `{}", "y".repeat(99))).ends_with('…'));
    }

    #[cfg(unix)]
    #[test]
    fn links_are_refused_and_never_followed() {
        let d = tempfile::tempdir().unwrap();
        let target = d.path().join("target.txt");
        std::fs::write(&target, "keep").unwrap();
        let link = d.path().join("run.log");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        let e = check_entries(d.path(), &["summary.json", "run.log"]).unwrap_err();
        assert_eq!(e, link_message(&link));
        let mut o = OpenOptions::new();
        o.write(true).create(true).truncate(true);
        let e = open_nofollow(&o, &link).unwrap_err();
        assert!(e.to_string().contains("is a symbolic link"), "{e}");
        // past the check (a link planted after it): O_NOFOLLOW fails the open
        assert!(nofollow(&mut o.clone()).open(&link).is_err());
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "keep");
        let sub = d.path().join("sub");
        std::os::unix::fs::symlink(d.path(), &sub).unwrap();
        assert!(create_dir_in(d.path(), "sub").is_err());
        assert!(create_dir_in(d.path(), "fresh").unwrap().is_dir());
    }

    #[test]
    fn lines_are_bounded() {
        let text = format!("a\r\nb\n{}\nc", "x".repeat(MAX_LINE));
        let got: Vec<_> = lines(text.as_bytes()).collect();
        assert_eq!(got.len(), 4);
        assert_eq!(got[0].as_deref(), Ok("a"));
        assert_eq!(got[3].as_deref(), Ok("c"));
        let long = format!("a\n{}", "y".repeat(MAX_LINE + 10));
        let got: Vec<_> = lines(long.as_bytes()).collect();
        assert_eq!(got.len(), 2);
        assert!(got[1]
            .as_ref()
            .unwrap_err()
            .starts_with("line 2: longer than"));
    }

    #[test]
    fn only_regular_files_are_read() {
        let d = tempfile::tempdir().unwrap();
        assert_eq!(regular_file(d.path()).unwrap_err(), "not a regular file");
        let p = d.path().join("a.toml");
        std::fs::write(&p, "dim = 1\n").unwrap();
        assert_eq!(read_text(&p, 100).unwrap(), "dim = 1\n");
        assert!(read_text(&p, 3).unwrap_err().contains("more than the 3"));
        #[cfg(target_os = "linux")]
        {
            assert_eq!(
                regular_file(Path::new("/dev/zero")).unwrap_err(),
                "not a regular file"
            );
            // a /proc file (reporting length 0, made up on reading) is not read at all
            let e = read_text(Path::new("/proc/self/maps"), 8).unwrap_err();
            assert!(
                e.starts_with("a file of the kernel's /proc (procfs)"),
                "{e}"
            );
            let e = regular_file(Path::new("/sys/kernel/mm/transparent_hugepage/enabled"));
            assert!(
                e.map_or_else(|e| e.contains("sysfs"), |_| false)
                    || !Path::new("/sys/kernel").exists()
            );
        }
    }
}
