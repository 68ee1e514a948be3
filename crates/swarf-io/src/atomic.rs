//! Atomic file writes: write a temporary file in the target's directory, flush it to
//! disk, then rename it over the target.
//!
//! `rename` within one directory (one file system) replaces the target atomically on
//! POSIX and Windows, so a reader sees the old file or the complete new one, never a
//! half-written mix, and a failure (full disk, a writer callback's error, a panic)
//! leaves the old file untouched and the temporary file removed. The temporary file
//! is created with `create_new`, so two writers never share one, and it takes the
//! target's permissions when the target exists. After the rename the directory is
//! synced too (best effort) so the new name survives a crash.

use crate::error::IoError;
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Buffer of the streaming writer, bytes.
const BUFFER: usize = 1 << 16;

/// Writes `bytes` to `path` atomically, creating parent directories.
///
/// # Errors
/// [`IoError::Io`] naming `path` when a directory cannot be created or the file
/// cannot be written or renamed; the previous file at `path`, if any, is then intact.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), IoError> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// Streams to `path` atomically: `write` gets a buffered writer on a temporary file
/// that replaces `path` only when `write` returns `Ok` and everything reached disk.
///
/// # Errors
/// As [`write_atomic`]; an error returned by `write` is reported the same way
/// (return `io::Error::other(..)` to fail with a message of your own).
///
/// # Example
/// ```
/// let path = std::env::temp_dir().join(format!("swarf-doc-{}.txt", std::process::id()));
/// swarf_io::write_atomic_with(&path, |w| writeln!(w, "x,y")).unwrap();
/// let failed = swarf_io::write_atomic_with(&path, |w| {
///     writeln!(w, "partial")?;
///     Err(std::io::Error::other("stopped"))
/// });
/// assert!(failed.unwrap_err().to_string().ends_with("cannot write: stopped"));
/// assert_eq!(std::fs::read_to_string(&path).unwrap(), "x,y\n");
/// # std::fs::remove_file(&path).unwrap();
/// ```
pub fn write_atomic_with<F>(path: &Path, write: F) -> Result<(), IoError>
where
    F: FnOnce(&mut dyn Write) -> io::Result<()>,
{
    let Some(name) = path.file_name() else {
        let e = io::Error::new(io::ErrorKind::InvalidInput, "the path names no file");
        return Err(IoError::io(path, "write", e));
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    fs::create_dir_all(dir).map_err(|e| IoError::io(dir, "create directory", e))?;
    let (file, temp) =
        create_temp(dir, name).map_err(|e| IoError::io(path, "create a temporary file for", e))?;
    let mut writer = BufWriter::with_capacity(BUFFER, file);
    write(&mut writer).map_err(|e| IoError::io(path, "write", e))?;
    let file = writer
        .into_inner()
        .map_err(|e| IoError::io(path, "write", e.into_error()))?;
    if let Ok(meta) = fs::metadata(path) {
        file.set_permissions(meta.permissions())
            .map_err(|e| IoError::io(path, "set permissions of", e))?;
    }
    file.sync_all()
        .map_err(|e| IoError::io(path, "flush to disk", e))?;
    drop(file);
    fs::rename(&temp.0, path).map_err(|e| IoError::io(path, "replace", e))?;
    temp.disarm();
    if let Ok(d) = File::open(dir) {
        let _ = d.sync_all();
    }
    Ok(())
}

/// Removes the temporary file when dropped, unless disarmed after the rename.
struct TempFile(PathBuf);

impl TempFile {
    fn disarm(self) {
        std::mem::forget(self);
    }
}

impl Drop for TempFile {
    fn drop(&mut self) {
        let _ = fs::remove_file(&self.0);
    }
}

/// A new file `.NAME.PID.N.tmp` in `dir`.
fn create_temp(dir: &Path, name: &std::ffi::OsStr) -> io::Result<(File, TempFile)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let mut temp_name = std::ffi::OsString::from(".");
        temp_name.push(name);
        temp_name.push(format!(".{}.{n}.tmp", std::process::id()));
        let temp = dir.join(temp_name);
        match File::options().write(true).create_new(true).open(&temp) {
            Ok(f) => return Ok((f, TempFile(temp))),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::scratch_dir;

    fn entries(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn writes_replaces_and_creates_parents() {
        let dir = scratch_dir("atomic");
        let path = dir.join("a/b/out.txt");
        write_atomic(&path, b"one").unwrap();
        write_atomic(&path, b"two, longer").unwrap();
        assert_eq!(fs::read(&path).unwrap(), b"two, longer");
        assert_eq!(entries(&dir.join("a/b")), vec!["out.txt"]);
        write_atomic_with(&path, |w| {
            for i in 0..100_000 {
                write!(w, "{i},")?;
            }
            Ok(())
        })
        .unwrap();
        assert!(fs::read_to_string(&path).unwrap().ends_with("99999,"));
    }

    #[test]
    fn failed_write_leaves_existing_file_untouched() {
        let dir = scratch_dir("atomic-fail");
        let path = dir.join("keep.txt");
        write_atomic(&path, b"original").unwrap();
        let e = write_atomic_with(&path, |w| {
            w.write_all(&[b'x'; 200_000])?;
            Err(io::Error::other("generator failed"))
        })
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            format!("{}: cannot write: generator failed", path.display())
        );
        assert_eq!(fs::read(&path).unwrap(), b"original");
        assert_eq!(entries(&dir), vec!["keep.txt"]);
        let panicked = std::panic::catch_unwind(|| write_atomic_with(&path, |_| panic!("boom")));
        assert!(panicked.is_err());
        assert_eq!(fs::read(&path).unwrap(), b"original");
        assert_eq!(entries(&dir), vec!["keep.txt"]);
    }

    #[test]
    fn errors_name_the_path() {
        let dir = scratch_dir("atomic-err");
        let blocker = dir.join("file");
        fs::write(&blocker, b"").unwrap();
        let e = write_atomic(&blocker.join("sub/x.txt"), b"1").unwrap_err();
        assert!(e.to_string().contains("cannot create directory"), "{e}");
        let e = write_atomic(&dir, b"1").unwrap_err();
        assert!(e.to_string().starts_with(&dir.display().to_string()), "{e}");
        assert_eq!(entries(&dir), vec!["file"]);
    }

    #[cfg(unix)]
    #[test]
    fn keeps_permissions() {
        use std::os::unix::fs::PermissionsExt;
        let dir = scratch_dir("atomic-perm");
        let path = dir.join("p.txt");
        write_atomic(&path, b"1").unwrap();
        fs::set_permissions(&path, fs::Permissions::from_mode(0o640)).unwrap();
        write_atomic(&path, b"2").unwrap();
        assert_eq!(
            fs::metadata(&path).unwrap().permissions().mode() & 0o777,
            0o640
        );
    }
}
