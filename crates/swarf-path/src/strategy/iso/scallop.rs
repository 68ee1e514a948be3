//! Iso-scallop finishing: each path placed so that the scallop to the previous one
//! equals `h` (Feng & Li 2002; paper 004, iso-scallop section).
//!
//! On each patch the first CC path is a boundary curve (`v = v_min` for
//! `direction = "u"`, `v_max` with `start = "max"`; `u` curves for `direction = "v"`).
//! Every path is sampled by the forward stepper at the chordal tolerance; between its
//! samples further *stations* are added so that they are at most [`STATION_SPACING`]
//! apart, and from every station the next CC point is solved so that the scallop
//! between the two tools is `h` ([`crate::stepping::scallop_step`]). The next path is the
//! polyline through those points in the parameter plane (straight in `(u, v)`
//! between stations, which moves the path across by at most `k L^2 / 8` for a
//! station spacing `L` and a curvature `k` of the path in the parameter plane,
//! well below the side steps for the spacing used), sampled again by the forward
//! stepper.
//!
//! What a path can do on the way:
//! - **shrink or grow**: stations follow the path; the forward stepper resamples it;
//! - **leave the patch**: a point whose cross-section leaves the patch before the
//!   scallop reaches `h` sits on the far edge, so the path runs along that edge there;
//!   from such points the next cross-section leaves at once and they are dropped;
//! - **split**: the points that are dropped cut the next path into pieces, each
//!   followed on its own;
//! - **turn**: where neighbouring points get very different steps (a cutter whose
//!   effective radius jumps with the tilt), steps are shortened so that the step
//!   changes by at most 0.5 per unit length along the path;
//! - **fold**: on the concave side of a bend the offset curve loops back (the classic
//!   swallowtail); points that do not advance along the path are removed (at a path's
//!   end on a side edge, the interior points beyond the end point instead, so that
//!   the path keeps reaching the edge).
//!
//! Cutters other than the ball: each patch is planned as for a ball of the least
//! effective cutting radius ([`crate::stepping::side_step`]) over the tilts the patch has
//! (surveyed on a grid; a margin of one survey step in tilt), and of the corner
//! radius across a convex ridge ([`crate::stepping::scallop_crest`]). This is conservative (the
//! scallop stays below `h`, at the price of closer paths on level regions), and it is
//! what works: the effective radius at each station instead was tried on wave.toml
//! (`h = 0.15`) and fails in two ways. The effective radius of a nearly level bull is
//! tens of millimetres (its flat bottom) but drops to the corner radius wherever a
//! convex ridge lies between two paths (the tools touch it with facing corners,
//! [`crate::stepping::side_step`], "Convex ridges"); without that rule the measured scallop
//! (the swept-tool oracle of the tests) reaches 0.43 mm for `bull:d=10,r=2`. With it,
//! the rule switches on and off along iso-scallop paths that run nearly along wave's
//! ridge, neighbouring points get steps of 1.5 mm and 7 mm, and the path family
//! breaks into slivers and turns back over covered ground: `bull:d=10,r=2` needed 82
//! paths (with the steps smoothed over 3 mm; 16 126 mm cutting, scallop 0.1497 mm)
//! against 80 here, `bull:d=8,r=1` did not finish in minutes. A flat end mill (a
//! sharp rim) cannot cut a convex ridge between two passes at all; the ridge is
//! reported uncovered.
//!
//! Planning ends when no point is left: the surface is covered up to its boundary.
//! Paths keep the direction of travel of the first one; zigzag reverses every other
//! row when the passes are ordered. On parts of several patches each patch is planned
//! on its own; CC points under another patch are left out of the passes but still
//! carry the paths across ([`crate::envelope`]).

use super::IsoParams;
use super::pass_bound::Feed;
use crate::cl_curve::{ClMap, tool_side_curvature, tool_side_normal};
use crate::error::PathError;
use crate::ordering::Row;
use crate::params::{Cutting, ParamDir, StartSide};
use crate::plan::{Plan, PlanReport, Uncovered};
use crate::stepping::forward_step::{Sample, sample_curve};
use crate::stepping::scallop_step::{Next, NextPoint, Station, next_point, point_at_offset};
use crate::stepping::side_step::corners_face;
use crate::strategy::iso::parametric::Figures;
use crate::strategy::iso::setup::IsoSetup;
use rayon::prelude::*;
use swarf_geom::{Part, Point3};
use swarf_toolpath::Pass;

/// Largest distance between stations, mm.
pub const STATION_SPACING: f64 = 1.0;
/// Most rows planned on one patch (a guard against a path that stops advancing).
const MAX_ROWS: usize = 100_000;
/// Largest change of the side step per unit length along a path (dimensionless;
/// see `limit_turning`).
const MAX_OFFSET_SLOPE: f64 = 0.5;
/// A next point must advance along the path by this much over the last one kept, mm.
const MIN_ADVANCE: f64 = 1e-6;

/// Plans iso-scallop finishing of every patch of `part`.
///
/// # Errors
/// [`PathError::InvalidParameter`] naming `scallop` or `tolerance`
/// when out of range; [`PathError::NoPath`] when no CC point can be reached;
/// [`PathError::Geom`] when the part cannot be prepared for the gouge check.
pub fn plan(part: &Part, cutting: &Cutting, params: &IsoParams) -> Result<Plan, PathError> {
    let setup = IsoSetup::new(part, params.job(cutting, "iso-scallop"))?;
    let mut rows = Vec::new();
    let mut report = PlanReport::default();
    let mut figures = Figures::default();
    for face in 0..part.patches.len() {
        IsoScallop::new(&setup, face).plan(&mut rows, &mut figures, &mut report);
    }
    figures.write(&mut report);
    let mut plan = setup.finish(rows, report)?;
    plan.report.pass_bound = setup.pass_bound(Feed::Param(params.direction));
    Ok(plan)
}

/// A CC path: a polyline in the parameter plane and its forward-stepped samples
/// (`Sample::t` runs along the polyline: vertex `k` at `t = k`).
struct Path {
    curve: Vec<[f64; 2]>,
    samples: Vec<Sample>,
}

/// Iso-scallop paths on one patch.
struct IsoScallop<'s, 'a> {
    setup: &'s IsoSetup<'a>,
    map: ClMap<'a>,
    first: Vec<[f64; 2]>,
    inward: [f64; 2],
    /// Effective cutting radius used on this patch (module doc), mm.
    radius: f64,
}

impl<'s, 'a> IsoScallop<'s, 'a> {
    fn new(setup: &'s IsoSetup<'a>, face: usize) -> Self {
        let map = setup.cl_map(face);
        let [[u0, u1], [v0, v1]] = map.patch().domain();
        let min = setup.params.start == StartSide::Min;
        let (first, inward) = match setup.params.direction {
            ParamDir::U => {
                let v = if min { v0 } else { v1 };
                (vec![[u0, v], [u1, v]], [0.0, if min { 1.0 } else { -1.0 }])
            }
            ParamDir::V => {
                let u = if min { u0 } else { u1 };
                (vec![[u, v0], [u, v1]], [if min { 1.0 } else { -1.0 }, 0.0])
            }
        };
        let radius = setup.side.least_radius_up_to(max_tilt(map.patch()));
        IsoScallop {
            setup,
            map,
            first,
            inward,
            radius,
        }
    }

    fn plan(&self, rows: &mut Vec<Row>, figures: &mut Figures, report: &mut PlanReport) {
        let mut paths = self.paths_on(self.first.clone());
        let Some(sign) = self.orientation(&paths) else {
            return;
        };
        let mut ridge = Vec::new();
        for _ in 0..MAX_ROWS {
            if paths.is_empty() {
                report.uncovered.extend(self.uncut_ridge(&ridge));
                return;
            }
            rows.push(paths.iter().flat_map(|p| self.emit(p)).collect());
            let next: Vec<Vec<[f64; 2]>> = paths
                .iter()
                .flat_map(|p| self.next_curves(p, sign, figures, &mut ridge))
                .collect();
            paths = next.into_iter().flat_map(|c| self.paths_on(c)).collect();
        }
        report.uncovered.extend(self.uncut_ridge(&ridge));
        report.uncovered.push(Uncovered {
            region: format!("patch {}", self.map.face()),
            reason: format!(
                "iso-scallop stopped after {MAX_ROWS} paths without covering the patch"
            ),
        });
    }

    fn uv_at(curve: &[[f64; 2]], t: f64) -> [f64; 2] {
        let k = (t.floor().max(0.0) as usize).min(curve.len().saturating_sub(2));
        let f = t - k as f64;
        if curve.len() < 2 {
            return curve[0];
        }
        let (a, b) = (curve[k], curve[k + 1]);
        [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1])]
    }

    /// The forward-stepped paths along `curve` (one per run where CL points exist).
    fn paths_on(&self, curve: Vec<[f64; 2]>) -> Vec<Path> {
        if curve.is_empty() {
            return Vec::new();
        }
        let f = |t: f64| {
            let uv = Self::uv_at(&curve, t);
            self.map.at(uv[0], uv[1])
        };
        let end = (curve.len() - 1) as f64;
        sample_curve(&f, 0.0, end, &self.setup.step)
            .into_iter()
            .map(|samples| Path {
                curve: curve.clone(),
                samples,
            })
            .collect()
    }

    /// The passes a path contributes: its samples, less points under other patches.
    fn emit(&self, path: &Path) -> Vec<Pass> {
        if self.setup.envelope.is_none() {
            return vec![Pass {
                points: path.samples.iter().map(|s| s.point).collect(),
                ..Pass::default()
            }];
        }
        let (Some(a), Some(b)) = (path.samples.first(), path.samples.last()) else {
            return Vec::new();
        };
        let f = |t: f64| {
            let uv = Self::uv_at(&path.curve, t);
            self.setup.reachable(&self.map, uv[0], uv[1])
        };
        sample_curve(&f, a.t, b.t, &self.setup.step)
            .into_iter()
            .map(|run| Pass {
                points: run.iter().map(|s| s.point).collect(),
                ..Pass::default()
            })
            .collect()
    }

    /// `+1` or `-1`: the sign that turns `N x T` of the first path into the patch.
    fn orientation(&self, paths: &[Path]) -> Option<f64> {
        let path = paths.iter().max_by_key(|p| p.samples.len())?;
        let st = self.stations(path, 1.0);
        let mid = st.get(st.len() / 2)?;
        let inward = mid.d.du * self.inward[0] + mid.d.dv * self.inward[1];
        Some(if mid.side.dot(&inward) < 0.0 {
            -1.0
        } else {
            1.0
        })
    }

    /// Stations along `path` (module doc), side direction `sign N x T`.
    fn stations(&self, path: &Path, sign: f64) -> Vec<Station> {
        let mut ts = Vec::new();
        for w in path.samples.windows(2) {
            let chord = (w[1].point.pose.cl - w[0].point.pose.cl).norm();
            let n = (chord / STATION_SPACING).ceil().max(1.0) as usize;
            ts.extend((0..n).map(|k| w[0].t + (w[1].t - w[0].t) * k as f64 / n as f64));
        }
        ts.extend(path.samples.last().map(|s| s.t));
        let patch = self.map.patch();
        let frames: Vec<_> = ts
            .iter()
            .filter_map(|&t| {
                let uv = Self::uv_at(&path.curve, t);
                let d = patch.derivs(uv[0], uv[1]);
                Some((uv, d, tool_side_normal(&d)?))
            })
            .collect();
        let last = frames.len().saturating_sub(1);
        (0..frames.len())
            .filter_map(|i| {
                let (uv, d, normal) = frames[i];
                // Tangent over a baseline of at least half a station spacing each way
                // (the first segments of a path can be very short).
                let here = d.point;
                let far = |k: &usize| (frames[*k].1.point - here).norm() >= 0.5 * STATION_SPACING;
                let a = (0..i).rev().find(far).unwrap_or(0);
                let b = (i + 1..=last).find(far).unwrap_or(last);
                let chord = frames[b].1.point - frames[a].1.point;
                let tangent = (chord - normal * normal.dot(&chord)).try_normalize(0.0)?;
                let side = sign * normal.cross(&tangent);
                let kappa = tool_side_curvature(&d, &side)?;
                Some(Station {
                    uv,
                    d,
                    normal,
                    tangent,
                    side,
                    step: self.setup.side.step_for_radius(self.radius, kappa),
                    radius: self.radius,
                    end: i == 0 || i == last,
                })
            })
            .collect()
    }

    /// Shortens steps so that the side offset changes along the path by at most
    /// [`MAX_OFFSET_SLOPE`] per unit length: the least Lipschitz envelope of the
    /// offsets over each run of points, and the points re-placed at it. Shorter steps
    /// keep the scallop below `h`; without this, a cutter whose effective radius jumps
    /// with the tilt (a flat bottom turning level) gives neighbouring stations very
    /// different steps, the next path turns across the side direction and the family
    /// folds back over itself.
    fn limit_turning(&self, stations: &[Station], next: &mut [Next]) {
        let offset = |st: &Station, q: &NextPoint| st.side.dot(&(q.point - st.d.point));
        let mut w: Vec<Option<f64>> = stations
            .iter()
            .zip(next.iter())
            .map(|(st, q)| match q {
                Next::Point(q) => Some(offset(st, q)),
                _ => None,
            })
            .collect();
        let gap = |a: usize, b: usize| (stations[a].d.point - stations[b].d.point).norm();
        for i in 1..w.len() {
            if let (Some(prev), Some(cur)) = (w[i - 1], w[i]) {
                w[i] = Some(cur.min(prev + MAX_OFFSET_SLOPE * gap(i - 1, i)));
            }
        }
        for i in (0..w.len().saturating_sub(1)).rev() {
            if let (Some(after), Some(cur)) = (w[i + 1], w[i]) {
                w[i] = Some(cur.min(after + MAX_OFFSET_SLOPE * gap(i, i + 1)));
            }
        }
        let patch = self.map.patch();
        next.par_iter_mut()
            .zip(stations.par_iter().zip(w.par_iter()))
            .for_each(|(q, (st, w))| {
                if let (Next::Point(p), Some(w)) = (*q, *w)
                    && w < offset(st, &p) * (1.0 - 1e-9)
                {
                    *q = point_at_offset(patch, &self.setup.side, st, w)
                        .map_or(Next::Skip, Next::Point);
                }
            });
    }

    /// The report for the points of a convex ridge between paths that a sharp rim
    /// leaves uncut ([`crate::stepping::scallop_crest`]).
    fn uncut_ridge(&self, ridge: &[Point3]) -> Option<Uncovered> {
        let first = ridge.first()?;
        Some(Uncovered {
            region: format!(
                "patch {}, a convex ridge between adjacent paths ({} points, first near x {:.1}, y {:.1})",
                self.map.face(),
                ridge.len(),
                first.x,
                first.y
            ),
            reason: "the cutter's sharp rim touches the ridge with the rims of the two paths facing each other, so nothing cuts it (a ball or bull end mill does)".into(),
        })
    }

    /// The next CC curves from `path`: one per run of points that were not dropped.
    /// For a cutter with a sharp rim, the points with a convex ridge between them and
    /// their stations are added to `ridge`.
    fn next_curves(
        &self,
        path: &Path,
        sign: f64,
        figures: &mut Figures,
        ridge: &mut Vec<Point3>,
    ) -> Vec<Vec<[f64; 2]>> {
        let stations = self.stations(path, sign);
        let patch = self.map.patch();
        let side = &self.setup.side;
        let mut next: Vec<Next> = stations
            .par_iter()
            .map(|st| next_point(patch, side, st))
            .collect();
        self.limit_turning(&stations, &mut next);
        let mut curves = Vec::new();
        let mut current: Vec<NextPoint> = Vec::new();
        let mut beside: Option<NextPoint> = None;
        for (st, q) in stations.iter().zip(&next) {
            match q {
                Next::Skip => {}
                Next::Point(q) => {
                    figures.add_step(q.across, Some(q.scallop));
                    if side.corner() <= 0.0 {
                        let n = tool_side_normal(&patch.derivs(q.uv[0], q.uv[1]));
                        if n.is_some_and(|n| corners_face(&st.normal, &n, &(q.point - st.d.point)))
                        {
                            ridge.push(q.point);
                        }
                    }
                    if current.is_empty() {
                        current.extend(beside.take());
                    }
                    let advances =
                        |l: &NextPoint| (q.point - l.point).dot(&st.tangent) > MIN_ADVANCE;
                    if q.slid {
                        while current.last().is_some_and(|l| !advances(l)) {
                            current.pop();
                        }
                    }
                    if current.last().is_none_or(advances) {
                        current.push(*q);
                    }
                }
                Next::Covered(edge) => {
                    if !current.is_empty() {
                        current.extend(edge);
                        curves.push(std::mem::take(&mut current));
                    }
                    beside = *edge;
                }
            }
        }
        if !current.is_empty() {
            curves.push(current);
        }
        curves
            .into_iter()
            .map(|c| c.iter().map(|q| q.uv).collect())
            .collect()
    }
}

/// Survey nodes per direction for a patch's largest tilt.
const TILT_SURVEY: usize = 33;

/// The largest angle between a normal of `patch` and the tool axis (radians), from a
/// survey grid.
fn max_tilt(patch: &swarf_geom::Patch) -> f64 {
    let [[u0, u1], [v0, v1]] = patch.domain();
    let n = TILT_SURVEY - 1;
    let mut worst: f64 = 0.0;
    for i in 0..=n {
        for j in 0..=n {
            let d = patch.derivs(
                u0 + (u1 - u0) * i as f64 / n as f64,
                v0 + (v1 - v0) * j as f64 / n as f64,
            );
            if let Some(nn) = tool_side_normal(&d) {
                worst = worst.max(nn.x.hypot(nn.y).atan2(nn.z));
            }
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::TestJob;
    use crate::stepping::side_step::ball_step;

    fn job(tool: &str, h: f64) -> TestJob<IsoParams> {
        TestJob::new(tool, IsoParams::new(h))
    }

    fn plan(part: &Part, j: &TestJob<IsoParams>) -> Result<Plan, PathError> {
        super::plan(part, &j.cut, &j.params)
    }

    /// Angle (degrees) of the CC points of a pass around the cylinder axis.
    fn angle(p: &Pass) -> f64 {
        let c = p.points[p.points.len() / 2].contact.unwrap().point;
        c.y.atan2(c.z).to_degrees()
    }

    #[test]
    fn cylinder_paths_keep_the_exact_step_and_reach_the_far_edge() {
        let h = 0.1;
        let plan = plan(&swarf_testkit::parts::cylinder(1.0), &job("ball:d=8", h)).unwrap();
        let passes = &plan.toolpath.passes;
        let step = ball_step(4.0, -1.0 / 60.0, h).unwrap();
        let deg = (step / 60.0).to_degrees();
        for w in passes.windows(2).take(passes.len() - 2) {
            let d = angle(&w[1]) - angle(&w[0]);
            assert!((d - deg).abs() < 2e-3 * deg, "{d} vs {deg}");
        }
        // The last path is within one step of the far edge (30 degrees).
        let last = angle(passes.last().unwrap());
        assert!(last > 30.0 - deg && last <= 30.0 + 1e-9, "{last}");
        // Each path spans the patch from x = 0 to x = 40.
        for p in passes {
            let xs: Vec<f64> = p
                .points
                .iter()
                .map(|q| q.contact.unwrap().point.x)
                .collect();
            let near = |x: f64| xs.iter().any(|v| (v - x).abs() < 1e-9);
            assert!(near(0.0) && near(40.0), "{xs:?}");
        }
        let pred = plan.report.predicted_max_scallop.unwrap();
        assert!(pred <= h && pred > 0.99 * h, "{pred}");
    }

    #[test]
    fn bull_cutter_plans_with_its_least_effective_radius() {
        let h = 0.1;
        let part = swarf_testkit::parts::cylinder(1.0);
        let bull = plan(&part, &job("bull:d=10,r=2", h)).unwrap();
        // The cylinder tilts up to 30 degrees: the least effective radius up to there,
        // used as a ball on the convex radius 60, sets the interior side step.
        let side = crate::stepping::side_step::SideStep::new(&"bull:d=10,r=2".parse().unwrap(), h)
            .unwrap();
        let re = side.least_radius_up_to(max_tilt(&part.patches[0]));
        assert!(re < 4.0, "{re}");
        let want = side.step_for_radius(re, -1.0 / 60.0);
        let [_, top] = bull.report.side_step_range.unwrap();
        assert!((top - want).abs() < 5e-3 * want, "{top} vs {want}");
        assert!(bull.report.predicted_max_scallop.unwrap() <= h);
        assert_eq!(bull.report.lifted_points, 0);
        assert!((max_tilt(&part.patches[0]) - 30f64.to_radians()).abs() < 1e-9);
    }
}
