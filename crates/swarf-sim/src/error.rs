//! The error type of swarf-sim.

use thiserror::Error;

/// What can go wrong when building a stock, simulating a program or writing a report.
#[derive(Debug, Error, Clone, PartialEq)]
pub enum SimError {
    /// A numeric parameter is out of range (cell size <= 0, tolerance NaN, ...).
    #[error("{name} = {value}: expected {expected}")]
    InvalidParameter {
        /// The parameter as the user knows it (`--cell`, `stock allowance`, ...).
        name: String,
        /// The value given.
        value: f64,
        /// What was expected instead.
        expected: String,
    },
    /// The grid would need more memory than allowed.
    #[error(
        "a grid of {nx} x {ny} cells ({cells} cells at {cell} mm) needs {} of memory, more than \
         the {} allowed: use a larger cell size (--cell; about {} mm fits) or raise the limit \
         (--max-memory)",
        gib(*needed), gib(*limit), swarf_geom::domain::show((*suggested * 1000.0).ceil() / 1000.0)
    )]
    GridTooLarge {
        /// Cells along x.
        nx: usize,
        /// Cells along y.
        ny: usize,
        /// Total cells (`nx * ny`, saturating).
        cells: usize,
        /// Cell size asked for, mm.
        cell: f64,
        /// Bytes the grid and its companion arrays need.
        needed: u64,
        /// Bytes allowed.
        limit: u64,
        /// A cell size that fits in the limit, mm.
        suggested: f64,
    },
    /// The system cannot give the memory a grid needs.
    #[error(
        "a grid of {cell} mm cells needs {}, which this machine cannot give now: use a \
         larger cell size (--cell)",
        gib(*needed)
    )]
    NoMemory {
        /// Bytes needed.
        needed: u64,
        /// The cell size asked for, mm.
        cell: f64,
    },
    /// Sampling the motions within the tolerance asked would take too many samples.
    #[error(
        "{file}: {}sweeping within the sample tolerance would take {} samples, more than the {} \
         swarf takes{}: use a sample tolerance of at least {} mm (--sample-tol)",
        line.map_or(String::new(), |l| format!("line {l}: ")),
        swarf_geom::domain::show(samples.round()),
        swarf_geom::domain::show(*limit),
        if line.is_some() { " for one motion" } else { " for a program" },
        swarf_geom::domain::show(*suggested)
    )]
    TooManySamples {
        /// The program file.
        file: String,
        /// The motion's source line (None: the program as a whole).
        line: Option<usize>,
        /// Samples the tolerance asks for.
        samples: f64,
        /// The most allowed.
        limit: f64,
        /// A sample tolerance that fits, mm.
        suggested: f64,
    },
    /// A tilted motion takes the tool's tip below the floor
    /// ([`crate::sweep_budget::floor`]).
    #[error(
        "{file}: line {line}: the tilted tool's tip goes down to z = {}, below the floor \
         at z = {} (the design's lowest point less the tool's reach): such a motion cuts \
         through whatever holds the part; swarf refuses it rather than sample it",
        swarf_geom::domain::show(*tip),
        swarf_geom::domain::show(*floor)
    )]
    BelowFloor {
        /// The program file.
        file: String,
        /// The motion's source line.
        line: usize,
        /// The tip's lowest height on the motion, mm.
        tip: f64,
        /// The floor, mm.
        floor: f64,
    },
    /// There is nothing to build a grid over (an empty part, a degenerate box).
    #[error("{0}")]
    Empty(String),
    /// A program or its tool cannot be simulated.
    #[error("{0}")]
    Unsupported(String),
    /// Writing a report or picture failed.
    #[error("{path}: {message}")]
    Write {
        /// The file.
        path: String,
        /// What went wrong.
        message: String,
    },
}

impl SimError {
    /// Checks that `value` is finite and strictly positive.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] naming `name` otherwise.
    pub fn check_positive(name: &str, value: f64) -> Result<f64, SimError> {
        if value.is_finite() && value > 0.0 {
            Ok(value)
        } else {
            Err(SimError::InvalidParameter {
                name: name.into(),
                value,
                expected: "a finite number > 0".into(),
            })
        }
    }

    /// Checks that `value` is finite and not negative.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] naming `name` otherwise.
    pub fn check_non_negative(name: &str, value: f64) -> Result<f64, SimError> {
        if value.is_finite() && value >= 0.0 {
            Ok(value)
        } else {
            Err(SimError::InvalidParameter {
                name: name.into(),
                value,
                expected: "a finite number >= 0".into(),
            })
        }
    }
}

/// Bytes as GiB or MiB text.
pub(crate) fn gib(bytes: u64) -> String {
    let b = bytes as f64;
    if b >= (1u64 << 30) as f64 {
        format!("{:.2} GiB", b / (1u64 << 30) as f64)
    } else {
        format!("{:.1} MiB", b / (1u64 << 20) as f64)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_name_the_parameter_and_sizes() {
        let e = SimError::check_positive("--cell", -0.5).unwrap_err();
        assert_eq!(e.to_string(), "--cell = -0.5: expected a finite number > 0");
        assert!(SimError::check_positive("--cell", f64::NAN).is_err());
        assert_eq!(SimError::check_non_negative("a", 0.0), Ok(0.0));
        assert!(SimError::check_non_negative("a", -1e-9).is_err());
        let e = SimError::GridTooLarge {
            nx: 100_000,
            ny: 50_000,
            cells: 5_000_000_000,
            cell: 0.002,
            needed: 140 << 30,
            limit: 4 << 30,
            suggested: 0.0125,
        };
        let s = e.to_string();
        assert!(
            s.contains("140.00 GiB") && s.contains("4.00 GiB") && s.contains("0.013 mm"),
            "{s}"
        );
        assert_eq!(gib(3 << 20), "3.0 MiB");
    }
}
