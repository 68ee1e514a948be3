//! The least number of passes that any family of full-length passes needs on a patch
//! at scallop height `h`: a yardstick for the three iso strategies.
//!
//! # Derivation
//!
//! Take a family of passes that all run the full length of the patch in the feed
//! direction `T` (a parameter direction, or the drive-plane direction of iso-planar)
//! and a *column*: a curve across them, here the iso-parameter curve `C(s)` at a fixed
//! value of the feed parameter (for feed along `u`, `C(s) = S(u_c, s)`, `s = v`).
//! At a point of the column the side direction is `B = N x T` (`N` the normal toward
//! the tool) and the scallop limit allows adjacent passes at most `w` apart across the
//! feed, `w` the planner's own side step ([`crate::stepping::side_step::SideStep::step`], normal
//! curvature along `B`, tilt of `N` in the section normal to `T`). Passes `w` apart
//! along `B` cross the column every `w / |B . C'/|C'||` of its arc length, so the number
//! of intervals between passes along the column is at least
//!
//! `n(u_c) = integral over s of |B . C'(s)| / w(s) ds`
//!
//! and every column must be crossed that often. The first pass lies on the start
//! boundary. The last need not lie on the far one: a single tool leaves at most `h`
//! up to half a side step from its contact (in the circle model of
//! [`crate::stepping::side_step`] the crest between two tools `w` apart is `h` above the
//! surface on their bisector, so each tool alone leaves `h` there), and the strategies
//! leave out a far pass where the one before already leaves at most `h` on the edge.
//! So the family needs at least
//!
//! `passes = max over u_c of n(u_c) + 1/2`
//!
//! (with passes on both boundaries, `n + 1`; with the first pass also inset by half a
//! step from its edge, `n`). A discrete family needs the next whole number.
//! The integral is taken by composite Simpson's rule over [`SIMPSON_INTERVALS`]
//! intervals, the columns on [`COLUMNS`] samples of the feed parameter with the largest
//! refined by golden-section search.
//!
//! # Assumptions
//!
//! - A continuous estimate: a discrete family whose every gap meets the local step
//!   spans about one unit of the integral per gap; where `w` changes within a gap the
//!   count can differ from the integral by a fraction of a pass.
//! - The side direction is the one perpendicular to the feed direction `T`; passes that
//!   cross a column obliquely see a different side curvature.
//! - Only passes that cross the column are counted: the bound is for families of
//!   passes running the full length of the patch (iso-parametric, iso-planar,
//!   iso-scallop). A contour-parallel or spiral path, whose passes run around the
//!   patch rather than across the columns, is not bound by it.
//! - On a part of several patches every patch is bounded on its own, over the whole
//!   patch (also where another patch lies above it).
//!
//! What it says about paper 004's comparison (iso-scallop section, after Feng and Li
//! 2002): iso-scallop keeps every gap at `w` locally, iso-parametric and
//! iso-planar take each gap at the least `w` over the pass; where the column that needs
//! most passes is the same for every pass (a separable parametrisation), the per-pass
//! minimum is already within a fraction of a pass of this bound and iso-scallop can
//! only save cutting length.

use crate::cl_curve::{tool_side_curvature, tool_side_normal};
use crate::params::ParamDir;
use crate::stepping::side_step::SideStep;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use swarf_geom::solve::golden_max;
use swarf_geom::{Part, Patch, Point3, SurfaceDerivs, Vec3};

/// Columns sampled across the feed parameter before refining the largest.
pub const COLUMNS: usize = 65;
/// Simpson intervals along each column (even).
pub const SIMPSON_INTERVALS: usize = 128;
/// Golden-section steps refining the bottleneck column.
const GOLDEN_STEPS: usize = 30;

/// The feed direction of a pass family.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Feed {
    /// Passes run along a parameter (iso-parametric, iso-scallop): `T = S_u` or `S_v`.
    Param(ParamDir),
    /// Passes are sections by vertical planes along `(cos a, sin a, 0)` (iso-planar,
    /// angle in radians): `T ~ N x M`, `M = (-sin a, cos a, 0)`.
    Plane(f64),
}

/// The pass bound of one patch (module doc).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PassBound {
    /// Patch index in the part.
    pub patch: usize,
    /// Intervals between passes needed along the bottleneck column (its integral).
    pub intervals: f64,
    /// Least number of passes (fractional): `intervals + 1/2` (module doc).
    pub passes: f64,
    /// The column's parameter: `"u"` for columns of constant u (feed along u).
    pub column_param: String,
    /// The bottleneck column's value of that parameter.
    pub column: f64,
    /// The middle of the bottleneck column on the surface, mm.
    pub at: Point3,
}

/// The pass bound of every patch of `part` for the side-step model `side` and the
/// feed direction `feed` (module doc).
///
/// # Units
/// Passes (dimensionless); positions mm.
///
/// # Example
/// ```
/// use swarf_geom::{Part, Patch, Point3};
/// use swarf_path::params::ParamDir;
/// use swarf_path::strategy::iso::pass_bound::{Feed, pass_bound};
/// use swarf_path::stepping::side_step::{SideStep, ball_step};
/// // A 40 x 20 mm plane, ball d = 8, h = 0.15: 20 mm / flat step + 1/2 passes.
/// let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
/// let plane = Patch::bezier([1, 1], vec![p(0.0, 0.0), p(0.0, 20.0), p(40.0, 0.0), p(40.0, 20.0)]).unwrap();
/// let part = Part::new("plane", vec![plane]);
/// let side = SideStep::new(&"ball:d=8".parse().unwrap(), 0.15).unwrap();
/// let b = pass_bound(&part, &side, Feed::Param(ParamDir::U));
/// let want = 20.0 / ball_step(4.0, 0.0, 0.15).unwrap() + 0.5;
/// assert!((b[0].passes - want).abs() < 1e-9);
/// ```
pub fn pass_bound(part: &Part, side: &SideStep, feed: Feed) -> Vec<PassBound> {
    part.patches
        .iter()
        .enumerate()
        .map(|(k, patch)| patch_bound(patch, k, side, feed))
        .collect()
}

/// Which parameter the passes run along: 0 for u, 1 for v.
fn along(patch: &Patch, feed: Feed) -> usize {
    match feed {
        Feed::Param(ParamDir::U) => 0,
        Feed::Param(ParamDir::V) => 1,
        Feed::Plane(a) => {
            let [[u0, u1], [v0, v1]] = patch.domain();
            let d = patch.derivs(0.5 * (u0 + u1), 0.5 * (v0 + v1));
            let f = Vec3::new(a.cos(), a.sin(), 0.0);
            let share = |s: &Vec3| s.try_normalize(0.0).map_or(0.0, |s| s.dot(&f).abs());
            usize::from(share(&d.dv) > share(&d.du))
        }
    }
}

fn patch_bound(patch: &Patch, index: usize, side: &SideStep, feed: Feed) -> PassBound {
    let dom = patch.domain();
    let p = along(patch, feed);
    let [t0, t1] = dom[p];
    let column = |t: f64| column_integral(patch, side, feed, p, t);
    let values: Vec<f64> = (0..COLUMNS)
        .into_par_iter()
        .map(|k| column(t0 + (t1 - t0) * k as f64 / (COLUMNS - 1) as f64))
        .collect();
    let best = (0..COLUMNS)
        .max_by(|&a, &b| values[a].total_cmp(&values[b]))
        .unwrap_or(0);
    let at = |k: usize| t0 + (t1 - t0) * k as f64 / (COLUMNS - 1) as f64;
    let (a, b) = (at(best.saturating_sub(1)), at((best + 1).min(COLUMNS - 1)));
    let (mut t, mut n) = (at(best), values[best]);
    if let Some((x, f)) = golden_max(column, a, b, GOLDEN_STEPS).best
        && f > n
    {
        (t, n) = (x, f);
    }
    let [s0, s1] = dom[1 - p];
    let mid = uv(p, t, 0.5 * (s0 + s1));
    PassBound {
        patch: index,
        intervals: n,
        passes: n + 0.5,
        column_param: if p == 0 { "u" } else { "v" }.into(),
        column: t,
        at: patch.eval(mid[0], mid[1]),
    }
}

/// `(u, v)` from the feed parameter `t` (parameter `p`) and the column parameter `s`.
fn uv(p: usize, t: f64, s: f64) -> [f64; 2] {
    if p == 0 { [t, s] } else { [s, t] }
}

/// `n(t)`: intervals between passes needed along the column at feed parameter `t`.
fn column_integral(patch: &Patch, side: &SideStep, feed: Feed, p: usize, t: f64) -> f64 {
    let [s0, s1] = patch.domain()[1 - p];
    let n = SIMPSON_INTERVALS;
    let ds = (s1 - s0) / n as f64;
    let sum: f64 = (0..=n)
        .map(|k| {
            let [u, v] = uv(p, t, s0 + ds * k as f64);
            let d = patch.derivs(u, v);
            let (tangent, across) = if p == 0 { (d.du, d.dv) } else { (d.dv, d.du) };
            let tangent = match feed {
                Feed::Param(_) => tangent,
                Feed::Plane(a) => match tool_side_normal(&d) {
                    Some(nn) => nn.cross(&Vec3::new(-a.sin(), a.cos(), 0.0)),
                    None => tangent,
                },
            };
            let weight = if k == 0 || k == n {
                1.0
            } else if k % 2 == 1 {
                4.0
            } else {
                2.0
            };
            weight * crossing_density(side, &d, &tangent, &across)
        })
        .sum();
    sum * ds / 3.0
}

/// `|B . across| / w` at `d` for passes along `tangent` (module doc); 0 at a point
/// without a normal or side curvature.
fn crossing_density(side: &SideStep, d: &SurfaceDerivs, tangent: &Vec3, across: &Vec3) -> f64 {
    let Some(normal) = tool_side_normal(d) else {
        return 0.0;
    };
    let Some(t) = (tangent - normal * normal.dot(tangent)).try_normalize(1e-300) else {
        return 0.0;
    };
    let b = normal.cross(&t);
    let Some(kappa) = tool_side_curvature(d, &b) else {
        return 0.0;
    };
    let tilt = b.z.abs().atan2(normal.z);
    b.dot(across).abs() / side.step(kappa, tilt)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stepping::side_step::ball_step;
    use swarf_tool::Cutter;

    const R: f64 = swarf_testkit::parts::CYLINDER_RADIUS;

    fn side(tool: &str, h: f64) -> SideStep {
        SideStep::new(&tool.parse::<Cutter>().unwrap(), h).unwrap()
    }

    #[test]
    fn cylinder_bound_is_the_arc_over_the_exact_step() {
        let (h, s) = (0.1, side("ball:d=8", 0.1));
        let arc = R * 60f64.to_radians();
        let want = arc / ball_step(4.0, -1.0 / R, h).unwrap() + 0.5;
        for c in [1.0, 1.7] {
            let b = &pass_bound(
                &swarf_testkit::parts::cylinder(c),
                &s,
                Feed::Param(ParamDir::U),
            )[0];
            assert!(
                (b.passes - want).abs() < 1e-6 * want,
                "c {c}: {b:?} vs {want}"
            );
            assert_eq!(b.column_param, "u");
        }
        // Drive planes along x are the same family.
        let b = &pass_bound(&swarf_testkit::parts::cylinder(1.0), &s, Feed::Plane(0.0))[0];
        assert!((b.passes - want).abs() < 1e-6 * want, "{b:?}");
        // Along the arc the side direction is the straight generator (no curvature,
        // no tilt): 40 mm over the flat step.
        let b = &pass_bound(
            &swarf_testkit::parts::cylinder(1.0),
            &s,
            Feed::Param(ParamDir::V),
        )[0];
        let want = 40.0 / ball_step(4.0, 0.0, h).unwrap() + 0.5;
        assert!((b.passes - want).abs() < 1e-9 * want, "{b:?} vs {want}");
        assert_eq!(b.column_param, "v");
    }

    /// A cone around the x axis, radius 50 at x = 0 to 70 at x = 40, over a 60-degree
    /// arc: the linear blend of two rational arcs with the same weights. Along the
    /// rulings (feed u) the side direction is the parallel circle, whose normal curvature
    /// is `cos(beta) / R(x)` (`beta` the half-angle): the columns need
    /// `R(u) pi / 3 / ball_step(4, -cos(beta) / R(u), h)` intervals, most at u = 1.
    #[test]
    fn cone_bound_is_at_the_wide_end() {
        let (r0, r1, len, h) = (50.0, 70.0, 40.0, 0.15);
        let half = 30f64.to_radians();
        let w = half.cos();
        let mut pts = Vec::new();
        for (x, r) in [(0.0, r0), (len, r1)] {
            pts.push(Point3::new(x, -r * half.sin(), r * half.cos()));
            pts.push(Point3::new(x, 0.0, r / w));
            pts.push(Point3::new(x, r * half.sin(), r * half.cos()));
        }
        let weights = vec![1.0, w, 1.0, 1.0, w, 1.0];
        let patch = Patch::new([1, 2], pts, [None, None], Some(weights)).unwrap();
        let part = Part::new("cone", vec![patch]);
        let b = &pass_bound(&part, &side("ball:d=8", h), Feed::Param(ParamDir::U))[0];
        let cos_beta = len / len.hypot(r1 - r0);
        let want = r1 * 60f64.to_radians() / ball_step(4.0, -cos_beta / r1, h).unwrap() + 0.5;
        assert!((b.passes - want).abs() < 1e-6 * want, "{b:?} vs {want}");
        assert!(b.column > 1.0 - 1e-6, "{b:?}");
        assert!(
            (b.at - Point3::new(len, 0.0, r1)).norm() < 1e-6,
            "{:?}",
            b.at
        );
    }

    /// A parabolic ridge z = 20 - c y^2 over y in [-30, 30], extruded along x:
    /// compared with the integral of `ds / w(kappa(y), tilt(y))` from the closed forms
    /// `kappa = -2c / (1 + 4 c^2 y^2)^(3/2)`, `tilt = atan(2 c |y|)`,
    /// `ds = sqrt(1 + 4 c^2 y^2) dy` (trapezoid, 200 000 intervals), for a bull
    /// cutter whose effective radius changes with the tilt.
    #[test]
    fn parabolic_ridge_matches_the_closed_form_integral_for_a_bull() {
        let (y_half, c) = (30.0, 0.02);
        let mut pts = Vec::new();
        for x in [0.0, 50.0] {
            pts.push(Point3::new(x, -y_half, 20.0 - c * y_half * y_half));
            pts.push(Point3::new(x, 0.0, 20.0 + c * y_half * y_half));
            pts.push(Point3::new(x, y_half, 20.0 - c * y_half * y_half));
        }
        let part = Part::new("ridge", vec![Patch::bezier([1, 2], pts).unwrap()]);
        let s = side("bull:d=10,r=2", 0.15);
        let b = &pass_bound(&part, &s, Feed::Param(ParamDir::U))[0];
        let n = 200_000;
        let dy = 2.0 * y_half / n as f64;
        let f = |y: f64| {
            let g = 1.0 + 4.0 * c * c * y * y;
            let kappa = -2.0 * c / g.powf(1.5);
            let tilt = (2.0 * c * y.abs()).atan();
            g.sqrt() / s.step(kappa, tilt)
        };
        let integral: f64 = (0..n)
            .map(|k| 0.5 * (f(-y_half + dy * k as f64) + f(-y_half + dy * (k + 1) as f64)) * dy)
            .sum();
        // The effective-radius table is piecewise constant in the tilt: Simpson on
        // 128 intervals sees its steps to a few parts in a thousand.
        let got = b.intervals;
        assert_eq!(b.passes, got + 0.5);
        assert!(
            (got - integral).abs() < 3e-3 * integral,
            "{got} vs {integral}"
        );
    }
}
