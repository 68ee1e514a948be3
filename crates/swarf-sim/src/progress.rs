//! Progress reporting for long runs, without tying the library to a terminal.
//!
//! The CLI implements [`Progress`] with progress bars (hidden when stderr is not a
//! terminal); tests and library users pass [`Quiet`]. Calls come from worker threads,
//! hence `Sync`.

/// Receives progress of a long computation.
pub trait Progress: Sync {
    /// A stage begins with `total` units of work.
    fn begin(&self, _stage: &str, _total: u64) {}
    /// `n` more units are done.
    fn advance(&self, _n: u64) {}
    /// The current stage is over.
    fn end(&self) {}
}

/// Reports nothing.
#[derive(Debug, Clone, Copy, Default)]
pub struct Quiet;

impl Progress for Quiet {}
