//! Free-format parameter data (IGES 5.3 sec. 2.2.3): fields separated by the
//! parameter delimiter and ended by the record delimiter; a string is Hollerith,
//! `nH` followed by exactly `n` characters (which may hold delimiters); reals may
//! use a `D` exponent (`1.0D-3`); an empty field takes the default.

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
