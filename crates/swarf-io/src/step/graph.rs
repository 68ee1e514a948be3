//! Typed access to the entity graph: every accessor names the file, the line, the
//! `#id`, the entity and the argument it could not read, and what it expected.

use super::parser::{Exchange, Value};
use crate::error::{At, IoError};

/// The parsed file and its name, for messages.
pub struct Graph<'a> {
    /// The instances.
    pub ex: &'a Exchange,
    /// The file, as given.
    pub file: &'a str,
}

/// One partial record of an instance (the whole of a simple instance).
#[derive(Clone, Copy)]
pub struct Ent<'a> {
    /// `#id`.
    pub id: u64,
    /// Entity name of this record.
    pub name: &'a str,
    /// Its arguments.
    pub args: &'a [Value],
    /// Line of the instance.
    pub line: usize,
    file: &'a str,
}

/// Short description of a value for messages.
fn describe(v: &Value) -> String {
    match v {
        Value::Ref(r) => format!("#{r}"),
        Value::Num(x) => format!("{x}"),
        Value::Str(s) => format!("'{s}'"),
        Value::Enum(e) => format!(".{e}."),
        Value::List(l) => format!("a list of {}", l.len()),
        Value::Typed(n, _) => format!("{n}(..)"),
        Value::Null => "$".into(),
        Value::Derived => "*".into(),
    }
}

impl<'a> Graph<'a> {
    /// An error at the file level.
    pub fn file_err(&self, msg: impl Into<String>) -> IoError {
        IoError::format(self.file, At::File, msg)
    }

    /// The partial records of `#id` (one for a simple instance).
    ///
    /// # Errors
    /// A dangling reference, naming `from` (the referring entity) when given.
    pub fn parts(&self, id: u64, from: Option<&Ent<'_>>) -> Result<Vec<Ent<'a>>, IoError> {
        let Some(inst) = self.ex.instances.get(&id) else {
            return Err(match from {
                Some(e) => e.err(format!("refers to #{id}, which the file does not define")),
                None => self.file_err(format!("#{id} is not defined")),
            });
        };
        Ok(inst
            .parts
            .iter()
            .map(|(n, a)| Ent {
                id,
                name: n,
                args: a,
                line: inst.line,
                file: self.file,
            })
            .collect())
    }

    /// `#id` as one record: the simple instance, or the partial named like one of
    /// `names` of a complex instance; `None` when neither.
    pub fn find(
        &self,
        id: u64,
        names: &[&str],
        from: &Ent<'_>,
    ) -> Result<Option<Ent<'a>>, IoError> {
        Ok(self
            .parts(id, Some(from))?
            .into_iter()
            .find(|e| names.contains(&e.name)))
    }

    /// `#id`, which must be one of `names`.
    ///
    /// # Errors
    /// Dangling, or another entity: names both.
    pub fn get(&self, id: u64, names: &[&str], from: &Ent<'_>) -> Result<Ent<'a>, IoError> {
        match self.find(id, names, from)? {
            Some(e) => Ok(e),
            None => {
                let p = self.parts(id, Some(from))?;
                let found: Vec<&str> = p.iter().map(|e| e.name).collect();
                Err(p[0].err(format!(
                    "expected {} (referred to by #{} {}), found {}",
                    names.join(" or "),
                    from.id,
                    from.name,
                    found.join(" ")
                )))
            }
        }
    }
}

impl<'a> Ent<'a> {
    /// An error naming this entity.
    pub fn err(&self, msg: impl Into<String>) -> IoError {
        IoError::format(
            self.file,
            At::Line(self.line),
            format!("#{} {}: {}", self.id, self.name, msg.into()),
        )
    }

    /// An error naming argument `i`.
    pub fn arg_err(&self, i: usize, expected: &str) -> IoError {
        let found = self
            .args
            .get(i)
            .map_or_else(|| "nothing".to_string(), describe);
        self.err(format!(
            "argument {}: expected {expected}, found {found}",
            i + 1
        ))
    }

    /// Argument `i`.
    pub fn arg(&self, i: usize, expected: &str) -> Result<&'a Value, IoError> {
        self.args.get(i).ok_or_else(|| {
            self.err(format!(
                "expected at least {} arguments ({expected} at {}), found {}",
                i + 1,
                i + 1,
                self.args.len()
            ))
        })
    }

    /// Argument `i` as a number (a typed measure such as `LENGTH_MEASURE(2.)` too).
    pub fn num(&self, i: usize) -> Result<f64, IoError> {
        match self.arg(i, "a number")? {
            Value::Num(x) => Ok(*x),
            Value::Typed(_, v) if matches!(v.as_slice(), [Value::Num(_)]) => match v[0] {
                Value::Num(x) => Ok(x),
                _ => Err(self.arg_err(i, "a number")),
            },
            _ => Err(self.arg_err(i, "a number")),
        }
    }

    /// Argument `i` as a non-negative integer.
    pub fn int(&self, i: usize) -> Result<usize, IoError> {
        let x = self.num(i)?;
        if x >= 0.0 && x.fract() == 0.0 && x < 1e9 {
            Ok(x as usize)
        } else {
            Err(self.arg_err(i, "a non-negative integer"))
        }
    }

    /// Argument `i` as a reference.
    pub fn refr(&self, i: usize) -> Result<u64, IoError> {
        match self.arg(i, "a reference")? {
            Value::Ref(r) => Ok(*r),
            _ => Err(self.arg_err(i, "a reference #id")),
        }
    }

    /// Argument `i` as a list.
    pub fn list(&self, i: usize) -> Result<&'a [Value], IoError> {
        match self.arg(i, "a list")? {
            Value::List(l) => Ok(l),
            _ => Err(self.arg_err(i, "a list")),
        }
    }

    /// Argument `i` as a list of references.
    pub fn refs(&self, i: usize) -> Result<Vec<u64>, IoError> {
        self.list(i)?
            .iter()
            .map(|v| match v {
                Value::Ref(r) => Ok(*r),
                _ => Err(self.arg_err(i, "a list of references")),
            })
            .collect()
    }

    /// Argument `i` as a list of numbers.
    pub fn nums(&self, i: usize) -> Result<Vec<f64>, IoError> {
        nums_of(self.list(i)?).ok_or_else(|| self.arg_err(i, "a list of numbers"))
    }

    /// Argument `i` as a boolean `.T.` / `.F.`.
    pub fn boolean(&self, i: usize) -> Result<bool, IoError> {
        match self.arg(i, "a boolean")? {
            Value::Enum(e) if e == "T" => Ok(true),
            Value::Enum(e) if e == "F" => Ok(false),
            _ => Err(self.arg_err(i, "a boolean .T. or .F.")),
        }
    }

    /// Argument `i` as a string (`$` = empty).
    pub fn string(&self, i: usize) -> Result<&'a str, IoError> {
        match self.arg(i, "a string")? {
            Value::Str(s) => Ok(s),
            Value::Null => Ok(""),
            _ => Err(self.arg_err(i, "a string")),
        }
    }
}

/// The numbers of a list, `None` if any item is not a number.
pub fn nums_of(l: &[Value]) -> Option<Vec<f64>> {
    l.iter()
        .map(|v| match v {
            Value::Num(x) => Some(*x),
            _ => None,
        })
        .collect()
}
