//! Atomic writes of one file: a one-file [`OutputSet`], staged as a temporary file
//! in the target's directory, flushed to disk, then renamed over the target.
//!
//! A reader sees the old file or the complete new one, never a half-written mix, and
//! a failure (full disk, a writer callback's error, a panic) leaves the old file
//! untouched and the temporary file removed. Commands that write several files stage
//! them in one [`OutputSet`] instead, so the set is replaced as a whole.

use crate::error::IoError;
use crate::output_set::OutputSet;
use std::io::{self, Write};
use std::path::Path;

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
    let mut set = OutputSet::new();
    set.write_with(path, write)?;
    set.commit()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::{entries, scratch_dir};
    use std::fs;

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
