//! Sectioning gouge detection (thesis 000 §7.2).
//!
//! For each move only the points of its generating curves that lie on the section
//! planes are computed ("there is no need actually to compute the whole generating
//! curve"): the curve is sampled at its fixed layout ([`crate::gencurve`]), every plane
//! value between two consecutive samples brackets a crossing, and the crossing
//! parameter is refined on the continuous curve by the Illinois variant of regula falsi
//! to [`ROOT_TOL`]. At each crossing the design height is looked up
//! ([`DesignSurface::height`]) and the depth `z_design - z_tool` recorded; a pose gouges
//! when its deepest point is more than the tolerance below the design.
//!
//! Pose `i` carries two curves, the front and the back half of the tool moving as the
//! path does there; the back half is the front half of the reversed motion, so both
//! halves are checked, as the thesis does "after reversing the tool path". The first
//! and last pose
//! of a pass are also checked whole (the "caps": the tool comes down along its axis
//! there, so its whole lower surface was in the material): meridians all around the
//! axis, each the profile up to the wall height as a polyline, cut by the same planes.
//!
//! Generating curves are the envelope of a smooth motion. Where the motion turns at a
//! pose (the lead changing from pose to pose, a curved path with coarse steps), a patch
//! of the tool between the arriving and the leaving envelope is on the machined surface
//! too: it faces into the material for the arriving motion and away from it for the
//! leaving one, and no generating curve runs through it (on die.toml with a 24 degree
//! lead and 2 mm steps, 0.15 mm gouges hide there). `whole_tool` checks every pose's
//! tool whole, like a cap, and the tool against the design's boundary curves (section
//! planes can pass a thin corner of the design without a point in it); it costs about
//! ten times the curves and is what the final check of the automatic tilt and the gouge
//! reports use.

use crate::design::DesignSurface;
use crate::gencurve::{CurveOptions, Half, PoseCurve};
use crate::sections::Sections;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;
use swarf_geom::Point3;
use swarf_tool::{Pose, Profile, ProfileTable};

/// Crossings are refined until the point is this close to its plane (mm).
pub const ROOT_TOL: f64 = 1e-6;
/// Most refinement steps per crossing.
const ROOT_STEPS: usize = 8;
/// Polyline pieces per profile arc in the caps.
const CAP_ARC_PIECES: usize = 32;

/// How the sectioning check runs.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GougeOptions {
    /// The section planes.
    pub sections: Sections,
    /// Depth below the design allowed, mm.
    pub tolerance: f64,
    /// Sampling of the generating curves.
    pub curve: CurveOptions,
    /// Meridians around the axis for the whole-tool checks at pass ends (0: none).
    pub cap_meridians: usize,
    /// Also check the whole tool at every pose, not only at pass ends (module doc).
    pub whole_tool: bool,
}

/// The deepest checked point under one pose.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PoseGouge {
    /// Largest `z_design - z_tool` over the checked points, mm (positive: below the
    /// design); `-inf` when no point was over the design.
    pub depth: f64,
    /// The tool point where it occurs, mm.
    pub at: Point3,
    /// The half of the tool it belongs to.
    pub half: Half,
    /// Number of section points compared with the design.
    pub points: usize,
}

impl PoseGouge {
    /// Nothing checked yet.
    pub fn none() -> PoseGouge {
        PoseGouge {
            depth: f64::NEG_INFINITY,
            at: Point3::origin(),
            half: Half::Front,
            points: 0,
        }
    }

    /// True when the deepest point is more than `tolerance` below the design.
    pub fn gouges(&self, tolerance: f64) -> bool {
        self.depth > tolerance
    }

    fn record(&mut self, design: &DesignSurface, p: Point3, half: Half) {
        if let Some((z, _)) = design.height(p.x, p.y) {
            self.points += 1;
            let depth = z - p.z;
            if depth > self.depth {
                self.depth = depth;
                self.at = p;
                self.half = half;
            }
        }
    }

    /// The deeper of the two, with the points of both counted.
    pub fn merge(self, other: PoseGouge) -> PoseGouge {
        let points = self.points + other.points;
        let mut deeper = if other.depth > self.depth {
            other
        } else {
            self
        };
        deeper.points = points;
        deeper
    }
}

/// Checks the curve of one half at one pose on the section planes, into `out`.
pub fn check_curve(
    design: &DesignSurface,
    mh: &PoseCurve<'_>,
    sections: &Sections,
    half: Half,
    out: &mut PoseGouge,
) {
    let curve = mh.curve();
    let values: Vec<f64> = curve.iter().map(|p| sections.coordinate(p)).collect();
    for j in 0..curve.len().saturating_sub(1) {
        for k in sections.between(values[j], values[j + 1]) {
            let c = sections.value(k);
            let p = refine(mh, sections, c, j as f64, values[j] - c, values[j + 1] - c);
            out.record(design, p, half);
        }
    }
}

/// The crossing of the curve with the plane of value `c` between parameters `a` and
/// `a + 1`, where the signed distances are `fa` and `fb`.
fn refine(mh: &PoseCurve<'_>, sections: &Sections, c: f64, a: f64, fa: f64, fb: f64) -> Point3 {
    let (mut a, mut fa, mut b, mut fb) = (a, fa, a + 1.0, fb);
    if fa == 0.0 {
        return mh.curve_at(a);
    }
    let mut p = mh.curve_at(a);
    for _ in 0..ROOT_STEPS {
        let t = if fb != fa {
            a - fa * (b - a) / (fb - fa)
        } else {
            0.5 * (a + b)
        };
        p = mh.curve_at(t);
        let f = sections.coordinate(&p) - c;
        if f.abs() <= ROOT_TOL {
            break;
        }
        if (f > 0.0) != (fb > 0.0) {
            (a, fa) = (b, fb);
        } else {
            fa *= 0.5;
        }
        (b, fb) = (t, f);
    }
    p
}

/// The whole cutting surface of the tool at `pose`, up to `top`, on the section planes.
pub fn check_cap(
    design: &DesignSurface,
    profile: &Profile,
    pose: &Pose,
    top: f64,
    sections: &Sections,
    meridians: usize,
    out: &mut PoseGouge,
) {
    let meridian = profile.polyline(CAP_ARC_PIECES, top);
    let (b1, b2) = pose.frame();
    for m in 0..meridians {
        let (s, c) = (TAU * m as f64 / meridians as f64).sin_cos();
        let u = c * b1 + s * b2;
        let pts: Vec<Point3> = meridian
            .iter()
            .map(|q| pose.cl + q.rho * u + q.z * pose.axis)
            .collect();
        for w in pts.windows(2) {
            let (va, vb) = (sections.coordinate(&w[0]), sections.coordinate(&w[1]));
            for k in sections.between(va, vb) {
                let f = (sections.value(k) - va) / (vb - va);
                let half = if (w[0] - pose.cl).dot(&u) >= 0.0 {
                    Half::Front
                } else {
                    Half::Back
                };
                out.record(design, w[0] + (w[1] - w[0]) * f, half);
            }
        }
    }
}

/// The design's boundary points ([`DesignSurface::boundary`]) under the tool at `pose`:
/// the tool's lowest point above each, by sphere tracing the vertical line with the
/// tool's exact signed distance (1-Lipschitz, so a step of the distance never enters
/// the tool; the solid is convex, so a step that does not shrink the distance means a
/// miss).
pub fn check_boundary(
    design: &DesignSurface,
    profile: &Profile,
    pose: &Pose,
    top: f64,
    out: &mut PoseGouge,
) {
    // The tool up to `top` lies within `reach` of the tip (the generating curves and
    // the caps stop there too).
    let reach = profile.radius() + top;
    let c = pose.cl.xy();
    for q in design.boundary() {
        let (dx, dy) = (q.x - c.x, q.y - c.y);
        if dx * dx + dy * dy > reach * reach || q.z < pose.cl.z - reach {
            continue;
        }
        if let Some(z) = lowest_tool_z(profile, pose, q.x, q.y, pose.cl.z - reach) {
            let depth = q.z - z;
            if depth > out.depth {
                out.depth = depth;
                out.at = Point3::new(q.x, q.y, z);
                out.half = Half::Front;
            }
            out.points += 1;
        }
    }
}

/// The lowest point of the tool at `pose` on the vertical line through `(x, y)`,
/// marching up from `z0` (below the tool); `None` when the line misses it.
fn lowest_tool_z(profile: &Profile, pose: &Pose, x: f64, y: f64, z0: f64) -> Option<f64> {
    let mut z = z0;
    let mut last = f64::INFINITY;
    for _ in 0..MARCH_STEPS {
        let d = profile.signed_distance(pose, &Point3::new(x, y, z));
        if d <= MARCH_HIT {
            return Some(z);
        }
        if d >= last {
            return None;
        }
        last = d;
        z += d;
    }
    None
}

/// Points of the boundary and the tool's lowest point over each, for tests.
#[cfg(test)]
pub(crate) fn tool_height(profile: &Profile, pose: &Pose, x: f64, y: f64) -> Option<f64> {
    lowest_tool_z(profile, pose, x, y, pose.cl.z - 100.0)
}

/// The march of [`lowest_tool_z`] stops this close to the tool (mm).
const MARCH_HIT: f64 = 1e-7;
/// Most march steps.
const MARCH_STEPS: usize = 400;

/// The sectioning check of pose `i` of a pass (module doc). Poses must have unit axes.
pub fn pose_gouge(
    design: &DesignSurface,
    table: &ProfileTable<'_>,
    poses: &[Pose],
    i: usize,
    opts: &GougeOptions,
) -> PoseGouge {
    let mut out = PoseGouge::none();
    for half in [Half::Front, Half::Back] {
        let pc = PoseCurve::new(table, poses, i, half, opts.curve);
        check_curve(design, &pc, &opts.sections, half, &mut out);
    }
    if opts.whole_tool {
        let top = wall_top(table.profile(), &opts.curve);
        check_boundary(design, table.profile(), &poses[i], top, &mut out);
    }
    if opts.cap_meridians > 0 && (opts.whole_tool || i == 0 || i + 1 == poses.len()) {
        let profile = table.profile();
        let top = wall_top(profile, &opts.curve);
        check_cap(
            design,
            profile,
            &poses[i],
            top,
            &opts.sections,
            opts.cap_meridians,
            &mut out,
        );
    }
    out
}

/// The wall height used for the curves and the caps, mm.
pub fn wall_top(profile: &Profile, curve: &CurveOptions) -> f64 {
    curve
        .wall_height
        .unwrap_or_else(|| profile.full_radius_height())
        .min(profile.top().z)
}

/// The sectioning check of every pose of a pass.
pub fn check_pass(
    design: &DesignSurface,
    table: &ProfileTable<'_>,
    poses: &[Pose],
    opts: &GougeOptions,
) -> Vec<PoseGouge> {
    (0..poses.len())
        .map(|i| pose_gouge(design, table, poses, i, opts))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::gencurve::CurveOptions;
    use swarf_geom::{Part, Patch, Vec3};
    use swarf_tool::Cutter;

    fn plane_part(z: f64) -> Part {
        let p = |x: f64, y: f64| Point3::new(x, y, z);
        Part {
            name: "plane".into(),
            faces: Vec::new(),
            patches: vec![
                Patch::bezier(
                    [1, 1],
                    vec![
                        p(-50.0, -50.0),
                        p(-50.0, 50.0),
                        p(50.0, -50.0),
                        p(50.0, 50.0),
                    ],
                )
                .unwrap(),
            ],
        }
    }

    fn opts() -> GougeOptions {
        GougeOptions {
            sections: Sections::along(std::f64::consts::FRAC_PI_2, 0.5).unwrap(),
            tolerance: 1e-3,
            curve: CurveOptions::default(),
            cap_meridians: 64,
            whole_tool: false,
        }
    }

    #[test]
    fn flat_bull_on_a_plane_touches_and_a_lowered_one_gouges() {
        let bull = Cutter::bull(10.0, 2.0, Some(20.0)).unwrap();
        let profile = bull.profile();
        let design = DesignSurface::new(&plane_part(0.0)).unwrap();
        let poses: Vec<Pose> = (0..6)
            .map(|i| Pose::vertical(Point3::new(0.0, i as f64, 0.0)))
            .collect();
        let o = opts();
        let table = ProfileTable::new(&profile);
        for g in check_pass(&design, &table, &poses, &o) {
            assert!(g.points > 0);
            assert!(g.depth.abs() < 1e-9, "{g:?}");
            assert!(!g.gouges(o.tolerance));
        }
        let low: Vec<Pose> = poses
            .iter()
            .map(|p| Pose::vertical(p.cl - 0.05 * Vec3::z()))
            .collect();
        for g in check_pass(&design, &table, &low, &o) {
            assert!((g.depth - 0.05).abs() < 1e-9, "{g:?}");
        }
    }

    #[test]
    fn section_points_lie_on_their_planes() {
        let bull = Cutter::bull(10.0, 2.0, Some(20.0)).unwrap();
        let profile = bull.profile();
        let from = Pose::new(Point3::new(0.0, 0.0, 0.0), Vec3::new(0.1, 0.05, 1.0)).unwrap();
        let to = Pose::new(Point3::new(0.3, 1.0, 0.2), Vec3::new(0.12, 0.02, 1.0)).unwrap();
        let s = Sections::along(1.0, 0.7).unwrap();
        let poses = [from, to];
        let table = ProfileTable::new(&profile);
        let mh = PoseCurve::new(&table, &poses, 0, Half::Front, CurveOptions::default());
        let curve = mh.curve();
        let mut found = 0;
        for j in 0..curve.len() - 1 {
            let (a, b) = (s.coordinate(&curve[j]), s.coordinate(&curve[j + 1]));
            for k in s.between(a, b) {
                let p = refine(
                    &mh,
                    &s,
                    s.value(k),
                    j as f64,
                    a - s.value(k),
                    b - s.value(k),
                );
                assert!((s.coordinate(&p) - s.value(k)).abs() <= ROOT_TOL);
                assert!(profile.signed_distance(&from, &p).abs() < 1e-9);
                found += 1;
            }
        }
        assert!(found >= 10, "{found}");
    }

    #[test]
    fn march_finds_the_lowest_tool_point_and_edges_are_checked() {
        let ball = Cutter::ball(10.0, Some(30.0)).unwrap().profile();
        let pose = Pose::new(Point3::new(1.0, 2.0, 3.0), Vec3::new(0.3, 0.0, 1.0)).unwrap();
        let centre = pose.cl + 5.0 * pose.axis;
        for (dx, dy) in [(0.0, 0.0), (2.0, 1.0), (-3.0, 2.5)] {
            let z = tool_height(&ball, &pose, centre.x + dx, centre.y + dy).unwrap();
            let expected = centre.z - (25.0f64 - dx * dx - dy * dy).sqrt();
            assert!((z - expected).abs() < 1e-6, "{z} vs {expected}");
        }
        assert!(tool_height(&ball, &pose, centre.x, centre.y + 5.5).is_none());
        // A bull beyond the edge x = 50 of a plane at z = 0, 0.05 mm low: no section
        // point lies on the design, the edge check finds the depth.
        let bull = Cutter::bull(10.0, 2.0, Some(20.0)).unwrap();
        let profile = bull.profile();
        let design = DesignSurface::new(&plane_part(0.0)).unwrap();
        let low = Pose::vertical(Point3::new(53.0, 0.0, -0.05));
        let mut g = PoseGouge::none();
        check_boundary(&design, &profile, &low, 2.0, &mut g);
        assert!((g.depth - 0.05).abs() < 1e-6, "{g:?}");
        let mut g = PoseGouge::none();
        check_boundary(
            &design,
            &profile,
            &Pose::vertical(Point3::new(53.0, 0.0, 0.0)),
            2.0,
            &mut g,
        );
        assert!(g.depth.abs() < 1e-6, "{g:?}");
    }
}
