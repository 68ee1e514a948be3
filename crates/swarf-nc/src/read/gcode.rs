//! RS274/NGC G-code programs as LinuxCNC reads them, for what surface-finishing
//! programs use: the line loop around the lexer ([`crate::read::lexer`]) and the modal
//! state machine ([`crate::read::modal`]), program delimiters and the end of the
//! program.
//!
//! - A first line `%` opens the program and the next `%` closes it; `M2`/`M30` end it.
//!   Text after the end is not read (a warning says so, at its first line).
//! - `/` block delete: LinuxCNC's switch is off by default and the line runs; with
//!   [`GcodeReadOptions::block_delete`] on, the line is skipped. Either way the first
//!   such line gets a warning.
//! - An `O1234` line is a Fanuc program number; numbers without a decimal point then
//!   get a warning (a Fanuc control may read `X10` as 0.010 mm).
//! - The first motion starts at [`GcodeReadOptions::initial`] (the tip at the origin,
//!   as `rs274` assumes).
//! - Rotary axis words need [`GcodeReadOptions::kinematics`] (a machine file):
//!   [`crate::read::kinematics`] for how the axes become poses over the part, and
//!   [`crate::read::feed`] for G93 inverse-time and G94 feeds.

use crate::error::NcError;
use crate::read::axes::Axes;
use crate::read::kinematics::{DEFAULT_KINEMATICS_TOL, Kinematics};
use crate::read::lexer::lex_line;
use crate::read::modal::{Flow, Interpreter};
use crate::read::program::{Diagnostic, Program};
use swarf_geom::Point3;
use swarf_tool::Pose;

/// Options of the G-code reader.
#[derive(Debug, Clone, Copy)]
pub struct GcodeReadOptions<'k> {
    /// Where the tool is when the program starts; mm. With kinematics only the tip
    /// counts: the rotary axes start at 0.
    pub initial: Pose,
    /// The block delete switch: when on, lines starting with `/` are skipped.
    pub block_delete: bool,
    /// The machine's forward kinematics, for five-axis programs: program coordinates
    /// are then machine axes and rotary words are read. `None`: program coordinates
    /// are the tool tip in the part frame and rotary words are refused.
    pub kinematics: Option<&'k dyn Kinematics>,
    /// Chordal tolerance of the motions a five-axis move is split into, mm.
    pub kinematics_tol: f64,
}

impl Default for GcodeReadOptions<'_> {
    /// Tip at the origin, axis +Z; block delete off (LinuxCNC's defaults); no
    /// kinematics.
    fn default() -> Self {
        GcodeReadOptions {
            initial: Pose::vertical(Point3::origin()),
            block_delete: false,
            kinematics: None,
            kinematics_tol: DEFAULT_KINEMATICS_TOL,
        }
    }
}

impl PartialEq for GcodeReadOptions<'_> {
    /// Equal values, and the same kinematics object (or none on both sides).
    fn eq(&self, other: &Self) -> bool {
        let same = match (self.kinematics, other.kinematics) {
            (None, None) => true,
            (Some(a), Some(b)) => std::ptr::addr_eq(a, b),
            _ => false,
        };
        same && self.initial == other.initial
            && self.block_delete == other.block_delete
            && self.kinematics_tol == other.kinematics_tol
    }
}

/// Reads G-code text.
///
/// Errors inside the program (an unknown or unsupported word, an arc whose radius does
/// not match its end point, a feed move without feed, rotary axis words without
/// kinematics, a malformed number ...) stop the reading: the result is `Ok` with the
/// motions before the error and [`Program::stopped`] set, so that a verifier can still
/// report on them.
///
/// # Units
/// The program's units (G20/G21) are converted: motions in mm, feeds in mm/min of the
/// tool tip over the part.
///
/// # Errors
/// [`NcError::Unreadable`] when the text is not a program at all (binary data);
/// [`NcError::InvalidOption`] when `opts.kinematics_tol` is not a positive length.
///
/// # Example
/// ```
/// use swarf_nc::read::{GcodeReadOptions, MotionKind, parse_gcode};
/// let p = parse_gcode("G21 G90 F300\nG1 X10\nG2 X20 I5\nM30\n", "a.ngc", &GcodeReadOptions::default())
///     .unwrap();
/// assert_eq!(p.motions.len(), 2);
/// assert!(matches!(p.motions[1].kind, MotionKind::Arc { clockwise: true, .. }));
/// assert!(p.stopped.is_none());
/// ```
pub fn parse_gcode(text: &str, source: &str, opts: &GcodeReadOptions) -> Result<Program, NcError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    check_text(text, source)?;
    if !(opts.kinematics_tol.is_finite() && opts.kinematics_tol > 0.0) {
        return Err(NcError::InvalidOption {
            field: "kinematics_tol",
            message: format!(
                "expected a finite length > 0 mm, found {}",
                opts.kinematics_tol
            ),
        });
    }
    let mut program = Program::new(source);
    let axes = Axes::new(&opts.initial, opts.kinematics, opts.kinematics_tol);
    let mut machine = Interpreter::with_axes(axes);
    let mut lines = text.lines().enumerate().map(|(i, l)| (i + 1, l));
    let mut opened = false;
    let mut started = false;
    let mut delete_warned = false;
    let mut ended: Option<&str> = None;
    for (line, raw) in lines.by_ref() {
        let block = match lex_line(raw, line) {
            Ok(block) => block,
            Err(d) => {
                program.stopped = Some(d);
                break;
            }
        };
        if block.percent {
            if started {
                ended = Some("the closing %");
                break;
            }
            opened = true;
            started = true;
            continue;
        }
        if block.is_empty() {
            continue;
        }
        started = true;
        if block.block_delete && skip_deleted(&mut machine, opts, line, &mut delete_warned) {
            continue;
        }
        if block.program_number.is_some() {
            machine.fanuc = true;
        }
        match machine.execute(&block, line) {
            Ok(Flow::Continue) => {}
            Ok(Flow::End) => {
                ended = Some("M2/M30");
                break;
            }
            Err(d) => {
                program.stopped = Some(d);
                break;
            }
        }
    }
    if let Some(after) = ended {
        warn_trailing(&mut machine, lines, after);
    } else if program.stopped.is_none() {
        warn_unended(&mut machine, text, opened);
    }
    program.motions = machine.motions;
    program.warnings = machine.warnings.finish();
    Ok(program)
}

/// Whether a block delete (`/`) line at `line` is skipped (the switch of `opts`);
/// the first such line warns which way the switch is.
fn skip_deleted(
    machine: &mut Interpreter,
    opts: &GcodeReadOptions,
    line: usize,
    warned: &mut bool,
) -> bool {
    if !*warned {
        *warned = true;
        let what = if opts.block_delete {
            "block delete (/) lines are skipped: the block delete switch is on"
        } else {
            "block delete (/) lines run: the block delete switch is off, as LinuxCNC starts"
        };
        machine.warnings.push(Diagnostic::new(line, 1, what));
    }
    opts.block_delete
}

/// A warning at the last line of a program that ends without M2/M30 or `%`.
fn warn_unended(machine: &mut Interpreter, text: &str, opened: bool) {
    let last = text.lines().count().max(1);
    let what = if opened {
        "the program opens with % but has no closing % (nor M2/M30)"
    } else {
        "the program ends without M2/M30 or %: LinuxCNC reports an error here"
    };
    machine.warnings.push(Diagnostic::new(last, 1, what));
}

/// A warning at the first non-blank, non-comment line after the end of the program.
fn warn_trailing<'a>(
    machine: &mut Interpreter,
    mut lines: impl Iterator<Item = (usize, &'a str)>,
    after: &str,
) {
    let content = lines
        .find(|(line, raw)| lex_line(raw, *line).map_or(true, |b| !(b.is_empty() || b.percent)));
    if let Some((line, _)) = content {
        machine.warnings.push(Diagnostic::new(
            line,
            1,
            format!("text after the end of the program ({after}) is not read"),
        ));
    }
}

/// Refuses binary data: a NUL or other control character (tab, CR, LF and form feed
/// excepted) in the text.
pub(crate) fn check_text(text: &str, source: &str) -> Result<(), NcError> {
    for (i, line) in text.lines().enumerate() {
        if let Some((column, c)) = line
            .chars()
            .enumerate()
            .find(|(_, c)| c.is_control() && !matches!(c, '\t' | '\r' | '\u{c}'))
        {
            return Err(NcError::Unreadable {
                file: source.to_string(),
                line: i + 1,
                column: column + 1,
                message: format!(
                    "control character U+{:04X}: this is not a text program",
                    u32::from(c)
                ),
            });
        }
    }
    Ok(())
}
