//! Progress bars on stderr, hidden when stderr is not a terminal: one per stage of a
//! verification, and one over the passes of a five-axis positioning.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::Mutex;
use swarf_app::Reporter;
use swarf_sim::Progress;

/// The command line's progress bars.
#[derive(Default)]
pub struct Bars {
    stage: Mutex<Option<ProgressBar>>,
    passes: Mutex<Option<ProgressBar>>,
}

/// A bar on stderr with `template`, hidden when stderr is not a terminal.
fn bar(total: Option<u64>, template: &str, message: String) -> ProgressBar {
    let target = if std::io::stderr().is_terminal() {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    };
    let bar = ProgressBar::with_draw_target(total, target);
    if let Ok(style) = ProgressStyle::with_template(template) {
        bar.set_style(style.progress_chars("=> "));
    }
    bar.set_message(message);
    bar
}

impl Progress for Bars {
    fn begin(&self, stage: &str, total: u64) {
        let b = bar(
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
                bar(
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
}
