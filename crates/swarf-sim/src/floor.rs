//! Motions below the floor: the lowest height a job lets its tool reach (a fixture,
//! the table, or the part's lowest point). Every motion of every stage, rapids
//! included, is followed by the lowest point of its tool: the tip of a vertical
//! tool, the point of a tilted tool's profile that faces straight down
//! ([`swarf_tool::Profile::lowest_when_tilted`]). On a straight motion whose axis
//! does not turn that point moves on a line, so its ends bound it; arcs and motions
//! whose axis turns are sampled every [`SAMPLE_TURN`] of arc or of axis turn (at
//! most [`MAX_SAMPLES`] per motion: past that the samples of a multi-turn arc are
//! coarser).
//!
//! A program does not say where the machine stood before its first motion (the
//! simulation takes that motion as placing the tool), so of each stage's first
//! motion only the end is checked.
//!
//! A motion is below the floor when its tool goes deeper than the verification's
//! tolerance below it, as a gouge is a cut deeper than the tolerance below the
//! design: the posts round coordinates to their resolution, and a pass cut to the
//! floor lies on it.

use crate::simulate::MotionNote;
use crate::stage::Stage;
use serde::Serialize;
use swarf_tool::Profile;
use swarf_toolpath::{Motion, MotionKind};

/// Angle of arc or of axis turn between samples, radians (1 degree).
pub const SAMPLE_TURN: f64 = std::f64::consts::PI / 180.0;

/// Most samples of one motion.
pub const MAX_SAMPLES: usize = 4096;

/// The floor check of a verification.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FloorCheck {
    /// The floor, mm.
    pub floor: f64,
    /// Motions whose tool goes deeper than the tolerance below it, in program
    /// order, with the depth of the tool's lowest point below the floor, mm.
    pub below: Vec<MotionNote>,
}

/// Height of the lowest point of the tool of profile `tool` over `motion`, mm.
pub fn lowest_over(motion: &Motion, tool: &Profile) -> f64 {
    let low = |t: f64| tool.lowest_at(&motion.point_at(t));
    let turn = motion.start.axis.angle(&motion.end.axis);
    let sweep = match motion.kind {
        MotionKind::Arc { .. } => motion.sweep().unwrap_or(0.0),
        MotionKind::Rapid | MotionKind::Linear => 0.0,
    };
    let steps = (turn.max(sweep) / SAMPLE_TURN).ceil();
    let steps = if steps.is_finite() && steps >= 1.0 {
        (steps as usize).min(MAX_SAMPLES)
    } else {
        1
    };
    (0..=steps)
        .map(|k| low(k as f64 / steps as f64))
        .fold(f64::INFINITY, f64::min)
}

/// The motions of `stages` (numbered on from one stage to the next, as the
/// simulation numbers them) whose tool goes more than `tol` below `floor`.
pub fn check(stages: &[Stage<'_>], floor: f64, tol: f64) -> FloorCheck {
    let mut below = Vec::new();
    let mut first = 0;
    for stage in stages {
        let tool = stage.cutter.profile();
        for (k, m) in stage.program.motions.iter().enumerate() {
            let lowest = if k == 0 {
                tool.lowest_at(&m.end)
            } else {
                lowest_over(m, &tool)
            };
            let depth = floor - lowest;
            if depth > tol {
                below.push(MotionNote {
                    motion: first + k,
                    line: m.line,
                    amount: depth,
                });
            }
        }
        first += stage.program.motions.len();
    }
    FloorCheck { floor, below }
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::{Point3, Vec3};
    use swarf_tool::{Cutter, Pose};
    use swarf_toolpath::program::Program;

    fn motion(kind: MotionKind, start: Pose, end: Pose) -> Motion {
        Motion {
            kind,
            start,
            end,
            feed: 100.0,
            line: 7,
        }
    }

    #[test]
    fn the_lowest_point_of_straight_arc_and_tilting_motions() {
        let bull = Cutter::bull(10.0, 2.0, None).unwrap();
        let p = bull.profile();
        let v = |x: f64, z: f64| Pose::vertical(Point3::new(x, 0.0, z));
        // A straight vertical move: its lower end.
        let m = motion(MotionKind::Linear, v(0.0, 3.0), v(10.0, -1.0));
        assert_eq!(lowest_over(&m, &p), -1.0);
        // Half circles in XZ about (0, 0, 5), radius 5, from x = 5 to x = -5: about
        // +y counter-clockwise through its bottom (the tip reaches z = 0), clockwise
        // over its top (its ends are lowest).
        let arc = |clockwise: bool| {
            let kind = MotionKind::Arc {
                center: Point3::new(0.0, 0.0, 5.0),
                normal: Vec3::y(),
                clockwise,
                turns: 1,
            };
            motion(kind, v(5.0, 5.0), v(-5.0, 5.0))
        };
        let sag = 5.0 * (1.0 - (SAMPLE_TURN / 2.0).cos());
        assert!(lowest_over(&arc(false), &p).abs() <= sag + 1e-12);
        assert!((lowest_over(&arc(true), &p) - 5.0).abs() < 1e-12);
        // Turning the axis from vertical to 40 degrees at a fixed tip: the tilted
        // end is lowest, by the closed form of the bull.
        let t = 40f64.to_radians();
        let tilted = Pose {
            cl: Point3::new(0.0, 0.0, 3.0),
            axis: Vec3::new(t.sin(), 0.0, t.cos()),
        };
        let turn = motion(MotionKind::Linear, v(0.0, 3.0), tilted);
        let want = 3.0 + 2.0 * t.cos() - 3.0 * t.sin() - 2.0;
        assert!((lowest_over(&turn, &p) - want).abs() < 1e-12);
    }

    #[test]
    fn motions_deeper_than_the_tolerance_below_the_floor_are_named() {
        let ball = Cutter::ball(6.0, None).unwrap();
        let v = |z: f64| Pose::vertical(Point3::new(0.0, 0.0, z));
        let mut program = Program::new("test");
        program.motions = vec![
            // From an unknown start (taken as placing the tool): its end alone.
            motion(MotionKind::Rapid, v(-50.0), v(1.0)),
            motion(MotionKind::Linear, v(1.0), v(-0.005)),
            motion(MotionKind::Linear, v(-0.005), v(-0.5)),
        ];
        let stage = Stage {
            program: &program,
            cutter: &ball,
        };
        let found = check(&[stage, stage], 0.0, 0.01);
        let named: Vec<(usize, f64)> = found.below.iter().map(|n| (n.motion, n.amount)).collect();
        assert_eq!(named, vec![(2, 0.5), (5, 0.5)]);
    }
}
