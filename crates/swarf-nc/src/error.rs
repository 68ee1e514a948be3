//! The error type of swarf-nc.

use thiserror::Error;

/// What can go wrong when writing or reading an NC program.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum NcError {
    /// A 3-axis post was given a pose whose tool axis is not +Z.
    #[error(
        "move {index}: tool axis ({:.6}, {:.6}, {:.6}) is not +Z; a 3-axis program needs a \
         vertical tool (use a machine file for five-axis output)", axis[0], axis[1], axis[2]
    )]
    NotThreeAxis {
        /// Index of the offending move.
        index: usize,
        /// Its tool axis.
        axis: [f64; 3],
    },
    /// A coordinate or feed is not finite.
    #[error("move {index}: {what} is not a finite number")]
    NonFinite {
        /// Index of the offending move.
        index: usize,
        /// Which value.
        what: &'static str,
    },
    /// A value too large to be a position or rate on any machine (outside
    /// [`swarf_geom::domain::COORDINATE`] or [`swarf_geom::domain::RATE`]).
    #[error("move {index}: {what}: {message}")]
    OutOfDomain {
        /// Index of the offending move.
        index: usize,
        /// Which value.
        what: &'static str,
        /// What was expected and found.
        message: String,
    },
    /// An option is out of range.
    #[error("{field}: {message}")]
    InvalidOption {
        /// The option's name.
        field: &'static str,
        /// What was expected.
        message: String,
    },
    /// A post description that cannot be used: the file, the field (`toml` for
    /// malformed TOML, with the line in the message) and what is wrong.
    #[error("{file}: {field}: {message}")]
    Post {
        /// The post file (or built-in name).
        file: String,
        /// The field.
        field: String,
        /// What is wrong.
        message: String,
    },
    /// A program the post cannot express (inverse-time feed or rotary axes on a
    /// control without them).
    #[error("post {post}: {field}: {message}")]
    Unsupported {
        /// The post's name.
        post: String,
        /// The post field that refuses it.
        field: &'static str,
        /// The operation and what the control lacks.
        message: String,
    },
    /// A program file that cannot be read within bounds (not a regular file, too
    /// large, an I/O error): the message names the file.
    #[error("{0}")]
    Input(String),
    /// A file name whose extension names no program format swarf reads.
    #[error(
        "{path}: unknown program format: expected .ngc, .nc, .tap or .gcode (G-code), \
         .h (Heidenhain conversational), .cl, .apt or .cls (APT CL), or .csv (pose CSV)"
    )]
    UnknownFormat {
        /// The file.
        path: String,
    },
    /// A program that is not text of its format at all (binary data, a pose CSV without
    /// its header). Errors inside a readable program do not come here: they stop the
    /// reading and are reported in `Program::stopped`.
    #[error("{file}:{line}:{column}: {message}")]
    Unreadable {
        /// The file (or the name the text was given).
        file: String,
        /// 1-based line.
        line: usize,
        /// 1-based column, in characters.
        column: usize,
        /// What is wrong.
        message: String,
    },
}
