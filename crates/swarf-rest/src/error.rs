//! The error type of swarf-rest.

use swarf_path::PathError;
use thiserror::Error;

/// What can go wrong when detecting rest material or planning its cleanup.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum RestError {
    /// A parameter is out of its domain.
    #[error("{field} = {value}: expected {expected}")]
    InvalidParameter {
        /// The parameter as a job names it (`merge`, ...).
        field: String,
        /// The value given, as written.
        value: String,
        /// What was expected instead.
        expected: String,
    },
    /// A parameter is missing, or does not fit the others.
    #[error("{field}: {message}")]
    Parameter {
        /// The parameter as a job names it (`scallop`, `restmaterial`, ...).
        field: String,
        /// What is wrong.
        message: String,
    },
    /// The cleanup tool cannot do what the reference tool could not.
    #[error("the cleanup tool {cleanup} is not smaller than the reference tool {reference}")]
    ToolNotSmaller {
        /// The cleanup tool.
        cleanup: String,
        /// The reference (parent) tool.
        reference: String,
    },
    /// Planning on the part failed (an empty mesh, ...).
    #[error(transparent)]
    Path(#[from] PathError),
}

impl RestError {
    /// The parameter the error is about and what is wrong with it, for a caller
    /// that places it (`None` for errors about no one parameter).
    pub fn field(&self) -> Option<(&str, String)> {
        match self {
            RestError::InvalidParameter {
                field,
                value,
                expected,
            } => Some((field, format!("{value}: expected {expected}"))),
            RestError::Parameter { field, message }
            | RestError::Path(PathError::InvalidParameter { field, message }) => {
                Some((field, message.clone()))
            }
            _ => None,
        }
    }

    /// Checks that `value` is finite and `> 0` (`allow_zero`: `>= 0`).
    ///
    /// # Errors
    /// [`RestError::InvalidParameter`] naming `field`.
    pub fn check(field: &str, value: f64, allow_zero: bool) -> Result<f64, RestError> {
        let ok = value.is_finite() && (value > 0.0 || (allow_zero && value == 0.0));
        if ok {
            Ok(value)
        } else {
            Err(RestError::InvalidParameter {
                field: field.into(),
                value: value.to_string(),
                expected: if allow_zero {
                    "a finite length >= 0 mm".into()
                } else {
                    "a finite length > 0 mm".into()
                },
            })
        }
    }
}
