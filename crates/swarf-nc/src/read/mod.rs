//! Reading NC programs for verification: RS274/NGC G-code (as LinuxCNC reads it, or
//! Fanuc macro B), Heidenhain conversational ([`heidenhain`]), APT CL data and pose
//! CSV, each turned into a [`Program`]: motions (straight,
//! rapid, circular and helical) in mm and mm/min in the part frame, with the source
//! line of each, and warnings for what was read but not simulated.
//!
//! Five-axis G-code (`X Y Z` and two rotary words, G93 or G94 feeds) is read with a
//! machine's forward kinematics ([`Kinematics`], given in
//! [`GcodeReadOptions::kinematics`]); APT CL and pose CSV are in the part frame
//! already and need none.
//!
//! Reading has two kinds of failure. A file that cannot be read at all (missing, not
//! text, an unknown extension, a pose CSV without its header) is an `Err`
//! ([`NcError`]). An error inside a program (an unknown word, an arc whose radius does
//! not match its end point, a rotary axis word without kinematics ...) stops the
//! reading at that line:
//! the result is `Ok`, holds the motions before the error, and sets
//! [`Program::stopped`] to the diagnostic (line, column, message), so that a verifier
//! can still write its partial report and then fail.

pub mod arc;
pub mod axes;
pub mod cl;
pub mod cl_record;
pub mod codes;
pub mod comp;
pub mod comp_geometry;
pub mod cycle;
pub mod expr;
pub mod expr_parse;
pub mod fanuc;
pub mod feed;
pub mod flow;
pub mod gcode;
pub mod heidenhain;
pub mod kinematics;
pub mod lexer;
pub mod modal;
pub mod motion;
pub mod offsets;
pub mod oword;
pub mod params;
pub mod pose_csv;
pub mod source;
pub mod statement;
pub mod tooltable;
pub mod warnings;
pub mod words;

pub use cl::parse_cl;
pub use flow::FlowLimits;
pub use gcode::{GcodeReadOptions, parse_gcode};
pub use kinematics::{AxisPosition, Kinematics};
pub use params::parse_var_file;
pub use pose_csv::parse_pose_csv;
pub use swarf_toolpath::program::{Diagnostic, Motion, MotionKind, Program, ToolUse};
pub use tooltable::{Tool, ToolTable};

use crate::error::NcError;
use std::path::Path;

/// The formats [`read_program`] tells apart by file extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ProgramFormat {
    /// RS274/NGC G-code: `.ngc`, `.nc`, `.tap`, `.gcode`.
    Gcode,
    /// APT CL data: `.cl`, `.apt`, `.cls`.
    Cl,
    /// Pose CSV: `.csv`.
    PoseCsv,
    /// Heidenhain conversational: `.h`.
    Heidenhain,
}

impl ProgramFormat {
    /// The format of `path` from its extension (any case); `None` when unknown.
    pub fn of(path: &Path) -> Option<ProgramFormat> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "ngc" | "nc" | "tap" | "gcode" => Some(ProgramFormat::Gcode),
            "cl" | "apt" | "cls" => Some(ProgramFormat::Cl),
            "csv" => Some(ProgramFormat::PoseCsv),
            "h" => Some(ProgramFormat::Heidenhain),
            _ => None,
        }
    }
}

/// Reads the program at `path`, choosing the reader by extension: G-code or
/// Heidenhain conversational (`.h`) (with
/// [`GcodeReadOptions::default`]), APT CL or pose CSV; [`read_program_with`] takes
/// the G-code reader's options (a machine's kinematics). Text that is not valid UTF-8
/// is read with the bad bytes replaced (they can only sit in comments of a valid
/// program; elsewhere the reader reports them with their line and column).
///
/// An error inside the program stops the reading and is reported in
/// [`Program::stopped`], with the motions before it kept (see the module docs).
///
/// # Units
/// Motions in mm, feeds in mm/min, whatever units the file uses.
///
/// # Errors
/// [`NcError::UnknownFormat`] for an unknown extension, [`NcError::Input`] when the
/// file cannot be read (missing, not a regular file, too large), [`NcError::Unreadable`] when it is not a program of its
/// format at all.
pub fn read_program(path: &Path) -> Result<Program, NcError> {
    read_program_with(path, &GcodeReadOptions::default())
}

/// [`read_program`] with `gcode` as the G-code reader's options (APT CL and pose CSV
/// do not use them).
///
/// # Units
/// Motions in mm, feeds in mm/min, whatever units the file uses.
///
/// # Errors
/// As [`read_program`]; [`NcError::InvalidOption`] for a G-code program when
/// `gcode.kinematics_tol` is not a positive length.
pub fn read_program_with(path: &Path, gcode: &GcodeReadOptions) -> Result<Program, NcError> {
    read_program_as(path, path, gcode)
}

/// [`read_program_with`] reading the bytes of `file` as the program `name`: its
/// format comes from `name`'s extension and messages name `name` (a program staged
/// in a temporary file before it is renamed into place).
///
/// # Errors
/// As [`read_program_with`].
pub fn read_program_as(
    file: &Path,
    name: &Path,
    gcode: &GcodeReadOptions,
) -> Result<Program, NcError> {
    let source = name.display().to_string();
    let format = ProgramFormat::of(name).ok_or_else(|| NcError::UnknownFormat {
        path: source.clone(),
    })?;
    let bytes = swarf_io::read_input(file).map_err(|e| NcError::Input(e.to_string()))?;
    let text = String::from_utf8_lossy(&bytes);
    match format {
        ProgramFormat::Gcode => parse_gcode(&text, &source, gcode),
        ProgramFormat::Cl => parse_cl(&text, &source),
        ProgramFormat::PoseCsv => parse_pose_csv(&text, &source),
        ProgramFormat::Heidenhain => heidenhain::parse_heidenhain(&text, &source, gcode),
    }
}
