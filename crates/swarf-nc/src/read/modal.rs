//! The RS274/NGC modal state machine, as LinuxCNC 2.9's interpreter keeps it
//! (`interp_execute.cc`, `interp_convert.cc`): executes one block of evaluated words
//! against the modal state and emits motions.
//!
//! Within a block the words act in LinuxCNC's order: feed mode, `F`, `S`, `T`, the M
//! codes (tool change, spindle), dwell `G4`, plane, units, cutter compensation, tool
//! length offset, coordinate system, path control, distance modes, retract mode, the
//! non-modal codes (`G10 G28 G30 G52 G92` ...), motion, then stop (`M0 M1 M2 M30`). So
//! `G20 F10` sets the feed in the units in force *before* the block (the reader warns
//! about it), and `G91 X1` moves incrementally.
//!
//! Like LinuxCNC, the machine keeps the current point in *program* coordinates: the
//! active coordinate system (`G54`-`G59.3`, with its XY rotation), the `G92`/`G52`
//! offsets and the tool length offset (`G43`) in the program's units
//! ([`crate::read::offsets`]). Every motion is carried into the part frame when it is
//! emitted: `machine = rot(p + g92) + g5x + tool offset`, LinuxCNC's canonical
//! transform, minus the loaded tool's own offset from the tool table, so that the
//! motion is the path of the tool *tip* (with `G43` of the loaded tool the two cancel).
//! With no offsets and no tool table the part frame is the program's.
//!
//! With a machine's kinematics the program coordinates are the machine's axes
//! (`X Y Z` and two rotary words, in degrees, absolute in G90 and incremental in G91,
//! not scaled by G20), turned into part-frame motions by [`crate::read::axes`]. Feeds
//! follow G93/G94 as [`crate::read::feed`] describes.
//!
//! The tool words and the loaded tool's table entry are in `tools`; the state as
//! parameters and callers read it (codes, the current point) in `queries`.

use crate::read::arc::Plane;
use crate::read::axes::Axes;
use crate::read::codes::{Action, SpindleTurn};
use crate::read::comp::Comp;
use crate::read::cycle::CycleState;
use crate::read::kinematics::DEFAULT_KINEMATICS_TOL;
use crate::read::offsets::Offsets;
use crate::read::params::Params;
use crate::read::tooltable::ToolTable;
use crate::read::warnings::Warnings;
use crate::read::words::{Word, Words};
use swarf_geom::units::MM_PER_INCH;
use swarf_tool::Pose;
use swarf_toolpath::program::{Diagnostic, Motion};

mod queries;
mod tools;

/// Most turns one G2/G3 block may make (`P`): thread milling needs tens; more is
/// taken for a mistake rather than handed to a simulation that samples every turn.
pub const MAX_TURNS: u32 = 10_000;

/// A position `X Y Z A B C`: program units and degrees.
pub type Pos = [f64; 6];

/// What the caller does after a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    /// Read the next line.
    Continue,
    /// The program ended (M2, M30).
    End,
}

/// The machine the program runs on: its tool table and units.
#[derive(Debug, Clone, Copy, Default)]
pub struct Setup<'k> {
    /// The tool table (diameters for G41/G42, offsets for G43), if any.
    pub tool_table: Option<&'k ToolTable>,
    /// The machine's units are inches: tool table values and the offsets stored in
    /// parameters (#5161-#5390) are inches (LinuxCNC's standalone `rs274`); otherwise mm.
    pub machine_inch: bool,
    /// The Fanuc dialect (unknown M codes are warnings, not errors).
    pub fanuc: bool,
}

/// The modal state and what has been read so far.
pub struct Interpreter<'k> {
    /// Motions emitted so far.
    pub motions: Vec<Motion>,
    /// Warnings so far.
    pub warnings: Warnings,
    /// Numbered and global named parameters.
    pub params: Params,
    pub(crate) setup: Setup<'k>,
    /// The tool table as the program has changed it (G10 L1).
    pub(crate) tools: ToolTable,
    /// Axis positions and the tool's pose in the part frame (what was emitted).
    pub(crate) axes: Axes<'k>,
    /// The current point, program coordinates (LinuxCNC's `current_x` ...).
    pub(crate) cur: Pos,
    pub(crate) motion: Option<Action>,
    pub(crate) plane: Plane,
    pub(crate) absolute: bool,
    pub(crate) ijk_absolute: bool,
    pub(crate) inch: bool,
    units_seen: bool,
    /// Feed in G94, mm/min.
    pub(crate) feed: f64,
    /// Feed in G94 for moves of the rotary axes alone, degrees/min.
    pub(crate) rotary_feed: f64,
    /// G93 inverse-time feed mode.
    pub(crate) inverse_time: bool,
    selected_tool: Option<u32>,
    /// The tool in the spindle (M6, M61).
    pub(crate) loaded_tool: Option<u32>,
    /// The tool the program cuts with now (noted at its first motion).
    cutting_tool: Option<u32>,
    /// Each tool the program cuts with, from its first motion.
    pub(crate) tool_uses: Vec<swarf_toolpath::program::ToolUse>,
    pub(crate) spindle: SpindleTurn,
    pub(crate) offsets: Offsets,
    pub(crate) cycle: CycleState,
    pub(crate) comp: Comp,
    /// An `O` program number was read: numbers without a decimal point are suspicious.
    pub fanuc: bool,
    fanuc_warned: bool,
    tool_warned: bool,
}

impl Interpreter<'static> {
    /// A three-axis machine at `initial`, in G17 G21 G90 G91.1 G94 G54 with no motion
    /// mode and no feed (LinuxCNC's start-up state).
    pub fn new(initial: Pose) -> Self {
        Interpreter::with_axes(
            Axes::new(&initial, None, DEFAULT_KINEMATICS_TOL),
            Setup::default(),
            Params::default(),
        )
    }
}

impl<'k> Interpreter<'k> {
    /// A machine whose axes start at `axes`, otherwise as [`Interpreter::new`].
    pub fn with_axes(axes: Axes<'k>, setup: Setup<'k>, params: Params) -> Self {
        let mut machine = Interpreter {
            motions: Vec::new(),
            warnings: Warnings::default(),
            params,
            setup,
            tools: setup.tool_table.cloned().unwrap_or_default(),
            axes,
            cur: [0.0; 6],
            motion: None,
            plane: Plane::Xy,
            absolute: true,
            ijk_absolute: false,
            inch: false,
            units_seen: false,
            feed: 0.0,
            rotary_feed: 0.0,
            inverse_time: false,
            selected_tool: None,
            loaded_tool: None,
            cutting_tool: None,
            tool_uses: Vec::new(),
            spindle: SpindleTurn::Stopped,
            offsets: Offsets::default(),
            cycle: CycleState::default(),
            comp: Comp::default(),
            fanuc: false,
            fanuc_warned: false,
            tool_warned: false,
        };
        machine.start_in_g54();
        machine.cur = machine.program_of_axes();
        machine
    }

    /// mm per program unit.
    pub(crate) fn scale(&self) -> f64 {
        if self.inch { MM_PER_INCH } else { 1.0 }
    }

    /// A length in the machine's units (tool table, stored offsets) in program units.
    pub(crate) fn user_to_program(&self, v: f64) -> f64 {
        match (self.setup.machine_inch, self.inch) {
            (true, false) => v * MM_PER_INCH,
            (false, true) => v / MM_PER_INCH,
            _ => v,
        }
    }

    /// A length in program units in the machine's units.
    pub(crate) fn program_to_user(&self, v: f64) -> f64 {
        match (self.setup.machine_inch, self.inch) {
            (true, false) => v / MM_PER_INCH,
            (false, true) => v * MM_PER_INCH,
            _ => v,
        }
    }

    pub(crate) fn warn(&mut self, line: usize, column: usize, message: impl Into<String>) {
        self.warnings.push(Diagnostic::new(line, column, message));
    }

    /// Executes one block of evaluated words.
    ///
    /// # Errors
    /// A [`Diagnostic`] at the offending word; the state is then unspecified and the
    /// caller stops reading.
    pub fn execute(&mut self, block: &[Word], line: usize) -> Result<Flow, Diagnostic> {
        let parsed = Words::sort(block, line, self.setup.fanuc, &mut self.warnings)?;
        let to_be = self.motion_to_be(&parsed, line)?;
        let rotary = self.axes.rotary_letters();
        let mode = to_be.or(self.motion);
        parsed.check_letters(mode, rotary, line, &mut self.warnings)?;
        self.machine_words(&parsed, line)?;
        self.m_codes(&parsed, line)?;
        self.set_modes(&parsed, line)?;
        self.modal_zero(&parsed, line)?;
        if let Some(action) = to_be {
            self.motion_words(action, &parsed, line)?;
        } else if parsed.has_g(Action::CancelMotion).is_some() {
            self.motion = None;
            self.cycle.initial_level = None;
        }
        self.stop(&parsed, line)
    }

    /// The motion this block makes, with LinuxCNC's checks (`enhance_block`).
    fn motion_to_be(&self, parsed: &Words, line: usize) -> Result<Option<Action>, Diagnostic> {
        let axis = parsed.axis_word(self.axes.rotary_letters());
        let polar = parsed.get('@').or(parsed.get('^'));
        let ijk = ['I', 'J', 'K'].iter().find_map(|&l| parsed.get(l));
        let covets = parsed.g.iter().find(|g| {
            matches!(
                g.2,
                Action::SetData | Action::Home { .. } | Action::AxisOffset { .. }
            )
        });
        let err = |column: usize, m: &str| Err(Diagnostic::new(line, column, m));
        if let Some(p) = polar {
            if self.plane != Plane::Xy {
                return err(
                    p.column,
                    "polar coordinates (@, ^) can only be used in the G17 plane",
                );
            }
            if let Some(w) = parsed.get('X').or(parsed.get('Y')) {
                return err(
                    w.column,
                    "cannot give both polar coordinates (@, ^) and X or Y words",
                );
            }
        }
        let moved = axis.or(polar);
        if let Some((action, word)) = parsed.motion_code() {
            if action == Action::CancelMotion {
                if let (Some(_), None) = (moved, covets) {
                    return err(word.column, "axis words with G80 (motion cancelled)");
                }
                return Ok(None);
            }
            if let Some(g) = covets {
                return err(
                    g.3.column,
                    "two G codes that both use axis values in one block (a motion and G10, \
                     G28, G30, G52 or G92)",
                );
            }
            if moved.is_none() && matches!(action, Action::Cycle(_)) {
                return err(word.column, "all axes missing with a canned cycle");
            }
            return Ok(Some(action));
        }
        let dynamic = parsed
            .g
            .iter()
            .any(|g| matches!(g.2, Action::LengthOffsetGiven | Action::LengthOffsetAdd));
        if covets.is_some() || dynamic {
            return Ok(None);
        }
        if let Some(w) = moved {
            return match self.motion {
                Some(mode) => Ok(Some(mode)),
                None => err(
                    w.column,
                    "axis words without a motion mode: program G0, G1, G2 or G3 first",
                ),
            };
        }
        if ijk.is_some() && matches!(self.motion, Some(Action::ArcCw | Action::ArcCcw)) {
            return Ok(self.motion);
        }
        Ok(None)
    }

    /// Feed mode, F, S, T, in that order. In G93 the F word belongs to its block's
    /// motion ([`crate::read::motion`]).
    fn machine_words(&mut self, parsed: &Words, line: usize) -> Result<(), Diagnostic> {
        if parsed.has_g(Action::InverseTime).is_some() {
            self.inverse_time = true;
        }
        if parsed.has_g(Action::UnitsPerMinute).is_some() {
            self.inverse_time = false;
            self.feed = 0.0;
            self.rotary_feed = 0.0;
        }
        if let Some(f) = parsed.get('F').filter(|f| f.value < 0.0) {
            return Err(Diagnostic::new(line, f.column, "negative feed rate F"));
        }
        if let Some(f) = parsed.get('F').filter(|_| !self.inverse_time) {
            self.feed = f.value * self.scale();
            self.rotary_feed = f.value;
            let to_inch = parsed.has_g(Action::Inch).is_some();
            let to_mm = parsed.has_g(Action::Mm).is_some();
            if (to_inch && !self.inch) || (to_mm && self.inch) {
                self.warn(
                    line,
                    f.column,
                    "F in the same block as a change of units is read in the units in force \
                     before the block (RS274/NGC order of execution)",
                );
            }
        }
        if let Some(s) = parsed.get('S').filter(|s| s.value < 0.0) {
            return Err(Diagnostic::new(line, s.column, "negative spindle speed S"));
        }
        if let Some(t) = parsed.get('T') {
            let n = whole(t, line, "tool number T")?;
            if n != 0 && self.setup.tool_table.is_some() && self.tools.get(n).is_none() {
                return Err(Diagnostic::new(
                    line,
                    t.column,
                    format!("requested tool {n} not found in the tool table"),
                ));
            }
            self.selected_tool = Some(n);
        }
        Ok(())
    }

    /// Plane, units, cutter compensation, tool length offset, coordinate system,
    /// distance modes and retract mode, in LinuxCNC's order.
    fn set_modes(&mut self, parsed: &Words, line: usize) -> Result<(), Diagnostic> {
        let g = |action: Action| parsed.g.iter().find(|g| g.2 == action).map(|g| g.3);
        for &(_, _, action, w) in &parsed.g {
            if let Action::PlaneXy | Action::PlaneXz | Action::PlaneYz = action {
                if self.comp.is_on() && action != Action::PlaneXy {
                    return Err(Diagnostic::new(
                        line,
                        w.column,
                        "cannot change to the XZ or YZ plane with cutter radius compensation on",
                    ));
                }
                self.plane = match action {
                    Action::PlaneXz => Plane::Xz,
                    Action::PlaneYz => Plane::Yz,
                    _ => Plane::Xy,
                };
            }
        }
        if g(Action::Inch).is_some() {
            self.set_units(true);
        } else if g(Action::Mm).is_some() {
            self.set_units(false);
        }
        for &(_, _, action, w) in &parsed.g {
            match action {
                Action::CompOff => self.comp_off(line)?,
                Action::Comp { left, diameter } => self.comp_on(left, diameter, parsed, w, line)?,
                _ => {}
            }
        }
        for &(_, _, action, w) in &parsed.g {
            match action {
                Action::LengthOffset
                | Action::LengthOffsetOff
                | Action::LengthOffsetGiven
                | Action::LengthOffsetAdd => self.tool_length_offset(action, parsed, w, line)?,
                Action::CoordSystem(n) => self.select_coordinate_system(n, w, line)?,
                _ => {}
            }
        }
        for &(_, _, action, _) in &parsed.g {
            match action {
                Action::Absolute => self.absolute = true,
                Action::Incremental => self.absolute = false,
                Action::ArcAbsolute => self.ijk_absolute = true,
                Action::ArcIncremental => self.ijk_absolute = false,
                Action::RetractOldZ => self.cycle.retract_to_r = false,
                Action::RetractR => self.cycle.retract_to_r = true,
                _ => {}
            }
        }
        Ok(())
    }

    /// G20 (`inch`) or G21: the current point, the offsets and the compensation are
    /// carried into the new units, as LinuxCNC's `convert_length_units` does.
    fn set_units(&mut self, inch: bool) {
        self.units_seen = true;
        if inch == self.inch {
            return;
        }
        let k = if inch { 1.0 / MM_PER_INCH } else { MM_PER_INCH };
        for v in self.cur[..3].iter_mut() {
            *v *= k;
        }
        self.comp.scale(k);
        self.offsets.scale(k);
        self.inch = inch;
    }

    /// M0 and M1 flush the compensation queue; M2 and M30 end the program.
    fn stop(&mut self, parsed: &Words, line: usize) -> Result<Flow, Diagnostic> {
        let stop = parsed
            .m
            .iter()
            .find(|m| matches!(m.1, Action::End | Action::Pause));
        let Some(&(_, action, _)) = stop else {
            return Ok(Flow::Continue);
        };
        self.comp_flush_here(line)?;
        Ok(if action == Action::End {
            Flow::End
        } else {
            Flow::Continue
        })
    }

    /// Emits what the compensation still holds (the end of the program).
    ///
    /// # Errors
    /// When a queued move cannot be finished (see [`crate::read::comp`]).
    pub fn finish(&mut self, line: usize) -> Result<(), Diagnostic> {
        self.comp_flush_here(line)
    }

    /// Fanuc-style programs read `X10` as ten least increments; LinuxCNC as 10 units.
    pub(crate) fn suspicious_numbers(&mut self, parsed: &Words, line: usize) {
        if !self.units_seen {
            self.units_seen = true;
            let column = self.motion_column(parsed);
            self.warn(
                line,
                column,
                "no G20/G21 before the first motion: assuming millimetres (G21)",
            );
        }
        if !self.fanuc || self.fanuc_warned {
            return;
        }
        for l in ['X', 'Y', 'Z', 'I', 'J', 'K', 'R'] {
            if let Some(w) = parsed.get(l).filter(|w| !w.has_point && w.value != 0.0) {
                self.fanuc_warned = true;
                self.warn(
                    line,
                    w.column,
                    "number without a decimal point in a program with an O number: read as \
                     whole units (as LinuxCNC does); a Fanuc control may read least increments \
                     (only the first such number is reported)",
                );
                return;
            }
        }
    }
}

/// A whole number >= 0 from a word (tool numbers).
pub(crate) fn whole(w: Word, line: usize, what: &str) -> Result<u32, Diagnostic> {
    if w.value < 0.0 || (w.value - w.value.round()).abs() > 1e-4 || w.value > f64::from(u32::MAX) {
        return Err(Diagnostic::new(
            line,
            w.column,
            format!("{what} must be a whole number >= 0"),
        ));
    }
    Ok(w.value.round() as u32)
}
