//! The RS274/NGC modal state machine: executes one lexed block against the modal
//! state (motion mode, plane, distance modes, units, feed, tool) and emits motions.
//!
//! Within a block the words act in RS274/NGC's order of execution (NIST RS274/NGC
//! v3 §3.8, as LinuxCNC follows it): feed `F`, spindle `S`, tool select `T`, tool change
//! `M6`, spindle and coolant, dwell `G4`, plane, units, cutter compensation, tool
//! length offset, coordinate system, path control, distance modes, motion, stop. So
//! `G20 F10` sets the feed in the units in force *before* the block (the reader warns
//! about it), and `G91 X1` moves incrementally.
//!
//! Program coordinates are the tool tip in the part frame: the reader assumes the
//! control applies the tool length (G43 H, or the tool table) so that the programmed
//! point is the tip, and that the work offset (G54) puts the part frame where the
//! program's zero is. With a machine's kinematics the program coordinates are the
//! machine's axes (`X Y Z` and two rotary words, in degrees, absolute in G90 and
//! incremental in G91, not scaled by G20), turned into part-frame motions by
//! [`crate::read::axes`]. Feeds follow G93/G94 as [`crate::read::feed`] describes.

use crate::read::arc::{ArcRequest, CenterWords, Plane, arc_center};
use crate::read::axes::Axes;
use crate::read::codes::Action;
use crate::read::feed::BlockFeed;
use crate::read::kinematics::{AxisPosition, DEFAULT_KINEMATICS_TOL};
use crate::read::lexer::{Block, Word};
use crate::read::program::{Diagnostic, Motion, MotionKind};
use crate::read::warnings::Warnings;
use crate::read::words::Words;
use swarf_geom::units::MM_PER_INCH;
use swarf_geom::{Point3, Vec3};
use swarf_tool::Pose;

/// Most turns one G2/G3 block may make (`P`): thread milling needs tens; more is
/// taken for a mistake rather than handed to a simulation that samples every turn.
pub const MAX_TURNS: u32 = 10_000;

/// What the caller does after a block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Flow {
    /// Read the next line.
    Continue,
    /// The program ended (M2, M30).
    End,
}

/// The modal state and what has been read so far.
pub struct Interpreter<'k> {
    /// Motions emitted so far.
    pub motions: Vec<Motion>,
    /// Warnings so far.
    pub warnings: Warnings,
    /// Axis positions and the tool's pose.
    axes: Axes<'k>,
    motion: Option<Action>,
    plane: Plane,
    absolute: bool,
    ijk_absolute: bool,
    inch: bool,
    units_seen: bool,
    /// Feed in G94, mm/min.
    feed: f64,
    /// Feed in G94 for moves of the rotary axes alone, degrees/min.
    rotary_feed: f64,
    /// G93 inverse-time feed mode.
    inverse_time: bool,
    selected_tool: Option<u32>,
    active_tool: Option<u32>,
    /// An `O` program number was read: numbers without a decimal point are suspicious.
    pub fanuc: bool,
    fanuc_warned: bool,
}

impl Interpreter<'static> {
    /// A three-axis machine at `initial`, in G17 G21 G90 G91.1 G94 with no motion mode
    /// and no feed (LinuxCNC's start-up state).
    pub fn new(initial: Pose) -> Self {
        Interpreter::with_axes(Axes::new(&initial, None, DEFAULT_KINEMATICS_TOL))
    }
}

impl<'k> Interpreter<'k> {
    /// A machine whose axes start at `axes`, otherwise as [`Interpreter::new`].
    pub fn with_axes(axes: Axes<'k>) -> Self {
        Interpreter {
            motions: Vec::new(),
            warnings: Warnings::default(),
            axes,
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
            active_tool: None,
            fanuc: false,
            fanuc_warned: false,
        }
    }

    fn scale(&self) -> f64 {
        if self.inch { MM_PER_INCH } else { 1.0 }
    }

    fn warn(&mut self, line: usize, column: usize, message: impl Into<String>) {
        self.warnings.push(Diagnostic::new(line, column, message));
    }

    /// Executes one block.
    ///
    /// # Errors
    /// A [`Diagnostic`] at the offending word; the state is then unspecified and the
    /// caller stops reading.
    pub fn execute(&mut self, block: &Block, line: usize) -> Result<Flow, Diagnostic> {
        let parsed = Words::sort(block, line, &mut self.warnings)?;
        let is_arc = matches!(
            self.block_mode(&parsed),
            Some(Action::ArcCw | Action::ArcCcw)
        );
        let rotary = self.axes.rotary_letters();
        parsed.check_letters(is_arc, rotary, line, &mut self.warnings)?;
        self.machine_words(&parsed, line)?;
        self.set_modes(&parsed);
        self.motion_words(&parsed, line)?;
        let end = parsed.m.iter().any(|m| m.1 == Action::End);
        Ok(if end { Flow::End } else { Flow::Continue })
    }
    /// The motion mode this block runs in.
    fn block_mode(&self, parsed: &Words) -> Option<Action> {
        match parsed.motion_code() {
            Some((Action::CancelMotion, _)) => None,
            Some((action, _)) => Some(action),
            None => self.motion,
        }
    }

    /// Feed mode, F, S, T, M6 and G4, in that order. In G93 the F word belongs to its
    /// block's motion ([`Interpreter::block_feed`]).
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
            if t.value < 0.0 || t.value.fract() != 0.0 || t.value > f64::from(u32::MAX) {
                return Err(Diagnostic::new(
                    line,
                    t.column,
                    "tool number T must be a whole number >= 0",
                ));
            }
            self.selected_tool = Some(t.value as u32);
        }
        if let Some(m6) = parsed.m.iter().find(|m| m.1 == Action::ToolChange) {
            let tool = self.selected_tool.unwrap_or(0);
            match self.active_tool {
                Some(active) if active != tool && !self.motions.is_empty() => {
                    return Err(Diagnostic::new(
                        line,
                        m6.2.column,
                        format!(
                            "tool change from T{active} to T{tool} after motions: swarf verifies \
                             one tool per program; split the program at the tool change"
                        ),
                    ));
                }
                _ => self.active_tool = Some(tool),
            }
        }
        if let Some(g4) = parsed.has_g(Action::Dwell) {
            self.warn(
                line,
                g4.column,
                "G4 dwell ignored: machining times exclude it",
            );
        }
        Ok(())
    }

    /// Plane, units, distance modes.
    fn set_modes(&mut self, parsed: &Words) {
        for &(_, _, action, _) in &parsed.g {
            match action {
                Action::PlaneXy => self.plane = Plane::Xy,
                Action::PlaneXz => self.plane = Plane::Xz,
                Action::PlaneYz => self.plane = Plane::Yz,
                Action::Inch | Action::Mm => {
                    self.inch = action == Action::Inch;
                    self.units_seen = true;
                }
                Action::Absolute => self.absolute = true,
                Action::Incremental => self.absolute = false,
                Action::ArcAbsolute => self.ijk_absolute = true,
                Action::ArcIncremental => self.ijk_absolute = false,
                _ => {}
            }
        }
    }

    /// The motion this block commands, if any.
    fn motion_words(&mut self, parsed: &Words, line: usize) -> Result<(), Diagnostic> {
        let mode = self.block_mode(parsed);
        self.motion = mode;
        let rotary = self.axes.rotary_letters().unwrap_or(['X'; 2]);
        let axes: Vec<Word> = ['X', 'Y', 'Z', rotary[0], rotary[1]]
            .iter()
            .filter_map(|&l| parsed.get(l))
            .collect();
        let arc_words = ['I', 'J', 'K', 'R']
            .iter()
            .any(|&l| parsed.get(l).is_some());
        if axes.is_empty() && !arc_words {
            return Ok(());
        }
        let column = parsed
            .motion_code()
            .map(|(_, w)| w.column)
            .or_else(|| axes.first().map(|w| w.column))
            .unwrap_or(1);
        let Some(mode) = mode else {
            let why = if parsed.has_g(Action::CancelMotion).is_some() {
                "axis words with G80 (motion cancelled)"
            } else {
                "axis words without a motion mode: program G0, G1, G2 or G3 first"
            };
            return Err(Diagnostic::new(line, column, why));
        };
        self.suspicious_numbers(parsed, line);
        if !self.units_seen {
            self.units_seen = true;
            self.warn(
                line,
                column,
                "no G20/G21 before the first motion: assuming millimetres (G21)",
            );
        }
        let end = self.end_position(parsed);
        let kind = match mode {
            Action::Rapid => MotionKind::Rapid,
            Action::Linear => MotionKind::Linear,
            _ => self.arc_kind(parsed, mode == Action::ArcCw, &end, line, column)?,
        };
        let feed = self.block_feed(kind, parsed, line, column)?;
        let motions = self.axes.move_to(kind, end, feed, line);
        self.motions.extend(motions);
        Ok(())
    }

    /// How the feed of a motion block is given (see [`crate::read::feed`]).
    ///
    /// # Errors
    /// A feed move in G94 with no feed rate; in G93, one without an F word or with F0.
    fn block_feed(
        &self,
        kind: MotionKind,
        parsed: &Words,
        line: usize,
        column: usize,
    ) -> Result<BlockFeed, Diagnostic> {
        if kind == MotionKind::Rapid {
            return Ok(BlockFeed::Rapid);
        }
        if self.inverse_time {
            return match parsed.get('F') {
                Some(f) if f.value > 0.0 => Ok(BlockFeed::InverseTime(f.value)),
                Some(f) => Err(Diagnostic::new(
                    line,
                    f.column,
                    "F0 in inverse-time feed mode (G93): the block would never end",
                )),
                None => Err(Diagnostic::new(
                    line,
                    column,
                    "F word missing on a feed move in inverse-time mode (G93): every G1, \
                     G2 and G3 block needs its own F (1 / minutes)",
                )),
            };
        }
        if self.feed <= 0.0 {
            return Err(Diagnostic::new(
                line,
                column,
                "feed move with zero feed rate: program F before the first G1, G2 or G3",
            ));
        }
        Ok(BlockFeed::PerMinute {
            linear: self.feed,
            rotary: self.rotary_feed,
        })
    }

    /// The axis position at the end of the block's motion: mm, and radians for the
    /// rotary axes (whose words are degrees, not scaled by G20).
    fn end_position(&self, parsed: &Words) -> AxisPosition {
        let mut end = *self.axes.position();
        let rotary = self.axes.rotary_letters();
        let letters = ['X', 'Y', 'Z']
            .into_iter()
            .chain(rotary.into_iter().flatten());
        for (k, letter) in letters.enumerate() {
            if let Some(w) = parsed.get(letter) {
                let v = if k < 3 {
                    w.value * self.scale()
                } else {
                    w.value.to_radians()
                };
                end[k] = if self.absolute { v } else { end[k] + v };
            }
        }
        end
    }

    fn arc_kind(
        &self,
        parsed: &Words,
        clockwise: bool,
        end: &AxisPosition,
        line: usize,
        column: usize,
    ) -> Result<MotionKind, Diagnostic> {
        let err = |column: usize, message: String| Err(Diagnostic::new(line, column, message));
        let plane = self.plane;
        let foreign = plane.foreign_offset();
        if let Some(w) = parsed.get(foreign) {
            return err(
                w.column,
                format!(
                    "{foreign} word given for an arc in the {} plane",
                    plane.name()
                ),
            );
        }
        let [oa, ob] = plane.offset_letters().map(|l| parsed.get(l));
        let center = match (parsed.get('R'), oa.or(ob)) {
            (Some(r), Some(_)) => {
                return err(
                    r.column,
                    "mixed radius (R) and centre (I/J/K) format for an arc".into(),
                );
            }
            (Some(r), None) => CenterWords::Radius(r.value),
            (None, Some(_)) => CenterWords::Offsets([oa, ob].map(|w| w.map_or(0.0, |w| w.value))),
            (None, None) => {
                let [la, lb] = plane.offset_letters();
                return err(column, format!("arc without R, {la} or {lb} words"));
            }
        };
        let turns = match parsed.get('P') {
            None => 1,
            Some(p)
                if p.value >= 1.0 && p.value.fract() == 0.0 && p.value <= f64::from(MAX_TURNS) =>
            {
                p.value as u32
            }
            Some(p) => {
                return err(
                    p.column,
                    format!("P (turns) of an arc must be a whole number from 1 to {MAX_TURNS}"),
                );
            }
        };
        let scale = self.scale();
        let request = ArcRequest {
            plane,
            clockwise,
            start: xyz(self.axes.position()) / scale,
            end: xyz(end) / scale,
            center,
            ijk_absolute: self.ijk_absolute,
            inch: self.inch,
        };
        let center = arc_center(&request).map_err(|m| Diagnostic::new(line, column, m))?;
        let mut normal = Vec3::zeros();
        normal[plane.indices()[2]] = 1.0;
        Ok(MotionKind::Arc {
            center: Point3::from(center.coords * scale),
            normal,
            clockwise,
            turns,
        })
    }

    /// Fanuc-style programs read `X10` as ten least increments; LinuxCNC as 10 units.
    fn suspicious_numbers(&mut self, parsed: &Words, line: usize) {
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

    /// The tool number of the last M6, if any.
    pub fn tool_number(&self) -> Option<u32> {
        self.active_tool
    }
}

/// The `X Y Z` of an axis position.
fn xyz(p: &AxisPosition) -> Point3 {
    Point3::new(p[0], p[1], p[2])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::read::lexer::lex_line;

    fn run(lines: &[&str]) -> (Interpreter<'static>, Option<Diagnostic>) {
        let mut machine = Interpreter::new(Pose::vertical(Point3::origin()));
        for (i, text) in lines.iter().enumerate() {
            let block = lex_line(text, i + 1).unwrap();
            match machine.execute(&block, i + 1) {
                Ok(Flow::Continue) => {}
                Ok(Flow::End) => break,
                Err(d) => return (machine, Some(d)),
            }
        }
        (machine, None)
    }

    #[test]
    fn order_of_execution_within_a_block() {
        // F before units: F10 is mm/min; G91 before the motion: X1 is incremental inches
        let (m, err) = run(&["G21 G0 X1", "G20 G91 F10 G1 X1"]);
        assert!(err.is_none());
        let last = m.motions[1];
        assert_eq!(last.feed, 10.0);
        assert!((last.end.cl.x - 26.4).abs() < 1e-12);
    }

    #[test]
    fn incremental_arcs_and_absolute_centres() {
        let (m, err) = run(&[
            "G21 G91 F100",
            "G3 X10 Y10 I0 J10",
            "G90 G90.1 G2 X20 Y0 I10 J0",
        ]);
        assert!(err.is_none(), "{err:?}");
        let MotionKind::Arc {
            center, clockwise, ..
        } = m.motions[0].kind
        else {
            panic!("{:?}", m.motions[0]);
        };
        assert_eq!((center, clockwise), (Point3::new(0.0, 10.0, 0.0), false));
        let MotionKind::Arc { center, .. } = m.motions[1].kind else {
            panic!("{:?}", m.motions[1]);
        };
        assert_eq!(center, Point3::new(10.0, 0.0, 0.0));
    }

    #[test]
    fn inverse_time_on_three_axes_as_rs274_reads_it() {
        // rs274 -g: SET_FEED_RATE(20) for the 2 mm line at F10, 31.4159 for the half
        // circle of radius 2 at F5; G0 needs no F.
        let (m, err) = run(&["G21 G93", "G1 X2 F10", "G0 X0", "G2 X4 I2 F5"]);
        assert!(err.is_none(), "{err:?}");
        assert!((m.motions[0].feed - 20.0).abs() < 1e-12);
        assert_eq!(m.motions[1].feed, 0.0);
        assert!((m.motions[2].feed - 10.0 * std::f64::consts::PI).abs() < 1e-12);
        let (_, err) = run(&["G21 G93", "G1 X2 F10", "X3"]);
        assert_eq!(err.map(|d| (d.line, d.column)), Some((3, 1)));
    }

    #[test]
    fn modes_persist_and_end_stops() {
        let (m, err) = run(&["G21 G18 F50", "G2 X10 Z0 I5 K0", "M30", "G0 X99"]);
        assert!(err.is_none());
        assert_eq!(m.motions.len(), 1);
        let MotionKind::Arc { normal, .. } = m.motions[0].kind else {
            panic!();
        };
        assert_eq!(normal, Vec3::y());
        let (_, err) = run(&["G21 G1 X1 F10", "G80", "X2"]);
        assert_eq!(err.map(|d| (d.line, d.column)), Some((3, 1)));
    }
}
