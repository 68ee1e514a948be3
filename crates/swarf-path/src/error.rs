//! The error type of swarf-path.

use thiserror::Error;

/// What can go wrong when planning a tool path.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum PathError {
    /// A planning parameter is out of range.
    #[error("{field}: {message}")]
    InvalidParameter {
        /// The parameter as the user knows it (e.g. `scallop`).
        field: String,
        /// What was expected.
        message: String,
    },
    /// The strategy cannot produce any pass (e.g. the drive planes miss the part,
    /// or the tool is too large for any valid position).
    #[error("{0}")]
    NoPath(String),
    /// A geometric operation failed.
    #[error(transparent)]
    Geom(#[from] swarf_geom::GeomError),
}
