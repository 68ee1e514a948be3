//! The CC paths of a planned tool path, and the linking of positioned passes.
//!
//! 1. **CC paths.** The planned passes keep the contact each pose was planned from
//!    (the 3-axis gouge lift moves a pose's tip, never its contact). A point without
//!    a contact (a bridge across a gap between two pieces of a row, placed by a
//!    vertical drop) splits its pass there; runs of fewer than two contacts are
//!    dropped, as no feed direction can be taken from them ([`cc_paths`]). A contact
//!    within [`MIN_CC_GAP`] of the one before replaces it (section curves can end in
//!    two samples a few 1e-13 mm apart, whose chord gives no feed direction).
//! 2. **Linking** ([`linking`]). A tool tilted by `alpha` from `+z` reaches below its
//!    tip by the depth of its lowest point, the profile point that faces straight
//!    down ([`swarf_tool::Profile::lowest_when_tilted`]; a bull's `(R - r)
//!    sin(alpha) + r (1 - cos(alpha))`). The part lies below the top of its control
//!    box (the patches are in the convex hull of their control points). Retracts and
//!    rapids carry the tool at the orientation of a pass end (or turn it between two,
//!    by the slerp, whose tilt from `+z` peaks at an end); with the tip at `top +`
//!    the largest such depth over the pass ends, `top` the higher of the part's top
//!    and the highest tip, the whole tool is above the part. The job's clearance is
//!    raised to that height when below it; by default it is that height plus
//!    [`swarf_toolpath::DEFAULT_CLEARANCE_MARGIN`]. The stock's top is raised by the
//!    same reach, so the rapid down to `approach` above it keeps the tilted tool out
//!    of the stock.

use swarf_geom::Part;
use swarf_path::Cutting;
use swarf_toolpath::{Contact, Linking, Pass, Toolpath, top_z};

/// Consecutive contacts closer than this are merged by [`cc_paths`], mm.
pub const MIN_CC_GAP: f64 = 1e-6;

/// The contacts of every pass of `toolpath`, split where a point has none (module
/// doc); runs of fewer than two contacts are left out.
pub fn cc_paths(toolpath: &Toolpath) -> Vec<Vec<Contact>> {
    let mut out = Vec::new();
    for pass in &toolpath.passes {
        let mut run: Vec<Contact> = Vec::new();
        for p in &pass.points {
            match p.contact {
                Some(c) => {
                    if let Some(last) = run.last_mut()
                        && (c.point - last.point).norm() < MIN_CC_GAP
                    {
                        *last = c;
                    } else {
                        run.push(c);
                    }
                }
                None => {
                    if run.len() > 1 {
                        out.push(std::mem::take(&mut run));
                    }
                    run.clear();
                }
            }
        }
        if run.len() > 1 {
            out.push(run);
        }
    }
    out
}

/// The linking of positioned `passes` on `part` with `cutting`'s tool, linking rule
/// and material (module doc): the clearance plane and the material top are raised by
/// the most the tilted tool reaches below its tip at a pass end.
pub fn linking(cutting: &Cutting, part: &Part, passes: &[Pass]) -> Linking {
    let tool = cutting.tool.profile();
    let top = part.control_box().max.z.max(top_z(passes));
    let below = passes
        .iter()
        .flat_map(|p| [p.points.first(), p.points.last()])
        .flatten()
        .map(|p| -tool.lowest_when_tilted(p.pose.axis.z))
        .fold(0.0, f64::max);
    cutting
        .linking
        .for_top(top + below, cutting.material_top.map(|m| m + below))
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::{Point3, Vec3};
    use swarf_tool::Pose;
    use swarf_toolpath::PathPoint;

    fn point(x: f64, contact: bool) -> PathPoint {
        let p = Point3::new(x, 0.0, 1.0);
        PathPoint {
            pose: Pose::vertical(p),
            contact: contact.then_some(Contact {
                point: p,
                normal: Vec3::z(),
                face: 0,
                uv: [0.0; 2],
            }),
            lifted: 0.0,
        }
    }

    #[test]
    fn cc_paths_split_at_bridges_and_drop_short_runs() {
        let pass = |flags: &[bool]| Pass {
            points: flags
                .iter()
                .enumerate()
                .map(|(i, &c)| point(i as f64, c))
                .collect(),
            ..Pass::default()
        };
        let tp = Toolpath {
            passes: vec![
                pass(&[true, true, false, false, true, true, true]),
                pass(&[true, false, true]),
                Pass {
                    points: [0.0, 1.0, 1.0 + 1e-9, 2.0, 2.0 + 1e-13]
                        .into_iter()
                        .map(|x| point(x, true))
                        .collect(),
                    ..Pass::default()
                },
            ],
            feeds: Default::default(),
            linking: Default::default(),
        };
        let cc = cc_paths(&tp);
        let xs: Vec<Vec<f64>> = cc
            .iter()
            .map(|r| r.iter().map(|c| c.point.x).collect())
            .collect();
        assert_eq!(
            xs,
            vec![
                vec![0.0, 1.0],
                vec![4.0, 5.0, 6.0],
                vec![0.0, 1.0 + 1e-9, 2.0 + 1e-13]
            ]
        );
    }

    /// The clearance clears a tilted bull `d = 20, r = 4` over a plane at z = 20: the
    /// lowest point of the tool at the clearance plane (sampled on its profile in the
    /// plane of the tilt) is 5 mm above the part.
    #[test]
    fn clearance_is_above_the_part_under_the_whole_tilted_tool() {
        let tool: swarf_tool::Cutter = "bull:d=20,r=4".parse().unwrap();
        let p = |x: f64, y: f64| Point3::new(x, y, 20.0);
        let part = Part {
            name: "plane".into(),
            faces: Vec::new(),
            patches: vec![
                swarf_geom::Patch::bezier(
                    [1, 1],
                    vec![p(0.0, 0.0), p(0.0, 9.0), p(9.0, 0.0), p(9.0, 9.0)],
                )
                .unwrap(),
            ],
        };
        let a = 30f64.to_radians();
        let axis = Vec3::new(a.sin(), 0.0, a.cos());
        let at = |z: f64| {
            PathPoint::new(Pose {
                cl: Point3::new(0.0, 0.0, z),
                axis,
            })
        };
        let profile = tool.profile();
        let lowest = |tip: f64| {
            (0..=2000)
                .map(|k| profile.point_at(k as f64 / 2000.0).0)
                .map(|q| tip + q.z * a.cos() - q.rho * a.sin())
                .fold(f64::INFINITY, f64::min)
        };
        for (tip, top) in [(10.0, 20.0), (30.0, 30.0)] {
            let passes = vec![Pass {
                points: vec![at(tip), at(tip)],
                ..Pass::default()
            }];
            let l = linking(&Cutting::new(tool), &part, &passes);
            let low = lowest(l.clearance);
            assert!(low >= top + 5.0 - 1e-9, "{low} vs {top}");
            // Exact but for the profile's sampling.
            assert!(low <= top + 5.0 + 1e-3, "{low} vs {top}");
        }
    }
}
