//! The error type of the geometry kernel.

use thiserror::Error;

/// Everything that can go wrong when building or querying geometry.
///
/// Messages name the offending field and say what was expected, so that a caller
/// that knows the file can prefix it and hand the result to a user unchanged.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum GeomError {
    /// A patch definition is inconsistent (degree, counts, knots, weights, points).
    #[error("{field}: {message}")]
    InvalidPatch {
        /// The part-file field at fault (e.g. `knots_u`, `points[3]`).
        field: String,
        /// What was wrong and what was expected.
        message: String,
    },
    /// A numeric parameter is out of its valid range (tolerance <= 0, NaN, ...).
    #[error("{name} = {}: {expected}", crate::domain::show(*value))]
    InvalidParameter {
        /// Parameter name as the user knows it.
        name: String,
        /// The value given.
        value: f64,
        /// What was expected instead.
        expected: String,
    },
    /// A mesh is unusable (empty, non-finite vertices, index out of range...).
    #[error("mesh: {0}")]
    InvalidMesh(String),
}

impl GeomError {
    /// Shorthand for [`GeomError::InvalidPatch`].
    pub fn patch(field: impl Into<String>, message: impl Into<String>) -> Self {
        GeomError::InvalidPatch {
            field: field.into(),
            message: message.into(),
        }
    }

    /// Checks that `value` is finite and strictly positive.
    ///
    /// # Errors
    /// [`GeomError::InvalidParameter`] naming `name` otherwise.
    pub fn check_positive(name: &str, value: f64) -> Result<f64, GeomError> {
        if value.is_finite() && value > 0.0 {
            Ok(value)
        } else {
            Err(GeomError::InvalidParameter {
                name: name.into(),
                value,
                expected: "a finite number > 0".into(),
            })
        }
    }
}
