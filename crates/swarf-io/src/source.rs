//! Where a named input comes from: built into the binary, or a file.
//!
//! Parts, machines and posts are named the same way in jobs and on the command
//! line: `builtin:NAME` for one built into the binary, otherwise a path, relative to
//! the job's directory unless absolute. [`Source::parse`] makes that choice in one
//! place; each loader matches on the result (posts and parts also take a bare
//! built-in name, as their loaders document).

use std::path::{Path, PathBuf};

/// The prefix that names a built-in part, machine or post.
pub const BUILTIN_PREFIX: &str = "builtin:";

/// A built-in name or a file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Source<'a> {
    /// `builtin:NAME`: the name, without the prefix.
    Builtin(&'a str),
    /// A file: the path joined to the directory it is relative to (an absolute path
    /// stays as given).
    File(PathBuf),
}

impl<'a> Source<'a> {
    /// `spec` as a source, a file relative to `dir`.
    pub fn parse(spec: &'a str, dir: &Path) -> Source<'a> {
        match spec.strip_prefix(BUILTIN_PREFIX) {
            Some(name) => Source::Builtin(name),
            None => Source::File(dir.join(spec)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_prefix_or_a_path_relative_to_the_directory() {
        let dir = Path::new("/jobs");
        assert_eq!(Source::parse("builtin:die", dir), Source::Builtin("die"));
        assert_eq!(
            Source::parse("m/xyzac.toml", dir),
            Source::File(PathBuf::from("/jobs/m/xyzac.toml"))
        );
        assert_eq!(
            Source::parse("/abs/part.step", dir),
            Source::File(PathBuf::from("/abs/part.step"))
        );
        assert_eq!(
            Source::parse("builtin", dir),
            Source::File(PathBuf::from("/jobs/builtin"))
        );
    }
}
