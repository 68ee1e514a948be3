//! APT CL records: physical lines joined into records, split into a name and fields
//! that remember their line and column.
//!
//! A record is `NAME` or `NAME/field,field,...`. `$$` starts a comment that runs to the
//! end of the line; a line that ends in a single `$` continues on the next line.
//! Names are case-insensitive (kept upper-case); numbers are decimal with an optional
//! exponent (`1.0E+01`), and must be finite.

use swarf_toolpath::program::Diagnostic;

/// One field of a record.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// The text, trimmed.
    pub text: String,
    /// 1-based line of its first character.
    pub line: usize,
    /// 1-based column of its first character.
    pub column: usize,
}

impl Field {
    /// The field as a finite number.
    ///
    /// # Errors
    /// A diagnostic at the field when it is not one.
    pub fn number(&self) -> Result<f64, Diagnostic> {
        let value: f64 = self
            .text
            .parse()
            .map_err(|_| self.error(format!("expected a number, found '{}'", self.text)))?;
        if value.is_finite() {
            Ok(value)
        } else {
            Err(self.error(format!("expected a finite number, found '{}'", self.text)))
        }
    }

    /// The field upper-cased, for keywords.
    pub fn word(&self) -> String {
        self.text.to_ascii_uppercase()
    }

    /// A diagnostic at this field.
    pub fn error(&self, message: impl Into<String>) -> Diagnostic {
        Diagnostic::new(self.line, self.column, message)
    }

    /// Decimal places written after the point (0 when none), to judge printed precision.
    pub fn decimals(&self) -> usize {
        let mantissa = self.text.split(['e', 'E']).next().unwrap_or("");
        mantissa.split_once('.').map_or(0, |(_, frac)| frac.len())
    }
}

/// A record: its name, where the name starts, and its fields.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// Upper-case name (`GOTO`, `FEDRAT`, ...; for `PPRINT text` the first word).
    pub name: String,
    /// 1-based line where the record starts.
    pub line: usize,
    /// 1-based column of the name.
    pub column: usize,
    /// Fields after the `/`, split at commas.
    pub fields: Vec<Field>,
}

/// The records of `text`, in order, with comments and continuations resolved.
pub fn records(text: &str) -> Vec<Record> {
    let mut out = Vec::new();
    let mut pending: Vec<(char, usize, usize)> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let code = raw.find("$$").map_or(raw, |at| &raw[..at]);
        let trimmed = code.trim_end();
        let (body, continues) = match trimmed.strip_suffix('$') {
            Some(body) => (body, true),
            None => (trimmed, false),
        };
        pending.extend(body.chars().enumerate().map(|(k, c)| (c, line, k + 1)));
        if continues {
            pending.push((' ', line, body.chars().count() + 1));
            continue;
        }
        if let Some(record) = split(&pending) {
            out.push(record);
        }
        pending.clear();
    }
    if let Some(record) = split(&pending) {
        out.push(record);
    }
    out
}

/// Splits positioned characters into name and fields; `None` for a blank record.
fn split(chars: &[(char, usize, usize)]) -> Option<Record> {
    let start = chars.iter().position(|c| !c.0.is_whitespace())?;
    let chars = &chars[start..];
    let (line, column) = (chars[0].1, chars[0].2);
    let slash = chars.iter().position(|c| c.0 == '/');
    let name_end = slash.unwrap_or_else(|| {
        chars
            .iter()
            .position(|c| c.0.is_whitespace())
            .unwrap_or(chars.len())
    });
    let name: String = chars[..name_end].iter().map(|c| c.0).collect();
    let mut fields = Vec::new();
    if let Some(slash) = slash {
        for piece in chars[slash + 1..].split(|c| c.0 == ',') {
            let first = piece.iter().position(|c| !c.0.is_whitespace());
            let (fl, fc) = match first {
                Some(k) => (piece[k].1, piece[k].2),
                None => piece.first().map_or((line, column), |c| (c.1, c.2)),
            };
            let text: String = piece.iter().map(|c| c.0).collect();
            fields.push(Field {
                text: text.trim().to_string(),
                line: fl,
                column: fc,
            });
        }
    }
    Some(Record {
        name: name.trim().to_ascii_uppercase(),
        line,
        column,
        fields,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn records_with_comments_and_continuations() {
        let text =
            "PARTNO/WAVE $$ the part\n  goto / 1.5, -2 ,$\n   3.0E+00\n$$ only a comment\nRAPID\n";
        let r = records(text);
        assert_eq!(r.len(), 3);
        assert_eq!(r[0].name, "PARTNO");
        assert_eq!(r[1].name, "GOTO");
        assert_eq!((r[1].line, r[1].column), (2, 3));
        let f: Vec<_> = r[1]
            .fields
            .iter()
            .map(|f| (f.text.as_str(), f.line, f.column))
            .collect();
        assert_eq!(f, vec![("1.5", 2, 10), ("-2", 2, 15), ("3.0E+00", 3, 4)]);
        assert_eq!(r[1].fields[2].number(), Ok(3.0));
        assert_eq!(r[1].fields[0].decimals(), 1);
        assert_eq!(r[2].name, "RAPID");
        assert!(r[2].fields.is_empty());
    }

    #[test]
    fn bad_numbers_point_at_the_field() {
        let r = records("GOTO/1,abc,inf");
        assert_eq!(r[0].fields[1].number().unwrap_err().column, 8);
        assert!(r[0].fields[2].number().is_err());
    }
}
