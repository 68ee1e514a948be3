//! Compensated arcs (G2, G3): the centre and radius checks, the entry arc after
//! G41/G42 (`convert_arc_comp1`) and an arc after it with its corner
//! (`convert_arc_comp2`), as the parent module describes.

use crate::read::arc::{
    ArcRequest, CenterWords, Plane, SPIRAL_TOLERANCE_INCH, SPIRAL_TOLERANCE_MM, arc_center,
};
use crate::read::comp_geometry::{arc_to_arc_corner, find_turn, inside, line_to_arc_corner};
use crate::read::expr::TOLERANCE_EQUAL;
use crate::read::feed::BlockFeed;
use crate::read::modal::{Interpreter, Pos};
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use swarf_toolpath::program::Diagnostic;

use super::{CORNER_SLACK, Queued, with_xy, with_z};

impl Interpreter<'_> {
    /// A G2/G3 block with compensation on and a radius.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn comp_arc(
        &mut self,
        clockwise: bool,
        center: CenterWords,
        turns: u32,
        end: Pos,
        feed: Option<BlockFeed>,
        line: usize,
        column: usize,
    ) -> Result<(), Diagnostic> {
        let err = |m: &str| Err(Diagnostic::new(line, column, m));
        let left = self.comp.left == Some(true);
        let r = self.comp.radius;
        let turn = if clockwise {
            -(turns as i32)
        } else {
            turns as i32
        };
        let first = self.comp.firstmove;
        let start = if first {
            [self.cur[0], self.cur[1], self.cur[2]]
        } else {
            self.comp.program
        };
        if first && (end[0] - start[0]).hypot(end[1] - start[1]) <= r {
            return err(
                "radius of cutter compensation entry arc is not greater than the tool radius",
            );
        }
        let request = ArcRequest {
            plane: Plane::Xy,
            clockwise,
            start: swarf_geom::Point3::new(start[0], start[1], start[2]),
            end: crate::read::motion::xyz(&end),
            center,
            ijk_absolute: self.ijk_absolute,
            inch: self.inch,
        };
        let c = arc_center(&request).map_err(|m| Diagnostic::new(line, column, m))?;
        let c = [c.x, c.y];
        let arc_radius = (c[0] - end[0]).hypot(c[1] - end[1]);
        let tool_inside = inside(left, turn);
        if tool_inside && arc_radius <= r {
            return err("tool radius not less than arc radius with cutter radius compensation");
        }
        if first {
            return self.comp_arc_entry(left, r, c, turn, end, feed, line, column);
        }
        self.comp_arc_corner(left, r, c, turn, end, feed, line)
    }

    /// The first move after G41/G42 is an arc (`convert_arc_comp1`).
    #[allow(clippy::too_many_arguments)]
    fn comp_arc_entry(
        &mut self,
        left: bool,
        r: f64,
        c: [f64; 2],
        turn: i32,
        end: Pos,
        feed: Option<BlockFeed>,
        line: usize,
        column: usize,
    ) -> Result<(), Diagnostic> {
        let (cx, cy) = (self.cur[0], self.cur[1]);
        let (ex, ey) = (end[0], end[1]);
        let gamma = if inside(left, turn) {
            (c[1] - ey).atan2(c[0] - ex)
        } else {
            (ey - c[1]).atan2(ex - c[0])
        };
        self.comp.firstmove = false;
        self.comp.program = [ex, ey, end[2]];
        let (tx, ty) = (ex + r * gamma.cos(), ey + r * gamma.sin());
        let b_len = (cy - ty).hypot(cx - tx) / 2.0;
        let ab_ang = (c[1] - ty).atan2(c[0] - tx);
        let a_ang = (cy - ty).atan2(cx - tx) - ab_ang;
        if a_ang.cos().abs() < TOLERANCE_EQUAL {
            return Err(Diagnostic::new(
                line,
                column,
                "tool radius not less than arc radius with cutter radius compensation",
            ));
        }
        let c_len = b_len / a_ang.cos();
        let center = [tx + c_len * ab_ang.cos(), ty + c_len * ab_ang.sin()];
        let tol = if self.inch {
            SPIRAL_TOLERANCE_INCH
        } else {
            SPIRAL_TOLERANCE_MM
        };
        let r_end = (center[0] - tx).hypot(center[1] - ty);
        let r_start = (center[0] - cx).hypot(center[1] - cy);
        if (r_end - r_start).abs() > tol {
            return Err(Diagnostic::new(
                line,
                column,
                "cutter compensation could not fit the entry arc",
            ));
        }
        let tool_end = with_xy(end, tx, ty);
        self.comp.queue.push(Queued::Arc {
            sweep: find_turn([cx, cy], center, turn, [tx, ty]),
            end: tool_end,
            center,
            turn,
            feed,
            line,
        });
        self.cur = tool_end;
        Ok(())
    }

    /// An arc after the first move (`convert_arc_comp2`).
    #[allow(clippy::too_many_arguments)]
    fn comp_arc_corner(
        &mut self,
        left: bool,
        r: f64,
        c: [f64; 2],
        turn: i32,
        end: Pos,
        feed: Option<BlockFeed>,
        line: usize,
    ) -> Result<(), Diagnostic> {
        let [opx, opy, _] = self.comp.program;
        let (cx, cy, cz) = (self.cur[0], self.cur[1], self.cur[2]);
        let (ex, ey) = (end[0], end[1]);
        let arc_radius = (c[0] - ex).hypot(c[1] - ey);
        let mut theta = (cy - opy).atan2(cx - opx);
        theta = if left {
            theta - FRAC_PI_2
        } else {
            theta + FRAC_PI_2
        };
        let mut delta = (c[1] - opy).atan2(c[0] - opx);
        let ccw = turn > 0;
        let alpha = if ccw {
            delta - FRAC_PI_2
        } else {
            delta + FRAC_PI_2
        };
        let mut beta = if left { theta - alpha } else { alpha - theta };
        if beta > 1.5 * PI {
            beta -= TAU;
        } else if beta < -FRAC_PI_2 {
            beta += TAU;
        }
        let tool_inside = inside(left, turn);
        let gamma = if tool_inside {
            (c[1] - ey).atan2(c[0] - ex)
        } else {
            delta += PI;
            (ey - c[1]).atan2(ex - c[0])
        };
        let new_end = with_xy(end, ex + r * gamma.cos(), ey + r * gamma.sin());
        let this = Queued::Arc {
            sweep: find_turn([opx, opy], c, turn, [ex, ey]),
            end: new_end,
            center: c,
            turn,
            feed,
            line,
        };
        let concave = !(-CORNER_SLACK..=PI + CORNER_SLACK).contains(&beta)
            || ((beta - PI).abs() < CORNER_SLACK && !tool_inside);
        if concave {
            let (mx, my) = match self.comp.queue.first().copied() {
                Some(Queued::Arc {
                    end: qend,
                    center: pc,
                    turn: pturn,
                    ..
                }) => arc_to_arc_corner(left, r, c, turn, arc_radius, qend, pc, pturn),
                _ => line_to_arc_corner(tool_inside, r, c, arc_radius, turn, theta, beta),
            }
            .map_err(|m| Diagnostic::new(line, 1, m))?;
            self.move_endpoint_and_flush(mx, my, line)?;
            self.comp.queue.push(this);
        } else if beta > CORNER_SLACK {
            let mid = [opx + r * delta.cos(), opy + r * delta.sin()];
            self.dequeue(line)?;
            self.comp.queue.push(Queued::Arc {
                sweep: 0.0,
                end: with_xy(with_z(self.cur, cz), mid[0], mid[1]),
                center: [opx, opy],
                turn: if left { -1 } else { 1 },
                feed,
                line,
            });
            self.dequeue(line)?;
            self.comp.endpoint = Some(mid);
            self.comp.queue.push(this);
        } else {
            self.dequeue(line)?;
            self.comp.endpoint = Some([cx, cy]);
            self.comp.queue.push(this);
        }
        self.comp.program = [ex, ey, end[2]];
        self.cur = new_end;
        Ok(())
    }
}
