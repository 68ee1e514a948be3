//! The error type of swarf-io: every message names the file, and the line or byte
//! where relevant, and says what was expected.

use std::fmt;
use std::path::Path;
use thiserror::Error;

/// Where in a file an error was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum At {
    /// The file as a whole (or no better place is known).
    File,
    /// A 1-based line number (text formats).
    Line(usize),
    /// A 0-based byte offset (binary formats).
    Byte(u64),
}

impl fmt::Display for At {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            At::File => Ok(()),
            At::Line(n) => write!(f, ": line {n}"),
            At::Byte(b) => write!(f, ": byte {b}"),
        }
    }
}

/// Everything that can go wrong reading or writing swarf's files.
#[derive(Debug, Error)]
pub enum IoError {
    /// The operating system refused (missing file, permissions, disk full...).
    #[error("{file}: cannot {action}: {cause}")]
    Io {
        /// The file, as given.
        file: String,
        /// What was being done (`read`, `write`, `create directory`...).
        action: &'static str,
        /// The operating system's error.
        cause: std::io::Error,
    },
    /// The content does not follow the format.
    #[error("{file}{at}: {message}")]
    Format {
        /// The file, as given.
        file: String,
        /// Where in the file.
        at: At,
        /// What was found and what was expected.
        message: String,
    },
    /// A field of a structured file (part file) has a bad value.
    #[error("{file}{at}: {field}: {message}")]
    Field {
        /// The file, as given.
        file: String,
        /// Where in the file.
        at: At,
        /// The field path, e.g. `patch[0].knots_u[3]`.
        field: String,
        /// What was found and what was expected.
        message: String,
    },
    /// A mesh file whose extension names no supported format.
    #[error("{file}: unsupported mesh file type {found:?}; expected .stl or .obj")]
    UnsupportedFormat {
        /// The file, as given.
        file: String,
        /// The extension found (`.ply`), or `no extension`.
        found: String,
    },
}

impl IoError {
    /// Shorthand for [`IoError::Io`].
    pub fn io(path: &Path, action: &'static str, cause: std::io::Error) -> IoError {
        IoError::Io {
            file: path.display().to_string(),
            action,
            cause,
        }
    }

    /// Shorthand for [`IoError::Format`].
    pub fn format(file: &str, at: At, message: impl Into<String>) -> IoError {
        IoError::Format {
            file: file.to_owned(),
            at,
            message: message.into(),
        }
    }

    /// Shorthand for [`IoError::Field`].
    pub fn field(
        file: &str,
        at: At,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> IoError {
        IoError::Field {
            file: file.to_owned(),
            at,
            field: field.into(),
            message: message.into(),
        }
    }

    /// Where in the file the error is, when known.
    pub fn at(&self) -> At {
        match self {
            IoError::Format { at, .. } | IoError::Field { at, .. } => *at,
            IoError::Io { .. } | IoError::UnsupportedFormat { .. } => At::File,
        }
    }
}

pub use swarf_geom::domain::line_of;

pub(crate) use swarf_geom::domain::excerpt;

/// A TOML parse error of `text` as "line N: message", for readers of TOML files
/// (jobs, machines) that prefix the file name themselves.
pub fn toml_message(text: &str, e: &toml::de::Error) -> String {
    swarf_geom::domain::at_line(text, e.span().map(|s| s.start), e.message())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_file_and_place() {
        let e = IoError::field(
            "wave.toml",
            At::Line(12),
            "patch[0].knots_u",
            "knots must not decrease",
        );
        assert_eq!(
            e.to_string(),
            "wave.toml: line 12: patch[0].knots_u: knots must not decrease"
        );
        let e = IoError::format(
            "part.stl",
            At::Byte(84),
            "file ends inside triangle 3 of 12",
        );
        assert_eq!(
            e.to_string(),
            "part.stl: byte 84: file ends inside triangle 3 of 12"
        );
        assert_eq!(e.at(), At::Byte(84));
        let e = IoError::io(
            Path::new("a/b.obj"),
            "read",
            std::io::ErrorKind::NotFound.into(),
        );
        assert!(e.to_string().starts_with("a/b.obj: cannot read: "), "{e}");
        assert_eq!(
            IoError::format("x", At::File, "empty").to_string(),
            "x: empty"
        );
    }

    #[test]
    fn lines_and_excerpts() {
        assert_eq!(line_of("a\nb\nc", 0), 1);
        assert_eq!(line_of("a\nb\nc", 2), 2);
        assert_eq!(line_of("a\nb\nc", 99), 3);
    }
}
