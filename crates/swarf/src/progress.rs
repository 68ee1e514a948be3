//! Progress bars on stderr, hidden when stderr is not a terminal: one over the jobs of
//! a comparison (or the sections of the demo), one per stage of a verification, and
//! one over the passes of a five-axis positioning, drawn together.

use indicatif::{MultiProgress, ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::Mutex;
use swarf_app::Reporter;
use swarf_sim::Progress;

/// The command line's progress bars.
pub struct Bars {
    multi: MultiProgress,
    jobs: Mutex<Option<ProgressBar>>,
    stage: Mutex<Option<ProgressBar>>,
    passes: Mutex<Option<ProgressBar>>,
}

impl Default for Bars {
    /// Bars on stderr, hidden when stderr is not a terminal.
    fn default() -> Self {
        let target = if std::io::stderr().is_terminal() {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        };
        Bars {
            multi: MultiProgress::with_draw_target(target),
            jobs: Mutex::new(None),
            stage: Mutex::new(None),
            passes: Mutex::new(None),
        }
    }
}

impl Bars {
    /// A bar with `template`, drawn with the others.
    fn bar(&self, total: Option<u64>, template: &str, message: String) -> ProgressBar {
        self.multi.add(bar(total, template, message))
    }
}

/// A bar with `template` (drawn by the [`MultiProgress`] it is added to).
fn bar(total: Option<u64>, template: &str, message: String) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(total, ProgressDrawTarget::hidden());
    if let Ok(style) = ProgressStyle::with_template(template) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(message);
    bar
}

impl Progress for Bars {
    fn begin(&self, stage: &str, total: u64) {
        let b = self.bar(
            Some(total),
            "{msg:>16} [{bar:40}] {percent:>3}% {eta}",
            stage.to_string(),
        );
        if let Ok(mut slot) = self.stage.lock() {
            *slot = Some(b);
        }
    }

    fn advance(&self, n: u64) {
        if let Ok(slot) = self.stage.lock()
            && let Some(b) = slot.as_ref()
        {
            b.inc(n);
        }
    }

    fn end(&self) {
        if let Ok(mut slot) = self.stage.lock()
            && let Some(b) = slot.take()
        {
            b.finish_and_clear();
        }
    }
}

impl Reporter for Bars {
    fn passes(&self, done: usize, total: usize) {
        if let Ok(mut slot) = self.passes.lock() {
            let b = slot.get_or_insert_with(|| {
                self.bar(
                    None,
                    "{msg:>16} [{bar:40}] {pos}/{len} passes {eta}",
                    "positioning".to_string(),
                )
            });
            b.set_length(total as u64);
            b.set_position(done as u64);
        }
    }

    fn passes_done(&self) {
        if let Ok(mut slot) = self.passes.lock()
            && let Some(b) = slot.take()
        {
            b.finish_and_clear();
        }
    }

    fn job(&self, done: usize, total: usize, name: &str) {
        if let Ok(mut slot) = self.jobs.lock() {
            let b = slot.get_or_insert_with(|| {
                self.bar(None, "{msg:>24} [{bar:40}] {pos}/{len}", String::new())
            });
            b.set_length(total as u64);
            b.set_position(done as u64);
            b.set_message(name.to_string());
        }
    }

    fn jobs_done(&self) {
        if let Ok(mut slot) = self.jobs.lock()
            && let Some(b) = slot.take()
        {
            b.finish_and_clear();
        }
    }
}
