//! Number formatting for NC words and units at the output edge.
//!
//! Values always carry a decimal point: a Fanuc-style control reads `X10` as ten
//! least increments (0.010 mm), not 10 mm. Trailing zeros are trimmed and `-0` is
//! written as `0.`.

use serde::{Deserialize, Serialize};
use swarf_geom::units::MM_PER_INCH;

/// Length units of an output program.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
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
    fn inch_conversion() {
        assert_eq!(Units::Inch.from_mm(25.4), 1.0);
        assert_eq!(Units::Mm.from_mm(25.4), 25.4);
    }
}
