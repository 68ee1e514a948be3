//! Control statements: LinuxCNC's O words (`interp_o_word.cc`) and Fanuc macro B's
//! `IF`/`GOTO`/`WHILE`/`DO`/`END`, as the lexer ([`crate::read::lexer`]) finds them;
//! [`crate::read::flow`] runs them.
//!
//! LinuxCNC: `o<label> keyword [args]`, the label a number (`o100`) or a name
//! (`o<name>`), the keyword one of `sub endsub call return do while endwhile if
//! elseif else endif repeat endrepeat break continue`; `call` takes any number of
//! bracketed arguments, `while if elseif repeat` one, `return endsub` an optional
//! value. Fanuc: `IF [c] GOTO n`, `IF [c] THEN #i = e`, `GOTO n`, `WHILE [c] DOm`, `DOm`,
//! `ENDm` (m from 1 to 3).

use crate::read::expr::Expr;
use crate::read::lexer::{Assignment, Cursor, Syntax, assignment};
use std::fmt;
use swarf_toolpath::program::Diagnostic;

/// Most arguments an O-word call takes (#1 to #30).
pub const MAX_CALL_ARGUMENTS: usize = 30;

/// An O-word label.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Label {
    /// `o100`.
    Number(u32),
    /// `o<name>` (lower case).
    Name(Box<str>),
    /// A loop or condition label inside subroutine `.0` (LinuxCNC scopes them by the
    /// subroutine they are in; shown as the label itself).
    Scoped(Box<Label>, Box<Label>),
}

impl fmt::Display for Label {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Label::Number(n) => write!(f, "o{n}"),
            Label::Name(n) => write!(f, "o<{n}>"),
            Label::Scoped(_, l) => write!(f, "{l}"),
        }
    }
}

/// An O-word keyword.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Keyword {
    /// `sub`
    Sub,
    /// `endsub`
    EndSub,
    /// `call`
    Call,
    /// `return`
    Return,
    /// `do`
    Do,
    /// `while`
    While,
    /// `endwhile`
    EndWhile,
    /// `if`
    If,
    /// `elseif`
    ElseIf,
    /// `else`
    Else,
    /// `endif`
    EndIf,
    /// `repeat`
    Repeat,
    /// `endrepeat`
    EndRepeat,
    /// `break`
    Break,
    /// `continue`
    Continue,
}

/// Keywords, longest first where one starts another.
const KEYWORDS: [(&str, Keyword); 15] = [
    ("endsub", Keyword::EndSub),
    ("endwhile", Keyword::EndWhile),
    ("endif", Keyword::EndIf),
    ("endrepeat", Keyword::EndRepeat),
    ("elseif", Keyword::ElseIf),
    ("else", Keyword::Else),
    ("sub", Keyword::Sub),
    ("call", Keyword::Call),
    ("return", Keyword::Return),
    ("do", Keyword::Do),
    ("while", Keyword::While),
    ("if", Keyword::If),
    ("repeat", Keyword::Repeat),
    ("break", Keyword::Break),
    ("continue", Keyword::Continue),
];

impl Keyword {
    /// The keyword as written.
    pub fn name(self) -> &'static str {
        KEYWORDS
            .iter()
            .find(|(_, k)| *k == self)
            .map_or("?", |(n, _)| n)
    }
}

/// A LinuxCNC O-word statement.
#[derive(Debug, Clone, PartialEq)]
pub struct Control {
    /// The label.
    pub label: Label,
    /// What it does.
    pub keyword: Keyword,
    /// Bracketed arguments (call), condition (while, if, elseif), count (repeat) or
    /// value (return, endsub).
    pub args: Vec<Expr>,
    /// Column of the `O`.
    pub column: usize,
}

/// A Fanuc macro statement.
#[derive(Debug, Clone, PartialEq)]
pub enum FanucStatement {
    /// `GOTO n`, or `IF [c] GOTO n` with the condition.
    Goto {
        /// Condition, if any.
        condition: Option<Expr>,
        /// The sequence number to go to.
        target: Expr,
    },
    /// `IF [c] THEN #i = e`.
    IfThen {
        /// Condition.
        condition: Expr,
        /// The setting made when it holds.
        then: Assignment,
    },
    /// `WHILE [c] DOm`, or `DOm` alone (no condition).
    Do {
        /// Condition, if any.
        condition: Option<Expr>,
        /// Loop identifier m.
        id: u8,
    },
    /// `ENDm`.
    End(u8),
}

/// The O-word statement at the cursor (on the `O`).
///
/// # Errors
/// A bad label, an unknown keyword, wrong arguments or text after the statement.
pub(crate) fn control(cursor: &mut Cursor) -> Result<Control, Diagnostic> {
    let column = cursor.column();
    cursor.bump();
    let label = if cursor.peek() == Some('<') {
        Label::Name(cursor.name()?)
    } else {
        let (n, point) = cursor.plain_number(column, 'O')?;
        if point || n < 0.0 || n > f64::from(u32::MAX) {
            return Err(cursor.error(column, "O-word label must be a whole number or <name>"));
        }
        Label::Number(n as u32)
    };
    let at = cursor.column();
    let Some(keyword) = KEYWORDS
        .iter()
        .find(|(text, _)| cursor.eat(text))
        .map(|(_, k)| *k)
    else {
        return Err(cursor.error(
            at,
            format!(
                "unknown O-word statement after {label}: expected sub, endsub, call, return, \
                 do, while, endwhile, if, elseif, else, endif, repeat, endrepeat, break or \
                 continue, found {}",
                cursor.found()
            ),
        ));
    };
    let mut args = Vec::new();
    while cursor.peek() == Some('[') {
        args.push(cursor.bracketed()?);
    }
    if !cursor.at_end() {
        return Err(cursor.error(
            cursor.column(),
            format!("unexpected text after '{label} {}'", keyword.name()),
        ));
    }
    let (least, most) = match keyword {
        Keyword::Call => (0, MAX_CALL_ARGUMENTS),
        Keyword::While | Keyword::If | Keyword::ElseIf | Keyword::Repeat => (1, 1),
        Keyword::Return | Keyword::EndSub => (0, 1),
        _ => (0, 0),
    };
    if args.len() < least || args.len() > most {
        let expected = match (least, most) {
            (1, 1) => "one bracketed expression".to_string(),
            (0, 1) => "at most one bracketed value".to_string(),
            (0, 0) => "no arguments".to_string(),
            _ => format!("at most {most} arguments"),
        };
        return Err(cursor.error(
            column,
            format!(
                "'{label} {}' takes {expected}, found {}",
                keyword.name(),
                args.len()
            ),
        ));
    }
    Ok(Control {
        label,
        keyword,
        args,
        column,
    })
}

/// A Fanuc macro statement at the cursor, or `None` when the line is something else.
///
/// # Errors
/// A malformed statement.
pub(crate) fn fanuc_statement(cursor: &mut Cursor) -> Result<Option<FanucStatement>, Diagnostic> {
    let column = cursor.column();
    let statement = if cursor.eat("if[") {
        cursor_back(cursor);
        let condition = cursor.bracketed()?;
        if cursor.eat("goto") {
            FanucStatement::Goto {
                condition: Some(condition),
                target: cursor.operations(None)?,
            }
        } else if cursor.eat("then") {
            if cursor.peek() != Some('#') {
                return Err(
                    cursor.error(cursor.column(), "THEN must be followed by #i = expression")
                );
            }
            FanucStatement::IfThen {
                condition,
                then: assignment(cursor, Syntax { fanuc: true })?,
            }
        } else {
            return Err(cursor.error(
                cursor.column(),
                format!(
                    "IF [..] must be followed by GOTO or THEN, found {}",
                    cursor.found()
                ),
            ));
        }
    } else if cursor.eat("goto") {
        FanucStatement::Goto {
            condition: None,
            target: cursor.operations(None)?,
        }
    } else if cursor.eat("while[") {
        cursor_back(cursor);
        let condition = cursor.bracketed()?;
        if !cursor.eat("do") {
            return Err(cursor.error(cursor.column(), "WHILE [..] must be followed by DOm"));
        }
        FanucStatement::Do {
            condition: Some(condition),
            id: loop_id(cursor, column)?,
        }
    } else if cursor.peek() == Some('d')
        && cursor.peek_at(1) == Some('o')
        && cursor.peek_at(2).is_some_and(|c| c.is_ascii_digit())
    {
        cursor.eat("do");
        FanucStatement::Do {
            condition: None,
            id: loop_id(cursor, column)?,
        }
    } else if cursor.peek_at(3).is_some_and(|c| c.is_ascii_digit()) && cursor.eat("end") {
        FanucStatement::End(loop_id(cursor, column)?)
    } else {
        return Ok(None);
    };
    if !cursor.at_end() {
        return Err(cursor.error(cursor.column(), "unexpected text after the macro statement"));
    }
    Ok(Some(statement))
}

/// Steps back over the `[` that `eat("if[")` / `eat("while[")` consumed.
fn cursor_back(cursor: &mut Cursor) {
    cursor.unbump();
}

/// The `m` of `DOm`/`ENDm`: 1 to 3.
fn loop_id(cursor: &mut Cursor, column: usize) -> Result<u8, Diagnostic> {
    let (n, point) = cursor.plain_number(column, 'D')?;
    if point || !(1.0..=3.0).contains(&n) {
        return Err(cursor.error(column, "loop identifier of DO/END must be 1, 2 or 3"));
    }
    Ok(n as u8)
}
