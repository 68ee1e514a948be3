//! Messages from comments: `(MSG, ...)` as written, `(DEBUG, ...)` and
//! `(PRINT, ...)` with their parameters replaced by values, as LinuxCNC writes them.

use super::Runner;
use super::scope::Scope;
use crate::read::expr::ParamSource;
use crate::read::lexer::Line;

impl Runner<'_> {
    /// `(MSG, ...)`, `(DEBUG, ...)` and `(PRINT, ...)` comments become messages.
    pub(super) fn comments(&mut self, lexed: &Line, line: usize) {
        for c in &lexed.comments {
            let lower = c.trim_start().to_ascii_lowercase();
            let Some((kind, rest)) = lower.split_once(',') else {
                continue;
            };
            let body = &c.trim_start()[kind.len() + 1..];
            let text = match kind.trim() {
                "msg" => body.to_string(),
                "debug" | "print" => self.expand(body),
                _ => continue,
            };
            let _ = rest;
            let d = self.error(line, 1, text);
            self.messages.push(d);
        }
    }

    /// `#n` and `#<name>` in a comment replaced by their values, as LinuxCNC's
    /// `convert_param_comment` writes them: six decimals, or as set by a preceding
    /// `%d` (none), `%f` (four) or `%.Nf` (N); `######` for an unknown parameter.
    fn expand(&self, body: &str) -> String {
        let scope = Scope { runner: self };
        let chars: Vec<char> = body.chars().collect();
        let mut out = String::new();
        let mut decimals = 6;
        let mut i = 0;
        while i < chars.len() {
            let c = chars[i];
            i += 1;
            match c {
                '%' => match (chars.get(i), chars.get(i + 1), chars.get(i + 2)) {
                    (Some('d'), _, _) => (decimals, i) = (0, i + 1),
                    (Some('f'), _, _) => (decimals, i) = (4, i + 1),
                    (Some('.'), Some(d), Some('f')) if d.is_ascii_digit() => {
                        (decimals, i) = (d.to_digit(10).unwrap_or(6) as usize, i + 3);
                    }
                    _ => out.push('%'),
                },
                '#' => {
                    let value = if chars.get(i) == Some(&'<') {
                        let close = chars[i..].iter().position(|&c| c == '>');
                        let name: String = chars[i + 1..i + close.unwrap_or(1)]
                            .iter()
                            .filter(|c| !c.is_whitespace())
                            .map(|c| c.to_ascii_lowercase())
                            .collect();
                        i += close.map_or(chars.len(), |k| k + 1);
                        scope.named(&name).ok()
                    } else {
                        let digits: String = chars[i..]
                            .iter()
                            .take_while(|c| c.is_ascii_digit())
                            .collect();
                        if digits.is_empty() {
                            out.push('#');
                            continue;
                        }
                        i += digits.len();
                        digits
                            .parse::<i64>()
                            .ok()
                            .and_then(|n| scope.numbered(n).ok())
                    };
                    match value {
                        Some(v) => {
                            let v = if v.abs() < crate::read::expr::TOLERANCE_EQUAL {
                                0.0
                            } else {
                                v
                            };
                            out.push_str(&format!("{v:.decimals$}"));
                        }
                        None => out.push_str("######"),
                    }
                }
                c => out.push(c),
            }
        }
        out
    }
}

/// A line holding only the comments of another (for [`Runner::comments`]).
pub(super) fn lexed_comments(comments: Vec<String>) -> Line {
    Line {
        comments,
        ..Line::default()
    }
}
