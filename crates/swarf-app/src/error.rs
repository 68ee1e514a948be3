//! The error type of swarf-app: the errors of the crates it calls, and its own
//! messages with the file, flag or field they concern.

use thiserror::Error;

/// What can go wrong in a job, a comparison or a verification.
#[derive(Debug, Error)]
pub enum AppError {
    /// Reading or writing a file.
    #[error(transparent)]
    Io(#[from] swarf_io::IoError),
    /// Geometry.
    #[error(transparent)]
    Geom(#[from] swarf_geom::GeomError),
    /// A tool spec.
    #[error(transparent)]
    Tool(#[from] swarf_tool::ToolError),
    /// Planning.
    #[error(transparent)]
    Path(#[from] swarf_path::PathError),
    /// Five-axis positioning, machines and the five-axis post.
    #[error(transparent)]
    FiveAxis(#[from] swarf_fiveaxis::FiveAxisError),
    /// Writing or reading NC programs.
    #[error(transparent)]
    Nc(#[from] swarf_nc::NcError),
    /// Simulation and verification.
    #[error(transparent)]
    Sim(#[from] swarf_sim::SimError),
    /// Rest detection or cleanup planning failed.
    #[error(transparent)]
    Rest(#[from] swarf_rest::RestError),
    /// Drawing pictures.
    #[error(transparent)]
    Report(#[from] swarf_report::ReportError),
    /// Writing to an output stream.
    #[error(transparent)]
    Output(#[from] std::io::Error),
    /// Writing JSON.
    #[error(transparent)]
    Json(#[from] serde_json::Error),
    /// A job file that is malformed or out of range.
    #[error("{file}: {message}")]
    Job {
        /// The job file.
        file: String,
        /// Line and field, and what was expected.
        message: String,
    },
    /// A message of this crate: the file, flag or field, and what was expected.
    #[error("{0}")]
    Message(String),
    /// An error with what was being done when it happened (shown as `context: error`).
    #[error("{context}")]
    Context {
        /// What was being done.
        context: String,
        /// The error.
        #[source]
        source: Box<dyn std::error::Error + Send + Sync + 'static>,
    },
}

/// The result type of swarf-app.
pub type Result<T, E = AppError> = std::result::Result<T, E>;

/// Adds what was being done to an error.
pub trait Context<T> {
    /// Wraps the error with the context `f()` gives.
    ///
    /// # Errors
    /// The error, wrapped.
    fn with_context<F: FnOnce() -> String>(self, f: F) -> Result<T>;
}

impl<T, E: std::error::Error + Send + Sync + 'static> Context<T> for Result<T, E> {
    fn with_context<F: FnOnce() -> String>(self, f: F) -> Result<T> {
        self.map_err(|e| AppError::Context {
            context: f(),
            source: Box::new(e),
        })
    }
}

impl<T> Context<T> for Option<T> {
    fn with_context<F: FnOnce() -> String>(self, f: F) -> Result<T> {
        self.ok_or_else(|| AppError::Message(f()))
    }
}

/// Returns early with an [`AppError::Message`].
macro_rules! bail {
    ($($arg:tt)*) => {
        return Err($crate::error::AppError::Message(format!($($arg)*)))
    };
}
pub(crate) use bail;
