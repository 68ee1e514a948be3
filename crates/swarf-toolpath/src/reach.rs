//! Where a tool path may cut: never below the floor (the lowest height the tool
//! may reach: the part's lowest point unless the job lowers or raises it) and no
//! further outside the stock than the tool reaches. The floor bounds the tool's
//! lowest point, the tip of a vertical tool and, of a tilted one, the point of its
//! profile that faces straight down ([`Profile::lowest_when_tilted`]). A strategy extends its passes
//! past the part by what the cutter needs to finish its edges; past a part's outer
//! edge the drop of the cutter follows the sides down, and over an open mesh's end
//! it falls as far as the cutter's flank lets it. [`clip`] keeps of every pass only
//! what lies in the region where the tool may go, and splits a pass that leaves it
//! and comes back into two, which the link planner then joins by a link.
//!
//! The region is convex (a box in XY, a half-space above the floor), so each segment
//! of a pass meets it in one interval of its parameter, found by clipping the segment
//! against the six planes in turn (Liang and Barsky's line clipping); along a segment
//! whose axis turns, the lowest point's depth below the tip is taken as linear
//! between its ends (the point where the piece ends is then lifted onto the floor
//! by its own axis). A piece of a
//! pass ends where its segment leaves the region, at the point of the segment on the
//! boundary: the machine moves along the segment anyway, so the shortened move cuts
//! what the whole one would, no more.

use crate::path::{Pass, PathPoint};
use swarf_geom::math::slerp;
use swarf_tool::Pose;
use swarf_tool::profile::Profile;

/// The region a tool tip may reach, mm.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Reach {
    /// The lowest height of the tool's lowest point, mm.
    pub floor: f64,
    /// `[x_min, y_min, x_max, y_max]` of the tool tip: the stock's XY box grown by
    /// the tool's radius (outside it the tool cuts nothing); `None`: unbounded.
    pub footprint: Option<[f64; 4]>,
}

impl Reach {
    /// The reach of a tool of `radius` over a stock whose XY box is `[x_min, y_min,
    /// x_max, y_max]`, above `floor` (mm).
    pub fn around(floor: f64, [x0, y0, x1, y1]: [f64; 4], radius: f64) -> Reach {
        Reach {
            floor,
            footprint: Some([x0 - radius, y0 - radius, x1 + radius, y1 + radius]),
        }
    }
}

/// What [`clip`] removed.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Clipped {
    /// Poses outside the region, dropped.
    pub points: usize,
    /// Passes that left the region and came back, each split in two per return.
    pub splits: usize,
}

/// A point may lie this far outside the region and still count as inside, mm (a
/// drop on a floor rounds to either side of it).
const SLACK: f64 = 1e-9;
/// A piece shorter than this cuts nothing (the pass only touches the region), mm.
const MIN_PIECE: f64 = 1e-6;

/// The depth of the tool's lowest point below its tip at `p`, mm (>= 0).
fn depth(p: &PathPoint, tool: &Profile) -> f64 {
    p.pose.cl.z - tool.lowest_at(&p.pose)
}

/// The part of the segment `a`→`b` inside `reach`, as `[t0, t1]` in `[0, 1]`;
/// `None` when it misses.
fn segment_interval(
    a: &PathPoint,
    b: &PathPoint,
    reach: &Reach,
    tool: &Profile,
) -> Option<[f64; 2]> {
    let (pa, d) = (a.pose.cl, b.pose.cl - a.pose.cl);
    let (low_a, low_b) = (pa.z - depth(a, tool), b.pose.cl.z - depth(b, tool));
    // Each constraint as p t <= q.
    let mut planes = vec![(low_a - low_b, low_a - reach.floor + SLACK)];
    if let Some([x0, y0, x1, y1]) = reach.footprint {
        planes.extend([
            (-d.x, pa.x - x0 + SLACK),
            (d.x, x1 - pa.x + SLACK),
            (-d.y, pa.y - y0 + SLACK),
            (d.y, y1 - pa.y + SLACK),
        ]);
    }
    let (mut t0, mut t1) = (0.0_f64, 1.0_f64);
    for (p, q) in planes {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else if p < 0.0 {
            t0 = t0.max(q / p);
        } else {
            t1 = t1.min(q / p);
        }
    }
    (t0 <= t1).then_some([t0, t1])
}

/// `a` moved to parameter `t` along the segment to `b` (the axis by the one slerp),
/// its lowest point not below `floor` (the slack's width); no contact.
fn along(a: &PathPoint, b: &PathPoint, t: f64, floor: f64, tool: &Profile) -> PathPoint {
    if t == 0.0 {
        return *a;
    }
    if t == 1.0 {
        return *b;
    }
    let mut p = PathPoint::new(Pose {
        cl: a.pose.cl + (b.pose.cl - a.pose.cl) * t,
        axis: slerp(&a.pose.axis, &b.pose.axis, t),
    });
    p.pose.cl.z = p.pose.cl.z.max(floor + depth(&p, tool));
    p
}

fn inside(p: &PathPoint, reach: &Reach, tool: &Profile) -> bool {
    segment_interval(p, p, reach, tool).is_some()
}

/// `pass` cut to `reach`: its pieces in order (none when no pose is inside); the
/// first keeps the pass's skim and cleared height, the others are linked to by the
/// ordinary link (what lies between is not known to be clear).
fn clip_pass(pass: Pass, reach: &Reach, tool: &Profile, clipped: &mut Clipped) -> Vec<Pass> {
    let inside = |p: &PathPoint| inside(p, reach, tool);
    clipped.points += pass.points.iter().filter(|p| !inside(p)).count();
    if pass.points.len() < 2 {
        return if pass.points.iter().all(inside) {
            vec![pass]
        } else {
            Vec::new()
        };
    }
    let mut pieces: Vec<Vec<PathPoint>> = Vec::new();
    let mut open = false;
    for w in pass.points.windows(2) {
        let Some([t0, t1]) = segment_interval(&w[0], &w[1], reach, tool) else {
            open = false;
            continue;
        };
        if !open || t0 > 0.0 {
            pieces.push(vec![along(&w[0], &w[1], t0, reach.floor, tool)]);
        }
        let end = along(&w[0], &w[1], t1, reach.floor, tool);
        if let Some(piece) = pieces.last_mut()
            && piece.last() != Some(&end)
        {
            piece.push(end);
        }
        open = t1 == 1.0;
    }
    pieces.retain(|p| {
        p.windows(2)
            .map(|w| (w[1].pose.cl - w[0].pose.cl).norm())
            .sum::<f64>()
            >= MIN_PIECE
    });
    clipped.splits += pieces.len().saturating_sub(1);
    pieces
        .into_iter()
        .enumerate()
        .map(|(k, points)| Pass {
            points,
            skim: if k == 0 { pass.skim } else { None },
            clear_from: if k == 0 { pass.clear_from } else { None },
        })
        .collect()
}

/// `passes` of a tool of profile `tool` cut to `reach` (module doc), in their
/// order, with what was removed.
pub fn clip(passes: Vec<Pass>, reach: &Reach, tool: &Profile) -> (Vec<Pass>, Clipped) {
    let mut clipped = Clipped::default();
    let out = passes
        .into_iter()
        .flat_map(|p| clip_pass(p, reach, tool, &mut clipped))
        .collect();
    (out, clipped)
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::{Point3, Vec3};

    fn pass(points: &[[f64; 3]]) -> Pass {
        Pass {
            points: points
                .iter()
                .map(|&[x, y, z]| {
                    PathPoint::new(Pose {
                        cl: Point3::new(x, y, z),
                        axis: Vec3::z(),
                    })
                })
                .collect(),
            skim: Some(7.0),
            clear_from: Some(3.0),
        }
    }

    fn ball() -> Profile {
        swarf_tool::Cutter::ball(6.0, None).unwrap().profile()
    }

    /// The pass's tips, rounded to 1e-6 mm.
    fn cls(p: &Pass) -> Vec<[f64; 3]> {
        let r = |v: f64| (v * 1e6).round() / 1e6 + 0.0;
        p.points
            .iter()
            .map(|p| [r(p.pose.cl.x), r(p.pose.cl.y), r(p.pose.cl.z)])
            .collect()
    }

    #[test]
    fn a_pass_diving_past_an_edge_ends_on_the_floor() {
        // Down a side from z = 5 to z = -5 and back up: cut at z = 0 both ways.
        let p = pass(&[[0.0, 0.0, 5.0], [10.0, 0.0, -5.0], [20.0, 0.0, 5.0]]);
        let reach = Reach {
            floor: 0.0,
            footprint: None,
        };
        let (out, c) = clip(vec![p], &reach, &ball());
        assert_eq!(
            c,
            Clipped {
                points: 1,
                splits: 1
            }
        );
        assert_eq!(cls(&out[0]), vec![[0.0, 0.0, 5.0], [5.0, 0.0, 0.0]]);
        assert_eq!(cls(&out[1]), vec![[15.0, 0.0, 0.0], [20.0, 0.0, 5.0]]);
        assert_eq!((out[0].skim, out[0].clear_from), (Some(7.0), Some(3.0)));
        assert_eq!((out[1].skim, out[1].clear_from), (None, None));
    }

    #[test]
    fn a_pass_on_the_floor_and_inside_is_kept_whole() {
        let p = pass(&[[0.0, 0.0, 0.0], [10.0, 0.0, 0.0], [20.0, 5.0, 1.0]]);
        let reach = Reach {
            floor: 0.0,
            footprint: Some([0.0, 0.0, 20.0, 5.0]),
        };
        let (out, c) = clip(vec![p.clone()], &reach, &ball());
        assert_eq!(c, Clipped::default());
        assert_eq!(out, vec![p]);
    }

    #[test]
    fn a_pass_is_cut_where_it_leaves_the_footprint() {
        let p = pass(&[[-10.0, 1.0, 2.0], [10.0, 1.0, 2.0], [10.0, 30.0, 2.0]]);
        let reach = Reach {
            floor: -1.0,
            footprint: Some([-5.0, -5.0, 5.0, 20.0]),
        };
        let (out, c) = clip(vec![p], &reach, &ball());
        assert_eq!(
            c,
            Clipped {
                points: 3,
                splits: 0
            }
        );
        assert_eq!(out.len(), 1);
        assert_eq!(cls(&out[0]), vec![[-5.0, 1.0, 2.0], [5.0, 1.0, 2.0]]);
    }

    #[test]
    fn a_pass_wholly_outside_or_grazing_is_dropped() {
        let reach = Reach {
            floor: 0.0,
            footprint: None,
        };
        let below = pass(&[[0.0, 0.0, -1.0], [5.0, 0.0, -2.0]]);
        let grazing = pass(&[[0.0, 0.0, -1.0], [5.0, 0.0, 0.0], [10.0, 0.0, -1.0]]);
        let (out, c) = clip(vec![below, grazing], &reach, &ball());
        assert!(out.is_empty());
        assert_eq!(c.points, 4);
    }

    #[test]
    fn a_tilted_tool_stops_where_its_lowest_point_meets_the_floor() {
        // A bull d10 r2 tilted 30 deg reaches r cos - (R - r) sin - r below its tip.
        let bull = swarf_tool::Cutter::bull(10.0, 2.0, None).unwrap().profile();
        let t = 30f64.to_radians();
        let depth = 2.0 * (1.0 - t.cos()) + 3.0 * t.sin();
        let axis = Vec3::new(t.sin(), 0.0, t.cos());
        let mut p = pass(&[[0.0, 0.0, 5.0], [10.0, 0.0, 0.0], [20.0, 0.0, 5.0]]);
        for q in &mut p.points {
            q.pose.axis = axis;
        }
        let reach = Reach {
            floor: 0.0,
            footprint: None,
        };
        let (out, c) = clip(vec![p], &reach, &bull);
        assert_eq!(
            c,
            Clipped {
                points: 1,
                splits: 1
            }
        );
        let x = 10.0 * (5.0 - depth) / 5.0;
        assert_eq!(cls(&out[0])[1], cls(&pass(&[[x, 0.0, depth]]))[0]);
        assert_eq!(cls(&out[1])[0], cls(&pass(&[[20.0 - x, 0.0, depth]]))[0]);
        assert!(
            out.iter()
                .flat_map(|p| &p.points)
                .all(|q| (q.pose.axis - axis).norm() < 1e-12)
        );
    }
}
