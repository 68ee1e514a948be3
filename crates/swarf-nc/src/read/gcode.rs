//! RS274/NGC G-code programs as LinuxCNC 2.9 reads them (and Fanuc macro B programs
//! with [`GcodeReadOptions::language`]; Heidenhain conversational programs go to
//! [`crate::read::heidenhain`]): the runner ([`crate::read::flow`]) around the
//! lexer ([`crate::read::lexer`]) and the modal state machine
//! ([`crate::read::modal`]), program delimiters and the end of the program.
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
use crate::post::Language;
use crate::read::axes::Axes;
use crate::read::flow::{End, FlowLimits, FlowOptions, Runner};
use crate::read::kinematics::{DEFAULT_KINEMATICS_TOL, Kinematics};
use crate::read::lexer::{Syntax, lex_line};
use crate::read::modal::{Interpreter, Setup};
use crate::read::params::Params;
use crate::read::source::Source;
use crate::read::tooltable::ToolTable;
use std::path::{Path, PathBuf};
use swarf_geom::Point3;
use swarf_tool::Pose;
use swarf_toolpath::program::{Diagnostic, Program};

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
    /// The language: LinuxCNC's RS274/NGC, Fanuc macro B, or Heidenhain
    /// conversational (read by [`crate::read::heidenhain`]).
    pub language: Language,
    /// The tool table (G41/G42 diameters, G43 offsets), if any.
    pub tool_table: Option<&'k ToolTable>,
    /// The machine's units are inches: tool table values and offsets stored in
    /// parameters are inches (LinuxCNC's standalone `rs274` is such a machine).
    pub machine_inch: bool,
    /// Parameter values at the start (a LinuxCNC var file), by number.
    pub parameters: &'k [(usize, f64)],
    /// Folders searched for subroutine files, in order (then the program's own).
    pub sub_path: &'k [PathBuf],
    /// Bounds on loops and on the lines run.
    pub limits: FlowLimits,
}

impl Default for GcodeReadOptions<'_> {
    /// Tip at the origin, axis +Z; block delete off (LinuxCNC's defaults); no
    /// kinematics; LinuxCNC's dialect, no tool table, a millimetre machine, all
    /// parameters 0, no search path, [`FlowLimits::default`].
    fn default() -> Self {
        GcodeReadOptions {
            initial: Pose::vertical(Point3::origin()),
            block_delete: false,
            kinematics: None,
            kinematics_tol: DEFAULT_KINEMATICS_TOL,
            language: Language::Linuxcnc,
            tool_table: None,
            machine_inch: false,
            parameters: &[],
            sub_path: &[],
            limits: FlowLimits::default(),
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
            && self.language == other.language
            && self.tool_table == other.tool_table
            && self.machine_inch == other.machine_inch
            && self.parameters == other.parameters
            && self.sub_path == other.sub_path
            && self.limits == other.limits
    }
}

/// Reads G-code text; `source` names it (a file path: its folder is searched for
/// subroutine files after [`GcodeReadOptions::sub_path`]).
///
/// Errors inside the program (an unknown or unsupported word, an arc whose radius does
/// not match its end point, a feed move without feed, rotary axis words without
/// kinematics, a malformed number, a loop that does not end ...) stop the reading:
/// the result is `Ok` with the motions before the error and [`Program::stopped`] set,
/// so that a verifier can still report on them.
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
/// let text = "G21 G90 F300\n#<r> = 5\nG1 X[2 * #<r>]\nG2 X20 I#<r>\nM30\n";
/// let p = parse_gcode(text, "a.ngc", &GcodeReadOptions::default()).unwrap();
/// assert_eq!(p.motions.len(), 2);
/// assert_eq!(p.motions[0].end.cl.x, 10.0);
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
    if opts.language == Language::Heidenhain {
        return crate::read::heidenhain::parse_heidenhain(text, source, opts);
    }
    let fanuc = opts.language == Language::Fanuc;
    let syntax = Syntax { fanuc };
    let axes = Axes::new(&opts.initial, opts.kinematics, opts.kinematics_tol);
    let setup = Setup {
        tool_table: opts.tool_table,
        machine_inch: opts.machine_inch,
        fanuc,
    };
    let mut machine = Interpreter::with_axes(axes, setup, Params::with_values(opts.parameters));
    machine.fanuc = fanuc;
    let program_dir = Path::new(source)
        .parent()
        .filter(|d| d.is_dir())
        .map(Path::to_path_buf);
    let flow = FlowOptions {
        sub_path: opts.sub_path.to_vec(),
        program_dir,
        fanuc,
        block_delete: opts.block_delete,
        limits: opts.limits,
    };
    let mut runner = Runner::new(machine, Source::new(source, text, syntax), flow);
    let mut program = Program::new(source);
    match runner.run() {
        Ok(end) => {
            let last = runner.pc.1;
            if let Err(d) = runner.machine.finish(last.max(1)) {
                program.stopped = Some(d);
            } else if let End::Ended(after) = end {
                if runner.pc.0 == 0 {
                    warn_trailing(&mut runner.machine, text, last, after, syntax);
                }
            } else {
                warn_unended(&mut runner.machine, text, syntax);
            }
        }
        Err(d) => program.stopped = Some(d),
    }
    program.messages = std::mem::take(&mut runner.messages);
    program.motions = std::mem::take(&mut runner.machine.motions);
    program.tools = std::mem::take(&mut runner.machine.tool_uses);
    program.warnings = std::mem::take(&mut runner.machine.warnings).finish();
    program.check_domain();
    Ok(program)
}

/// A warning at the last line of a program that ends without M2/M30 or `%`.
fn warn_unended(machine: &mut Interpreter, text: &str, syntax: Syntax) {
    let last = text.lines().count().max(1);
    let opened = text
        .lines()
        .enumerate()
        .find_map(|(i, l)| lex_line(l, i + 1, syntax).ok().filter(|b| !b.is_empty()))
        .is_some_and(|b| b.percent);
    let what = if opened {
        "the program opens with % but has no closing % (nor M2/M30)"
    } else {
        "the program ends without M2/M30 or %: LinuxCNC reports an error here"
    };
    machine.warnings.push(Diagnostic::new(last, 1, what));
}

/// A warning at the first non-blank, non-comment line after the end of the program
/// (line index `from` on).
fn warn_trailing(machine: &mut Interpreter, text: &str, from: usize, after: &str, syntax: Syntax) {
    let content = text.lines().enumerate().skip(from).find(|(i, raw)| {
        lex_line(raw, i + 1, syntax).map_or(true, |b| !(b.is_empty() || b.percent))
    });
    if let Some((i, _)) = content {
        machine.warnings.push(Diagnostic::new(
            i + 1,
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
