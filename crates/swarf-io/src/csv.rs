//! Numeric CSV of 2D points: one `x,y` per line.
//!
//! `#` starts a comment (whole line or after the values); blank lines are skipped; the
//! first non-comment line may be a header when none of its fields is a number. A
//! UTF-8 byte-order mark is ignored. Anything else that is not two finite numbers is
//! an error naming the line and quoting it.

use crate::error::{At, IoError, excerpt};
use std::path::Path;
use swarf_geom::domain::COORDINATE;

/// Longest quote of a bad line in an error, characters.
const EXCERPT: usize = 60;

/// Reads `x,y` points from a CSV file.
///
/// # Units
/// As written in the file (the caller knows; swarf uses mm).
///
/// # Errors
/// [`IoError::Io`] when the file cannot be read, [`IoError::Format`] with the line for
/// text that is not UTF-8 or a line that is not two finite numbers.
pub fn read_xy_points(path: &Path) -> Result<Vec<[f64; 2]>, IoError> {
    let bytes = crate::input::read_input(path)?;
    let file = path.display().to_string();
    let text = std::str::from_utf8(&bytes).map_err(|e| {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        IoError::format(&file, At::Line(line), "not UTF-8 text")
    })?;
    parse_xy_points(text, &file)
}

/// Parses `x,y` points from CSV text; `source` names it in errors.
///
/// # Errors
/// As [`read_xy_points`].
///
/// # Example
/// ```
/// let pts = swarf_io::parse_xy_points("x,y\n1,2\n# note\n3.5, -4 # last\n", "p.csv").unwrap();
/// assert_eq!(pts, vec![[1.0, 2.0], [3.5, -4.0]]);
/// let e = swarf_io::parse_xy_points("1,2\n3;4\n", "p.csv").unwrap_err();
/// assert_eq!(e.to_string(), "p.csv: line 2: expected two numbers `x,y`, found `3;4`");
/// ```
pub fn parse_xy_points(text: &str, source: &str) -> Result<Vec<[f64; 2]>, IoError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut points = Vec::new();
    let mut first = true;
    for (i, raw) in text.lines().enumerate() {
        let line = raw.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        let fields: Vec<&str> = line.split(',').map(str::trim).collect();
        let numbers: Vec<Option<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
        let header = first && numbers.iter().all(Option::is_none);
        first = false;
        if header {
            continue;
        }
        let bad = |what: &str| {
            IoError::format(
                source,
                At::Line(i + 1),
                format!("expected {what}, found `{}`", excerpt(line, EXCERPT)),
            )
        };
        match numbers.as_slice() {
            [Some(x), Some(y)] if x.is_finite() && y.is_finite() => {
                for v in [*x, *y] {
                    COORDINATE.check(v).map_err(|m| {
                        IoError::format(source, At::Line(i + 1), format!("x,y: {m}"))
                    })?;
                }
                points.push([*x, *y]);
            }
            [Some(_), Some(_)] => return Err(bad("two finite numbers `x,y`")),
            _ => return Err(bad("two numbers `x,y`")),
        }
    }
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testutil::scratch_dir;

    fn err(text: &str) -> String {
        parse_xy_points(text, "p.csv").unwrap_err().to_string()
    }

    #[test]
    fn header_comments_blank_lines_and_bom() {
        let text = "\u{feff}# made by hand\n\n x , y \n1,2\r\n  -3.5e1 ,4 # inline\n\n";
        assert_eq!(
            parse_xy_points(text, "p.csv").unwrap(),
            vec![[1.0, 2.0], [-35.0, 4.0]]
        );
        assert_eq!(parse_xy_points("1,2\n", "p.csv").unwrap(), vec![[1.0, 2.0]]);
        assert!(parse_xy_points("", "p.csv").unwrap().is_empty());
        assert!(parse_xy_points("a,b\n", "p.csv").unwrap().is_empty());
    }

    #[test]
    fn bad_lines_are_named() {
        assert_eq!(
            err("x,y\n1,2\nx,y\n"),
            "p.csv: line 3: expected two numbers `x,y`, found `x,y`"
        );
        assert_eq!(
            err("1,2\n3\n"),
            "p.csv: line 2: expected two numbers `x,y`, found `3`"
        );
        assert_eq!(
            err("1,2,3\n"),
            "p.csv: line 1: expected two numbers `x,y`, found `1,2,3`"
        );
        assert_eq!(
            err("x,2\n"),
            "p.csv: line 1: expected two numbers `x,y`, found `x,2`"
        );
        assert_eq!(
            err("# c\n\n1,nan\n"),
            "p.csv: line 3: expected two finite numbers `x,y`, found `1,nan`"
        );
        assert_eq!(
            err("1,\n"),
            "p.csv: line 1: expected two numbers `x,y`, found `1,`"
        );
    }

    #[test]
    fn reads_files_and_names_them() {
        let dir = scratch_dir("csv");
        let path = dir.join("pts.csv");
        std::fs::write(&path, "x,y\n0.5,1\n").unwrap();
        assert_eq!(read_xy_points(&path).unwrap(), vec![[0.5, 1.0]]);
        std::fs::write(&path, b"1,2\n\xff,3\n").unwrap();
        let e = read_xy_points(&path).unwrap_err().to_string();
        assert_eq!(e, format!("{}: line 2: not UTF-8 text", path.display()));
        let e = read_xy_points(&dir.join("none.csv"))
            .unwrap_err()
            .to_string();
        assert!(e.contains("none.csv: cannot read"), "{e}");
    }
}
