//! Compensated straight moves (G0, G1): the entry line after G41/G42
//! (`convert_straight_comp1`) and a line after it with its corner
//! (`convert_straight_comp2`), as the parent module describes.

use crate::read::comp_geometry::{arc_to_line_corner, inside, line_to_line_corner};
use crate::read::feed::BlockFeed;
use crate::read::modal::{Interpreter, Pos};
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use swarf_toolpath::program::{Diagnostic, MotionKind};

use super::{CORNER_SLACK, Queued, with_xy, with_z};

impl Interpreter<'_> {
    /// A G0/G1 block with compensation on, to the programmed `end`.
    pub(crate) fn comp_straight(
        &mut self,
        rapid: bool,
        end: Pos,
        feed: Option<BlockFeed>,
        line: usize,
    ) -> Result<(), Diagnostic> {
        if !self.comp.active() {
            self.emit_straight(
                if rapid {
                    MotionKind::Rapid
                } else {
                    MotionKind::Linear
                },
                end,
                feed,
                line,
            )?;
            self.cur = end;
            return Ok(());
        }
        if self.comp.firstmove {
            return self.comp_entry_line(rapid, end, feed, line);
        }
        self.comp_corner_line(rapid, end, feed, line)
    }

    /// The first move after G41/G42 is a line (`convert_straight_comp1`).
    fn comp_entry_line(
        &mut self,
        rapid: bool,
        end: Pos,
        feed: Option<BlockFeed>,
        line: usize,
    ) -> Result<(), Diagnostic> {
        let left = self.comp.left == Some(true);
        let r = self.comp.radius;
        let (px, py) = (end[0], end[1]);
        let (cx, cy) = (self.cur[0], self.cur[1]);
        if (px - cx).hypot(py - cy) <= r {
            return Err(Diagnostic::new(
                line,
                1,
                "length of cutter compensation entry move is not greater than the tool radius",
            ));
        }
        let alpha = (py - cy).atan2(px - cx) + if left { FRAC_PI_2 } else { -FRAC_PI_2 };
        let tool_end = with_xy(end, px + r * alpha.cos(), py + r * alpha.sin());
        self.comp.endpoint = Some([cx, cy]);
        self.comp.queue.push(Queued::Straight {
            rapid,
            dir: [alpha.cos(), alpha.sin()],
            end: tool_end,
            feed,
            line,
        });
        self.comp.firstmove = false;
        self.cur = tool_end;
        self.comp.program = [px, py, end[2]];
        Ok(())
    }

    /// A line after the first move (`convert_straight_comp2`): the corner with the
    /// move before it, then the line, queued.
    fn comp_corner_line(
        &mut self,
        rapid: bool,
        end: Pos,
        feed: Option<BlockFeed>,
        line: usize,
    ) -> Result<(), Diagnostic> {
        let left = self.comp.left == Some(true);
        let r = self.comp.radius;
        let (px, py) = (end[0], end[1]);
        let (cx, cy) = (self.cur[0], self.cur[1]);
        let [opx, opy, _] = self.comp.program;
        let cz = self.cur[2];
        if px == opx && py == opy {
            let still = with_xy(end, cx, cy);
            self.comp.queue.push(Queued::Straight {
                rapid,
                dir: [0.0, 0.0],
                end: still,
                feed,
                line,
            });
            (self.cur, self.comp.program) = (still, [px, py, end[2]]);
            return Ok(());
        }
        let mut theta = (cy - opy).atan2(cx - opx);
        let mut alpha = (py - opy).atan2(px - opx);
        let (beta, gamma) = if left {
            if theta < alpha {
                theta += TAU;
            }
            (theta - alpha - FRAC_PI_2, FRAC_PI_2)
        } else {
            if alpha < theta {
                alpha += TAU;
            }
            (alpha - theta - FRAC_PI_2, -FRAC_PI_2)
        };
        let tool_end = with_xy(
            end,
            px + r * (alpha + gamma).cos(),
            py + r * (alpha + gamma).sin(),
        );
        let mid = [
            opx + r * (alpha + gamma).cos(),
            opy + r * (alpha + gamma).sin(),
        ];
        let front_arc_turn = self.comp.queue.first().and_then(|q| match q {
            Queued::Arc { turn, .. } => Some(*turn),
            Queued::Straight { .. } => None,
        });
        let concave = !(-CORNER_SLACK..=PI + CORNER_SLACK).contains(&beta)
            || (beta > PI - CORNER_SLACK && front_arc_turn.is_some_and(|t| inside(!left, t)));
        if !concave && beta > CORNER_SLACK {
            self.move_endpoint_and_flush(cx, cy, line)?;
            let mid_pos = with_xy(with_z(self.cur, cz), mid[0], mid[1]);
            self.comp
                .queue
                .push(turn_round(rapid, mid_pos, [opx, opy], left, feed, line));
            self.dequeue(line)?;
            self.comp.endpoint = Some(mid);
        } else if concave {
            let (mx, my) = match self.comp.queue.first().copied() {
                Some(Queued::Arc {
                    end: qend,
                    center,
                    turn,
                    ..
                }) => arc_to_line_corner(left, r, [opx, opy], [px, py], qend, center, turn)
                    .map_err(|m| Diagnostic::new(line, 1, m))?,
                _ => line_to_line_corner(r, [cx, cy], theta + gamma, beta)
                    .map_err(|m| Diagnostic::new(line, 1, m))?,
            };
            self.move_endpoint_and_flush(mx, my, line)?;
        } else {
            self.dequeue(line)?;
            self.comp.endpoint = Some([cx, cy]);
        }
        self.comp.queue.push(Queued::Straight {
            rapid,
            dir: [px - opx, py - opy],
            end: tool_end,
            feed,
            line,
        });
        (self.cur, self.comp.program) = (tool_end, [px, py, end[2]]);
        Ok(())
    }
}

/// The move round a convex corner to `end` about the programmed point `center`: an
/// arc, or a straight rapid for G0.
fn turn_round(
    rapid: bool,
    end: Pos,
    center: [f64; 2],
    left: bool,
    feed: Option<BlockFeed>,
    line: usize,
) -> Queued {
    if rapid {
        return Queued::Straight {
            rapid: true,
            dir: [0.0, 0.0],
            end,
            feed,
            line,
        };
    }
    Queued::Arc {
        sweep: 0.0,
        end,
        center,
        turn: if left { -1 } else { 1 },
        feed,
        line,
    }
}
