//! The tool path model: passes of poses, the links between them, feeds, and the
//! motion (rapid and feed moves) that a post-processor writes.
//!
//! A pass is a sequence of cutting poses (CL point = tool tip on the axis, plus the
//! unit tool axis), each remembering the cutter contact (CC) it was planned from.
//! Passes are cut in the order stored; strategies reverse alternate passes for zigzag.
//! Linking between passes: retract along the tool axis to the clearance plane, rapid
//! above the next pass, rapid down to `approach` above the material (the stock's
//! top, [`Linking::material_top`], or the pass's first pose where that is higher),
//! then feed in at the plunge rate. Rapids therefore never enter the stock, however
//! far below its top a pass starts. A pass with a skim height is linked to at that
//! height instead (the strategy has checked the part below the link), but never
//! lower than `approach` above the material. The first move of a program starts
//! from the clearance plane.

use serde::{Deserialize, Serialize};
use swarf_geom::{Point3, Vec3};
use swarf_tool::Pose;

/// Where the cutter touched the design when a pose was planned.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Contact {
    /// CC point on the design surface, mm.
    pub point: Point3,
    /// Unit surface normal at the CC point, pointing out of the material.
    pub normal: Vec3,
    /// Face the contact lies on: patch index for parametric parts, triangle index for meshes.
    pub face: usize,
    /// Surface parameters `(u, v)` on the patch (NaN for meshes).
    pub uv: [f64; 2],
}

/// One planned cutting pose with its provenance.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PathPoint {
    /// Tool tip and axis.
    pub pose: Pose,
    /// Contact it was planned from, if any.
    pub contact: Option<Contact>,
    /// How far the gouge check lifted the pose along its axis, mm (0 when untouched).
    pub lifted: f64,
}

impl PathPoint {
    /// A pose without contact information.
    pub fn new(pose: Pose) -> Self {
        PathPoint {
            pose,
            contact: None,
            lifted: 0.0,
        }
    }
}

/// A continuous cut: the tool stays in the material from first to last pose.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Pass {
    /// Poses in cutting order.
    pub points: Vec<PathPoint>,
    /// Skim link: the tool tip height for the link into this pass from the previous
    /// one (above the part along the way, set by the strategy), instead of the
    /// clearance plane. Ignored for the first pass and when above the clearance plane.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub skim: Option<f64>,
    /// The height above which no material stands over this pass's first pose when it
    /// is cut, mm (set by a strategy that cleared it, as roughing clears each level
    /// before the one below); the rapid down then stops `approach` above it instead
    /// of above the stock's top.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub clear_from: Option<f64>,
}

impl Pass {
    /// Length of the CL polyline, mm.
    pub fn length(&self) -> f64 {
        self.points
            .windows(2)
            .map(|w| (w[1].pose.cl - w[0].pose.cl).norm())
            .sum()
    }
}

/// Feeds and speeds. Feeds in mm/min, spindle in rev/min.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Feeds {
    /// Cutting feed, mm/min.
    pub feed: f64,
    /// Feed for the approach into the material, mm/min.
    pub plunge: f64,
    /// Rapid traverse rate of the machine, mm/min (for the time estimate only).
    pub rapid: f64,
    /// Spindle speed, rev/min (clockwise).
    pub spindle: f64,
}

impl Default for Feeds {
    fn default() -> Self {
        Feeds {
            feed: 300.0,
            plunge: 100.0,
            rapid: 5000.0,
            spindle: 1500.0,
        }
    }
}

/// How passes are joined.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Linking {
    /// Height of the clearance plane (absolute z, part frame), mm.
    pub clearance: f64,
    /// Distance above the material (or above a pass start higher than it) where the
    /// rapid down stops and the plunge feed begins, mm.
    pub approach: f64,
    /// The highest the material can be before the program cuts (the stock's top),
    /// mm: no rapid goes below `approach` above it.
    pub material_top: f64,
}

impl Default for Linking {
    /// Clearance plane at 10 mm, approach 2 mm, material up to 0.
    fn default() -> Self {
        Linking {
            clearance: 10.0,
            approach: 2.0,
            material_top: 0.0,
        }
    }
}

/// The highest CL point (tool tip) of `passes`, mm; `-inf` when they hold none.
pub fn top_z(passes: &[Pass]) -> f64 {
    passes
        .iter()
        .flat_map(|p| &p.points)
        .map(|p| p.pose.cl.z)
        .fold(f64::NEG_INFINITY, f64::max)
}

/// Height of the default clearance plane above the highest CL point, mm.
pub const DEFAULT_CLEARANCE_MARGIN: f64 = 5.0;

/// Linking as a job asks for it: the clearance plane may be left to swarf, which puts
/// it [`DEFAULT_CLEARANCE_MARGIN`] above the path and the material
/// ([`LinkingSpec::for_top`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct LinkingSpec {
    /// Clearance plane z, mm; default: 5 mm above the highest CL point of the path
    /// or the stock's top, whichever is higher.
    pub clearance: Option<f64>,
    /// Distance above the stock's top (or above a pass start higher than it) where
    /// the rapid down stops and the plunge feed begins, mm.
    pub approach: f64,
    /// Radius of arc leads into and out of each pass, mm (none: no arcs).
    pub lead_radius: Option<f64>,
    /// Ramp angle of the leads, degrees (none: level leads; with no arc, a straight
    /// ramp climbing the approach height).
    pub ramp_angle: Option<f64>,
}

impl Default for LinkingSpec {
    fn default() -> Self {
        LinkingSpec {
            clearance: None,
            approach: Linking::default().approach,
            lead_radius: None,
            ramp_angle: None,
        }
    }
}

impl LinkingSpec {
    /// The linking for a path whose highest CL point is at `top_z`, cut from
    /// material that reaches `material_top` (`None`: no more than the path's own
    /// top): the given clearance (raised to the higher of the two if it is below),
    /// else the higher plus [`DEFAULT_CLEARANCE_MARGIN`].
    ///
    /// # Units
    /// mm.
    pub fn for_top(&self, top_z: f64, material_top: Option<f64>) -> Linking {
        let material_top = material_top.unwrap_or(top_z);
        let top = top_z.max(material_top);
        Linking {
            clearance: self
                .clearance
                .map_or(top + DEFAULT_CLEARANCE_MARGIN, |c| c.max(top)),
            approach: self.approach,
            material_top,
        }
    }
}

/// A planned tool path: passes, linking and feeds.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Toolpath {
    /// Passes in cutting order.
    pub passes: Vec<Pass>,
    /// Feeds and speeds.
    pub feeds: Feeds,
    /// Linking between passes.
    pub linking: Linking,
}

/// Rapid or feed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum MoveKind {
    /// Positioning at the machine's rapid rate (G0).
    Rapid,
    /// Linear interpolation at a feed (G1).
    Feed,
}

/// One straight move of the program, to `to`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Move {
    /// Rapid or feed.
    pub kind: MoveKind,
    /// End pose.
    pub to: Pose,
    /// Feed rate of a feed move, mm/min (0 for rapids).
    pub feed: f64,
    /// Index of the pass a cutting move belongs to (`None` for links).
    pub pass: Option<usize>,
}

/// Lengths and times of a program's motion.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct MotionStats {
    /// Length of feed moves inside passes, mm.
    pub cutting_length: f64,
    /// Length of feed moves in links (approach), mm.
    pub approach_length: f64,
    /// Length of rapid moves, mm.
    pub rapid_length: f64,
    /// Estimated machining time, s (feed moves at their feed, rapids at the rapid rate).
    pub time_s: f64,
}

impl Toolpath {
    /// The whole program as straight moves, starting from the clearance plane above
    /// the first pose and ending back on it.
    pub fn moves(&self) -> Vec<Move> {
        let mut out = Vec::new();
        for (k, pass) in self.passes.iter().enumerate() {
            let Some(first) = pass.points.first() else {
                continue;
            };
            let height = self.link_height(pass, out.is_empty());
            let material = pass.clear_from.map_or(self.linking.material_top, |c| {
                c.min(self.linking.material_top)
            });
            self.link_in(&first.pose, out.is_empty(), (height, material), &mut out);
            out.extend(pass.points.iter().skip(1).map(|p| Move {
                kind: MoveKind::Feed,
                to: p.pose,
                feed: self.feeds.feed,
                pass: Some(k),
            }));
            let last = pass.points.last().map_or(first.pose, |p| p.pose);
            let next = self.passes[k + 1..].iter().find(|p| !p.points.is_empty());
            let up = next.map_or(self.linking.clearance, |p| self.link_height(p, false));
            out.push(rapid(lift_to(&last, up)));
        }
        out
    }

    /// The tip height of the link into `pass`: its skim height (no lower than
    /// `approach` above the material), else the clearance plane.
    fn link_height(&self, pass: &Pass, is_first: bool) -> f64 {
        let l = &self.linking;
        match pass.skim {
            Some(h) if !is_first && h < l.clearance => {
                h.max(l.material_top + l.approach).min(l.clearance)
            }
            _ => l.clearance,
        }
    }

    /// Moves from the link height down onto `start`, under which the material
    /// stands no higher than `material`.
    fn link_in(
        &self,
        start: &Pose,
        is_first: bool,
        (height, material): (f64, f64),
        out: &mut Vec<Move>,
    ) {
        let above = lift_to(start, height);
        if is_first {
            let mut high = above;
            high.cl.z = high.cl.z.max(self.linking.clearance);
            if high != above {
                out.push(rapid(high));
            }
        }
        out.push(rapid(above));
        let l = &self.linking;
        let mut entry = lift_to(start, material + l.approach);
        let near = start.cl + start.axis * l.approach;
        if near.z > entry.cl.z {
            entry.cl = near;
        }
        if entry.cl.z < above.cl.z {
            out.push(rapid(entry));
        }
        out.push(Move {
            kind: MoveKind::Feed,
            to: *start,
            feed: self.feeds.plunge,
            pass: None,
        });
    }

    /// Number of poses over all passes.
    pub fn pose_count(&self) -> usize {
        self.passes.iter().map(|p| p.points.len()).sum()
    }

    /// Number of poses the gouge check lifted.
    pub fn lifted_count(&self) -> usize {
        self.passes
            .iter()
            .flat_map(|p| &p.points)
            .filter(|p| p.lifted > 0.0)
            .count()
    }
}

/// The pose moved along its axis until its tip reaches the height `z` (a pose
/// already above it stays where it is).
fn lift_to(pose: &Pose, z: f64) -> Pose {
    let dz = z - pose.cl.z;
    if dz <= 0.0 || pose.axis.z <= 0.0 {
        return *pose;
    }
    Pose {
        cl: pose.cl + pose.axis * (dz / pose.axis.z),
        axis: pose.axis,
    }
}

fn rapid(to: Pose) -> Move {
    Move {
        kind: MoveKind::Rapid,
        to,
        feed: 0.0,
        pass: None,
    }
}

/// Lengths and the time estimate of a move list; the program starts at the first
/// move's end point. Rapids run at `rapid_rate`.
///
/// # Units
/// Lengths in mm, feeds and `rapid_rate` in mm/min, time in seconds.
pub fn motion_stats(moves: &[Move], rapid_rate: f64) -> MotionStats {
    let mut s = MotionStats::default();
    let Some(first) = moves.first() else {
        return s;
    };
    let mut at = first.to.cl;
    for m in moves {
        let d = (m.to.cl - at).norm();
        at = m.to.cl;
        match (m.kind, m.pass) {
            (MoveKind::Rapid, _) => {
                s.rapid_length += d;
                s.time_s += 60.0 * d / rapid_rate;
            }
            (MoveKind::Feed, pass) => {
                if pass.is_some() {
                    s.cutting_length += d;
                } else {
                    s.approach_length += d;
                }
                s.time_s += 60.0 * d / m.feed;
            }
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pass(x: f64, skim: Option<f64>) -> Pass {
        let p = |y: f64| PathPoint::new(Pose::vertical(Point3::new(x, y, 1.0)));
        Pass {
            points: vec![p(0.0), p(5.0)],
            skim,
            clear_from: None,
        }
    }

    fn rapids(material_top: f64) -> Vec<[f64; 3]> {
        let tp = Toolpath {
            passes: vec![pass(0.0, Some(3.0)), pass(2.0, Some(4.0)), pass(4.0, None)],
            feeds: Feeds::default(),
            linking: Linking {
                clearance: 20.0,
                approach: 1.0,
                material_top,
            },
        };
        tp.moves()
            .iter()
            .filter(|m| m.kind == MoveKind::Rapid)
            .map(|m| [m.to.cl.x, m.to.cl.y, m.to.cl.z])
            .collect()
    }

    #[test]
    fn rapids_stop_above_the_material_and_skims_do_not_dip_into_it() {
        // Material up to z 5: every rapid down stops at 6 (the feed takes the tool
        // down to the passes at z 1), the skim at 3 rises to 6, the one at 4 too.
        assert_eq!(
            rapids(5.0),
            vec![
                [0.0, 0.0, 20.0],
                [0.0, 0.0, 6.0],
                [0.0, 5.0, 6.0],
                [2.0, 0.0, 6.0],
                [2.0, 5.0, 20.0],
                [4.0, 0.0, 20.0],
                [4.0, 0.0, 6.0],
                [4.0, 5.0, 20.0],
            ]
        );
    }

    #[test]
    fn skim_links_stay_low_and_others_use_the_clearance_plane() {
        let rapids = rapids(-10.0);
        // First pass from the clearance plane (its skim ignored); into the second at
        // its skim height 4; into the third through the clearance plane; end on it.
        assert_eq!(
            rapids,
            vec![
                [0.0, 0.0, 20.0],
                [0.0, 0.0, 2.0],
                [0.0, 5.0, 4.0],
                [2.0, 0.0, 4.0],
                [2.0, 0.0, 2.0],
                [2.0, 5.0, 20.0],
                [4.0, 0.0, 20.0],
                [4.0, 0.0, 2.0],
                [4.0, 5.0, 20.0],
            ]
        );
    }
}
