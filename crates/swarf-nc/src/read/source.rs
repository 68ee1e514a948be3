//! Program texts the runner reads: the program and the subroutine files it calls,
//! as lines, with an index of their O-word statements (built once per file, so that a
//! jump or a call finds its target without reading every line again), their `N`
//! numbers and their program numbers (`O1234`, the Fanuc dialect's subprograms).

use crate::read::lexer::{Statement, Syntax, lex_line};
use crate::read::statement::{Keyword, Label};
use std::collections::HashMap;

/// A program text and its index.
#[derive(Debug, Clone)]
pub struct Source {
    /// The file name, for messages.
    pub name: String,
    text: String,
    starts: Vec<usize>,
    /// O-word statements by label: (line index, keyword), in file order.
    owords: HashMap<Label, Vec<(usize, Keyword)>>,
    /// Line indices by `N` number (Fanuc GOTO).
    numbers: HashMap<u64, usize>,
    /// Line indices of `O1234` program numbers.
    programs: HashMap<u32, usize>,
}

impl Source {
    /// Indexes `text` (a leading byte order mark is dropped) read in `syntax`.
    pub fn new(name: impl Into<String>, text: &str, syntax: Syntax) -> Self {
        let text = text.strip_prefix('\u{feff}').unwrap_or(text).to_string();
        let mut starts = vec![0];
        starts.extend(
            text.bytes()
                .enumerate()
                .filter(|&(_, b)| b == b'\n')
                .map(|(i, _)| i + 1),
        );
        if starts.last() == Some(&text.len()) && !text.is_empty() {
            starts.pop();
        }
        let mut source = Source {
            name: name.into(),
            text,
            starts,
            owords: HashMap::new(),
            numbers: HashMap::new(),
            programs: HashMap::new(),
        };
        source.index(syntax);
        source
    }

    /// Line `index` (0-based) without its line end; `None` past the end.
    pub fn line(&self, index: usize) -> Option<&str> {
        let start = *self.starts.get(index)?;
        let end = self
            .starts
            .get(index + 1)
            .map_or(self.text.len(), |&e| e.saturating_sub(1));
        let line = &self.text[start..end.max(start)];
        let line = line.strip_suffix('\n').unwrap_or(line);
        Some(line.strip_suffix('\r').unwrap_or(line))
    }

    /// The number of lines.
    pub fn line_count(&self) -> usize {
        if self.text.is_empty() {
            0
        } else {
            self.starts.len()
        }
    }

    fn index(&mut self, syntax: Syntax) {
        for i in 0..self.starts.len() {
            let Some(text) = self.line(i) else {
                continue;
            };
            let head = head_char(text);
            let wanted = match head {
                Some('o' | 'O') => true,
                Some('n' | 'N') => syntax.fanuc || text.contains(['o', 'O']),
                _ => false,
            };
            if !wanted {
                continue;
            }
            let Ok(lexed) = lex_line(text, i + 1, syntax) else {
                continue;
            };
            if let Some(n) = lexed.number {
                self.numbers.entry(n as u64).or_insert(i);
            }
            match lexed.statement {
                Statement::Control(c) => {
                    self.owords.entry(c.label).or_default().push((i, c.keyword))
                }
                Statement::ProgramNumber(n, _) => {
                    self.programs.entry(n).or_insert(i);
                }
                _ => {}
            }
        }
    }

    /// The O-word statements with `label`.
    pub fn owords(&self, label: &Label) -> &[(usize, Keyword)] {
        self.owords.get(label).map_or(&[], Vec::as_slice)
    }

    /// The first statement with `label` after line index `after` whose keyword is one
    /// of `keywords`.
    pub fn next(
        &self,
        label: &Label,
        after: usize,
        keywords: &[Keyword],
    ) -> Option<(usize, Keyword)> {
        self.owords(label)
            .iter()
            .find(|(i, k)| *i > after && keywords.contains(k))
            .copied()
    }

    /// The line index of the block numbered `n`.
    pub fn numbered(&self, n: u64) -> Option<usize> {
        self.numbers.get(&n).copied()
    }

    /// The line index of program number `O n`.
    pub fn program(&self, n: u32) -> Option<usize> {
        self.programs.get(&n).copied()
    }
}

/// The first character of a line after spaces, `/` and nothing else.
fn head_char(text: &str) -> Option<char> {
    text.chars().find(|c| !matches!(c, ' ' | '\t' | '/'))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_and_index() {
        let s = Source::new(
            "a.ngc",
            "G0 X1\r\no100 sub\nG1 X2\no100 endsub\nN20 O2000\n",
            Syntax::default(),
        );
        assert_eq!(s.line_count(), 5);
        assert_eq!(s.line(0), Some("G0 X1"));
        assert_eq!(s.line(5), None);
        let label = Label::Number(100);
        assert_eq!(s.owords(&label).len(), 2);
        assert_eq!(
            s.next(&label, 1, &[Keyword::EndSub]),
            Some((3, Keyword::EndSub))
        );
        let s = Source::new("b.nc", "N10 G0 X1\nN20 G1 X2\n", Syntax { fanuc: true });
        assert_eq!(s.numbered(20), Some(1));
        assert_eq!(Source::new("c", "", Syntax::default()).line_count(), 0);
    }
}
