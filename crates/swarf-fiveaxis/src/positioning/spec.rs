//! The `positioning` table of a five-axis job: how the tool is placed on the CC paths
//! of the strategy (thesis 000 §7.3). Plain data in degrees and mm, as the job file
//! gives it; [`crate::positioning`] carries it out.
//!
//! ```toml
//! positioning = { method = "inclined", alpha = 3, tilt = 0, sections = 1.0 }
//! positioning = { method = "gouge-free", max_alpha = 25, sections = 1.0, max_rate = 0.5 }
//! ```

use serde::{Deserialize, Serialize};

fn default_sections() -> f64 {
    1.0
}

/// The default largest change of a gouge-free lead per mm of feed, degrees/mm
/// (also the rate at which holder avoidance may tilt an inclined path).
pub const DEFAULT_MAX_RATE: f64 = 0.5;

fn default_rate() -> f64 {
    DEFAULT_MAX_RATE
}

/// How a job places the tool on its CC paths (degrees and mm; thesis 000 §7.3). Both
/// methods report the sectioning gouge check on planes `sections` mm apart, parallel
/// to the passes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(tag = "method", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Positioning {
    /// A fixed lead angle for the whole path.
    Inclined {
        /// Lead angle, degrees.
        alpha: f64,
        /// Side tilt, degrees.
        #[serde(default)]
        tilt: f64,
        /// Section spacing of the gouge report, mm.
        #[serde(default = "default_sections")]
        sections: f64,
    },
    /// The smallest gouge-free lead at every point, smoothed.
    GougeFree {
        /// Largest lead allowed, degrees.
        max_alpha: f64,
        /// Section spacing, mm.
        #[serde(default = "default_sections")]
        sections: f64,
        /// Side tilt, degrees.
        #[serde(default)]
        tilt: f64,
        /// Largest change of the lead per mm of feed, degrees/mm.
        #[serde(default = "default_rate")]
        max_rate: f64,
        /// Gouge tolerance, mm (default: the job's strategy tolerance).
        #[serde(default)]
        tolerance: Option<f64>,
    },
}

impl Positioning {
    /// Checks the ranges the TOML types cannot express; the error names the field
    /// (`positioning.alpha`, ...) and says what was expected.
    ///
    /// # Errors
    /// `(field, message)` for the first value out of range.
    pub fn validate(&self) -> Result<(), (&'static str, String)> {
        let angle = |field: &'static str, v: f64, lo_open: bool| {
            let ok = v.is_finite() && v < 90.0 && if lo_open { v > 0.0 } else { v >= 0.0 };
            let range = if lo_open { "(0, 90)" } else { "[0, 90)" };
            if ok {
                Ok(())
            } else {
                Err((
                    field,
                    format!("expected an angle in {range} degrees, found {v}"),
                ))
            }
        };
        let spacing = |v: f64| {
            swarf_geom::domain::SAMPLE
                .check(v)
                .map(|_| ())
                .map_err(|m| ("positioning.sections", m))
        };
        match *self {
            Positioning::Inclined {
                alpha,
                tilt,
                sections,
            } => {
                angle("positioning.alpha", alpha, false)?;
                angle("positioning.tilt", tilt.abs(), false)?;
                spacing(sections)
            }
            Positioning::GougeFree {
                max_alpha,
                sections,
                tilt,
                max_rate,
                tolerance,
            } => {
                angle("positioning.max_alpha", max_alpha, true)?;
                angle("positioning.tilt", tilt.abs(), false)?;
                spacing(sections)?;
                if !(max_rate.is_finite() && max_rate > 0.0) {
                    return Err((
                        "positioning.max_rate",
                        format!("expected a rate > 0 degrees per mm, found {max_rate}"),
                    ));
                }
                match tolerance {
                    Some(t) if t != 0.0 => swarf_geom::domain::TOLERANCE
                        .check(t)
                        .map(|_| ())
                        .map_err(|m| ("positioning.tolerance", format!("{m} (or 0)"))),
                    _ => Ok(()),
                }
            }
        }
    }

    /// The method's name as the job file spells it.
    pub fn method(&self) -> &'static str {
        match self {
            Positioning::Inclined { .. } => "inclined",
            Positioning::GougeFree { .. } => "gouge-free",
        }
    }
}
