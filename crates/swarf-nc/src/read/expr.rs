//! RS274/NGC expressions as LinuxCNC 2.9 evaluates them (`interp_read.cc`,
//! `interp_execute.cc`), and Fanuc macro B's where the dialect differs.
//!
//! A value is a number, a parameter (`#7`, `#[#1+2]`, `#<name>`), a bracketed
//! expression, a function of a bracketed expression (`sin[30]`; `atan[y]/[x]`;
//! `exists[#<name>]`), or `+`/`-` before a value. Binary operators bind in four levels,
//! each left-associative: `**`; then `* / mod`; then `+ -`; then the comparisons
//! `eq ne gt ge lt le`; then `and or xor`. Angles are degrees. Comparisons and logic
//! give 1 or 0; `eq`/`ne` compare within 0.0001 (LinuxCNC's `TOLERANCE_EQUAL`), any
//! non-zero is true; `mod` is never negative (`fmod` plus `|b|`); `fix`/`fup` are floor
//! and ceiling; `round` rounds half away from zero. LinuxCNC's domain errors are
//! errors here: division by zero, `sqrt` of a negative, `ln` of a non-positive,
//! `acos`/`asin` outside [-1, 1], a negative base to a non-integer power, and any
//! result that is not finite.
//!
//! In the Fanuc dialect ([`crate::read::lexer::Syntax::fanuc`]) a parameter may be *vacant* (never set, or
//! `#0`), carried here as NaN: a vacant value alone stays vacant (so an address word
//! given a vacant parameter is left out), counts as 0 in arithmetic, and equals only
//! another vacant value in `eq`/`ne`. `and or xor` are then bitwise on integers, and
//! `pow[a, b]`, `atan[a, b]` and `adp[a]` are accepted.

use std::fmt;

/// LinuxCNC `TOLERANCE_EQUAL`: `eq`/`ne` compare within this.
pub const TOLERANCE_EQUAL: f64 = 0.0001;

/// A binary operator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Op {
    /// `**`
    Pow,
    /// `*`
    Mul,
    /// `/`
    Div,
    /// `mod`
    Mod,
    /// `+`
    Add,
    /// `-`
    Sub,
    /// `eq`
    Eq,
    /// `ne`
    Ne,
    /// `gt`
    Gt,
    /// `ge`
    Ge,
    /// `lt`
    Lt,
    /// `le`
    Le,
    /// `and`
    And,
    /// `or`
    Or,
    /// `xor`
    Xor,
}

impl Op {
    /// Binding strength: higher binds first (LinuxCNC's `precedence`).
    pub fn precedence(self) -> u8 {
        match self {
            Op::Pow => 6,
            Op::Mul | Op::Div | Op::Mod => 5,
            Op::Add | Op::Sub => 4,
            Op::Eq | Op::Ne | Op::Gt | Op::Ge | Op::Lt | Op::Le => 3,
            Op::And | Op::Or | Op::Xor => 2,
        }
    }
}

/// A function of one argument.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Func {
    /// `abs`
    Abs,
    /// `acos`, degrees out
    Acos,
    /// `asin`, degrees out
    Asin,
    /// `cos`, degrees in
    Cos,
    /// `exp`
    Exp,
    /// `fix`: floor
    Fix,
    /// `fup`: ceiling
    Fup,
    /// `ln`
    Ln,
    /// `round`: half away from zero
    Round,
    /// `sin`, degrees in
    Sin,
    /// `sqrt`
    Sqrt,
    /// `tan`, degrees in
    Tan,
    /// Fanuc `adp`: a whole number of units gets a decimal point (no-op here: swarf
    /// reads numbers as written)
    Adp,
}

/// A parsed expression; `column` fields are 1-based source columns for errors.
#[derive(Debug, Clone, PartialEq)]
pub enum Expr {
    /// A number as written.
    Num(f64),
    /// `#index` with the index an expression.
    Param {
        /// The parameter number.
        index: Box<Expr>,
        /// Column of `#`.
        column: usize,
    },
    /// `#<name>` (lower case, spaces removed).
    Named {
        /// The name.
        name: Box<str>,
        /// Column of `#`.
        column: usize,
    },
    /// `exists[#<name>]`.
    Exists(Box<str>),
    /// `-value`.
    Neg(Box<Expr>),
    /// `func[arg]`.
    Unary {
        /// The function.
        func: Func,
        /// Its argument.
        arg: Box<Expr>,
        /// Column of the function name.
        column: usize,
    },
    /// `atan[y]/[x]` (or Fanuc `atan[y, x]`), degrees.
    Atan(Box<Expr>, Box<Expr>),
    /// `left op right`.
    Binary {
        /// The operator.
        op: Op,
        /// Left operand.
        left: Box<Expr>,
        /// Right operand.
        right: Box<Expr>,
        /// Column of the operator.
        column: usize,
    },
}

/// An evaluation error: column and message.
#[derive(Debug, Clone, PartialEq)]
pub struct EvalError {
    /// 1-based column.
    pub column: usize,
    /// What went wrong.
    pub message: String,
}

impl EvalError {
    /// An error at `column`.
    pub fn new(column: usize, message: impl Into<String>) -> Self {
        EvalError {
            column,
            message: message.into(),
        }
    }
}

impl fmt::Display for EvalError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.message)
    }
}

/// Where an expression reads its parameters.
pub trait ParamSource {
    /// Parameter `#index` (already checked to be a whole number).
    ///
    /// # Errors
    /// A message when the number is out of range or cannot be read now.
    fn numbered(&self, index: i64) -> Result<f64, String>;
    /// Parameter `#<name>`.
    ///
    /// # Errors
    /// A message when it is not defined.
    fn named(&self, name: &str) -> Result<f64, String>;
    /// Whether `#<name>` is defined.
    fn exists(&self, name: &str) -> bool;
    /// Whether the Fanuc dialect's rules apply (vacant values, bitwise logic).
    fn fanuc(&self) -> bool;
}

/// The whole number an index or count expression stands for, as LinuxCNC's
/// `read_integer_value` takes it: within 0.0001 of an integer.
///
/// # Errors
/// A message when `value` is not that close to an integer.
pub fn integer(value: f64) -> Result<i64, String> {
    if !value.is_finite() || value.abs() > 1e15 {
        return Err(format!("expected a whole number, found {value}"));
    }
    let floor = value.floor();
    let frac = value - floor;
    if frac > 0.9999 {
        Ok(floor as i64 + 1)
    } else if frac > 0.0001 {
        Err(format!("expected a whole number, found {value}"))
    } else {
        Ok(floor as i64)
    }
}

impl Expr {
    /// The value of the expression; NaN only for a vacant Fanuc value.
    ///
    /// # Errors
    /// Domain errors, undefined parameters and non-finite results, at their column.
    pub fn eval(&self, params: &dyn ParamSource) -> Result<f64, EvalError> {
        match self {
            Expr::Num(v) => Ok(*v),
            Expr::Param { index, column } => {
                let raw = index.eval(params)?;
                let i = integer(raw).map_err(|m| EvalError::new(*column, m))?;
                params.numbered(i).map_err(|m| EvalError::new(*column, m))
            }
            Expr::Named { name, column } => {
                params.named(name).map_err(|m| EvalError::new(*column, m))
            }
            Expr::Exists(name) => Ok(f64::from(u8::from(params.exists(name)))),
            Expr::Neg(e) => {
                let v = e.eval(params)?;
                Ok(if v.is_nan() { v } else { -v })
            }
            Expr::Unary { func, arg, column } => {
                let v = vacant_zero(arg.eval(params)?);
                finite(
                    unary(*func, v).map_err(|m| EvalError::new(*column, m))?,
                    *column,
                )
            }
            Expr::Atan(y, x) => {
                let y = vacant_zero(y.eval(params)?);
                let x = vacant_zero(x.eval(params)?);
                Ok(y.atan2(x).to_degrees())
            }
            Expr::Binary {
                op,
                left,
                right,
                column,
            } => {
                let a = left.eval(params)?;
                let b = right.eval(params)?;
                let v =
                    binary(*op, a, b, params.fanuc()).map_err(|m| EvalError::new(*column, m))?;
                finite(v, *column)
            }
        }
    }
}

fn vacant_zero(v: f64) -> f64 {
    if v.is_nan() { 0.0 } else { v }
}

fn finite(v: f64, column: usize) -> Result<f64, EvalError> {
    if v.is_nan() {
        Err(EvalError::new(
            column,
            "calculation resulted in 'not a number'",
        ))
    } else if v.is_infinite() {
        Err(EvalError::new(column, "calculation resulted in 'infinity'"))
    } else {
        Ok(v)
    }
}

fn unary(func: Func, v: f64) -> Result<f64, String> {
    Ok(match func {
        Func::Abs => v.abs(),
        Func::Acos | Func::Asin if !(-1.0..=1.0).contains(&v) => {
            let name = if func == Func::Acos { "acos" } else { "asin" };
            return Err(format!(
                "argument to {name} out of range: {v} (expected -1 to 1)"
            ));
        }
        Func::Acos => v.acos().to_degrees(),
        Func::Asin => v.asin().to_degrees(),
        Func::Cos => v.to_radians().cos(),
        Func::Sin => v.to_radians().sin(),
        Func::Tan => v.to_radians().tan(),
        Func::Exp => v.exp(),
        Func::Fix => v.floor(),
        Func::Fup => v.ceil(),
        Func::Ln if v <= 0.0 => {
            return Err(format!("zero or negative argument to ln: {v}"));
        }
        Func::Ln => v.ln(),
        Func::Round => (v + if v < 0.0 { -0.5 } else { 0.5 }).trunc(),
        Func::Sqrt if v < 0.0 => return Err(format!("negative argument to sqrt: {v}")),
        Func::Sqrt => v.sqrt(),
        Func::Adp => v,
    })
}

fn truth(v: bool) -> f64 {
    f64::from(u8::from(v))
}

fn binary(op: Op, a: f64, b: f64, fanuc: bool) -> Result<f64, String> {
    if matches!(op, Op::Eq | Op::Ne) && (a.is_nan() || b.is_nan()) {
        let equal = a.is_nan() && b.is_nan();
        return Ok(truth(equal == (op == Op::Eq)));
    }
    let (a, b) = (vacant_zero(a), vacant_zero(b));
    Ok(match op {
        Op::Pow if a < 0.0 && b.floor() != b => {
            return Err(format!(
                "attempt to raise negative {a} to non-integer power {b}"
            ));
        }
        Op::Pow => a.powf(b),
        Op::Mul => a * b,
        Op::Div if b == 0.0 => return Err("attempt to divide by zero".into()),
        Op::Div => a / b,
        Op::Mod => {
            let r = a % b;
            if r < 0.0 { r + b.abs() } else { r }
        }
        Op::Add => a + b,
        Op::Sub => a - b,
        Op::Eq => truth((a - b).abs() < TOLERANCE_EQUAL),
        Op::Ne => truth((a - b).abs() >= TOLERANCE_EQUAL),
        Op::Gt => truth(a > b),
        Op::Ge => truth(a >= b),
        Op::Lt => truth(a < b),
        Op::Le => truth(a <= b),
        Op::And | Op::Or | Op::Xor if fanuc => bitwise(op, a, b)?,
        Op::And => truth(a != 0.0 && b != 0.0),
        Op::Or => truth(a != 0.0 || b != 0.0),
        Op::Xor => truth((a != 0.0) != (b != 0.0)),
    })
}

/// Fanuc's `and or xor`: bitwise on whole numbers.
fn bitwise(op: Op, a: f64, b: f64) -> Result<f64, String> {
    let (a, b) = (integer(a)?, integer(b)?);
    let v = match op {
        Op::And => a & b,
        Op::Or => a | b,
        _ => a ^ b,
    };
    Ok(v as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn integers_within_linuxcnc_slack() {
        assert_eq!(integer(3.00005), Ok(3));
        assert_eq!(integer(2.99995), Ok(3));
        assert!(integer(2.5).is_err());
        assert_eq!(integer(-1.0), Ok(-1));
        assert!(integer(f64::INFINITY).is_err());
    }

    #[test]
    fn operators_as_linuxcnc() {
        let f = |op, a, b| binary(op, a, b, false).unwrap();
        assert_eq!(f(Op::Mod, -7.0, 3.0), 2.0);
        assert_eq!(f(Op::Mod, 7.0, -3.0), 1.0);
        assert_eq!(f(Op::Eq, 1.0, 1.00005), 1.0);
        assert_eq!(f(Op::Ne, 1.0, 1.0002), 1.0);
        assert_eq!(f(Op::Xor, 2.0, 0.0), 1.0);
        assert!(binary(Op::Div, 1.0, 0.0, false).is_err());
        assert!(binary(Op::Pow, -2.0, 0.5, false).is_err());
        assert_eq!(f(Op::Pow, -2.0, 3.0), -8.0);
        assert_eq!(binary(Op::Or, 5.0, 2.0, true).unwrap(), 7.0);
        // Fanuc vacant values
        assert_eq!(binary(Op::Eq, f64::NAN, 0.0, true).unwrap(), 0.0);
        assert_eq!(binary(Op::Eq, f64::NAN, f64::NAN, true).unwrap(), 1.0);
        assert_eq!(binary(Op::Add, f64::NAN, 2.0, true).unwrap(), 2.0);
    }

    #[test]
    fn functions_in_degrees() {
        assert!((unary(Func::Sin, 30.0).unwrap() - 0.5).abs() < 1e-15);
        assert!((unary(Func::Acos, 0.5).unwrap() - 60.0).abs() < 1e-12);
        assert_eq!(unary(Func::Round, -2.5).unwrap(), -3.0);
        assert_eq!(unary(Func::Round, 2.4999).unwrap(), 2.0);
        assert_eq!(unary(Func::Fix, -2.5).unwrap(), -3.0);
        assert_eq!(unary(Func::Fup, -2.5).unwrap(), -2.0);
        assert!(unary(Func::Ln, 0.0).is_err());
        assert!(unary(Func::Sqrt, -1.0).is_err());
        assert!(unary(Func::Asin, 1.5).is_err());
    }
}
