//! The output set of one command: every file a command writes is staged in one
//! [`swarf_io::OutputSet`] and the set is renamed into place when the command has
//! succeeded ([`Outputs::commit`]); a command that fails leaves the previous set whole.
//!
//! Files are named relative to a current directory ([`Outputs::dir`],
//! [`Outputs::in_dir`] for a section written into a subdirectory). A later step that
//! reads what an earlier one staged (the demo verifies the programs it planned) reads
//! the staged file ([`Outputs::read_program`]).

use crate::error::{AppError, Result};
use std::io::Write;
use std::path::{Path, PathBuf};
use swarf_io::OutputSet;
use swarf_nc::read::Program;

/// Files staged under a directory (module doc).
#[derive(Debug)]
pub struct Outputs {
    dir: PathBuf,
    set: OutputSet,
}

impl Outputs {
    /// An empty set whose relative names are under `dir`, made absolute (against the
    /// working directory) so that a path built from [`Outputs::path`] names the same
    /// file when it is given back.
    pub fn new(dir: &Path) -> Self {
        Outputs {
            dir: std::path::absolute(dir).unwrap_or_else(|_| dir.to_path_buf()),
            set: OutputSet::new(),
        }
    }

    /// The directory relative names are under.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The path of `rel` (relative to [`Outputs::dir`], or absolute).
    pub fn path(&self, rel: impl AsRef<Path>) -> PathBuf {
        self.dir.join(rel)
    }

    /// Stages `bytes` as `rel`.
    ///
    /// # Errors
    /// As [`OutputSet::write`].
    pub fn write(&mut self, rel: impl AsRef<Path>, bytes: &[u8]) -> Result<()> {
        let path = self.path(rel);
        Ok(self.set.write(&path, bytes)?)
    }

    /// Stages `value` as pretty-printed JSON in `rel`, every number checked finite
    /// ([`swarf_io::json`]).
    ///
    /// # Errors
    /// A non-finite number (naming the file and the field); as [`OutputSet::write`].
    pub fn write_json<T: serde::Serialize + ?Sized>(
        &mut self,
        rel: impl AsRef<Path>,
        value: &T,
    ) -> Result<()> {
        let path = self.path(rel);
        let text = swarf_io::json::to_pretty(value)
            .map_err(|e| AppError::Message(format!("{}: {e}", path.display())))?;
        Ok(self.set.write(&path, text.as_bytes())?)
    }

    /// Stages `mesh` as a binary STL in `rel` ([`swarf_io::write_stl`]).
    ///
    /// # Errors
    /// As [`swarf_io::write_stl`].
    pub fn write_stl(
        &mut self,
        rel: impl AsRef<Path>,
        mesh: &swarf_geom::TriMesh,
        name: &str,
    ) -> Result<()> {
        let path = self.path(rel);
        Ok(swarf_io::write_stl(&mut self.set, &path, mesh, name)?)
    }

    /// Stages what `write` writes as `rel`.
    ///
    /// # Errors
    /// As [`OutputSet::write_with`].
    pub fn write_with<F>(&mut self, rel: impl AsRef<Path>, write: F) -> Result<()>
    where
        F: FnOnce(&mut dyn Write) -> std::io::Result<()>,
    {
        let path = self.path(rel);
        Ok(self.set.write_with(&path, write)?)
    }

    /// Runs `f` with relative names under `dir/sub`.
    pub fn in_dir<R>(&mut self, sub: impl AsRef<Path>, f: impl FnOnce(&mut Outputs) -> R) -> R {
        let outer = self.dir.clone();
        self.dir = outer.join(sub);
        let r = f(self);
        self.dir = outer;
        r
    }

    /// Whether `rel` (relative to [`Outputs::dir`], or absolute) is staged in this set.
    pub fn is_staged(&self, rel: impl AsRef<Path>) -> bool {
        self.set.staged(&self.path(rel)).is_some()
    }

    /// The NC program `rel` as staged in this set (or, when it is not, as it is on
    /// disk), named by its final path.
    ///
    /// # Errors
    /// As [`swarf_nc::read::read_program`].
    pub fn read_program(&self, rel: impl AsRef<Path>) -> Result<Program> {
        let path = self.path(rel);
        let file = self.set.staged(&path).unwrap_or(&path);
        let opts = swarf_nc::read::GcodeReadOptions::default();
        Ok(swarf_nc::read::read_program_as(file, &path, &opts)?)
    }

    /// The text of the file at `path` (as given, not relative to [`Outputs::dir`]) as
    /// staged in this set, or, when it is not, as it is on disk.
    ///
    /// # Errors
    /// As [`swarf_io::read_input_text`].
    pub fn read_text(&self, path: &Path) -> Result<String> {
        let absolute = std::path::absolute(path).unwrap_or_else(|_| path.to_path_buf());
        let file = self.set.staged(&absolute).unwrap_or(path);
        Ok(swarf_io::read_input_text(file)?)
    }

    /// Renames every staged file into place.
    ///
    /// # Errors
    /// As [`OutputSet::commit`].
    pub fn commit(self) -> Result<()> {
        Ok(self.set.commit()?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_relative_folder_names_each_staged_file_once() {
        // `swarf demo --out swarf-demo`: the paths the set hands out are read back.
        let rel = PathBuf::from(format!("swarf-outputs-test-{}", std::process::id()));
        let mut out = Outputs::new(&rel);
        let job = out.path("jobs").join("a.toml");
        out.write(&job, b"name = \"a\"").unwrap();
        assert_eq!(out.read_text(&job).unwrap(), "name = \"a\"");
        assert_eq!(
            out.read_text(&rel.join("jobs/a.toml")).unwrap(),
            "name = \"a\""
        );
        drop(out);
        std::fs::remove_dir_all(&rel).ok();
    }
}
