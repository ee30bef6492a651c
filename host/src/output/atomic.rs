//! Atomic file writing: a failed run never leaves a file that looks complete.
//!
//! [`AtomicFile`] writes to a uniquely named temp file in the destination's directory
//! (`tempfile`: `.<name>.XXXXXX.tmp`, so two writers of one name never write into each
//! other's temp file), syncs it to disk, then renames it over the destination (rename within
//! one directory is atomic on POSIX file systems) and syncs the directory. A temp file whose
//! writer is dropped without committing is removed (by `tempfile`, also on unwinding).
//! [`tmp_path`] and [`commit_tmp`] serve files that a library writes by name (HDF5
//! snapshots and checkpoints): a fixed sibling `<name>.tmp`.
//!
//! The temp file is created with `O_EXCL` (never through a link) and the rename replaces a
//! link at the destination instead of following it, so an atomic write never writes outside
//! its folder. It is created with mode `0o666` less the umask, as `open` makes files (not
//! tempfile's `0o600`).

use std::ffi::OsString;
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

/// The temp path used while writing `path`: `<name>.tmp` in the same directory.
pub fn tmp_path(path: &Path) -> PathBuf {
    let mut name: OsString = path.file_name().map(OsString::from).unwrap_or_default();
    name.push(".tmp");
    path.with_file_name(name)
}

/// Syncs the directory holding `path`, so a rename into it survives a crash (best effort: not every
/// platform can open a directory for syncing).
pub fn sync_parent_dir(path: &Path) {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
}

/// Syncs `tmp` to disk and renames it to `path`; removes `tmp` if either fails.
pub fn commit_tmp(tmp: &Path, path: &Path) -> io::Result<()> {
    let result = File::open(tmp)
        .and_then(|f| f.sync_all())
        .and_then(|()| fs::rename(tmp, path));
    match result {
        Ok(()) => {
            sync_parent_dir(path);
            Ok(())
        }
        Err(e) => {
            let _ = fs::remove_file(tmp);
            Err(e)
        }
    }
}

/// Writes `bytes` to `path` atomically (temp file in the same directory, fsync, rename).
pub fn write_atomic(path: impl AsRef<Path>, bytes: &[u8]) -> io::Result<()> {
    let mut f = AtomicFile::create(path)?;
    f.write_all(bytes)?;
    f.commit()
}

/// A buffered file written under a unique temp name and renamed to its final name by
/// [`AtomicFile::commit`].
///
/// Dropping it without committing removes the temp file.
#[derive(Debug)]
pub struct AtomicFile {
    path: PathBuf,
    writer: Option<BufWriter<tempfile::NamedTempFile>>,
}

impl AtomicFile {
    /// Creates a temp file for `path` in its directory.
    pub fn create(path: impl AsRef<Path>) -> io::Result<Self> {
        let path = path.as_ref().to_path_buf();
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        let name = path
            .file_name()
            .map(|n| n.to_string_lossy())
            .unwrap_or_default();
        let prefix = format!(".{name}.");
        let mut b = tempfile::Builder::new();
        b.prefix(&prefix).suffix(".tmp");
        // as the umask says (tempfile's default is 0600: a group could not read results)
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            b.permissions(fs::Permissions::from_mode(super::safe::FILE_MODE));
        }
        let file = b.tempfile_in(dir)?;
        Ok(Self {
            path,
            writer: Some(BufWriter::new(file)),
        })
    }

    /// The final path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The temp path being written (empty once committed).
    pub fn tmp_path(&self) -> &Path {
        self.writer
            .as_ref()
            .map_or(Path::new(""), |w| w.get_ref().path())
    }

    /// Flushes, syncs and renames the temp file to the final path (the temp file is
    /// removed if any of it fails).
    pub fn commit(mut self) -> io::Result<()> {
        let writer = self
            .writer
            .take()
            .ok_or_else(|| io::Error::other("already committed"))?;
        let file = writer
            .into_inner()
            .map_err(io::IntoInnerError::into_error)?;
        file.as_file().sync_all()?;
        file.persist(&self.path).map_err(|e| e.error)?;
        sync_parent_dir(&self.path);
        Ok(())
    }

    fn writer(&mut self) -> io::Result<&mut BufWriter<tempfile::NamedTempFile>> {
        self.writer
            .as_mut()
            .ok_or_else(|| io::Error::other("already committed"))
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.writer()?.write(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.writer()?.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn tmp_path_is_sibling() {
        assert_eq!(
            tmp_path(Path::new("/a/b/final.csv")),
            Path::new("/a/b/final.csv.tmp")
        );
        assert_eq!(tmp_path(Path::new("x.json")), Path::new("x.json.tmp"));
    }

    #[test]
    fn write_atomic_leaves_no_tmp() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("summary.json");
        write_atomic(&p, b"{\"a\":1}").unwrap();
        write_atomic(&p, b"{\"a\":2}").unwrap();
        assert_eq!(fs::read(&p).unwrap(), b"{\"a\":2}");
        assert_eq!(names(dir.path()), vec!["summary.json"]);
    }

    #[test]
    fn atomic_file_commit_and_drop() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.txt");
        let mut f = AtomicFile::create(&p).unwrap();
        f.write_all(b"hello").unwrap();
        assert!(f.tmp_path().exists());
        assert_eq!(f.tmp_path().parent(), Some(dir.path()));
        assert!(!p.exists());
        // a second writer of the same name writes its own temp file
        let mut f2 = AtomicFile::create(&p).unwrap();
        assert_ne!(f.tmp_path(), f2.tmp_path());
        f2.write_all(b"other").unwrap();
        drop(f2);
        assert!(f.tmp_path().exists());
        f.commit().unwrap();
        assert_eq!(fs::read(&p).unwrap(), b"hello");

        let q = dir.path().join("dropped.txt");
        let mut g = AtomicFile::create(&q).unwrap();
        g.write_all(b"partial").unwrap();
        drop(g);
        assert_eq!(names(dir.path()), vec!["out.txt"]);
    }

    #[cfg(unix)]
    #[test]
    fn files_follow_the_umask_and_links_are_replaced_not_followed() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("summary.json");
        write_atomic(&p, b"{}").unwrap();
        let mode = fs::metadata(&p).unwrap().permissions().mode() & 0o777;
        // the umask of this process (the test harness's), read back from a plain create
        let plain = dir.path().join("plain");
        File::create(&plain).unwrap();
        let want = fs::metadata(&plain).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode, want, "{mode:o} vs {want:o}");
        let target = dir.path().join("target");
        fs::write(&target, b"keep").unwrap();
        let link = dir.path().join("final.csv");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write_atomic(&link, b"new").unwrap();
        assert_eq!(fs::read(&target).unwrap(), b"keep");
        assert!(!fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
    }

    #[test]
    fn write_atomic_into_missing_dir_fails_cleanly() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("nope").join("x.txt");
        assert!(write_atomic(&p, b"x").is_err());
        assert!(names(dir.path()).is_empty());
    }
}
