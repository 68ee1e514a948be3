//! Pose CSV (what [`crate::write_pose_csv`] writes) into motions.
//!
//! The first line that is not blank and not a `#` comment is the header, `x,y,z,i,j,k`
//! or `x,y,z` (any case, spaces allowed). Each following row is one pose: the tip
//! `(x, y, z)` and, with six columns, the tool axis (normalised; `+Z` with three).
//! The first pose is the start; every later pose is reached by a straight feed move
//! from the one before, so the file is one continuous cut.
//!
//! Comment lines set what the format does not carry: `# feed=300` the feed in mm/min
//! for the rows that follow (without it feeds are 0, "unknown"), and
//! `# units=inch` (or `mm`, the default) the length unit of the rows that follow
//! (a `feed=` after `units=inch` is in inches per minute). A comment starting with
//! `pass` (`# pass 3`) starts a new pass: the tool leaves the material between
//! passes, so no motion joins the last pose before it to the first pose after it.
//! Other comments are ignored.

use crate::error::NcError;
use crate::read::gcode::check_text;
use crate::read::warnings::Warnings;
use swarf_geom::units::MM_PER_INCH;
use swarf_geom::{Point3, Vec3};
use swarf_tool::Pose;
use swarf_toolpath::program::{Diagnostic, Motion, MotionKind, Program};

/// Reads pose CSV text.
///
/// A malformed row stops the reading: the result is `Ok` with the motions before it
/// and [`Program::stopped`] set.
///
/// # Units
/// mm (or inches after `# units=inch`, converted), feeds mm/min.
///
/// # Errors
/// [`NcError::Unreadable`] for binary data and for a first line that is not the
/// header `x,y,z,i,j,k` or `x,y,z`.
///
/// # Example
/// ```
/// use swarf_nc::read::parse_pose_csv;
/// let p = parse_pose_csv("# feed=250\nx,y,z\n0,0,0\n3,4,0\n", "p.csv").unwrap();
/// assert_eq!(p.motions.len(), 1);
/// assert_eq!((p.motions[0].length(), p.motions[0].feed), (5.0, 250.0));
/// ```
pub fn parse_pose_csv(text: &str, source: &str) -> Result<Program, NcError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    check_text(text, source)?;
    let mut program = Program::new(source);
    let mut state = CsvState {
        columns: 0,
        scale: 1.0,
        feed: 0.0,
        pose: None,
        motions: Vec::new(),
        warnings: Warnings::default(),
    };
    for (i, raw) in text.lines().enumerate() {
        let line = i + 1;
        let trimmed = raw.trim();
        if trimmed.is_empty() {
            continue;
        }
        let result = if let Some(comment) = trimmed.strip_prefix('#') {
            state.comment(comment, line, raw)
        } else if state.columns == 0 {
            state.header(trimmed, line, source)?;
            Ok(())
        } else {
            state.row(raw, line)
        };
        if let Err(d) = result {
            program.stopped = Some(d);
            break;
        }
    }
    if state.columns == 0 && program.stopped.is_none() {
        return Err(header_error(
            source,
            1,
            "empty file: expected the header x,y,z,i,j,k or x,y,z",
        ));
    }
    program.motions = state.motions;
    program.warnings = state.warnings.finish();
    program.check_domain();
    Ok(program)
}

fn header_error(source: &str, line: usize, message: &str) -> NcError {
    NcError::Unreadable {
        file: source.to_string(),
        line,
        column: 1,
        message: message.to_string(),
    }
}

struct CsvState {
    /// 3 or 6 once the header is read.
    columns: usize,
    /// mm per file unit.
    scale: f64,
    /// mm/min.
    feed: f64,
    pose: Option<Pose>,
    motions: Vec<Motion>,
    warnings: Warnings,
}

impl CsvState {
    fn header(&mut self, trimmed: &str, line: usize, source: &str) -> Result<(), NcError> {
        let names: Vec<String> = trimmed
            .split(',')
            .map(|s| s.trim().to_ascii_lowercase())
            .collect();
        self.columns = match names.join(",").as_str() {
            "x,y,z,i,j,k" => 6,
            "x,y,z" => 3,
            _ => {
                return Err(header_error(
                    source,
                    line,
                    &format!("expected the header x,y,z,i,j,k or x,y,z, found '{trimmed}'"),
                ));
            }
        };
        Ok(())
    }

    /// `# key=value` settings; other comments are ignored.
    fn comment(&mut self, comment: &str, line: usize, raw: &str) -> Result<(), Diagnostic> {
        if comment.trim().to_ascii_lowercase().starts_with("pass") {
            self.pose = None;
            return Ok(());
        }
        let Some((key, value)) = comment.split_once('=') else {
            return Ok(());
        };
        let column = raw.find('=').map_or(1, |b| raw[..b].chars().count() + 2);
        let value = value.trim();
        match key.trim().to_ascii_lowercase().as_str() {
            "feed" => {
                let rate = swarf_geom::domain::RATE;
                let feed = value
                    .parse()
                    .ok()
                    .map(|f: f64| f * self.scale)
                    .filter(|&f| rate.contains(f))
                    .ok_or_else(|| {
                        let shown = swarf_geom::domain::excerpt(value, 40);
                        Diagnostic::new(
                            line,
                            column,
                            format!("feed: expected {rate}, found '{shown}'"),
                        )
                    })?;
                self.feed = feed;
            }
            "units" => {
                self.scale = match value.to_ascii_lowercase().as_str() {
                    "mm" => 1.0,
                    "inch" | "in" | "inches" => MM_PER_INCH,
                    _ => {
                        return Err(Diagnostic::new(
                            line,
                            column,
                            format!("units: expected mm or inch, found '{value}'"),
                        ));
                    }
                };
            }
            other => self.warnings.push(Diagnostic::new(
                line,
                1,
                format!("comment setting '{other}' ignored"),
            )),
        }
        Ok(())
    }

    fn row(&mut self, raw: &str, line: usize) -> Result<(), Diagnostic> {
        let mut values = Vec::with_capacity(6);
        let mut column = 1;
        let fields: Vec<&str> = raw.split(',').collect();
        if fields.len() != self.columns {
            return Err(Diagnostic::new(
                line,
                1,
                format!(
                    "{} values in the row, expected {}",
                    fields.len(),
                    self.columns
                ),
            ));
        }
        for field in fields {
            let lead = field.chars().take_while(|c| c.is_whitespace()).count();
            let text = field.trim();
            let value = text
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| {
                    Diagnostic::new(
                        line,
                        column + lead,
                        format!("expected a number, found '{text}'"),
                    )
                })?;
            values.push(value);
            column += field.chars().count() + 1;
        }
        let s = self.scale;
        let cl = Point3::new(values[0] * s, values[1] * s, values[2] * s);
        let axis = if self.columns == 6 {
            Vec3::new(values[3], values[4], values[5])
                .try_normalize(swarf_geom::tol::LENGTH_EPS)
                .ok_or_else(|| Diagnostic::new(line, 1, "tool axis (i, j, k) is zero"))?
        } else {
            Vec3::z()
        };
        let to = Pose { cl, axis };
        if let Some(from) = self.pose.replace(to).filter(|from| *from != to) {
            self.motions.push(Motion {
                kind: MotionKind::Linear,
                start: from,
                end: to,
                feed: self.feed,
                line,
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pass_comments_break_the_cut() {
        let text = "x,y,z\n# pass 0\n0,0,0\n1,0,0\n# pass 1\n1,5,0\n0,5,0\n";
        let p = parse_pose_csv(text, "t.csv").unwrap();
        assert_eq!(p.motions.len(), 2);
        assert_eq!(p.motions[1].start.cl, Point3::new(1.0, 5.0, 0.0));
    }

    #[test]
    fn header_rows_and_settings() {
        let text = "# units=inch\n# feed=10\nX, Y, Z, I, J, K\n0,0,1,0,0,2\n1,0,1,0,0,1\n";
        let p = parse_pose_csv(text, "t.csv").unwrap();
        assert_eq!(p.motions.len(), 1);
        let m = &p.motions[0];
        assert_eq!(m.start.axis, Vec3::z());
        assert_eq!(m.end.cl, Point3::new(25.4, 0.0, 25.4));
        assert_eq!(m.feed, 254.0);
        assert_eq!(m.line, 5);
    }

    #[test]
    fn errors() {
        let bad_header = parse_pose_csv("a,b,c\n1,2,3\n", "t.csv").unwrap_err();
        assert!(matches!(bad_header, NcError::Unreadable { line: 1, .. }));
        assert!(parse_pose_csv("\n# only\n", "t.csv").is_err());
        let p = parse_pose_csv("x,y,z\n0,0,0\n1, zz,0\n2,0,0\n", "t.csv").unwrap();
        let stop = p.stopped.unwrap();
        assert_eq!((stop.line, stop.column), (3, 4));
        assert!(p.motions.is_empty());
        let p = parse_pose_csv("x,y,z\n0,0,0\n1,0\n", "t.csv").unwrap();
        assert_eq!(p.stopped.map(|d| d.line), Some(3));
        let p = parse_pose_csv("# feed=-3\nx,y,z\n", "t.csv").unwrap();
        assert_eq!(p.stopped.map(|d| (d.line, d.column)), Some((1, 8)));
        // A feed so small that the time is not finite: outside the stated domain.
        let p = parse_pose_csv("# feed=2e-308\nx,y,z\n0,0,0\n1,0,0\n", "t.csv").unwrap();
        let stop = p.stopped.expect("refused");
        assert!(stop.message.contains("expected a rate"), "{}", stop.message);
    }
}
