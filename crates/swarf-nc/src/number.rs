//! Number formatting for NC words and units at the output edge.
//!
//! Values always carry a decimal point: a Fanuc-style control reads `X10` as ten
//! least increments (0.010 mm), not 10 mm. Trailing zeros are trimmed and `-0` is
//! written as `0.`.

use crate::error::NcError;
use serde::{Deserialize, Serialize};
use swarf_geom::domain::{COORDINATE, Domain, RATE};
use swarf_geom::units::MM_PER_INCH;

/// Length units of an output program.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, schemars::JsonSchema,
)]
#[serde(rename_all = "lowercase")]
pub enum Units {
    /// Millimetres (G21).
    #[default]
    Mm,
    /// Inches (G20); lengths are divided by 25.4 on output.
    Inch,
}

impl Units {
    /// Converts a length in mm to these units.
    pub fn from_mm(self, mm: f64) -> f64 {
        match self {
            Units::Mm => mm,
            Units::Inch => mm / MM_PER_INCH,
        }
    }

    /// Decimal places written for lengths (0.1 micrometre in mm, 10 micro-inches).
    pub fn decimals(self) -> usize {
        match self {
            Units::Mm => 4,
            Units::Inch => 5,
        }
    }
}

/// `value` rounded to `decimals` places, with a decimal point, trailing zeros trimmed.
///
/// ```
/// use swarf_nc::number::format_decimal;
/// assert_eq!(format_decimal(10.0, 4), "10.");
/// assert_eq!(format_decimal(-0.00001, 4), "0.");
/// assert_eq!(format_decimal(2.50004, 4), "2.5");
/// ```
pub fn format_decimal(value: f64, decimals: usize) -> String {
    let mut s = format!("{value:.decimals$}");
    if s.contains('.') {
        let trimmed = s.trim_end_matches('0').len();
        s.truncate(trimmed);
    } else {
        s.push('.');
    }
    if s.starts_with("-") && s[1..].chars().all(|c| c == '0' || c == '.') {
        s.remove(0);
    }
    s
}

/// `mm` when it can be written as a coordinate: finite and within
/// [`COORDINATE`] (move `index`, value `what`, for the error).
///
/// # Errors
/// [`NcError::NonFinite`] for NaN and infinity, [`NcError::OutOfDomain`] beyond the
/// domain.
pub fn writable_length(index: usize, what: &'static str, mm: f64) -> Result<f64, NcError> {
    writable(index, what, mm, COORDINATE)
}

/// `mm_per_min` when it can be written as a feed rate: finite and within [`RATE`].
///
/// # Errors
/// As [`writable_length`].
pub fn writable_rate(index: usize, what: &'static str, mm_per_min: f64) -> Result<f64, NcError> {
    writable(index, what, mm_per_min, RATE)
}

/// `rpm` when it can be written as a spindle speed: finite, from 0 to 1e6 rpm.
///
/// # Errors
/// [`NcError::InvalidOption`] naming `spindle`.
pub fn writable_spindle(rpm: f64) -> Result<f64, NcError> {
    if rpm.is_finite() && (0.0..=1e6).contains(&rpm) {
        Ok(rpm)
    } else {
        Err(NcError::InvalidOption {
            field: "spindle",
            message: format!("expected a speed from 0 to 1e6 rpm, found {rpm}"),
        })
    }
}

fn writable(index: usize, what: &'static str, v: f64, domain: Domain) -> Result<f64, NcError> {
    if !v.is_finite() {
        return Err(NcError::NonFinite { index, what });
    }
    domain.check(v).map_err(|message| NcError::OutOfDomain {
        index,
        what,
        message,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimals_are_trimmed_and_marked() {
        assert_eq!(format_decimal(0.0, 4), "0.");
        assert_eq!(format_decimal(0.25, 4), "0.25");
        assert_eq!(format_decimal(-0.25, 4), "-0.25");
        assert_eq!(format_decimal(123.45678, 4), "123.4568");
        assert_eq!(format_decimal(-3.0, 3), "-3.");
        assert_eq!(format_decimal(1e-9, 4), "0.");
    }

    #[test]
    fn only_finite_values_within_their_domains_are_writable() {
        assert_eq!(writable_length(0, "x", -2.5), Ok(-2.5));
        assert!(matches!(
            writable_length(3, "x", f64::NAN),
            Err(NcError::NonFinite { index: 3, .. })
        ));
        let e = writable_length(4, "CL point", 1e300)
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("move 4: CL point: expected a coordinate"),
            "{e}"
        );
        assert!(writable_rate(0, "feed", 0.0).is_err());
        assert_eq!(writable_rate(0, "feed", 1200.0), Ok(1200.0));
    }

    #[test]
    fn inch_conversion() {
        assert_eq!(Units::Inch.from_mm(25.4), 1.0);
        assert_eq!(Units::Mm.from_mm(25.4), 25.4);
    }
}
