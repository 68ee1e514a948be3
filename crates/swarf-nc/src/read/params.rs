//! Numbered and global named parameters, as LinuxCNC keeps them
//! (`interp_namedparams.cc`, the RS274/NGC v3 parameter table).
//!
//! Numbered parameters run from `#1` to `#5601` (LinuxCNC's
//! `RS274NGC_MAX_PARAMETERS`), all 0 at the start unless a parameter file sets them
//! ([`Params::with_values`]). The ones that matter for motion: `#5161-#5169` and
//! `#5181-#5189` the G28 and G30 positions, `#5210` G92 applied, `#5211-#5219` the G92
//! offsets, `#5220` the coordinate system (1 = G54 ... 9 = G59.3), `#5221-#5230` G54
//! (X Y Z A B C U V W and the XY rotation R), then every 20 up to `#5381-#5390` for
//! G59.3; `#5400-#5410` the tool, `#5420-#5428` the current position. Offsets and the
//! stored positions are in the machine's units, not the program's (see
//! [`crate::read::GcodeReadOptions::machine_inch`]).
//!
//! Global named parameters (`#<_name>`) live here; local ones (`#<name>`) and
//! `#1-#30` of a subroutine belong to its frame ([`crate::read::flow`]).

use crate::error::NcError;
use std::collections::HashMap;

/// Reads a LinuxCNC parameter file (`.var`): one `number value` pair a line, blank
/// lines and anything after the two numbers ignored; `source` names the file in errors.
///
/// # Errors
/// [`NcError::Unreadable`] at a line whose first two fields are not a parameter number
/// from 1 to 5601 and a finite value.
pub fn parse_var_file(text: &str, source: &str) -> Result<Vec<(usize, f64)>, NcError> {
    let mut out = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let mut fields = line.split_whitespace();
        let Some(first) = fields.next() else {
            continue;
        };
        let err = |message: String| NcError::Unreadable {
            file: source.to_string(),
            line: i + 1,
            column: 1,
            message,
        };
        let number: usize = first
            .parse()
            .ok()
            .filter(|n| (1..PARAMETER_COUNT).contains(n))
            .ok_or_else(|| {
                err(format!(
                    "expected a parameter number from 1 to {}, found '{first}'",
                    PARAMETER_COUNT - 1
                ))
            })?;
        let value: f64 = fields
            .next()
            .and_then(|v| v.parse().ok())
            .filter(|v: &f64| v.is_finite())
            .ok_or_else(|| err(format!("parameter {number}: expected a finite value")))?;
        out.push((number, value));
    }
    Ok(out)
}

/// One past the largest parameter number: `#1` to `#5601`.
pub const PARAMETER_COUNT: usize = 5602;

/// Numbered parameters a program may read but not set: the current position and tool
/// (`#5400-#5428`, computed from the machine's state when read).
pub fn is_read_only(index: usize) -> bool {
    (5400..=5428).contains(&index) || index == 5399
}

/// The numbered and global named parameters.
#[derive(Debug, Clone)]
pub struct Params {
    numbered: Vec<f64>,
    globals: HashMap<Box<str>, f64>,
}

impl Default for Params {
    fn default() -> Self {
        Params {
            numbered: vec![0.0; PARAMETER_COUNT],
            globals: HashMap::new(),
        }
    }
}

impl Params {
    /// All zero but `values` (number, value); numbers out of range are left out.
    pub fn with_values(values: &[(usize, f64)]) -> Self {
        let mut p = Params::default();
        for &(i, v) in values {
            if (1..PARAMETER_COUNT).contains(&i) && v.is_finite() {
                p.numbered[i] = v;
            }
        }
        p
    }

    /// `#index`; `None` out of range.
    pub fn get(&self, index: usize) -> Option<f64> {
        (1..PARAMETER_COUNT)
            .contains(&index)
            .then(|| self.numbered[index])
    }

    /// The value at `index`, 0 out of range (for the machine's own reads).
    pub fn at(&self, index: usize) -> f64 {
        self.get(index).unwrap_or(0.0)
    }

    /// Sets `#index` (ignored out of range: callers check the range first).
    pub fn set(&mut self, index: usize, value: f64) {
        if (1..PARAMETER_COUNT).contains(&index) {
            self.numbered[index] = value;
        }
    }

    /// A global named parameter.
    pub fn global(&self, name: &str) -> Option<f64> {
        self.globals.get(name).copied()
    }

    /// Sets a global named parameter.
    pub fn set_global(&mut self, name: &str, value: f64) {
        if let Some(v) = self.globals.get_mut(name) {
            *v = value;
        } else {
            self.globals.insert(name.into(), value);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_and_values() {
        let mut p = Params::with_values(&[(5221, 10.0), (0, 1.0), (9999, 1.0)]);
        assert_eq!(p.get(5221), Some(10.0));
        assert_eq!(p.get(0), None);
        assert_eq!(p.get(PARAMETER_COUNT), None);
        p.set(1, 2.0);
        assert_eq!(p.at(1), 2.0);
        p.set_global("_a", 3.0);
        assert_eq!(p.global("_a"), Some(3.0));
        assert!(is_read_only(5420) && !is_read_only(5221));
    }

    #[test]
    fn var_files() {
        let v = parse_var_file("5161\t-0.5\n\n5220  1.000000\n", "a.var").unwrap();
        assert_eq!(v, vec![(5161, -0.5), (5220, 1.0)]);
        let e = parse_var_file("5161 x\n", "a.var").unwrap_err().to_string();
        assert!(e.starts_with("a.var:1:1:"), "{e}");
        assert!(parse_var_file("0 1\n", "a.var").is_err());
    }
}
