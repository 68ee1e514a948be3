//! Free-format parameter data (IGES 5.3 sec. 2.2.3): fields separated by the
//! parameter delimiter and ended by the record delimiter; a string is Hollerith,
//! `nH` followed by exactly `n` characters (which may hold delimiters); reals may
//! use a `D` exponent (`1.0D-3`); an empty field takes the default. [`Params`]
//! reads one entity's fields by index, each error naming the entity (`DE n type T`)
//! and the parameter.

use super::{Iges, Problem};
use crate::error::IoError;

/// One parameter field.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Tok {
    /// An empty field (default value).
    Empty,
    /// A number as written (integer or real, `D` exponent not yet converted).
    Num(String),
    /// A Hollerith string's characters.
    Str(String),
}

/// The fields of `text` up to the record delimiter `rd`, split at `pd`.
///
/// # Errors
/// A message when a Hollerith count runs past the text or the record delimiter is
/// missing.
pub(crate) fn tokenize(text: &str, pd: char, rd: char) -> Result<Vec<Tok>, String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut k = 0;
    loop {
        while k < chars.len() && chars[k] == ' ' {
            k += 1;
        }
        let start = k;
        while k < chars.len() && chars[k].is_ascii_digit() {
            k += 1;
        }
        let tok = if k > start && k < chars.len() && chars[k] == 'H' {
            let n: usize = chars[start..k]
                .iter()
                .collect::<String>()
                .parse()
                .map_err(|_| "bad Hollerith count".to_string())?;
            if n >= chars.len() - k {
                return Err(format!(
                    "field {}: Hollerith string of {n} characters runs past the end of the entity",
                    out.len() + 1
                ));
            }
            let s: String = chars[k + 1..k + 1 + n].iter().collect();
            k += 1 + n;
            while k < chars.len() && chars[k] == ' ' {
                k += 1;
            }
            Tok::Str(s)
        } else {
            while k < chars.len() && chars[k] != pd && chars[k] != rd {
                k += 1;
            }
            let s: String = chars[start..k].iter().filter(|c| **c != ' ').collect();
            if s.is_empty() {
                Tok::Empty
            } else {
                Tok::Num(s)
            }
        };
        out.push(tok);
        match chars.get(k) {
            Some(c) if *c == rd => return Ok(out),
            Some(c) if *c == pd => k += 1,
            Some(c) => {
                return Err(format!(
                    "field {}: expected a delimiter after it, found {c:?}",
                    out.len()
                ));
            }
            None => {
                return Err(format!(
                    "no record delimiter {rd:?} at the end of the entity"
                ));
            }
        }
    }
}

/// A number field as f64: `D` exponents accepted, only finite values.
pub(crate) fn number(s: &str) -> Option<f64> {
    let ok = s
        .chars()
        .all(|c| c.is_ascii_digit() || matches!(c, '.' | '+' | '-' | 'E' | 'e' | 'D' | 'd'));
    if !ok {
        return None;
    }
    s.replace(['D', 'd'], "E")
        .parse::<f64>()
        .ok()
        .filter(|x| x.is_finite())
}

/// One entity's parameters.
pub(crate) struct Params {
    pub de: usize,
    pub ty: i64,
    pub toks: Vec<Tok>,
}

impl Params {
    /// Parameter `k` (1-based after the type) as a finite real.
    pub(crate) fn real(&self, g: &Iges, k: usize) -> Result<f64, IoError> {
        match self.toks.get(k) {
            Some(Tok::Num(s)) => number(s).ok_or_else(|| {
                g.err(
                    self.de,
                    format!("parameter {k}: expected a finite number, found {s:?}"),
                )
            }),
            Some(Tok::Empty) => Ok(0.0),
            Some(Tok::Str(s)) => Err(g.err(
                self.de,
                format!("parameter {k}: expected a number, found string {s:?}"),
            )),
            None => Err(g.err(
                self.de,
                format!(
                    "parameter {k}: missing; the entity has {} parameters",
                    self.toks.len().saturating_sub(1)
                ),
            )),
        }
    }

    /// Parameter `k` as an integer (a real with no fraction is accepted).
    pub(crate) fn int(&self, g: &Iges, k: usize) -> Result<i64, IoError> {
        let x = self.real(g, k)?;
        if x.fract() != 0.0 || x.abs() > 1e15 {
            return Err(g.err(
                self.de,
                format!("parameter {k}: expected an integer, found {x}"),
            ));
        }
        Ok(x as i64)
    }

    /// Parameter `k` as a count in `0..=max`.
    pub(crate) fn count(&self, g: &Iges, k: usize, max: usize) -> Result<usize, IoError> {
        let n = self.int(g, k)?;
        usize::try_from(n)
            .ok()
            .filter(|n| *n <= max)
            .ok_or_else(|| {
                g.err(
                    self.de,
                    format!("parameter {k}: expected a count from 0 to {max}, found {n}"),
                )
            })
    }

    /// Parameter `k` as a DE pointer (0 = none).
    pub(crate) fn ptr(&self, g: &Iges, k: usize) -> Result<usize, IoError> {
        let max = 2 * g.rec.entries.len();
        let n = self.int(g, k)?;
        usize::try_from(n)
            .ok()
            .filter(|n| *n == 0 || (*n % 2 == 1 && *n < max))
            .ok_or_else(|| {
                g.err(
                    self.de,
                    format!(
                        "parameter {k}: expected a DE pointer (odd, 1 to {max}) or 0, found {n}"
                    ),
                )
            })
    }

    /// Parameters `k..k + n` as reals (checked to exist before allocating).
    pub(crate) fn reals(&self, g: &Iges, k: usize, n: usize) -> Result<Vec<f64>, IoError> {
        if k + n > self.toks.len() {
            return Err(g.err(
                self.de,
                format!(
                    "expected {n} values from parameter {k}, the entity has {} parameters",
                    self.toks.len().saturating_sub(1)
                ),
            ));
        }
        (k..k + n).map(|i| self.real(g, i)).collect()
    }

    /// An unsupported-entity problem about this entity.
    pub(crate) fn unsupported(&self, why: impl Into<String>) -> Problem {
        Problem::Unsupported {
            de: self.de,
            ty: self.ty,
            why: why.into(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fields_hollerith_and_exponents() {
        let t = tokenize("126,3H,;a, 1.5D-3 ,,-2;junk", ',', ';').unwrap();
        assert_eq!(
            t,
            vec![
                Tok::Num("126".into()),
                Tok::Str(",;a".into()),
                Tok::Num("1.5D-3".into()),
                Tok::Empty,
                Tok::Num("-2".into())
            ]
        );
        assert_eq!(number("1.5D-3"), Some(1.5e-3));
        assert_eq!(number("1."), Some(1.0));
        assert_eq!(number("inf"), None);
        assert_eq!(number("1e400"), None);
        assert!(
            tokenize("5Hab", ',', ';')
                .unwrap_err()
                .contains("Hollerith")
        );
        assert!(
            tokenize("1,2", ',', ';')
                .unwrap_err()
                .contains("record delimiter")
        );
    }
}
