//! Reading an input file within bounds: regular files only (a FIFO, a device such as
//! `/dev/zero` or a directory is refused before any byte is read, so nothing waits or
//! grows without end), and at most [`max_input_bytes`] bytes (1 GiB unless the
//! environment variable `SWARF_MAX_INPUT_MB` says otherwise). Every file swarf reads
//! (parts, meshes, jobs, programs, machines, tool tables, points) comes through here.
//!
//! A command-line run calls [`track_inputs`] first; from then on every file opened
//! here is remembered, and [`crate::OutputSet`] refuses to replace one of them.

use crate::error::IoError;
use std::io::Read;
use std::path::Path;
#[cfg(not(unix))]
use std::path::PathBuf;
use std::sync::Mutex;

/// The files read since [`track_inputs`] (`None`: not tracking).
static READ: Mutex<Option<Vec<FileId>>> = Mutex::new(None);

/// What identifies a file whatever the path that names it: device and inode on Unix,
/// the canonical path elsewhere.
#[derive(Debug, Clone, PartialEq, Eq)]
enum FileId {
    #[cfg(unix)]
    Inode(u64, u64),
    #[cfg(not(unix))]
    Path(PathBuf),
}

/// The identity of the existing file at `path`.
fn file_id(path: &Path) -> Option<FileId> {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        std::fs::metadata(path)
            .ok()
            .map(|m| FileId::Inode(m.dev(), m.ino()))
    }
    #[cfg(not(unix))]
    {
        std::fs::canonicalize(path).ok().map(FileId::Path)
    }
}

/// Starts remembering the files read, for the rest of the process (a command-line
/// run: one command per process).
pub fn track_inputs() {
    let mut read = READ
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    read.get_or_insert_with(Vec::new);
}

/// Whether the existing file at `path` was read since [`track_inputs`].
pub fn was_read(path: &Path) -> bool {
    let read = READ
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    match (
        read.as_ref(),
        read.is_some().then(|| file_id(path)).flatten(),
    ) {
        (Some(ids), Some(id)) => ids.contains(&id),
        _ => false,
    }
}

/// Remembers `path` as read when tracking.
fn remember(path: &Path) {
    let mut read = READ
        .lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    if let (Some(ids), Some(id)) = (read.as_mut(), file_id(path))
        && !ids.contains(&id)
    {
        ids.push(id);
    }
}

/// The largest input read when `SWARF_MAX_INPUT_MB` is not set, bytes (1 GiB).
pub const DEFAULT_MAX_INPUT_BYTES: u64 = 1 << 30;

/// The largest input file read, bytes: `SWARF_MAX_INPUT_MB` mebibytes when set to a
/// whole number from 1 up, else [`DEFAULT_MAX_INPUT_BYTES`].
pub fn max_input_bytes() -> u64 {
    std::env::var("SWARF_MAX_INPUT_MB")
        .ok()
        .and_then(|v| v.trim().parse::<u64>().ok())
        .filter(|&mb| mb >= 1)
        .map_or(DEFAULT_MAX_INPUT_BYTES, |mb| mb.saturating_mul(1 << 20))
}

/// The bytes of the file at `path`.
///
/// # Errors
/// [`IoError::Io`] when it cannot be opened or read; [`IoError::Format`] when it is not
/// a regular file or is larger than [`max_input_bytes`] (naming the limit and how to
/// raise it).
pub fn read_input(path: &Path) -> Result<Vec<u8>, IoError> {
    let limit = max_input_bytes();
    let file = checked_open(path, limit)?;
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| IoError::io(path, "read", e))?;
    if bytes.len() as u64 > limit {
        return Err(too_large(path, limit));
    }
    Ok(bytes)
}

/// The text of the file at `path`, with bytes that are not UTF-8 replaced.
///
/// # Errors
/// As [`read_input`].
pub fn read_input_text(path: &Path) -> Result<String, IoError> {
    let bytes = read_input(path)?;
    Ok(match String::from_utf8(bytes) {
        Ok(s) => s,
        Err(e) => String::from_utf8_lossy(e.as_bytes()).into_owned(),
    })
}

/// The file at `path`, opened for reading once it is known to be a regular file no
/// larger than `limit` bytes.
///
/// # Errors
/// As [`read_input`].
pub fn checked_open(path: &Path, limit: u64) -> Result<std::fs::File, IoError> {
    let meta = std::fs::metadata(path).map_err(|e| IoError::io(path, "read", e))?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a directory"
        } else {
            "not a regular file (a pipe, a device or a socket)"
        };
        return Err(IoError::format(
            &path.display().to_string(),
            crate::At::File,
            format!("{kind}: expected a regular file"),
        ));
    }
    if meta.len() > limit {
        return Err(too_large(path, limit));
    }
    let file = std::fs::File::open(path).map_err(|e| IoError::io(path, "read", e))?;
    remember(path);
    Ok(file)
}

fn too_large(path: &Path, limit: u64) -> IoError {
    IoError::format(
        &path.display().to_string(),
        crate::At::File,
        format!(
            "larger than {} MiB, the most swarf reads (set SWARF_MAX_INPUT_MB to read more)",
            limit >> 20
        ),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::scratch_dir;

    #[test]
    fn only_regular_files_within_the_limit() {
        let dir = scratch_dir("input");
        let f = dir.join("a.txt");
        std::fs::write(&f, "x\n").unwrap();
        assert_eq!(read_input_text(&f).unwrap(), "x\n");
        let e = read_input(&dir).unwrap_err().to_string();
        assert!(e.contains("a directory: expected a regular file"), "{e}");
        let e = read_input(Path::new("/dev/zero")).unwrap_err().to_string();
        assert!(e.starts_with("/dev/zero: not a regular file"), "{e}");
        let e = read_input(&dir.join("missing")).unwrap_err().to_string();
        assert!(e.contains("missing: cannot read"), "{e}");
        let big = dir.join("big");
        std::fs::write(&big, vec![b'x'; 3 << 20]).unwrap();
        let e = checked_open(&big, 2 << 20).unwrap_err().to_string();
        assert!(
            e.contains("larger than 2 MiB") && e.contains("SWARF_MAX_INPUT_MB"),
            "{e}"
        );
    }
}
