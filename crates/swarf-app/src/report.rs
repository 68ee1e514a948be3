//! How long work shows its progress: the caller (the command line, a script) decides
//! how; the pipeline only says how far it is.

use swarf_sim::{Progress, Quiet};

/// Progress of the pipeline: the stages of a verification ([`Progress`]) and the
/// passes of a five-axis positioning.
pub trait Reporter: Progress {
    /// Positioning has finished `done` of `total` passes.
    fn passes(&self, _done: usize, _total: usize) {}
    /// Positioning has ended (also when it failed).
    fn passes_done(&self) {}
    /// Job `done + 1` of `total` (of a comparison, or a section of the demo) begins:
    /// `name`.
    fn job(&self, _done: usize, _total: usize, _name: &str) {}
    /// The jobs are over.
    fn jobs_done(&self) {}
}

impl Reporter for Quiet {}
