//! Motion blocks (`interp_convert.cc`: `convert_straight`, `convert_arc`;
//! `interp_find.cc`: `find_ends`): the end point of a block in program coordinates
//! (absolute, incremental, polar, or machine coordinates with G53), its feed, and the
//! motions it emits into the part frame ([`crate::read::offsets`] for the transform).
//!
//! Polar words (`@` distance, `^` angle in degrees, G17 only) are about the origin of
//! the coordinate system: absolute, `@` and `^` place the point; a missing one keeps
//! the current point's. Incremental, `@` adds to its distance from the origin and `^`
//! turns it about the origin (not about the current point), as LinuxCNC does.

use crate::read::arc::{ArcRequest, CenterWords, Plane, arc_center};
use crate::read::codes::Action;
use crate::read::feed::BlockFeed;
use crate::read::modal::{Interpreter, MAX_TURNS, Pos};
use crate::read::words::Words;
use swarf_geom::{Point3, Vec3};
use swarf_toolpath::program::{Diagnostic, MotionKind};

/// An arc in program coordinates, ready to emit.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ArcMove {
    /// Centre (the normal coordinate that of the start), program units.
    pub center: [f64; 3],
    /// The plane.
    pub plane: Plane,
    /// Clockwise about the plane's normal.
    pub clockwise: bool,
    /// Turns (P).
    pub turns: u32,
}

impl Interpreter<'_> {
    /// Runs the motion of the block: `action` is the motion mode it runs in.
    pub(crate) fn motion_words(
        &mut self,
        action: Action,
        parsed: &Words,
        line: usize,
    ) -> Result<(), Diagnostic> {
        let previous = self.motion;
        self.motion = Some(action);
        if !matches!(action, Action::Cycle(_)) {
            self.cycle.initial_level = None;
        }
        self.suspicious_numbers(parsed, line);
        match action {
            Action::Rapid | Action::Linear => self.straight(action == Action::Rapid, parsed, line),
            Action::ArcCw | Action::ArcCcw => self.arc(action == Action::ArcCw, parsed, line),
            Action::Cycle(n) => self.canned_cycle(n, previous, parsed, line),
            _ => Ok(()),
        }
    }

    /// The column to report a motion's errors at: its G word or first axis word.
    pub(crate) fn motion_column(&self, parsed: &Words) -> usize {
        parsed
            .motion_code()
            .map(|(_, w)| w.column)
            .or_else(|| {
                parsed
                    .axis_word(self.axes.rotary_letters())
                    .map(|w| w.column)
            })
            .or_else(|| parsed.get('@').or(parsed.get('^')).map(|w| w.column))
            .unwrap_or(1)
    }

    /// G0 / G1.
    fn straight(&mut self, rapid: bool, parsed: &Words, line: usize) -> Result<(), Diagnostic> {
        let column = self.motion_column(parsed);
        let g53 = parsed.has_g(Action::MachineCoords);
        let kind = if rapid {
            MotionKind::Rapid
        } else {
            MotionKind::Linear
        };
        let feed = self.block_feed(kind, parsed, line, column)?;
        let end = self.find_ends(parsed, line, true)?;
        self.comp.arc_not_allowed = false;
        if self.comp.is_on() {
            if let Some(w) = g53 {
                return Err(Diagnostic::new(
                    line,
                    w.column,
                    "cannot use G53 with cutter radius compensation on",
                ));
            }
            return self.comp_straight(rapid, end, feed, line);
        }
        self.emit_straight(kind, end, feed, line)?;
        self.cur = end;
        Ok(())
    }

    /// G2 / G3.
    fn arc(&mut self, clockwise: bool, parsed: &Words, line: usize) -> Result<(), Diagnostic> {
        let column = self.motion_column(parsed);
        let err = |column: usize, message: String| Err(Diagnostic::new(line, column, message));
        if self.comp.arc_not_allowed {
            return err(
                column,
                "the move just after exiting cutter compensation mode must be straight, not an arc"
                    .into(),
            );
        }
        if let Some(w) = parsed.has_g(Action::MachineCoords) {
            return err(w.column, "G53 must be used with G0 or G1".into());
        }
        let plane = self.plane;
        let center = self.center_words(parsed, line, column)?;
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
        let kind = MotionKind::Arc {
            center: Point3::origin(),
            normal: Vec3::z(),
            clockwise,
            turns,
        };
        let feed = self.block_feed(kind, parsed, line, column)?;
        let end = self.find_ends(parsed, line, true)?;
        if self.comp.active() {
            return self.comp_arc(clockwise, center, turns, end, feed, line, column);
        }
        let request = ArcRequest {
            plane,
            clockwise,
            start: xyz(&self.cur),
            end: xyz(&end),
            center,
            ijk_absolute: self.ijk_absolute,
            inch: self.inch,
        };
        let c = arc_center(&request).map_err(|m| Diagnostic::new(line, column, m))?;
        let arc = ArcMove {
            center: [c.x, c.y, c.z],
            plane,
            clockwise,
            turns,
        };
        self.emit_arc(&arc, end, feed, line)?;
        self.cur = end;
        Ok(())
    }

    /// How an arc block gives its centre: `R`, or the plane's offset words (both in
    /// G90.1), with LinuxCNC's checks.
    fn center_words(
        &self,
        parsed: &Words,
        line: usize,
        column: usize,
    ) -> Result<CenterWords, Diagnostic> {
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
        let [la, lb] = plane.offset_letters();
        let [oa, ob] = [la, lb].map(|l| parsed.get(l));
        let center = match (parsed.get('R'), oa.or(ob)) {
            (Some(r), Some(_)) => {
                return err(
                    r.column,
                    "mixed radius (R) and centre (I/J/K) format for an arc".into(),
                );
            }
            (Some(r), None) => CenterWords::Radius(r.value),
            (None, Some(w)) => {
                let missing = [(la, oa), (lb, ob)].into_iter().find(|(_, o)| o.is_none());
                if let (true, Some((l, _))) = (self.ijk_absolute, missing) {
                    return err(w.column, format!("{l} word missing in absolute center arc"));
                }
                CenterWords::Offsets([oa, ob].map(|w| w.map_or(0.0, |w| w.value)))
            }
            (None, None) => return err(column, format!("arc without R, {la} or {lb} words")),
        };
        if let CenterWords::Radius(_) = center {
            let [xa, xb] = plane.axis_letters();
            let polar = parsed.get('@').or(parsed.get('^'));
            if parsed.get(xa).is_none() && parsed.get(xb).is_none() && polar.is_none() {
                return err(
                    column,
                    format!(
                        "{xa} and {xb} words missing for an R arc in the {} plane",
                        plane.name()
                    ),
                );
            }
        }
        Ok(center)
    }

    /// How the feed of a motion block is given (see [`crate::read::feed`]).
    ///
    /// # Errors
    /// A feed move in G94 with no feed rate; in G93, one without an F word or with F0.
    pub(crate) fn block_feed(
        &self,
        kind: MotionKind,
        parsed: &Words,
        line: usize,
        column: usize,
    ) -> Result<Option<BlockFeed>, Diagnostic> {
        if kind == MotionKind::Rapid {
            return Ok(None);
        }
        if self.inverse_time {
            return match parsed.get('F') {
                Some(f) if f.value > 0.0 => Ok(Some(BlockFeed::InverseTime(f.value))),
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
        Ok(Some(self.per_minute()))
    }

    /// The G94 feed in force.
    pub(crate) fn per_minute(&self) -> BlockFeed {
        BlockFeed::PerMinute {
            linear: self.feed,
            rotary: self.rotary_feed,
        }
    }

    /// The end point of the block's motion, program coordinates (`find_ends`); with
    /// `polar`, `@` and `^` words place it.
    pub(crate) fn find_ends(
        &self,
        parsed: &Words,
        line: usize,
        polar: bool,
    ) -> Result<Pos, Diagnostic> {
        let err = |column: usize, m: &str| Err(Diagnostic::new(line, column, m));
        let r_word = parsed.get('@').filter(|_| polar);
        let t_word = parsed.get('^').filter(|_| polar);
        if let Some(g53) = parsed.has_g(Action::MachineCoords) {
            if let Some(w) = r_word.or(t_word) {
                return err(w.column, "cannot use polar coordinates with G53");
            }
            if !self.absolute {
                return err(
                    g53.column,
                    "cannot use G53 in incremental distance mode (G91)",
                );
            }
            return Ok(self.machine_coordinates_end(parsed));
        }
        let middle = self.comp.is_on() && !self.comp.firstmove;
        let mut base = self.cur;
        if middle {
            base[0] = self.comp.program[0];
            base[1] = self.comp.program[1];
        }
        let mut end = base;
        let letters = ['X', 'Y', 'Z', 'A', 'B', 'C'];
        for (k, l) in letters.into_iter().enumerate() {
            if let Some(w) = parsed.get(l) {
                end[k] = if self.absolute {
                    w.value
                } else {
                    base[k] + w.value
                };
            }
        }
        if r_word.is_none() && t_word.is_none() {
            return Ok(end);
        }
        let column = r_word.or(t_word).map_or(1, |w| w.column);
        let (x, y) = (base[0], base[1]);
        if self.absolute {
            let (radius, theta) = match (r_word, t_word) {
                (Some(r), Some(t)) => (r.value, t.value.to_radians()),
                (Some(r), None) if x == 0.0 && y == 0.0 => {
                    return err(
                        r.column,
                        "must specify the angle (^) in polar coordinates at the origin",
                    );
                }
                (Some(r), None) => (r.value, y.atan2(x)),
                (None, Some(t)) => (y.hypot(x), t.value.to_radians()),
                (None, None) => (0.0, 0.0),
            };
            end[0] = radius * theta.cos();
            end[1] = radius * theta.sin();
        } else {
            if x == 0.0 && y == 0.0 {
                return err(
                    column,
                    "incremental motion with polar coordinates is indeterminate at the origin",
                );
            }
            let mut radius = y.hypot(x);
            let mut theta = y.atan2(x);
            if let Some(r) = r_word {
                radius += r.value;
            }
            if let Some(t) = t_word {
                theta += t.value.to_radians();
            }
            end[0] = radius * theta.cos();
            end[1] = radius * theta.sin();
        }
        Ok(end)
    }

    /// Emits a straight motion from where the tool is to the program point `end`.
    ///
    /// # Errors
    /// None today; the signature leaves room for travel limits.
    pub(crate) fn emit_straight(
        &mut self,
        kind: MotionKind,
        end: Pos,
        feed: Option<BlockFeed>,
        line: usize,
    ) -> Result<(), Diagnostic> {
        self.check_tool(kind != MotionKind::Rapid, line)?;
        self.check_tool_offset(line);
        let to = self.axis_position(&end);
        let feed = feed.unwrap_or(BlockFeed::Rapid);
        let motions = self.axes.move_to(kind, to, feed, line);
        self.motions.extend(motions);
        Ok(())
    }

    /// Emits an arc from where the tool is to the program point `end`.
    ///
    /// # Errors
    /// None today; the signature leaves room for travel limits.
    pub(crate) fn emit_arc(
        &mut self,
        arc: &ArcMove,
        end: Pos,
        feed: Option<BlockFeed>,
        line: usize,
    ) -> Result<(), Diagnostic> {
        self.check_tool(true, line)?;
        self.check_tool_offset(line);
        let mut c = [0.0; 6];
        c[..3].copy_from_slice(&arc.center);
        let m = self.to_machine(&c);
        let mut normal = [0.0; 3];
        normal[arc.plane.indices()[2]] = 1.0;
        let (nx, ny) = crate::read::offsets::rotate(normal[0], normal[1], self.offsets.rotation);
        let kind = MotionKind::Arc {
            center: Point3::new(m[0], m[1], m[2]),
            normal: Vec3::new(nx, ny, normal[2]),
            clockwise: arc.clockwise,
            turns: arc.turns,
        };
        let to = self.axis_position(&end);
        let feed = feed.unwrap_or(BlockFeed::Rapid);
        let motions = self.axes.move_to(kind, to, feed, line);
        self.motions.extend(motions);
        Ok(())
    }
}

/// The `X Y Z` of a position.
pub(crate) fn xyz(p: &Pos) -> Point3 {
    Point3::new(p[0], p[1], p[2])
}
