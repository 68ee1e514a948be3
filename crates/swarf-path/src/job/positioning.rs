//! The `positioning` table of a five-axis job: how the tool is placed on the CC paths
//! of the strategy (thesis 000 §7.3). Plain data in degrees and mm; swarf-fiveaxis
//! (`swarf_fiveaxis::positioning`) carries it out.
//!
//! ```toml
//! positioning = { method = "inclined", alpha = 3, tilt = 0, sections = 1.0 }
//! positioning = { method = "gouge-free", max_alpha = 25, sections = 1.0, max_rate = 0.5 }
//! ```

use serde::{Deserialize, Serialize};

fn default_sections() -> f64 {
    1.0
}

fn default_rate() -> f64 {
    0.5
}

/// How a job places the tool on its CC paths (degrees and mm; thesis 000 §7.3). Both
/// methods report the sectioning gouge check on planes `sections` mm apart, parallel
/// to the passes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
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
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err((
                    "positioning.sections",
                    format!("expected a section spacing > 0 mm, found {v}"),
                ))
            }
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
                    Some(t) if !(t.is_finite() && t >= 0.0) => Err((
                        "positioning.tolerance",
                        format!("expected a tolerance >= 0 mm, found {t}"),
                    )),
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::job::{Job, OutputFeedMode};

    const FIVE: &str = r#"
part = "builtin:die"
tool = "bull:d=38.1,r=6.35"
positioning = { method = "inclined", alpha = 3 }
[strategy]
kind = "iso-planar"
stepover = 3.5
angle = 60
[output]
machine = "builtin:xyzac-trunnion"
gcode = "die.ngc"
cl = "die.cl"
"#;

    #[test]
    fn positioning_tables_parse() {
        let job = Job::parse(FIVE, "die.toml").unwrap();
        assert_eq!(
            job.positioning,
            Some(Positioning::Inclined {
                alpha: 3.0,
                tilt: 0.0,
                sections: 1.0
            })
        );
        assert_eq!(job.strategy.stepover, Some(3.5));
        assert_eq!(
            job.output.machine.as_deref(),
            Some("builtin:xyzac-trunnion")
        );
        assert_eq!(job.output.feed_mode, OutputFeedMode::InverseTime);
        let auto = FIVE.replace(
            r#"{ method = "inclined", alpha = 3 }"#,
            r#"{ method = "gouge-free", max_alpha = 15, sections = 0.5 }"#,
        );
        let job = Job::parse(&auto, "die.toml").unwrap();
        assert_eq!(
            job.positioning,
            Some(Positioning::GougeFree {
                max_alpha: 15.0,
                sections: 0.5,
                tilt: 0.0,
                max_rate: 0.5,
                tolerance: None
            })
        );
        assert_eq!(job.positioning.map(|p| p.method()), Some("gouge-free"));
        let g94 = FIVE.replace(
            "gcode = ",
            "feed_mode = \"units-per-minute\"\ntool_length = 120\ngcode = ",
        );
        let job = Job::parse(&g94, "die.toml").unwrap();
        assert_eq!(job.output.feed_mode, OutputFeedMode::UnitsPerMinute);
        assert_eq!(job.output.tool_length, Some(120.0));
        // A machine without positioning (a vertical tool in five-axis words), and a
        // positioning with CL output only: both fine.
        let vertical = FIVE.replace("positioning = { method = \"inclined\", alpha = 3 }", "");
        assert!(
            Job::parse(&vertical, "die.toml")
                .unwrap()
                .positioning
                .is_none()
        );
        let cl_only = FIVE
            .replace("machine = \"builtin:xyzac-trunnion\"", "")
            .replace("gcode = \"die.ngc\"", "");
        assert!(Job::parse(&cl_only, "die.toml").is_ok());
    }

    #[test]
    fn bad_five_axis_jobs_name_the_field() {
        let inclined = r#"{ method = "inclined", alpha = 3 }"#;
        let cases = [
            (FIVE.replace("alpha = 3", "alpha = 95"), "positioning.alpha"),
            (FIVE.replace("alpha = 3", "alpha = -1"), "positioning.alpha"),
            (
                FIVE.replace("alpha = 3", "alpha = 3, tilt = 91"),
                "positioning.tilt",
            ),
            (
                FIVE.replace("alpha = 3", "alpha = 3, sections = 0"),
                "positioning.sections",
            ),
            (
                FIVE.replace(inclined, r#"{ method = "gouge-free", max_alpha = 0 }"#),
                "positioning.max_alpha",
            ),
            (
                FIVE.replace(
                    inclined,
                    r#"{ method = "gouge-free", max_alpha = 15, max_rate = -1 }"#,
                ),
                "positioning.max_rate",
            ),
            (
                FIVE.replace(
                    inclined,
                    r#"{ method = "gouge-free", max_alpha = 15, tolerance = -0.1 }"#,
                ),
                "positioning.tolerance",
            ),
            // Unknown method, unknown key, missing field: the TOML line.
            (FIVE.replace("\"inclined\"", "\"tilted\""), "line 4"),
            (FIVE.replace("alpha = 3", "alpha = 3, beta = 2"), "beta"),
            (
                FIVE.replace(inclined, r#"{ method = "gouge-free" }"#),
                "max_alpha",
            ),
            (
                FIVE.replace("machine = \"builtin:xyzac-trunnion\"", ""),
                "output.machine: a tilted tool path needs a machine file for G-code",
            ),
            (
                FIVE.replace("machine = \"builtin:xyzac-trunnion\"", "machine = \"\""),
                "output.machine",
            ),
            (
                FIVE.replace("gcode = ", "feed_mode = \"g93\"\ngcode = "),
                "line 11: unknown variant `g93`, expected `inverse-time`",
            ),
            (
                FIVE.replace("gcode = ", "tool_length = -5\ngcode = "),
                "output.tool_length",
            ),
            (
                FIVE.replace("stepover = 3.5", "stepover = 40"),
                "strategy.stepover",
            ),
            (
                FIVE.replace("stepover = 3.5", "stepover = 3.5\nscallop = 0.1"),
                "strategy.stepover",
            ),
            (
                FIVE.replace("iso-planar", "iso-scallop"),
                "strategy.stepover",
            ),
        ];
        for (text, want) in cases {
            let e = Job::parse(&text, "die.toml").unwrap_err().to_string();
            assert!(e.starts_with("die.toml: "), "{e}");
            assert!(e.contains(want), "want {want:?} in {e}");
        }
    }
}
