//! The stated domains of what a user gives swarf: every coordinate, length,
//! tolerance, cell, rate and count read from a file or the command line is checked
//! against one of these where it is read, and a value outside is refused with the
//! field's name, the value, the range and the nearest value that fits. Keeping the
//! inputs in these ranges is what keeps the work bounded and every computed number
//! finite (a coordinate of 1e308 mm makes lengths of `inf`; a tolerance of 5e-324 mm
//! makes a sample count that cannot be allocated).
//!
//! [`show`] writes a number as a person reads it in a message, [`excerpt`]
//! shortens a token quoted in a message, and [`line_of`] and [`at_line`] place a
//! message on a line of the text it is about.

use std::fmt;

/// A closed range of accepted values, with its unit and what the values are.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Domain {
    /// Smallest accepted value.
    pub min: f64,
    /// Largest accepted value.
    pub max: f64,
    /// The unit, as written after a value (`mm`, `mm/min`, or empty).
    pub unit: &'static str,
    /// What the values are (`a length`, `a tolerance` ...).
    pub what: &'static str,
}

/// Coordinates of parts, meshes, points and programs: within 1 km of the origin, mm.
pub const COORDINATE: Domain = Domain::new(-1e6, 1e6, "mm", "a coordinate");
/// Machining tolerances (chordal, gouge, excess, section spacing bounds), mm.
pub const TOLERANCE: Domain = Domain::new(1e-5, 10.0, "mm", "a tolerance");
/// Scallop heights, mm.
pub const SCALLOP: Domain = Domain::new(1e-4, 100.0, "mm", "a scallop height");
/// Tool diameters, mm.
pub const TOOL_DIAMETER: Domain = Domain::new(0.01, 1000.0, "mm", "a tool diameter");
/// Tool (flute) lengths and tool lengths from the gauge line, mm.
pub const TOOL_LENGTH: Domain = Domain::new(0.01, 2000.0, "mm", "a tool length");
/// Simulation cells, mm.
pub const CELL: Domain = Domain::new(1e-3, 100.0, "mm", "a cell size");
/// Distances that bound sampling (sample tolerances, sampling steps), mm.
pub const SAMPLE: Domain = Domain::new(1e-4, 100.0, "mm", "a sampling distance");
/// Steps and spacings of tool paths (stepovers, section spacings, drop steps), mm.
pub const STEP: Domain = Domain::new(1e-3, 1000.0, "mm", "a step");
/// Feed and rapid rates, mm/min.
pub const RATE: Domain = Domain::new(1e-3, 1e6, "mm/min", "a rate");
/// Allowances (stock above the design, material left), mm.
pub const ALLOWANCE: Domain = Domain::new(0.0, 1000.0, "mm", "an allowance");
/// Worker threads.
pub const THREADS: Domain = Domain::new(1.0, 1024.0, "", "a thread count");

impl Domain {
    /// A domain from `min` to `max` (both accepted).
    pub const fn new(min: f64, max: f64, unit: &'static str, what: &'static str) -> Self {
        Domain {
            min,
            max,
            unit,
            what,
        }
    }

    /// Whether `value` is in the domain (finite and within the bounds).
    pub fn contains(&self, value: f64) -> bool {
        value.is_finite() && value >= self.min && value <= self.max
    }

    /// `value` when it is in the domain.
    ///
    /// # Errors
    /// A message saying what was expected, what was found and the nearest value that
    /// fits (for callers to prefix with the field's name).
    pub fn check(&self, value: f64) -> Result<f64, String> {
        if self.contains(value) {
            return Ok(value);
        }
        let nearest = if value.is_nan() {
            String::new()
        } else {
            format!(
                " (the nearest that fits: {})",
                show(value.clamp(self.min, self.max))
            )
        };
        Err(format!("expected {self}, found {}{nearest}", show(value)))
    }

    /// [`Domain::check`] with the message prefixed by the field's name
    /// (`--tol: expected a tolerance from 1e-5 to 10 mm, found 0`).
    ///
    /// # Errors
    /// As [`Domain::check`].
    pub fn check_named(&self, name: &str, value: f64) -> Result<f64, String> {
        self.check(value).map_err(|m| format!("{name}: {m}"))
    }
}

impl fmt::Display for Domain {
    /// `a tolerance from 1e-5 to 10 mm`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let unit = if self.unit.is_empty() {
            String::new()
        } else {
            format!(" {}", self.unit)
        };
        write!(
            f,
            "{} from {} to {}{unit}",
            self.what,
            show(self.min),
            show(self.max)
        )
    }
}

/// Whether every coordinate of `p` is in [`COORDINATE`]: a mesh vertex outside it
/// (NaN, infinite, or farther than 1 km: an exporter's garbage) makes its triangles
/// unusable, and they are skipped and reported like those with NaN corners.
pub fn usable_point(p: &crate::Point3) -> bool {
    p.coords.iter().all(|&c| COORDINATE.contains(c))
}

/// 1-based line of byte `offset` in `text` (offsets past the end give the last line).
///
/// ```
/// use swarf_geom::domain::line_of;
/// assert_eq!(line_of("a = 1\nb = 2\n", 6), 2);
/// ```
pub fn line_of(text: &str, offset: usize) -> usize {
    let end = offset.min(text.len());
    text.as_bytes()[..end]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// A parser's `message` about `text` as "line N: message" when it knows the byte
/// `offset` it is about (readers of TOML files prefix the file name themselves).
pub fn at_line(text: &str, offset: Option<usize>, message: &str) -> String {
    let message = message.trim();
    match offset {
        Some(offset) => format!("line {}: {message}", line_of(text, offset)),
        None => message.to_string(),
    }
}

/// `value` as a person reads it: the shortest decimal for ordinary magnitudes,
/// scientific notation for very large or very small ones (`5e-324`, not 324 zeros).
///
/// ```
/// use swarf_geom::domain::show;
/// assert_eq!(show(0.25), "0.25");
/// assert_eq!(show(5e-324), "5e-324");
/// assert_eq!(show(1e308), "1e308");
/// assert_eq!(show(f64::INFINITY), "inf");
/// ```
pub fn show(value: f64) -> String {
    let a = value.abs();
    if value == 0.0 || !value.is_finite() || (1e-4..1e12).contains(&a) {
        format!("{value}")
    } else {
        format!("{value:e}")
    }
}

/// `text` on one line, at most `max` characters (`...` where it is cut), for
/// quoting what was found in a message.
///
/// ```
/// use swarf_geom::domain::excerpt;
/// assert_eq!(excerpt("[1,\n  2]", 40), "[1, 2]");
/// assert_eq!(excerpt("abcdefghij", 6), "abc...");
/// ```
pub fn excerpt(text: &str, max: usize) -> String {
    let one_line: String = text
        .chars()
        .take(max.saturating_mul(4).max(64))
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    let one_line = one_line.split_whitespace().collect::<Vec<_>>().join(" ");
    if one_line.chars().count() <= max && text.chars().nth(max.saturating_mul(4).max(64)).is_none()
    {
        one_line
    } else {
        let cut: String = one_line.chars().take(max.saturating_sub(3)).collect();
        format!("{cut}...")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_name_the_range_and_the_nearest_value() {
        assert_eq!(TOLERANCE.check(0.01), Ok(0.01));
        let e = TOLERANCE.check(5e-324).unwrap_err();
        assert_eq!(
            e,
            "expected a tolerance from 1e-5 to 10 mm, found 5e-324 (the nearest that fits: 1e-5)"
        );
        let e = CELL.check(f64::NAN).unwrap_err();
        assert_eq!(e, "expected a cell size from 0.001 to 100 mm, found NaN");
        assert!(COORDINATE.check(1e308).unwrap_err().contains("1000000"));
        assert!(
            THREADS
                .check(100_000.0)
                .unwrap_err()
                .contains("a thread count from 1 to 1024,")
        );
        assert!(!TOOL_DIAMETER.contains(f64::INFINITY));
    }

    #[test]
    fn long_tokens_are_cut() {
        let token = "9".repeat(10_000_000);
        let e = excerpt(&token, 40);
        assert_eq!(e.len(), 40);
        assert!(e.ends_with("..."));
    }
}
