//! Output sets: every file one command writes is staged first, as a complete
//! temporary file beside its target, and the set is renamed into place together when
//! the command has succeeded ([`OutputSet::commit`]). A command that fails before the
//! commit (an error, a panic, a full disk) removes its temporary files and leaves the
//! previous set whole: never a new G-code beside an old CL, nor a new report beside
//! old pictures.
//!
//! `rename` within one directory replaces a file atomically on POSIX and Windows, so
//! each file is the old one or the complete new one; the set's renames run back to
//! back after every file is on disk, so only a crash inside that last step (a few
//! renames) can mix sets. Temporary files are named `.NAME.PID.N.tmp`; a run that was
//! killed leaves them behind, and the next write into the same directory removes those
//! of processes that no longer run.
//!
//! An output that is one of the command's inputs is refused (see
//! [`crate::input::track_inputs`]): `swarf drop --points p.csv -o p.csv` would
//! otherwise replace its own input.

use crate::error::IoError;
use std::ffi::{OsStr, OsString};
use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Buffer of the streaming writer, bytes.
const BUFFER: usize = 1 << 16;

/// Files staged for one command, renamed into place by [`OutputSet::commit`] and
/// removed when the set is dropped uncommitted.
#[derive(Debug, Default)]
pub struct OutputSet {
    staged: Vec<Staged>,
}

/// One staged file.
#[derive(Debug)]
struct Staged {
    target: PathBuf,
    temp: TempFile,
}

impl OutputSet {
    /// An empty set.
    pub fn new() -> Self {
        OutputSet::default()
    }

    /// Stages `bytes` as the new content of `path` (parent directories are created).
    ///
    /// # Errors
    /// As [`OutputSet::write_with`].
    pub fn write(&mut self, path: &Path, bytes: &[u8]) -> Result<(), IoError> {
        self.write_with(path, |w| w.write_all(bytes))
    }

    /// Stages the new content of `path`: `write` gets a buffered writer on a temporary
    /// file beside `path`, which is flushed to disk when `write` returns `Ok`. Staging a
    /// path twice keeps the later content.
    ///
    /// # Errors
    /// [`IoError::Io`] naming `path` when it names no file, is one of the command's
    /// inputs, or a directory or the temporary file cannot be created or written; an
    /// error returned by `write` is reported the same way (return
    /// `io::Error::other(..)` to fail with a message of your own).
    pub fn write_with<F>(&mut self, path: &Path, write: F) -> Result<(), IoError>
    where
        F: FnOnce(&mut dyn Write) -> io::Result<()>,
    {
        let Some(name) = path.file_name() else {
            let e = io::Error::new(io::ErrorKind::InvalidInput, "the path names no file");
            return Err(IoError::io(path, "write", e));
        };
        if crate::input::was_read(path) {
            let e = io::Error::new(
                io::ErrorKind::InvalidInput,
                "it is an input of this command; choose another output",
            );
            return Err(IoError::io(path, "replace", e));
        }
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d,
            _ => Path::new("."),
        };
        fs::create_dir_all(dir).map_err(|e| IoError::io(dir, "create directory", e))?;
        clean_stale(dir, name);
        let (file, temp) = create_temp(dir, name)
            .map_err(|e| IoError::io(path, "create a temporary file for", e))?;
        let mut writer = BufWriter::with_capacity(BUFFER, file);
        write(&mut writer).map_err(|e| IoError::io(path, "write", e))?;
        let file = writer
            .into_inner()
            .map_err(|e| IoError::io(path, "write", e.into_error()))?;
        file.sync_all()
            .map_err(|e| IoError::io(path, "flush to disk", e))?;
        self.staged.retain(|s| s.target != path);
        self.staged.push(Staged {
            target: path.to_path_buf(),
            temp,
        });
        Ok(())
    }

    /// The temporary file staged for `path`, if any (for a later step of the same
    /// command that reads what an earlier one wrote).
    pub fn staged(&self, path: &Path) -> Option<&Path> {
        self.staged
            .iter()
            .find(|s| s.target == path)
            .map(|s| s.temp.0.as_path())
    }

    /// Number of staged files.
    pub fn len(&self) -> usize {
        self.staged.len()
    }

    /// Whether nothing is staged.
    pub fn is_empty(&self) -> bool {
        self.staged.is_empty()
    }

    /// Renames every staged file over its target (which takes the target's
    /// permissions when it exists) and syncs the directories.
    ///
    /// # Errors
    /// [`IoError::Io`] naming a target that is a directory (before anything is
    /// replaced), or the first file that cannot be replaced; the files staged after
    /// it are removed and their targets keep their previous content.
    pub fn commit(self) -> Result<(), IoError> {
        // What makes a rename fail for sure is checked before the first one.
        if let Some(s) = self.staged.iter().find(|s| s.target.is_dir()) {
            let e = io::Error::new(io::ErrorKind::IsADirectory, "it is a directory");
            return Err(IoError::io(&s.target, "replace", e));
        }
        let mut dirs: Vec<PathBuf> = Vec::new();
        for s in self.staged {
            if let Ok(meta) = fs::metadata(&s.target) {
                fs::set_permissions(&s.temp.0, meta.permissions())
                    .map_err(|e| IoError::io(&s.target, "set permissions of", e))?;
            }
            fs::rename(&s.temp.0, &s.target).map_err(|e| IoError::io(&s.target, "replace", e))?;
            s.temp.disarm();
            let dir = s.target.parent().unwrap_or(Path::new(".")).to_path_buf();
            if !dirs.contains(&dir) {
                dirs.push(dir);
            }
        }
        for dir in dirs {
            if let Ok(d) = File::open(if dir.as_os_str().is_empty() {
                Path::new(".")
            } else {
                &dir
            }) {
                let _ = d.sync_all();
            }
        }
        Ok(())
    }
}

/// Removes the temporary file when dropped, unless disarmed after the rename.
#[derive(Debug)]
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
fn create_temp(dir: &Path, name: &OsStr) -> io::Result<(File, TempFile)> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    loop {
        let n = COUNTER.fetch_add(1, Ordering::Relaxed);
        let temp = dir.join(temp_name(name, std::process::id(), n));
        match File::options().write(true).create_new(true).open(&temp) {
            Ok(f) => return Ok((f, TempFile(temp))),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
}

/// `.NAME.PID.N.tmp`.
fn temp_name(name: &OsStr, pid: u32, n: u64) -> OsString {
    let mut t = OsString::from(".");
    t.push(name);
    t.push(format!(".{pid}.{n}.tmp"));
    t
}

/// Removes the temporary files of `name` in `dir` left by processes that no longer
/// run (best effort: errors are ignored).
fn clean_stale(dir: &Path, name: &OsStr) {
    let Some(name) = name.to_str() else { return };
    let prefix = format!(".{name}.");
    let Ok(entries) = fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let file = entry.file_name();
        let Some(rest) = file
            .to_str()
            .and_then(|f| f.strip_prefix(&prefix))
            .and_then(|r| r.strip_suffix(".tmp"))
        else {
            continue;
        };
        let mut parts = rest.split('.');
        let (Some(pid), Some(n), None) = (parts.next(), parts.next(), parts.next()) else {
            continue;
        };
        if let (Ok(pid), Ok(_)) = (pid.parse::<u32>(), n.parse::<u64>())
            && pid != std::process::id()
            && !process_runs(pid, &entry.path())
        {
            let _ = fs::remove_file(entry.path());
        }
    }
}

/// Whether process `pid` still runs (on Linux, from `/proc`; elsewhere a temporary
/// file younger than a day counts as its writer's).
fn process_runs(pid: u32, temp: &Path) -> bool {
    if cfg!(target_os = "linux") {
        Path::new("/proc").join(pid.to_string()).exists()
    } else {
        fs::metadata(temp)
            .and_then(|m| m.modified())
            .ok()
            .and_then(|t| t.elapsed().ok())
            .is_none_or(|age| age.as_secs() < 86_400)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::{entries, scratch_dir};

    #[test]
    fn a_set_replaces_all_its_files_or_none() {
        let dir = scratch_dir("set");
        let (a, b) = (dir.join("a.ngc"), dir.join("sub/b.cl"));
        let mut set = OutputSet::new();
        set.write(&a, b"old a").unwrap();
        set.write(&b, b"old b").unwrap();
        assert!(!a.exists(), "nothing is in place before the commit");
        set.commit().unwrap();
        let mut set = OutputSet::new();
        set.write(&a, b"new a").unwrap();
        let e = set
            .write_with(&b, |w| {
                w.write_all(b"half")?;
                Err(io::Error::other("the planner failed"))
            })
            .unwrap_err();
        assert!(e.to_string().ends_with("cannot write: the planner failed"));
        drop(set);
        assert_eq!(fs::read(&a).unwrap(), b"old a");
        assert_eq!(fs::read(&b).unwrap(), b"old b");
        assert_eq!(entries(&dir), vec!["a.ngc", "sub"]);
        assert_eq!(entries(&dir.join("sub")), vec!["b.cl"]);
        let mut set = OutputSet::new();
        set.write(&a, b"new a").unwrap();
        set.write(&dir.join("sub"), b"over a directory").unwrap();
        let e = set.commit().unwrap_err().to_string();
        assert!(e.ends_with("sub: cannot replace: it is a directory"), "{e}");
        assert_eq!(fs::read(&a).unwrap(), b"old a");
        let mut set = OutputSet::new();
        set.write(&a, b"first").unwrap();
        set.write(&a, b"second").unwrap();
        assert_eq!(set.len(), 1);
        set.commit().unwrap();
        assert_eq!(fs::read(&a).unwrap(), b"second");
        assert_eq!(entries(&dir), vec!["a.ngc", "sub"]);
    }

    #[test]
    fn stale_temporaries_of_dead_processes_are_removed() {
        let dir = scratch_dir("stale");
        let name = OsStr::new("report.json");
        // PID 4194304 is above Linux's largest PID, so no process has it; our own
        // PID's temporaries are never touched.
        let dead = dir.join(temp_name(name, 4_194_304, 7));
        let ours = dir.join(temp_name(name, std::process::id(), 999_999));
        let other = dir.join(temp_name(OsStr::new("flagged.csv"), 4_194_304, 1));
        for f in [&dead, &ours, &other] {
            fs::write(f, b"x").unwrap();
        }
        let mut set = OutputSet::new();
        set.write(&dir.join("report.json"), b"{}").unwrap();
        set.commit().unwrap();
        assert_eq!(!dead.exists(), cfg!(target_os = "linux"));
        assert!(ours.exists() && other.exists());
    }
}
