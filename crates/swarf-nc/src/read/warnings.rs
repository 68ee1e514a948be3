//! Collecting warnings without drowning the user: a program that repeats one
//! harmless unsupported word on every line gets the first few warnings about it and
//! one summary with the count of the rest.

use std::collections::HashMap;
use swarf_toolpath::program::Diagnostic;

/// Warnings with the same message beyond this many are counted, not listed.
pub const MAX_SIMILAR_WARNINGS: usize = 20;

/// Warnings in source order, capped per message.
#[derive(Debug, Default)]
pub struct Warnings {
    list: Vec<Diagnostic>,
    /// Per message: how many were seen, and where the first unlisted one was.
    seen: HashMap<String, (usize, Option<(usize, usize)>)>,
    order: Vec<String>,
}

impl Warnings {
    /// Records `d` (listed unless [`MAX_SIMILAR_WARNINGS`] with its message are).
    pub fn push(&mut self, d: Diagnostic) {
        let entry = self.seen.entry(d.message.clone()).or_insert((0, None));
        entry.0 += 1;
        if entry.0 <= MAX_SIMILAR_WARNINGS {
            self.list.push(d);
        } else if entry.1.is_none() {
            entry.1 = Some((d.line, d.column));
            self.order.push(d.message);
        }
    }

    /// Whether a warning with `message` was recorded.
    pub fn has(&self, message: &str) -> bool {
        self.seen.contains_key(message)
    }

    /// The listed warnings, then one summary per message that had more.
    pub fn finish(mut self) -> Vec<Diagnostic> {
        for message in self.order {
            if let Some(&(count, Some((line, column)))) = self.seen.get(&message) {
                self.list.push(Diagnostic::new(
                    line,
                    column,
                    format!(
                        "{} more warnings like this one, from here on: {message}",
                        count - MAX_SIMILAR_WARNINGS
                    ),
                ));
            }
        }
        self.list
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn repeated_warnings_are_summarised() {
        let mut w = Warnings::default();
        for line in 1..=MAX_SIMILAR_WARNINGS + 5 {
            w.push(Diagnostic::new(line, 3, "D word ignored"));
        }
        w.push(Diagnostic::new(99, 1, "other"));
        let list = w.finish();
        assert_eq!(list.len(), MAX_SIMILAR_WARNINGS + 2);
        let last = &list[list.len() - 1];
        assert_eq!((last.line, last.column), (MAX_SIMILAR_WARNINGS + 1, 3));
        assert!(last.message.starts_with("5 more warnings"));
    }
}
