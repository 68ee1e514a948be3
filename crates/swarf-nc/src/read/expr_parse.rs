//! Parsing expressions (the grammar of [`crate::read::expr`]) from a line's
//! characters: values, bracketed expressions bound by operator precedence (a stack
//! of operators reduced while the one on top binds at least as tightly as the next,
//! which makes every level left-associative, as LinuxCNC's `read_real_expression`),
//! functions and their brackets.

use crate::read::expr::{Expr, Func, Op};
use crate::read::lexer::Cursor;
use swarf_toolpath::program::Diagnostic;

/// Deepest nesting of values (brackets, parameters of parameters, signs) in one
/// expression. LinuxCNC's lines are at most 256 characters, which bounds its nesting
/// near this; it keeps the recursive reading and evaluating within the stack.
pub(crate) const MAX_NESTING: usize = 128;

impl Cursor {
    /// One value (LinuxCNC's `read_real_value`): number, parameter, bracketed
    /// expression, function, or a sign before a value.
    pub(crate) fn value(&mut self) -> Result<Expr, Diagnostic> {
        let column = self.column();
        if self.depth >= MAX_NESTING {
            return Err(self.error(
                column,
                format!("expression nested deeper than {MAX_NESTING} levels"),
            ));
        }
        self.depth += 1;
        let v = self.nested_value(column);
        self.depth -= 1;
        v
    }

    /// [`Cursor::value`] one level down.
    fn nested_value(&mut self, column: usize) -> Result<Expr, Diagnostic> {
        match self.peek() {
            None => Err(self.error(column, "value missing at the end of the line")),
            Some('[') => self.bracketed(),
            Some('#') => {
                self.bump();
                if self.peek() == Some('<') {
                    Ok(Expr::Named {
                        name: self.name()?,
                        column,
                    })
                } else {
                    Ok(Expr::Param {
                        index: Box::new(self.value()?),
                        column,
                    })
                }
            }
            Some(s @ ('+' | '-')) if !self.starts_number() => {
                self.bump();
                let v = self.value()?;
                Ok(if s == '-' { Expr::Neg(Box::new(v)) } else { v })
            }
            Some(c) if c.is_ascii_alphabetic() => self.function(column),
            Some(_) if self.starts_number() => Ok(Expr::Num(self.plain_number(column, '#')?.0)),
            Some(c) => Err(self.error(column, format!("expected a value, found '{c}'"))),
        }
    }

    /// `[ expression ]`.
    pub(crate) fn bracketed(&mut self) -> Result<Expr, Diagnostic> {
        let open = self.column();
        self.expect('[', "to open an expression")?;
        let e = self.operations(Some(open))?;
        self.expect(']', "to close the expression")?;
        Ok(e)
    }

    /// Values joined by binary operators, bound by precedence, left to right; stops at
    /// `]` (inside brackets, `open` is the `[` column), a `,`, or the end of the line.
    pub(crate) fn operations(&mut self, open: Option<usize>) -> Result<Expr, Diagnostic> {
        let mut values = vec![self.value()?];
        let mut ops: Vec<(Op, usize)> = Vec::new();
        loop {
            match self.peek() {
                Some(']' | ',') => break,
                None if open.is_none() => break,
                None => {
                    return Err(
                        self.error(open.unwrap_or(1), "unclosed expression: '[' without ']'")
                    );
                }
                Some(_) if open.is_none() && !self.at_operator() => break,
                _ => {}
            }
            let column = self.column();
            let op = self.operator()?;
            while ops
                .last()
                .is_some_and(|(top, _)| top.precedence() >= op.precedence())
            {
                reduce(&mut values, &mut ops);
            }
            ops.push((op, column));
            values.push(self.value()?);
        }
        while !ops.is_empty() {
            reduce(&mut values, &mut ops);
        }
        Ok(values.pop().unwrap_or(Expr::Num(0.0)))
    }

    /// Whether an operator starts at the cursor.
    fn at_operator(&mut self) -> bool {
        let at = self.at;
        let found = self.operator().is_ok();
        self.at = at;
        found
    }

    fn operator(&mut self) -> Result<Op, Diagnostic> {
        let column = self.column();
        let table: [(&str, Op); 15] = [
            ("**", Op::Pow),
            ("*", Op::Mul),
            ("/", Op::Div),
            ("+", Op::Add),
            ("-", Op::Sub),
            ("mod", Op::Mod),
            ("and", Op::And),
            ("or", Op::Or),
            ("xor", Op::Xor),
            ("eq", Op::Eq),
            ("ne", Op::Ne),
            ("gt", Op::Gt),
            ("ge", Op::Ge),
            ("lt", Op::Lt),
            ("le", Op::Le),
        ];
        for (text, op) in table {
            if self.eat(text) {
                return Ok(op);
            }
        }
        Err(self.error(
            column,
            format!(
                "unknown operation: expected an operator or ']', found {}",
                self.found()
            ),
        ))
    }

    /// A function name and its bracketed argument(s).
    fn function(&mut self, column: usize) -> Result<Expr, Diagnostic> {
        let table: [(&str, Option<Func>); 16] = [
            ("abs", Some(Func::Abs)),
            ("acos", Some(Func::Acos)),
            ("asin", Some(Func::Asin)),
            ("atan", None),
            ("cos", Some(Func::Cos)),
            ("exp", Some(Func::Exp)),
            ("exists", None),
            ("fix", Some(Func::Fix)),
            ("fup", Some(Func::Fup)),
            ("ln", Some(Func::Ln)),
            ("round", Some(Func::Round)),
            ("sin", Some(Func::Sin)),
            ("sqrt", Some(Func::Sqrt)),
            ("tan", Some(Func::Tan)),
            ("adp", Some(Func::Adp)),
            ("pow", None),
        ];
        let Some((name, func)) = table.into_iter().find(|(name, _)| self.eat(name)) else {
            let word: String = (0..)
                .map_while(|k| self.peek_at(k).filter(char::is_ascii_alphabetic))
                .collect();
            return Err(self.error(column, format!("unknown function or word '{word}'")));
        };
        if self.peek() != Some('[') {
            return Err(self.error(
                self.column(),
                format!("left bracket missing after the function name {name}"),
            ));
        }
        match (name, func) {
            ("exists", _) => {
                self.bump();
                if !(self.peek() == Some('#') && self.peek_at(1) == Some('<')) {
                    return Err(
                        self.error(self.column(), "exists[] takes a named parameter #<name>")
                    );
                }
                self.bump();
                let n = self.name()?;
                self.expect(']', "to close exists[")?;
                Ok(Expr::Exists(n))
            }
            ("atan" | "pow", _) => self.two_arguments(name, column),
            (_, Some(func)) => Ok(Expr::Unary {
                func,
                arg: Box::new(self.bracketed()?),
                column,
            }),
            _ => Err(self.error(column, format!("unknown function {name}"))),
        }
    }

    /// `atan[y]/[x]`, and Fanuc's `atan[y, x]` and `pow[a, b]`.
    fn two_arguments(&mut self, name: &str, column: usize) -> Result<Expr, Diagnostic> {
        let open = self.column();
        self.bump();
        let first = self.operations(Some(open))?;
        let second = if self.peek() == Some(',') {
            self.bump();
            let e = self.operations(Some(open))?;
            self.expect(']', "to close the arguments")?;
            e
        } else if name == "atan" {
            self.expect(']', "to close atan's first argument")?;
            self.expect('/', "after atan[y] (atan[y]/[x])")?;
            if self.peek() != Some('[') {
                return Err(self.error(self.column(), "left bracket missing after slash with atan"));
            }
            self.bracketed()?
        } else {
            return Err(self.error(column, "pow takes two arguments: pow[a, b]"));
        };
        let (a, b) = (Box::new(first), Box::new(second));
        Ok(if name == "atan" {
            Expr::Atan(a, b)
        } else {
            Expr::Binary {
                op: Op::Pow,
                left: a,
                right: b,
                column,
            }
        })
    }
}

fn reduce(values: &mut Vec<Expr>, ops: &mut Vec<(Op, usize)>) {
    let (op, column) = ops.pop().unwrap_or((Op::Add, 1));
    let right = values.pop().unwrap_or(Expr::Num(0.0));
    let left = values.pop().unwrap_or(Expr::Num(0.0));
    values.push(Expr::Binary {
        op,
        left: Box::new(left),
        right: Box::new(right),
        column,
    });
}
