//! Errors of the report crate.

/// What can go wrong while making a report.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// Encoding or writing an output failed.
    #[error("{path}: {message}")]
    Write {
        /// What was being written (`<png>` for an in-memory picture).
        path: String,
        /// The encoder's message.
        message: String,
    },
}
