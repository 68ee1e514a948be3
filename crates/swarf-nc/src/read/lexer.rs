//! RS274/NGC lexer: one source line into a [`Line`]: its words (each value an
//! [`Expr`]), parameter settings, an O-word statement or a Fanuc macro statement, with
//! the source column of everything.
//!
//! As LinuxCNC reads a line (`interp_read.cc`): letters are case-insensitive and
//! spaces and tabs are ignored everywhere outside comments, even inside numbers and
//! names (`X 1 0.5` is `X10.5`, `#<my depth>` is `#<mydepth>`); a line may start with `/`
//! (block delete) and then an `N` line number; comments are `( ... )` (no nesting,
//! closed on the same line) or `;` to the end of the line; a number is signs, digits
//! and at most one decimal point with at least one digit (no exponent: `1e3` reads
//! as `1` then an `E` word). A word's value may be any value of [`crate::read::expr`]:
//! `X#1`, `Y[#2 * 2]`, `Zsin[30]`, `X-#<depth>`. `#n = value` and `#<name> = value` set
//! parameters; an `O` word starts a statement (`o100 sub`, `o<name> call [1] [2]`,
//! `o101 while [#1 lt 3]` ...). A line holding only `%` delimits the program.
//!
//! In the Fanuc dialect ([`Syntax::fanuc`]), a line may instead be `IF [c] GOTO n`,
//! `IF [c] THEN #i = e`, `GOTO n`, `WHILE [c] DOm`, `DOm` or `ENDm`; a setting's value is
//! a whole expression without brackets (`#3 = #1 + #2 * 2`); an `O` number alone on
//! its line starts a subprogram.
//!
//! Columns are 1-based and count characters, as an editor shows them.

use crate::read::expr::Expr;
use crate::read::statement::{Control, FanucStatement, control, fanuc_statement};
use swarf_toolpath::program::Diagnostic;

/// Which language the lexer reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Syntax {
    /// Fanuc macro B statements and expressions instead of LinuxCNC's O words.
    pub fanuc: bool,
}

/// One word: a letter and its value, with the column of the letter.
#[derive(Debug, Clone, PartialEq)]
pub struct WordExpr {
    /// Upper-case letter.
    pub letter: char,
    /// The value as written.
    pub value: Expr,
    /// A plain number written with a decimal point (or not a plain number).
    pub has_point: bool,
    /// 1-based column of the letter.
    pub column: usize,
}

/// `#n = value` or `#<name> = value`.
#[derive(Debug, Clone, PartialEq)]
pub struct Assignment {
    /// Which parameter.
    pub target: Target,
    /// The value.
    pub value: Expr,
    /// Column of `#`.
    pub column: usize,
}

/// The parameter an [`Assignment`] sets.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// `#index`.
    Numbered(Expr),
    /// `#<name>`.
    Named(Box<str>),
}

/// What a line holds besides its comments.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum Statement {
    /// Nothing (blank or comments only).
    #[default]
    Empty,
    /// Words and parameter settings.
    Words {
        /// The words, in order.
        words: Vec<WordExpr>,
        /// The settings, in order (they take effect after the line is read).
        assignments: Vec<Assignment>,
    },
    /// A program number `O1234` alone on the line, with its column.
    ProgramNumber(u32, usize),
    /// A LinuxCNC O-word statement.
    Control(Control),
    /// A Fanuc macro statement.
    Fanuc(FanucStatement),
}

/// A lexed source line.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Line {
    /// The line started with `/`.
    pub block_delete: bool,
    /// The line is a `%` program delimiter.
    pub percent: bool,
    /// The `N` number, if any.
    pub number: Option<f64>,
    /// What the line says.
    pub statement: Statement,
    /// Comment texts, without the parentheses or `;`.
    pub comments: Vec<String>,
}

impl Line {
    /// True when the line holds no statement and is no delimiter.
    pub fn is_empty(&self) -> bool {
        self.statement == Statement::Empty && !self.percent
    }
}

/// Lexes one line (`line` is its 1-based number, for diagnostics).
///
/// # Errors
/// A [`Diagnostic`] at the offending character: nested or unclosed comment, a letter
/// without a value, a malformed number, an unknown function or operator, an
/// unbalanced bracket, an `N` word away from the start, polar words (`@`, `^`), a
/// malformed O-word statement, any other character.
pub fn lex_line(text: &str, line: usize, syntax: Syntax) -> Result<Line, Diagnostic> {
    let mut out = Line::default();
    let mut cursor = Cursor::new(text, line, &mut out.comments)?;
    if cursor.peek() == Some('/') {
        out.block_delete = true;
        cursor.bump();
    }
    if cursor.rest_is('%') {
        out.percent = true;
        return Ok(out);
    }
    if cursor.peek() == Some('n') {
        let column = cursor.column();
        cursor.bump();
        let n = cursor.plain_number(column, 'N')?;
        if n.0 < 0.0 || n.0.fract() != 0.0 {
            return Err(cursor.error(column, "line number N must be a whole number >= 0"));
        }
        out.number = Some(n.0);
    }
    out.statement = statement(&mut cursor, syntax)?;
    Ok(out)
}

fn statement(cursor: &mut Cursor, syntax: Syntax) -> Result<Statement, Diagnostic> {
    if cursor.at_end() {
        return Ok(Statement::Empty);
    }
    if syntax.fanuc
        && let Some(s) = fanuc_statement(cursor)?
    {
        return Ok(Statement::Fanuc(s));
    }
    if cursor.peek() == Some('o') {
        let column = cursor.column();
        if cursor.peek_at(1).is_some_and(|c| c.is_ascii_digit()) && cursor.all_digits_after(1) {
            cursor.bump();
            let (value, _) = cursor.plain_number(column, 'O')?;
            if value > f64::from(u32::MAX) {
                return Err(cursor.error(column, "program number O out of range"));
            }
            return Ok(Statement::ProgramNumber(value as u32, column));
        }
        if syntax.fanuc {
            return Err(cursor.error(
                column,
                "O word in the Fanuc dialect: only a program number O1234 alone on its line",
            ));
        }
        return Ok(Statement::Control(control(cursor)?));
    }
    let mut words = Vec::new();
    let mut assignments = Vec::new();
    while let Some(c) = cursor.peek() {
        let column = cursor.column();
        match c {
            '#' => assignments.push(assignment(cursor, syntax)?),
            '@' | '^' | 'a'..='z' if c != 'n' && c != 'o' => {
                let letter = c.to_ascii_uppercase();
                cursor.bump();
                let (value, has_point) = cursor.word_value(column, letter)?;
                words.push(WordExpr {
                    letter,
                    value,
                    has_point,
                    column,
                });
            }
            'n' => {
                return Err(cursor.error(column, "line number N must be at the start of the block"));
            }
            'o' => {
                return Err(cursor.error(
                    column,
                    "O word after other words: an O-word statement must be alone on its line",
                ));
            }
            other => {
                return Err(cursor.error(column, format!("unexpected character '{other}'")));
            }
        }
    }
    Ok(Statement::Words { words, assignments })
}

/// `#index = value` or `#<name> = value` at the cursor; in the Fanuc dialect the value
/// is an expression without brackets.
pub(crate) fn assignment(cursor: &mut Cursor, syntax: Syntax) -> Result<Assignment, Diagnostic> {
    let column = cursor.column();
    cursor.bump();
    let target = if cursor.peek() == Some('<') {
        Target::Named(cursor.name()?)
    } else {
        Target::Numbered(cursor.value()?)
    };
    if cursor.peek() != Some('=') {
        return Err(cursor.error(
            cursor.column(),
            "equal sign missing in parameter setting (expected '#n = value')",
        ));
    }
    cursor.bump();
    let value = if syntax.fanuc {
        cursor.operations(None)?
    } else {
        cursor.value()?
    };
    Ok(Assignment {
        target,
        value,
        column,
    })
}

/// The significant characters of a line (lower case, spaces and comments removed),
/// each with its 1-based source column.
pub(crate) struct Cursor {
    chars: Vec<(char, usize)>,
    pub(crate) at: usize,
    line: usize,
    end_column: usize,
    /// Values being read, one inside the other ([`crate::read::expr_parse`]).
    pub(crate) depth: usize,
}

impl Cursor {
    fn new(text: &str, line: usize, comments: &mut Vec<String>) -> Result<Cursor, Diagnostic> {
        let raw: Vec<char> = text.chars().collect();
        let mut chars = Vec::with_capacity(raw.len());
        let mut i = 0;
        let error = |column: usize, m: &str| Diagnostic::new(line, column, m);
        while i < raw.len() {
            match raw[i] {
                ' ' | '\t' | '\r' | '\u{c}' => {}
                '(' => {
                    let close = raw[i + 1..].iter().position(|&c| c == ')' || c == '(');
                    match close.map(|k| (i + 1 + k, raw[i + 1 + k])) {
                        Some((k, ')')) => {
                            comments.push(raw[i + 1..k].iter().collect());
                            i = k;
                        }
                        Some((k, _)) => return Err(error(k + 1, "nested comment")),
                        None => {
                            return Err(error(
                                i + 1,
                                "unclosed comment: '(' without ')' on this line",
                            ));
                        }
                    }
                }
                ';' => {
                    comments.push(raw[i + 1..].iter().collect::<String>().trim().to_string());
                    break;
                }
                c => chars.push((c.to_ascii_lowercase(), i + 1)),
            }
            i += 1;
        }
        Ok(Cursor {
            chars,
            depth: 0,
            at: 0,
            line,
            end_column: raw.len() + 1,
        })
    }

    pub(crate) fn peek(&self) -> Option<char> {
        self.peek_at(0)
    }

    pub(crate) fn peek_at(&self, k: usize) -> Option<char> {
        self.chars.get(self.at + k).map(|c| c.0)
    }

    pub(crate) fn bump(&mut self) {
        self.at += 1;
    }

    pub(crate) fn unbump(&mut self) {
        self.at = self.at.saturating_sub(1);
    }

    pub(crate) fn at_end(&self) -> bool {
        self.at >= self.chars.len()
    }

    /// The column of the next character (one past the end at the end).
    pub(crate) fn column(&self) -> usize {
        self.chars.get(self.at).map_or(self.end_column, |c| c.1)
    }

    pub(crate) fn error(&self, column: usize, message: impl Into<String>) -> Diagnostic {
        Diagnostic::new(self.line, column, message)
    }

    fn rest_is(&self, c: char) -> bool {
        self.chars.len() == self.at + 1 && self.peek() == Some(c)
    }

    fn all_digits_after(&self, k: usize) -> bool {
        self.chars[self.at + k..]
            .iter()
            .all(|c| c.0.is_ascii_digit())
    }

    /// Consumes `word` (lower case) if the characters at the cursor spell it.
    pub(crate) fn eat(&mut self, word: &str) -> bool {
        let n = word.chars().count();
        let matches = word
            .chars()
            .enumerate()
            .all(|(k, c)| self.peek_at(k) == Some(c));
        if matches {
            self.at += n;
        }
        matches
    }

    /// Expects `c` at the cursor.
    pub(crate) fn expect(&mut self, c: char, what: &str) -> Result<(), Diagnostic> {
        if self.peek() == Some(c) {
            self.bump();
            Ok(())
        } else {
            Err(self.error(
                self.column(),
                format!("expected '{c}' {what}, found {}", self.found()),
            ))
        }
    }

    pub(crate) fn found(&self) -> String {
        self.peek()
            .map_or_else(|| "the end of the line".to_string(), |c| format!("'{c}'"))
    }

    /// `<name>` at the cursor: the name in lower case, spaces removed.
    pub(crate) fn name(&mut self) -> Result<Box<str>, Diagnostic> {
        let open = self.column();
        self.expect('<', "to open a name")?;
        let mut name = String::new();
        loop {
            match self.peek() {
                Some('>') => break,
                Some(c) => name.push(c),
                None => return Err(self.error(open, "name without a closing '>'")),
            }
            self.bump();
        }
        self.bump();
        if name.is_empty() {
            return Err(self.error(open, "empty name '<>'"));
        }
        Ok(name.into())
    }

    /// A word's value after its letter; the flag tells a plain number with a point.
    fn word_value(&mut self, column: usize, letter: char) -> Result<(Expr, bool), Diagnostic> {
        if matches!(letter, '@' | '^') && self.at_end() {
            return Err(self.error(column, format!("{letter} word without a value")));
        }
        if self.at_end() {
            return Err(self.error(
                column,
                format!("{letter} word without a number (found the end of the line)"),
            ));
        }
        if self.starts_number() {
            let (v, point) = self.plain_number(column, letter)?;
            return Ok((Expr::Num(v), point));
        }
        Ok((self.value()?, true))
    }

    pub(crate) fn starts_number(&self) -> bool {
        let mut k = 0;
        while matches!(self.peek_at(k), Some('+' | '-')) {
            k += 1;
        }
        matches!(self.peek_at(k), Some(c) if c.is_ascii_digit() || c == '.')
    }

    /// Signs, digits and one point (LinuxCNC's `read_real_number`).
    pub(crate) fn plain_number(
        &mut self,
        column: usize,
        letter: char,
    ) -> Result<(f64, bool), Diagnostic> {
        let start = self.at;
        let mut text = String::new();
        while let Some(c @ ('+' | '-')) = self.peek() {
            text.push(c);
            self.bump();
        }
        while let Some(c) = self.peek().filter(|c| c.is_ascii_digit() || *c == '.') {
            text.push(c);
            self.bump();
        }
        let digits = text.chars().filter(char::is_ascii_digit).count();
        let points = text.matches('.').count();
        let signs = text.matches(['+', '-']).count();
        if digits == 0 {
            self.at = start;
            return Err(self.error(
                column,
                format!("{letter} word without a number (found {})", self.found()),
            ));
        }
        if points > 1 || signs > 1 {
            return Err(self.error(column, format!("{letter} word: bad number '{text}'")));
        }
        let value: f64 = text
            .parse()
            .map_err(|_| self.error(column, format!("{letter} word: bad number '{text}'")))?;
        if !value.is_finite() {
            return Err(self.error(
                column,
                format!("{letter} word: number too large ({} digits)", digits),
            ));
        }
        Ok((value, points == 1))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::read::expr::ParamSource;

    struct NoParams;
    impl ParamSource for NoParams {
        fn numbered(&self, index: i64) -> Result<f64, String> {
            Ok(index as f64 * 10.0)
        }
        fn named(&self, name: &str) -> Result<f64, String> {
            if name == "depth" {
                Ok(2.5)
            } else {
                Err(format!("#<{name}> undefined"))
            }
        }
        fn exists(&self, name: &str) -> bool {
            name == "depth"
        }
        fn fanuc(&self) -> bool {
            false
        }
    }

    fn lex(text: &str) -> Line {
        lex_line(text, 1, Syntax::default()).unwrap()
    }

    fn words(text: &str) -> Vec<(char, f64, usize)> {
        match lex(text).statement {
            Statement::Words { words, .. } => words
                .iter()
                .map(|w| (w.letter, w.value.eval(&NoParams).unwrap(), w.column))
                .collect(),
            other => panic!("{other:?}"),
        }
    }

    fn value(text: &str) -> f64 {
        words(&format!("X{text}"))[0].1
    }

    fn err(text: &str) -> (usize, String) {
        let d = lex_line(text, 4, Syntax::default()).unwrap_err();
        assert_eq!(d.line, 4);
        (d.column, d.message)
    }

    #[test]
    fn nesting_is_bounded() {
        let deep = |n: usize| format!("X{}1{}", "[".repeat(n), "]".repeat(n));
        assert_eq!(value(&deep(100)[1..]), 1.0);
        for text in [deep(30_000), format!("X{}1", "#".repeat(100_000))] {
            let (column, message) = err(&text);
            assert!(
                message.contains("nested deeper than 128 levels"),
                "{message}"
            );
            assert!(column <= 130, "{column}");
        }
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
        assert_eq!(lex("N0010 G0X1Y2").number, Some(10.0));
        assert_eq!(words("N0010 G0X1Y2")[2], ('Y', 2.0, 11));
    }

    #[test]
    fn expressions_precedence_and_functions() {
        assert_eq!(value("[1 + 2 * 3]"), 7.0);
        assert_eq!(value("[2 ** 3 ** 2]"), 64.0);
        assert_eq!(
            value("[9+8*7/6+5-4*3**2+1]"),
            9.0 + 56.0 / 6.0 + 5.0 - 36.0 + 1.0
        );
        assert_eq!(value("[1 + 2 gt 2 and 1]"), 1.0);
        assert_eq!(value("[7 mod 3]"), 1.0);
        assert!((value("sin[30]") - 0.5).abs() < 1e-15);
        assert!((value("atan[1]/[1]") - 45.0).abs() < 1e-12);
        assert_eq!(value("-#2"), -20.0);
        assert_eq!(value("#[1+1]"), 20.0);
        assert_eq!(value("##1"), 100.0);
        assert_eq!(value("-[#<depth> * 2]"), -5.0);
        assert_eq!(value("exists[#<depth>]"), 1.0);
        assert_eq!(value("exists[#<other>]"), 0.0);
        assert_eq!(value("[fix[2.7] + fup[2.1]]"), 5.0);
    }

    #[test]
    fn settings_and_statements() {
        let l = lex("#1 = 5 #<depth>=[#1+1] G0 X#1 (c)");
        let Statement::Words { words, assignments } = l.statement else {
            panic!()
        };
        assert_eq!(words.len(), 2);
        assert_eq!(assignments.len(), 2);
        assert_eq!(assignments[1].target, Target::Named("depth".into()));
        assert_eq!(l.comments, vec!["c".to_string()]);
        assert!(matches!(
            lex("O1000 (PART)").statement,
            Statement::ProgramNumber(1000, 1)
        ));
        assert!(matches!(lex("o100 sub").statement, Statement::Control(_)));
        assert!(lex("  % ").percent);
        assert!(lex("(only a comment)").is_empty());
        assert!(lex("/N5 G0 X1").block_delete);
    }

    #[test]
    fn errors_point_at_the_culprit() {
        assert_eq!(err("G0 X1 (a (b) c)").0, 10);
        assert_eq!(err("G0 X1 (abc").0, 7);
        assert_eq!(err("G0 X1.2.3").0, 4);
        assert_eq!(err("G0 Xabc").0, 5);
        assert_eq!(err("G0 X").0, 4);
        assert_eq!(err("G0 X[1+2").0, 5);
        assert_eq!(err("G0 X[1 $ 2]").0, 8);
        assert_eq!(err("G0 X1 N20").0, 7);
        assert_eq!(err("G0 X1 $").0, 7);
        assert_eq!(err("G0 X--1").0, 4);
        assert_eq!(err("#1 5").0, 5);
        assert!(err("G1 X1 o100 call").1.contains("O-word"));
        assert!(
            err(&format!("G1 X1{}", "9".repeat(400)))
                .1
                .contains("too large")
        );
    }
}
