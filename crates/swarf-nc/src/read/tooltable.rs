//! LinuxCNC tool tables (`tool.tbl`): one tool a line,
//! `T<number> P<pocket> [X Y Z A B C U V W <offset>] [D<diameter>] [I J <angles>]
//! [Q<orientation>] [;comment]`, letters in either case, values in the machine's
//! units ([`crate::read::GcodeReadOptions::machine_inch`]). The G-code reader takes
//! cutter compensation radii (`G41 D`), tool length offsets (`G43 H`) and the loaded
//! tool's offset from it.

use crate::error::NcError;

/// One tool of a table.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Tool {
    /// The tool number (T).
    pub number: u32,
    /// Offsets X Y Z A B C, machine units (lengths) and degrees.
    pub offset: [f64; 6],
    /// Diameter (D), machine units; 0 when not given.
    pub diameter: f64,
    /// Lathe orientation (Q); 0 for a mill tool.
    pub orientation: i32,
}

/// A tool table.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct ToolTable {
    /// Tools in file order.
    pub tools: Vec<Tool>,
}

impl ToolTable {
    /// The tool with `number`, if the table has one.
    pub fn get(&self, number: u32) -> Option<&Tool> {
        self.tools.iter().find(|t| t.number == number)
    }

    /// Adds `tool`, or replaces the tool with its number.
    pub fn set(&mut self, tool: Tool) {
        match self.tools.iter_mut().find(|t| t.number == tool.number) {
            Some(t) => *t = tool,
            None => self.tools.push(tool),
        }
    }

    /// Reads a table from `text`; `source` names the file in errors.
    ///
    /// # Errors
    /// [`NcError::Unreadable`] at the line and column of a malformed entry: a word
    /// without a number, an unknown letter, a tool without T, a tool listed twice, a
    /// value that is not finite.
    pub fn parse(text: &str, source: &str) -> Result<ToolTable, NcError> {
        let mut tools: Vec<Tool> = Vec::new();
        for (i, raw) in text.lines().enumerate() {
            let line = i + 1;
            let content = raw.split(';').next().unwrap_or("");
            if content.trim().is_empty() {
                continue;
            }
            let err = |column: usize, message: String| NcError::Unreadable {
                file: source.to_string(),
                line,
                column,
                message,
            };
            let mut tool = Tool::default();
            let mut number = None;
            for (column, word) in words(content) {
                let mut chars = word.chars();
                let letter = chars.next().unwrap_or(' ').to_ascii_uppercase();
                let number_text = chars.as_str();
                let value: f64 = number_text.parse().map_err(|_| {
                    err(
                        column,
                        format!("{letter} word: expected a number, found '{number_text}'"),
                    )
                })?;
                if !value.is_finite() {
                    return Err(err(
                        column,
                        format!("{letter} word: the value is not finite"),
                    ));
                }
                match letter {
                    'T' if value >= 0.0 && value.fract() == 0.0 && value <= f64::from(u32::MAX) => {
                        number = Some(value as u32);
                    }
                    'T' => return Err(err(column, "T: expected a whole tool number >= 0".into())),
                    'P' | 'I' | 'J' => {}
                    'D' => tool.diameter = value,
                    'Q' => tool.orientation = value as i32,
                    'X' | 'Y' | 'Z' | 'A' | 'B' | 'C' => {
                        let k = "XYZABC".find(letter).unwrap_or(0);
                        tool.offset[k] = value;
                    }
                    'U' | 'V' | 'W' => {}
                    other => {
                        return Err(err(
                            column,
                            format!(
                                "unknown tool table word {other}: expected T P X Y Z A B C U V W D I J Q"
                            ),
                        ));
                    }
                }
            }
            let Some(n) = number else {
                return Err(err(1, "tool entry without a T number".into()));
            };
            if tools.iter().any(|t| t.number == n) {
                return Err(err(1, format!("tool T{n} is listed twice")));
            }
            tool.number = n;
            tools.push(tool);
        }
        Ok(ToolTable { tools })
    }
}

/// The whitespace-separated words of a line with their 1-based columns.
fn words(content: &str) -> impl Iterator<Item = (usize, &str)> {
    let mut out = Vec::new();
    let mut start = None;
    for (i, c) in content.char_indices() {
        match (c.is_whitespace(), start) {
            (true, Some(s)) => {
                out.push((s, &content[s..i]));
                start = None;
            }
            (false, None) => start = Some(i),
            _ => {}
        }
    }
    if let Some(s) = start {
        out.push((s, &content[s..]));
    }
    out.into_iter()
        .map(move |(s, w)| (content[..s].chars().count() + 1, w))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_linuxcnc_tables() {
        let t = ToolTable::parse(
            "T1 P1 D6.35 Z25.4 ;quarter inch\n\nt2 p2 z-1 d0.125 q0\n",
            "tool.tbl",
        )
        .unwrap();
        assert_eq!(t.tools.len(), 2);
        assert_eq!(t.get(1).unwrap().diameter, 6.35);
        assert_eq!(t.get(1).unwrap().offset[2], 25.4);
        assert_eq!(t.get(2).unwrap().offset[2], -1.0);
        assert!(t.get(3).is_none());
    }

    #[test]
    fn errors_name_the_place() {
        let e = ToolTable::parse("T1 P1\nT2 Dx\n", "t.tbl")
            .unwrap_err()
            .to_string();
        assert!(e.contains("t.tbl:2:4"), "{e}");
        let e = ToolTable::parse("T1\nT1\n", "t.tbl")
            .unwrap_err()
            .to_string();
        assert!(e.contains("listed twice"), "{e}");
        let e = ToolTable::parse("P1 D3\n", "t.tbl")
            .unwrap_err()
            .to_string();
        assert!(e.contains("without a T"), "{e}");
        let e = ToolTable::parse("T1 K3\n", "t.tbl")
            .unwrap_err()
            .to_string();
        assert!(e.contains("unknown tool table word K"), "{e}");
    }

    #[test]
    fn a_word_starting_with_a_multibyte_letter_is_an_error_not_a_panic() {
        let e = ToolTable::parse("T1 P1\n\u{e9}3 T2\n", "t.tbl")
            .unwrap_err()
            .to_string();
        assert!(e.contains("t.tbl:2:1"), "{e}");
        let e = ToolTable::parse("T1 D\u{20ac}\n", "t.tbl")
            .unwrap_err()
            .to_string();
        assert!(e.contains("expected a number"), "{e}");
    }
}
