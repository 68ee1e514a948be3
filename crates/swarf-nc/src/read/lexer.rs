//! RS274/NGC lexer: one source line into a block of words, with columns.
//!
//! As LinuxCNC reads a line: letters are case-insensitive and spaces and tabs are
//! ignored everywhere, even inside numbers (`X 1 0.5` is `X10.5`); a line may start
//! with `/` (block delete) and then an `N` line number; comments are `( ... )`
//! (no nesting, closed on the same line) or `;` to the end of the line; a real
//! number is an optional sign, digits with at most one decimal point and at least
//! one digit (no exponent: `1e3` reads as `1` followed by an `E` word). A line holding
//! only `%` delimits the program. An `O` number alone on a line is a Fanuc program
//! number; any other `O` word starts a LinuxCNC subroutine or control-flow statement,
//! which swarf does not run.
//!
//! Columns are 1-based and count characters, so that they match what an editor shows.

use crate::read::program::Diagnostic;

/// One word: a letter and its number, with the column of the letter.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Word {
    /// Upper-case letter.
    pub letter: char,
    /// The number as written (program units).
    pub value: f64,
    /// Whether the number was written with a decimal point.
    pub has_point: bool,
    /// 1-based column of the letter.
    pub column: usize,
}

/// What a line holds.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Block {
    /// The line started with `/`.
    pub block_delete: bool,
    /// The line is a `%` program delimiter.
    pub percent: bool,
    /// A Fanuc program number `O1234` alone on the line (with its column).
    pub program_number: Option<(u32, usize)>,
    /// The words after the optional line number, in order.
    pub words: Vec<Word>,
    /// Comment texts, without the parentheses or `;`.
    pub comments: Vec<String>,
}

impl Block {
    /// True when the line holds no word and is no delimiter (blank or comment only).
    pub fn is_empty(&self) -> bool {
        self.words.is_empty() && !self.percent && self.program_number.is_none()
    }
}

/// The refusal of LinuxCNC's polar words.
const POLAR: &str = "polar coordinates (@ distance, ^ angle) are not supported by swarf";

/// Lexes one line (`line` is its 1-based number, for diagnostics).
///
/// # Errors
/// A [`Diagnostic`] at the offending character: nested or unclosed comment, a
/// letter without a number, a malformed number, `#` parameters, `[` expressions,
/// an `N` word away from the start, an `O` subroutine word, any other character.
pub fn lex_line(text: &str, line: usize) -> Result<Block, Diagnostic> {
    let mut cursor = Cursor {
        chars: text.chars().collect(),
        at: 0,
        line,
    };
    let mut block = Block::default();
    cursor.skip_space();
    if cursor.peek() == Some('/') {
        block.block_delete = true;
        cursor.at += 1;
        cursor.skip_space();
    }
    if cursor.rest_is("%") {
        block.percent = true;
        return Ok(block);
    }
    if matches!(cursor.peek(), Some('n' | 'N')) {
        let column = cursor.column();
        cursor.at += 1;
        let number = cursor.number(column, 'N')?;
        if number.value < 0.0 || number.value.fract() != 0.0 {
            return Err(cursor.error(column, "line number N must be a whole number >= 0"));
        }
        cursor.expect_separator()?;
    }
    if matches!(cursor.peek(), Some('o' | 'O')) {
        block.program_number = Some(cursor.program_number(&mut block.comments)?);
        return Ok(block);
    }
    lex_words(&mut cursor, &mut block)?;
    Ok(block)
}

fn lex_words(cursor: &mut Cursor, block: &mut Block) -> Result<(), Diagnostic> {
    loop {
        cursor.skip_space();
        let Some(c) = cursor.peek() else {
            return Ok(());
        };
        let column = cursor.column();
        match c {
            '(' => block.comments.push(cursor.comment()?),
            ';' => {
                cursor.at += 1;
                block.comments.push(cursor.rest().trim().to_string());
                return Ok(());
            }
            '#' => {
                return Err(cursor.error(column, "parameters (#) are not supported by swarf"));
            }
            '[' => {
                return Err(cursor.error(column, "expressions ([...]) are not supported by swarf"));
            }
            '@' | '^' => return Err(cursor.error(column, POLAR)),
            'n' | 'N' => {
                return Err(cursor.error(column, "line number N must be at the start of the block"));
            }
            'o' | 'O' => {
                return Err(cursor.error(
                    column,
                    "O words (subroutines, loops, conditions) are not supported by swarf",
                ));
            }
            c if c.is_ascii_alphabetic() => {
                let letter = c.to_ascii_uppercase();
                cursor.at += 1;
                let number = cursor.number(column, letter)?;
                block.words.push(Word {
                    letter,
                    value: number.value,
                    has_point: number.has_point,
                    column,
                });
                cursor.expect_separator()?;
            }
            other => {
                return Err(cursor.error(column, format!("unexpected character '{other}'")));
            }
        }
    }
}

/// A number as read.
struct Number {
    value: f64,
    has_point: bool,
}

struct Cursor {
    chars: Vec<char>,
    at: usize,
    line: usize,
}

impl Cursor {
    fn peek(&self) -> Option<char> {
        self.chars.get(self.at).copied()
    }

    fn column(&self) -> usize {
        self.at + 1
    }

    fn error(&self, column: usize, message: impl Into<String>) -> Diagnostic {
        Diagnostic::new(self.line, column, message)
    }

    fn skip_space(&mut self) {
        while matches!(self.peek(), Some(' ' | '\t' | '\r')) {
            self.at += 1;
        }
    }

    fn rest(&self) -> String {
        self.chars[self.at.min(self.chars.len())..].iter().collect()
    }

    /// The rest of the line is `s` (spaces around it ignored).
    fn rest_is(&self, s: &str) -> bool {
        self.rest().trim() == s
    }

    /// A `( ... )` comment starting at the cursor.
    fn comment(&mut self) -> Result<String, Diagnostic> {
        let open = self.column();
        self.at += 1;
        let start = self.at;
        while let Some(c) = self.peek() {
            match c {
                ')' => {
                    let text: String = self.chars[start..self.at].iter().collect();
                    self.at += 1;
                    return Ok(text);
                }
                '(' => return Err(self.error(self.column(), "nested comment")),
                _ => self.at += 1,
            }
        }
        Err(self.error(open, "unclosed comment: '(' without ')' on this line"))
    }

    /// The number after a letter, spaces allowed anywhere inside it.
    fn number(&mut self, letter_column: usize, letter: char) -> Result<Number, Diagnostic> {
        let mut text = String::new();
        let mut digits = 0;
        let mut has_point = false;
        self.skip_space();
        if let Some(sign @ ('+' | '-')) = self.peek() {
            text.push(sign);
            self.at += 1;
        }
        loop {
            self.skip_space();
            match self.peek() {
                Some(c) if c.is_ascii_digit() => {
                    text.push(c);
                    digits += 1;
                }
                Some('.') if !has_point => {
                    text.push('.');
                    has_point = true;
                }
                _ => break,
            }
            self.at += 1;
        }
        if digits == 0 {
            match self.peek() {
                Some('#') => {
                    return Err(
                        self.error(self.column(), "parameters (#) are not supported by swarf")
                    );
                }
                Some('[') => {
                    return Err(self.error(
                        self.column(),
                        "expressions ([...]) are not supported by swarf",
                    ));
                }
                _ => {}
            }
            let found = match self.peek() {
                Some(c) => format!("'{c}'"),
                None => "the end of the line".to_string(),
            };
            return Err(self.error(
                letter_column,
                format!("{letter} word without a number (found {found})"),
            ));
        }
        let value: f64 = text.parse().map_err(|_| {
            self.error(letter_column, format!("{letter} word: bad number '{text}'"))
        })?;
        Ok(Number { value, has_point })
    }

    /// After a word: the next thing must start a word or comment, or end the line.
    fn expect_separator(&mut self) -> Result<(), Diagnostic> {
        self.skip_space();
        match self.peek() {
            None | Some('(' | ';') => Ok(()),
            Some(c) if c.is_ascii_alphabetic() || c == '#' || c == '[' => Ok(()),
            Some('@' | '^') => Err(self.error(self.column(), POLAR)),
            Some(c) => Err(self.error(
                self.column(),
                format!("bad number: unexpected '{c}' after the number"),
            )),
        }
    }

    /// `O1234` alone on a line (comments allowed after it).
    fn program_number(&mut self, comments: &mut Vec<String>) -> Result<(u32, usize), Diagnostic> {
        let column = self.column();
        self.at += 1;
        let not_supported = |cursor: &Cursor| {
            cursor.error(
                column,
                "O words (subroutines, loops, conditions) are not supported by swarf; \
                 only a program number O1234 alone on its line is",
            )
        };
        let number = self.number(column, 'O').map_err(|_| not_supported(self))?;
        let value = number.value;
        if number.has_point || value < 0.0 || value > f64::from(u32::MAX) {
            return Err(not_supported(self));
        }
        loop {
            self.skip_space();
            match self.peek() {
                None => break,
                Some('(') => comments.push(self.comment()?),
                Some(';') => {
                    self.at += 1;
                    comments.push(self.rest().trim().to_string());
                    break;
                }
                Some(_) => return Err(not_supported(self)),
            }
        }
        Ok((value as u32, column))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn words(text: &str) -> Vec<(char, f64, usize)> {
        lex_line(text, 1)
            .unwrap()
            .words
            .iter()
            .map(|w| (w.letter, w.value, w.column))
            .collect()
    }

    fn err(text: &str) -> (usize, String) {
        let d = lex_line(text, 4).unwrap_err();
        assert_eq!(d.line, 4);
        (d.column, d.message)
    }

    #[test]
    fn words_with_columns_and_spaces_inside_numbers() {
        assert_eq!(
            words("g1 x 1 0.5 Y-.5 z+2."),
            vec![
                ('G', 1.0, 1),
                ('X', 10.5, 4),
                ('Y', -0.5, 12),
                ('Z', 2.0, 17)
            ]
        );
        assert_eq!(words("G90.1"), vec![('G', 90.1, 1)]);
        assert_eq!(
            words("N0010 G0X1Y2"),
            vec![('G', 0.0, 7), ('X', 1.0, 9), ('Y', 2.0, 11)]
        );
    }

    #[test]
    fn comments_delete_and_delimiters() {
        let b = lex_line("/N5 G0 (move up) X1 ; done", 1).unwrap();
        assert!(b.block_delete);
        assert_eq!(b.comments, vec!["move up".to_string(), "done".to_string()]);
        assert_eq!(b.words.len(), 2);
        assert!(lex_line("  % ", 1).unwrap().percent);
        assert!(lex_line("(only a comment)", 1).unwrap().is_empty());
        assert!(lex_line("", 1).unwrap().is_empty());
        let o = lex_line("O1000 (PART)", 1).unwrap();
        assert_eq!(o.program_number, Some((1000, 1)));
    }

    #[test]
    fn errors_point_at_the_culprit() {
        assert_eq!(err("G0 X1 (a (b) c)").0, 10);
        assert_eq!(err("G0 X1 (abc").0, 7);
        assert_eq!(err("G0 X1.2.3").0, 8);
        assert_eq!(err("G0 Xabc").0, 4);
        assert_eq!(err("G0 X").0, 4);
        assert_eq!(err("G0 X#1").0, 5);
        assert_eq!(err("G0 X[1+2]").0, 5);
        assert_eq!(err("G0 X1 N20").0, 7);
        assert_eq!(err("G0 X1 $").0, 7);
        assert_eq!(err("o100 sub").0, 1);
        assert_eq!(err("G0 X--1").0, 4);
        assert!(err("#1 = 5").1.contains("parameters"));
        // LinuxCNC's polar words are named, not taken for a bad number.
        for (text, column) in [("G1 @10 ^45", 4), ("G1 X1@10", 6), ("G1 X1 ^45", 7)] {
            let (c, m) = err(text);
            assert_eq!(c, column, "{text}");
            assert!(m.contains("polar coordinates"), "{text}: {m}");
        }
    }
}
