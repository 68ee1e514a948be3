//! APT CL (cutter location) data into motions.
//!
//! Records read ([`crate::read::cl_record`] splits them):
//!
//! - `GOTO/x,y,z` or `GOTO/x,y,z,i,j,k`: a straight move of the tip to `(x, y, z)`; the
//!   axis `(i, j, k)` is normalised (three values keep the current axis, `+Z` at the
//!   start or the last `TLAXIS`). `GODLTA/dx,dy,dz` moves by a delta, `GODLTA/d` along
//!   the tool axis.
//! - `RAPID`: the next move only is a rapid. `FEDRAT/f`, `FEDRAT/f,MMPM|IPM|MMPR|IPR` or
//!   the same with the unit first; without a unit word the feed is in the `UNITS` per
//!   minute; per-revolution feeds use the last `SPINDL` speed.
//! - `UNITS/MM|INCHES`: lengths that follow (default mm). `CUTTER/d[,r[,e,f[,alpha,beta[,h]]]]`:
//!   the tool, as [`Cutter::Apt`] (angles in degrees in the file); given `e`, `f` must
//!   agree with those derived from the others to the file's printed precision.
//! - `FROM/x,y,z[,i,j,k]`: the start pose. Without `FROM`, the first move's end point
//!   is the start: the first `GOTO` moves nothing (where the tool came from is not in
//!   the file).
//! - `TLAXIS/i,j,k`: the axis for later three-value `GOTO`s.
//! - `PARTNO`, `SPINDL`, `COOLNT`, `LOADTL`, `SELCTL`, `MULTAX`, `PPRINT`, `END`,
//!   `STOP`, `OPSTOP`: nothing to simulate. `FINI` ends the data.
//!
//! Circular records (`CIRCLE`, `MOVARC`) and APT source motion statements (`GOFWD`,
//! ...) stop the reading: ignoring them would silently replace arcs by chords. A
//! second, different `CUTTER` after motions stops it too (one tool per program).
//! Other unknown records are warnings.

use crate::error::NcError;
use crate::read::cl_record::{Field, Record, records};
use crate::read::gcode::check_text;
use crate::read::warnings::Warnings;
use swarf_geom::units::MM_PER_INCH;
use swarf_geom::{Point3, Vec3};
use swarf_tool::{Apt, Cutter, Pose};
use swarf_toolpath::program::{Diagnostic, Motion, MotionKind, Program};

/// Reads APT CL text.
///
/// Errors inside the data stop the reading: the result is `Ok` with the motions
/// before the error and [`Program::stopped`] set.
///
/// # Units
/// Lengths converted from `UNITS` to mm, feeds to mm/min; `CUTTER` angles from degrees.
///
/// # Errors
/// [`NcError::Unreadable`] when the text is not a program at all (binary data).
///
/// # Example
/// ```
/// use swarf_nc::read::parse_cl;
/// let p = parse_cl("UNITS/MM\nGOTO/0,0,10\nFEDRAT/300,MMPM\nGOTO/10,0,10\nFINI\n", "a.cl").unwrap();
/// assert_eq!(p.motions.len(), 1);
/// assert_eq!(p.motions[0].feed, 300.0);
/// ```
pub fn parse_cl(text: &str, source: &str) -> Result<Program, NcError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    check_text(text, source)?;
    let mut reader = ClReader::default();
    let mut program = Program::new(source);
    let mut all = records(text).into_iter();
    for record in all.by_ref() {
        match reader.record(&record) {
            Ok(true) => {}
            Ok(false) => {
                if let Some(next) = all.next() {
                    reader.warnings.push(Diagnostic::new(
                        next.line,
                        next.column,
                        "records after FINI are not read",
                    ));
                }
                break;
            }
            Err(d) => {
                program.stopped = Some(d);
                break;
            }
        }
    }
    program.motions = reader.motions;
    program.tool = reader.tool;
    program.warnings = reader.warnings.finish();
    program.check_domain();
    Ok(program)
}

#[derive(Default)]
struct ClReader {
    motions: Vec<Motion>,
    warnings: Warnings,
    tool: Option<Cutter>,
    /// Current pose; `None` until a `FROM` or the first move.
    pose: Option<Pose>,
    /// Axis for three-value moves.
    axis: Option<Vec3>,
    inch: bool,
    /// Feed, mm/min (0 = not given yet).
    feed: f64,
    rapid_next: bool,
    spindle_rpm: Option<f64>,
    feed_warned: bool,
}

impl ClReader {
    fn scale(&self) -> f64 {
        if self.inch { MM_PER_INCH } else { 1.0 }
    }

    /// Runs one record; `Ok(false)` at `FINI`.
    fn record(&mut self, r: &Record) -> Result<bool, Diagnostic> {
        let at = |message: String| Diagnostic::new(r.line, r.column, message);
        match r.name.as_str() {
            "GOTO" => self.goto(r)?,
            "GODLTA" => self.godlta(r)?,
            "RAPID" => self.rapid_next = true,
            "FEDRAT" => self.fedrat(r)?,
            "UNITS" => self.units(r)?,
            "CUTTER" => self.cutter(r)?,
            "FROM" => self.from(r)?,
            "TLAXIS" => {
                let v = numbers(r, &[3])?;
                self.axis = Some(unit_axis(&v, &r.fields[0])?);
            }
            "SPINDL" => self.spindle(r),
            "FINI" => return Ok(false),
            "PARTNO" | "COOLNT" | "LOADTL" | "SELCTL" | "MULTAX" | "PPRINT" | "END" | "STOP"
            | "OPSTOP" | "TOOLNO" | "CLDATA" | "REMARK" => {}
            "CIRCLE" | "MOVARC" => {
                return Err(at(format!(
                    "{}: circular records are not supported yet; post the CL data with linear moves",
                    r.name
                )));
            }
            "GOFWD" | "GOLFT" | "GORGT" | "GOBACK" | "GOUP" | "GODOWN" | "GO" | "INDIRV"
            | "INDIRP" | "TLON" | "TLLFT" | "TLRGT" | "PSIS" => {
                return Err(at(format!(
                    "{}: an APT source statement; swarf reads CL data (GOTO records), not APT part programs",
                    r.name
                )));
            }
            "" => return Err(at("record without a name".to_string())),
            other => self
                .warnings
                .push(at(format!("unknown record {other} ignored"))),
        }
        Ok(true)
    }

    fn goto(&mut self, r: &Record) -> Result<(), Diagnostic> {
        let v = numbers(r, &[3, 6])?;
        let s = self.scale();
        let cl = Point3::new(v[0] * s, v[1] * s, v[2] * s);
        let axis = if v.len() == 6 {
            unit_axis(&v[3..], &r.fields[3])?
        } else {
            self.pose
                .map(|p| p.axis)
                .or(self.axis)
                .unwrap_or_else(Vec3::z)
        };
        self.move_to(Pose { cl, axis }, r);
        Ok(())
    }

    fn godlta(&mut self, r: &Record) -> Result<(), Diagnostic> {
        let v = numbers(r, &[1, 3])?;
        let Some(here) = self.pose else {
            return Err(Diagnostic::new(
                r.line,
                r.column,
                "GODLTA before any position (FROM or GOTO)",
            ));
        };
        let s = self.scale();
        let delta = if v.len() == 1 {
            here.axis * (v[0] * s)
        } else {
            Vec3::new(v[0], v[1], v[2]) * s
        };
        self.move_to(
            Pose {
                cl: here.cl + delta,
                axis: here.axis,
            },
            r,
        );
        Ok(())
    }

    fn move_to(&mut self, to: Pose, r: &Record) {
        let rapid = std::mem::take(&mut self.rapid_next);
        let Some(from) = self.pose.replace(to) else {
            return;
        };
        if from == to {
            return;
        }
        if !rapid && self.feed <= 0.0 && !self.feed_warned {
            self.feed_warned = true;
            self.warnings.push(Diagnostic::new(
                r.line,
                r.column,
                "feed move before any FEDRAT: its feed is unknown (0)",
            ));
        }
        self.motions.push(Motion {
            kind: if rapid {
                MotionKind::Rapid
            } else {
                MotionKind::Linear
            },
            start: from,
            end: to,
            feed: if rapid { 0.0 } else { self.feed },
            line: r.line,
        });
    }

    fn from(&mut self, r: &Record) -> Result<(), Diagnostic> {
        if !self.motions.is_empty() {
            return Err(Diagnostic::new(
                r.line,
                r.column,
                "FROM after motions: the tool cannot jump",
            ));
        }
        let v = numbers(r, &[3, 6])?;
        let s = self.scale();
        let axis = if v.len() == 6 {
            unit_axis(&v[3..], &r.fields[3])?
        } else {
            self.axis.unwrap_or_else(Vec3::z)
        };
        self.pose = Some(Pose {
            cl: Point3::new(v[0] * s, v[1] * s, v[2] * s),
            axis,
        });
        Ok(())
    }

    fn fedrat(&mut self, r: &Record) -> Result<(), Diagnostic> {
        let mut value = None;
        let mut unit = None;
        for f in &r.fields {
            match f.word().as_str() {
                w @ ("MMPM" | "IPM" | "MMPR" | "IPR") => unit = Some(w.to_string()),
                _ if value.is_none() => value = Some((f.number()?, f)),
                _ => {
                    return Err(f.error(
                        "FEDRAT: expected one value and an optional MMPM, IPM, MMPR or IPR",
                    ));
                }
            }
        }
        let Some((value, field)) = value else {
            return Err(Diagnostic::new(r.line, r.column, "FEDRAT without a value"));
        };
        if value <= 0.0 {
            return Err(field.error(format!("FEDRAT must be > 0, found {value}")));
        }
        let per_minute = match unit.as_deref() {
            Some("MMPM") => value,
            Some("IPM") => value * MM_PER_INCH,
            Some(per_rev) => {
                let Some(rpm) = self.spindle_rpm else {
                    return Err(field.error(format!(
                        "FEDRAT/{per_rev}: a feed per revolution needs an SPINDL speed first"
                    )));
                };
                let per_rev_mm = if per_rev == "IPR" {
                    value * MM_PER_INCH
                } else {
                    value
                };
                per_rev_mm * rpm
            }
            None => value * self.scale(),
        };
        self.feed = per_minute;
        Ok(())
    }

    fn units(&mut self, r: &Record) -> Result<(), Diagnostic> {
        let word = r.fields.first().map(Field::word).unwrap_or_default();
        self.inch = match word.as_str() {
            "MM" => false,
            "INCHES" | "INCH" => true,
            _ => {
                return Err(Diagnostic::new(
                    r.line,
                    r.column,
                    format!("UNITS/{word}: expected MM or INCHES"),
                ));
            }
        };
        Ok(())
    }

    fn spindle(&mut self, r: &Record) {
        let numbers: Vec<f64> = r.fields.iter().filter_map(|f| f.number().ok()).collect();
        if let Some(&rpm) = numbers.first().filter(|v| **v > 0.0) {
            self.spindle_rpm = Some(rpm);
        }
    }

    fn cutter(&mut self, r: &Record) -> Result<(), Diagnostic> {
        let v = numbers(r, &[1, 2, 3, 4, 5, 6, 7])?;
        match self.apt_cutter(r, &v) {
            Ok(cutter) => {
                if let Some(old) = self
                    .tool
                    .filter(|old| *old != cutter && !self.motions.is_empty())
                {
                    return Err(Diagnostic::new(
                        r.line,
                        r.column,
                        format!(
                            "a second CUTTER ({cutter}) after motions with {old}: swarf verifies one tool per program"
                        ),
                    ));
                }
                self.tool = Some(cutter);
            }
            Err(message) => self.warnings.push(Diagnostic::new(
                r.line,
                r.column,
                format!("CUTTER ignored: {message}"),
            )),
        }
        Ok(())
    }

    /// The APT tool of a `CUTTER` record, `e` and `f` checked to printed precision.
    fn apt_cutter(&self, r: &Record, v: &[f64]) -> Result<Cutter, String> {
        let s = self.scale();
        let at = |k: usize| v.get(k).copied().unwrap_or(0.0);
        let (alpha, beta) = (at(4).to_radians(), at(5).to_radians());
        let h = v.get(6).map(|h| h * s);
        let apt = Apt::from_parts(at(0) * s, at(1) * s, None, None, alpha, beta, h)
            .map_err(|e| e.to_string())?;
        for (k, name, derived) in [(2, "e", apt.e), (3, "f", apt.f)] {
            let Some(field) = r.fields.get(k).filter(|_| v.len() > k) else {
                continue;
            };
            let printed = 0.5 * 10f64.powi(-(field.decimals().min(15) as i32)) * s;
            let tol = printed.max(swarf_tool::apt::APT_PARAM_TOL) + 1e-9 * derived.abs();
            if (v[k] * s - derived).abs() > tol {
                return Err(format!(
                    "{name} = {} does not match {:.6} derived from d, r, alpha, beta",
                    v[k],
                    derived / s
                ));
            }
        }
        Ok(named_shape(&apt, h).unwrap_or(Cutter::Apt(apt)))
    }
}

/// The named cutter an APT tool without taper is (flat, ball or bull: `alpha = beta =
/// 0`), so that reports name it as its job did; `None` for tapered tools. `length`:
/// the record's `h`, if it has one.
fn named_shape(apt: &Apt, length: Option<f64>) -> Option<Cutter> {
    if apt.alpha != 0.0 || apt.beta != 0.0 {
        return None;
    }
    let named = if apt.r == 0.0 {
        Cutter::flat(apt.d, length)
    } else if (2.0 * apt.r - apt.d).abs() <= swarf_tool::apt::APT_PARAM_TOL {
        Cutter::ball(apt.d, length)
    } else {
        Cutter::bull(apt.d, apt.r, length)
    };
    named.ok()
}

/// The record's fields as numbers; their count must be one of `counts`.
fn numbers(r: &Record, counts: &[usize]) -> Result<Vec<f64>, Diagnostic> {
    if !counts.contains(&r.fields.len()) {
        let expected: Vec<String> = counts.iter().map(usize::to_string).collect();
        return Err(Diagnostic::new(
            r.line,
            r.column,
            format!(
                "{} with {} values: expected {}",
                r.name,
                r.fields.len(),
                expected.join(" or ")
            ),
        ));
    }
    r.fields.iter().map(Field::number).collect()
}

/// `(i, j, k)` normalised; an error at `field` when it is (nearly) zero.
fn unit_axis(v: &[f64], field: &Field) -> Result<Vec3, Diagnostic> {
    Vec3::new(v[0], v[1], v[2])
        .try_normalize(swarf_geom::tol::LENGTH_EPS)
        .ok_or_else(|| field.error("tool axis (i, j, k) is zero"))
}
