//! Cutter radius compensation (G40, G41, G42, G41.1, G42.1) as LinuxCNC 2.9 computes
//! it (`interp_convert.cc`: `convert_cutter_compensation_on/off`,
//! `convert_straight_comp1/2`, `convert_arc_comp1/2`; `interp_queue.cc`), in the XY plane.
//!
//! The radius `r` is half the tool table diameter of tool D (or of the loaded tool
//! without D), or half the D word of G41.1/G42.1; a negative radius swaps the side.
//! The tool runs `r` to the left (G41) or right (G42) of the programmed path:
//!
//! - **Entry** (the first move after G41/G42): a line from where the tool is to the
//!   point `r` to the side of the programmed end, perpendicular to the entry line (or
//!   an arc ending `r` off the programmed end along its radius, its centre moved so
//!   that it still passes through the start). The entry must be longer than `r`.
//! - **Corners.** At each programmed point the previous segment's direction (from the
//!   tool's radius there) and the next one's are compared with a slack of 0.05 rad. A
//!   convex corner gets an arc of radius `r` about the programmed point (a straight
//!   rapid for G0). At a concave corner the previous move, still held back in a queue,
//!   is shortened to where the tool touches both segments: back along a line by
//!   `r / tan((beta + pi) / 2)`, or to the intersection with the offset arc. A move that
//!   would have to run backwards, or an arc that would sweep further than programmed,
//!   cannot be cut without gouging and is an error, as in LinuxCNC.
//! - Moves without XY motion (Z only) stay in the queue with the move before them, so
//!   that a corner after them still trims that move. G40 (and M0, M1, M2, M30) ends the
//!   queue where the tool is; the next move must be straight.
//!
//! The moves themselves are in `straight` (G0, G1) and `arc` (G2, G3).

use crate::read::arc::Plane;
use crate::read::comp_geometry::find_turn;
use crate::read::feed::BlockFeed;
use crate::read::modal::{Interpreter, Pos};
use crate::read::motion::ArcMove;
use crate::read::words::{Word, Words};
use swarf_toolpath::program::{Diagnostic, MotionKind};

mod arc;
mod straight;

/// LinuxCNC `TOLERANCE_CONCAVE_CORNER`, radians.
const CORNER_SLACK: f64 = 0.05;

/// A move held back until the next corner is known.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Queued {
    Straight {
        rapid: bool,
        /// The programmed direction (for the backwards check).
        dir: [f64; 2],
        end: Pos,
        feed: Option<BlockFeed>,
        line: usize,
    },
    Arc {
        /// The angle the arc sweeps as programmed, signed (0: an added corner arc).
        sweep: f64,
        end: Pos,
        center: [f64; 2],
        /// Turns, positive counter-clockwise.
        turn: i32,
        feed: Option<BlockFeed>,
        line: usize,
    },
}

/// The compensation state.
#[derive(Debug, Clone, PartialEq)]
pub struct Comp {
    /// On, and to the left (G41) or right (G42).
    left: Option<bool>,
    /// Radius, program units (>= 0).
    radius: f64,
    /// No move since compensation was turned on.
    pub firstmove: bool,
    /// The programmed point (where the path would be without compensation).
    pub program: [f64; 3],
    /// The move after G40 must be straight.
    pub arc_not_allowed: bool,
    queue: Vec<Queued>,
    /// Where the queued moves start, when known.
    endpoint: Option<[f64; 2]>,
}

impl Default for Comp {
    fn default() -> Self {
        Comp {
            left: None,
            radius: 0.0,
            firstmove: true,
            program: [0.0; 3],
            arc_not_allowed: false,
            queue: Vec::new(),
            endpoint: None,
        }
    }
}

impl Comp {
    /// Whether G41/G42 is in force.
    pub fn is_on(&self) -> bool {
        self.left.is_some()
    }

    /// Left (true) or right (false) of the path, when on.
    pub fn side(&self) -> Option<bool> {
        self.left
    }

    /// Whether moves are compensated (on, with a radius).
    pub fn active(&self) -> bool {
        self.is_on() && self.radius > 0.0
    }

    /// Carries lengths into other units (`k` new units per old unit).
    pub fn scale(&mut self, k: f64) {
        self.radius *= k;
        for v in &mut self.program {
            *v *= k;
        }
        if let Some(e) = &mut self.endpoint {
            e[0] *= k;
            e[1] *= k;
        }
        for q in &mut self.queue {
            let end = match q {
                Queued::Straight { end, .. } => end,
                Queued::Arc { end, center, .. } => {
                    center[0] *= k;
                    center[1] *= k;
                    end
                }
            };
            for v in end[..3].iter_mut() {
                *v *= k;
            }
        }
    }
}

fn with_xy(mut p: Pos, x: f64, y: f64) -> Pos {
    p[0] = x;
    p[1] = y;
    p
}

impl Interpreter<'_> {
    /// G41/G42 (`left`), G41.1/G42.1 (`diameter`) with the block's D word.
    pub(crate) fn comp_on(
        &mut self,
        left: bool,
        diameter: bool,
        parsed: &Words,
        w: Word,
        line: usize,
    ) -> Result<(), Diagnostic> {
        let err = |column: usize, m: String| Err(Diagnostic::new(line, column, m));
        let name = if left { "G41" } else { "G42" };
        if self.plane != Plane::Xy {
            return err(
                w.column,
                "cutter radius compensation out of the XY plane (G17) is not supported: in G18 \
                 it is lathe compensation"
                    .into(),
            );
        }
        if self.comp.is_on() {
            return err(
                w.column,
                "cannot turn cutter radius compensation on when it is on".into(),
            );
        }
        let d = parsed.get('D');
        let mut radius = if diameter {
            let Some(d) = d else {
                return err(w.column, format!("{name}.1 with no D word"));
            };
            if let Some(l) = parsed.get('L') {
                return err(
                    l.column,
                    format!("{name}.1 with an L word: lathe tool orientation is not supported"),
                );
            }
            d.value / 2.0
        } else {
            let number = match d {
                Some(d) => {
                    let near = d.value.round();
                    if (near - d.value).abs() >= 1e-4 {
                        return err(
                            d.column,
                            format!("{name} requires the D word to be a whole number"),
                        );
                    }
                    if near < 0.0 {
                        return err(d.column, "negative D word tool radius index used".into());
                    }
                    Some(near as u32)
                }
                None => self.loaded_tool,
            };
            let tool = match number {
                Some(n) if n != 0 => match self.tools.get(n) {
                    Some(t) => *t,
                    None => {
                        return err(
                            d.map_or(w.column, |d| d.column),
                            format!(
                                "tool number {n} not found in the tool table: give the table with --tool-table"
                            ),
                        );
                    }
                },
                _ => Default::default(),
            };
            if tool.orientation != 0 && tool.orientation != 9 {
                return err(
                    w.column,
                    format!(
                        "{name} with a lathe tool (orientation {})",
                        tool.orientation
                    ),
                );
            }
            self.user_to_program(tool.diameter) / 2.0
        };
        let mut side = left;
        if radius < 0.0 {
            radius = -radius;
            side = !side;
        }
        self.comp.radius = radius;
        self.comp.left = Some(side);
        Ok(())
    }

    /// G40: the queue ends where the tool is.
    pub(crate) fn comp_off(&mut self, line: usize) -> Result<(), Diagnostic> {
        if self.comp.active() && !self.comp.firstmove {
            let (x, y) = (self.cur[0], self.cur[1]);
            self.move_endpoint_and_flush(x, y, line)?;
            self.dequeue(line)?;
            self.cur[..3].copy_from_slice(&self.comp.program);
            self.comp.arc_not_allowed = true;
        }
        self.comp.left = None;
        self.comp.firstmove = true;
        Ok(())
    }

    /// Refuses `what` while compensation is on (at `column` of `line`).
    pub(crate) fn refuse_with_comp(
        &self,
        what: &str,
        line: usize,
        column: usize,
    ) -> Result<(), Diagnostic> {
        if self.comp.is_on() {
            return Err(Diagnostic::new(
                line,
                column,
                format!("cannot {what} with cutter radius compensation on"),
            ));
        }
        Ok(())
    }

    /// Ends the queue where the tool is (M0, M1, M2, M30, the end of the program).
    pub(crate) fn comp_flush_here(&mut self, line: usize) -> Result<(), Diagnostic> {
        let (x, y) = (self.cur[0], self.cur[1]);
        self.move_endpoint_and_flush(x, y, line)?;
        self.dequeue(line)
    }

    fn dequeue(&mut self, _line: usize) -> Result<(), Diagnostic> {
        self.comp.endpoint = None;
        for q in std::mem::take(&mut self.comp.queue) {
            match q {
                Queued::Straight {
                    rapid,
                    end,
                    feed,
                    line,
                    ..
                } => {
                    let kind = if rapid {
                        MotionKind::Rapid
                    } else {
                        MotionKind::Linear
                    };
                    self.emit_straight(kind, end, feed, line)?;
                }
                Queued::Arc {
                    end,
                    center,
                    turn,
                    feed,
                    line,
                    ..
                } => {
                    let arc = ArcMove {
                        center: [center[0], center[1], end[2]],
                        plane: Plane::Xy,
                        clockwise: turn < 0,
                        turns: turn.unsigned_abs(),
                    };
                    self.emit_arc(&arc, end, feed, line)?;
                }
            }
        }
        Ok(())
    }

    /// Moves the XY end of every queued move to `(x, y)`, then emits them.
    fn move_endpoint_and_flush(&mut self, x: f64, y: f64, line: usize) -> Result<(), Diagnostic> {
        if self.comp.queue.is_empty() {
            return Ok(());
        }
        let endpoint = self.comp.endpoint;
        let slack = if self.inch { 0.001 } else { 0.0254 };
        for q in &mut self.comp.queue {
            match q {
                Queued::Arc {
                    sweep,
                    end,
                    center,
                    turn,
                    line: qline,
                    ..
                } => {
                    let r1 = (end[0] - center[0]).hypot(end[1] - center[1]);
                    let r2 = (x - center[0]).hypot(y - center[1]);
                    if (r1 - r2).abs() > 0.01 {
                        return Err(Diagnostic::new(
                            *qline,
                            1,
                            format!(
                                "cutter compensation made an arc with mismatched radii r1 {r1:.6} r2 {r2:.6}"
                            ),
                        ));
                    }
                    if let Some(e) = endpoint {
                        let l2 = find_turn(e, *center, *turn, [x, y]);
                        if *sweep != 0.0 && l2.abs() > sweep.abs() + slack {
                            return Err(Diagnostic::new(
                                line,
                                1,
                                "arc move in concave corner cannot be reached by the tool without gouging",
                            ));
                        }
                    }
                    *end = with_xy(*end, x, y);
                }
                Queued::Straight {
                    rapid, dir, end, ..
                } => {
                    if let Some(e) = endpoint {
                        let dot = dir[0] * (x - e[0]) + dir[1] * (y - e[1]);
                        if dot < 0.0 {
                            let what = if *rapid {
                                "straight traverse"
                            } else {
                                "straight feed"
                            };
                            return Err(Diagnostic::new(
                                line,
                                1,
                                format!(
                                    "{what} in concave corner cannot be reached by the tool without gouging"
                                ),
                            ));
                        }
                    }
                    *end = with_xy(*end, x, y);
                }
            }
        }
        self.dequeue(line)?;
        self.comp.endpoint = Some([x, y]);
        Ok(())
    }
}

fn with_z(mut p: Pos, z: f64) -> Pos {
    p[2] = z;
    p
}
