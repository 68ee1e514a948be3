//! Where the machine's axes are, and the part-frame motions of a block that moves them.
//!
//! The G-code reader tracks the program position of the axes ([`AxisPosition`]: `X Y Z`
//! and, on a five-axis machine, the two rotary axes) and the pose of the tool it puts
//! over the part. Without kinematics the program coordinates are the tool tip in the
//! part frame and the tool axis stays as it started. With a machine's
//! [`Kinematics`] (module docs there), a straight block (G0, G1) becomes the straight
//! motions between the poses of [`Kinematics::path`], all with the block's source line
//! and one tip feed ([`crate::read::feed`]); an arc (G2, G3, which cannot move rotary
//! axes) is carried rigidly into the part frame by [`arc_in_part_frame`].
//!
//! A program does not say where the machine stands before it, so the path of its
//! first move is unknown whatever the kinematics: the first block that moves becomes
//! one straight motion to its end, as in a three-axis program (a simulator then only
//! places the tool there), even where its end is the assumed start: after it, the
//! next move's path is known and cuts.

use crate::read::feed::BlockFeed;
use crate::read::kinematics::{AxisPosition, Kinematics, arc_in_part_frame, home_position};
use swarf_geom::Point3;
use swarf_tool::Pose;
use swarf_toolpath::program::{Motion, MotionKind};

/// The axes' program position and the tool's pose over the part.
#[derive(Debug, Clone, Copy)]
pub struct Axes<'k> {
    kinematics: Option<&'k dyn Kinematics>,
    tol: f64,
    position: AxisPosition,
    pose: Pose,
    /// A block has moved the axes: the path of the next one is known.
    moved: bool,
}

impl<'k> Axes<'k> {
    /// Axes whose tool tip is at `initial.cl`: without `kinematics` the tool is at
    /// `initial`; with them the rotary axes are at 0 (the tool axis is then the
    /// machine's at home) and moves are subdivided within `tol` mm.
    pub fn new(initial: &Pose, kinematics: Option<&'k dyn Kinematics>, tol: f64) -> Self {
        let (position, pose) = match kinematics {
            None => {
                let p = initial.cl;
                ([p.x, p.y, p.z, 0.0, 0.0], *initial)
            }
            Some(k) => {
                let position = home_position(k, &initial.cl);
                (position, k.pose(&position))
            }
        };
        Axes {
            kinematics,
            tol,
            position,
            pose,
            moved: false,
        }
    }

    /// The program position: mm, and radians for the rotary axes.
    pub fn position(&self) -> &AxisPosition {
        &self.position
    }

    /// The tool's pose in the part frame.
    pub fn pose(&self) -> &Pose {
        &self.pose
    }

    /// The rotary axis letters, when the axes have kinematics.
    pub fn rotary_letters(&self) -> Option<[char; 2]> {
        self.kinematics.map(|k| k.rotary_letters())
    }

    /// The motions of a block moving the axes to `to`: `kind` is `Rapid`, `Linear`, or
    /// an `Arc` whose centre and normal are in program coordinates. A straight block
    /// that does not move the axes has no motion.
    ///
    /// # Units
    /// mm, radians; feeds in mm/min (see [`BlockFeed::tip_feed`]).
    pub fn move_to(
        &mut self,
        kind: MotionKind,
        to: AxisPosition,
        feed: BlockFeed,
        line: usize,
    ) -> Vec<Motion> {
        let from = self.position;
        let poses = match (kind, self.kinematics) {
            (MotionKind::Rapid | MotionKind::Linear, Some(_)) if to == from && self.moved => {
                Vec::new()
            }
            (MotionKind::Arc { .. }, _) | (_, None) => vec![self.end_pose(&to)],
            (_, Some(_)) if !self.moved => vec![self.end_pose(&to)],
            (_, Some(k)) => k.path(&from, &to, self.tol),
        };
        let kind = match (kind, self.kinematics) {
            (
                MotionKind::Arc {
                    center,
                    normal,
                    clockwise,
                    turns,
                },
                Some(k),
            ) => {
                let (center, normal) = arc_in_part_frame(k, &from, &center, &normal);
                MotionKind::Arc {
                    center,
                    normal,
                    clockwise,
                    turns,
                }
            }
            (kind, _) => kind,
        };
        let straight = matches!(kind, MotionKind::Rapid | MotionKind::Linear);
        let mut motions = Vec::with_capacity(poses.len());
        let mut start = self.pose;
        for end in poses {
            // The first move is kept even where it does not change the assumed
            // start: it is where the program puts the tool.
            if straight && self.moved && (to == from || end == start) {
                continue;
            }
            motions.push(Motion {
                kind,
                start,
                end,
                feed: 0.0,
                line,
            });
            start = end;
        }
        let length: f64 = motions.iter().map(Motion::length).sum();
        let linear = match kind {
            MotionKind::Arc { .. } => length,
            _ => (0..3)
                .map(|k| (to[k] - from[k]).powi(2))
                .sum::<f64>()
                .sqrt(),
        };
        let rotary = (to[3] - from[3])
            .to_degrees()
            .hypot((to[4] - from[4]).to_degrees());
        let feed = feed.tip_feed(length, linear, rotary);
        for m in &mut motions {
            m.feed = feed;
        }
        self.moved |= !motions.is_empty();
        self.position = to;
        self.pose = motions.last().map_or_else(|| self.end_pose(&to), |m| m.end);
        motions
    }

    /// The tool's pose at the program position `to`.
    fn end_pose(&self, to: &AxisPosition) -> Pose {
        match self.kinematics {
            None => Pose {
                cl: Point3::new(to[0], to[1], to[2]),
                axis: self.pose.axis,
            },
            Some(k) => k.pose(to),
        }
    }
}
