//! Iso-planar finishing: CC paths are sections of the part by parallel vertical drive
//! planes (paper 004, iso-planar section; Lo 2000).
//!
//! The feed direction is `F = (cos a, sin a, 0)` (`angle = a`, degrees from
//! +X), the drive planes are `M . x = m` with `M = (-sin a, cos a, 0)`, and the planes
//! run from the part's lowest `M . x` (`start = "max"`: its highest) across it. The
//! paper's iso-planar section lost its symbols in extraction; the scheduling below is
//! derived from the geometry it describes (Lo 2000: the difference between CC points
//! of adjacent paths lies in the cross-section spanned by the side vector and the
//! tool axis):
//!
//! - On a surface with unit normal `N`, the section curve of the plane has tangent
//!   `T ~ N x M` and the side direction is `B = N x T`. The drive value `m = M . x`
//!   restricted to the surface changes fastest across the path, with gradient
//!   `M - (M . N) N = -(M . B) B`; so planes `dm` apart are `dm / |M . B|` apart on the
//!   surface, and the side step `dl` allowed by the scallop limit
//!   ([`crate::stepping::side_step`], normal curvature along `B`) gives `dm = dl |M . B|`.
//! - The plane spacing is the least of those over every sample of every section piece
//!   in the plane (conservative over the pass), then fitted like the iso-parametric
//!   interval: from each sample `P` the point `Q` of the next plane in the cross-section
//!   normal to `T` (on the surface, `T . Q = T . P`, `M . Q = m + dm`;
//!   [`crate::section_point`]) must be within the side step allowed at both `P` and
//!   `Q`. Where a convex ridge lies between `P` and `Q` (their normals lean toward
//!   each other), a bull end mill cuts it with its two facing corners, so the corner
//!   radius sets the step there ([`crate::stepping::side_step`], "Convex ridges"). A flat end
//!   mill has no corner: its ridges between planes are not detected here (a known gap;
//!   iso-parametric reports them).
//! - Sections come from [`swarf_geom::Patch::intersect_plane`] on every patch; between
//!   its samples the CC curve is the straight parameter segment pulled back onto the
//!   plane (a few Newton steps along the parameter gradient of `M . S`), so every CC
//!   point lies exactly on the plane and the surface; the forward stepper samples it
//!   at the chordal tolerance. Pieces under another patch (the part's upper envelope,
//!   [`crate::envelope`]) are trimmed; the pieces of one plane, from all patches, are
//!   ordered along `F` and joined across small gaps (the `ordering` module).
//! - The last plane, at the part's far extent, is left out when the tools of the one
//!   before already leave at most `h` all along it.
//! - A piece's last step, the remainder up to the end of its section, is evened with
//!   the step before when it is under half of it (`even_end`).
//!
//! **Fixed cross feed.** With `stepover = s` instead of a scallop limit (the
//! "cross feed 3.5 mm" of thesis 000 ch. 8) the planes are exactly `s` apart:
//! `floor(W / s) + 1` planes centred in the part's extent `W` along `M` (the same
//! margin, under `s / 2`, on both sides), cut from the `start` side. The scallop
//! figures are then the side-step model's prediction for that spacing
//! (`iso_setup`: a ball of the tool radius at that stepover); there are no boundary
//! passes.

use crate::error::PathError;
use crate::ordering::Row;
use crate::params::{Cutting, ParamDir, StartSide, check_angle};
use crate::plan::{Plan, PlanReport};
use crate::section_point::{PlaneEq, Solved, two_planes};
use crate::stepping::forward_step::{Sample, sample_curve};
use crate::stepping::side_step::corners_face;
use crate::strategy::iso::parametric::Figures;
use crate::strategy::iso::setup::IsoJob;
use crate::strategy::iso::setup::{IsoSetup, fit_interval};
use swarf_geom::math::point_segment_distance;
use swarf_geom::{Part, Patch, Plane, SectionCurve, Vec3};
use swarf_toolpath::{Pass, PathPoint};

pub use super::planar_params::IsoPlanarParams;

/// The first and last planes are moved this far inside the part's extent, mm.
const EDGE_INSET: f64 = 1e-4;
/// Survey grid for the part's extent along the plane normal, nodes per direction.
const EXTENT_SURVEY: usize = 129;
/// Bisection steps placing the point halfway along a pass's last two steps.
const HALFWAY_BISECTIONS: usize = 40;
/// Newton steps pulling an interpolated parameter point back onto the plane.
const PULL_BACK_STEPS: usize = 4;

/// Plans iso-planar finishing of `part` (all patches: the upper envelope).
///
/// # Errors
/// [`PathError::InvalidParameter`] naming `scallop`, `tolerance` or `angle` when out
/// of range; [`PathError::NoPath`] when no drive plane meets the part or no CC point
/// can be reached; [`PathError::Geom`] when a section fails.
pub fn plan(part: &Part, cutting: &Cutting, params: &IsoPlanarParams) -> Result<Plan, PathError> {
    check_angle(params.angle)?;
    let job = IsoJob {
        cutting,
        finish: params.finish,
        scallop: params.scallop,
        stepover: params.stepover,
        direction: ParamDir::U,
        start: params.start,
        kind: "iso-planar",
    };
    let setup = IsoSetup::new(part, job)?;
    let a = params.angle;
    let planar = IsoPlanar {
        setup: &setup,
        feed: Vec3::new(a.cos(), a.sin(), 0.0),
        normal: Vec3::new(-a.sin(), a.cos(), 0.0),
    };
    let mut report = PlanReport::default();
    let mut figures = Figures::default();
    let rows = planar.rows(&mut figures)?;
    if rows.iter().all(|r| r.is_empty()) {
        return Err(PathError::NoPath(format!(
            "no drive plane at {} degrees meets a reachable point of part {:?}",
            swarf_geom::units::shown_degrees(params.angle),
            part.name
        )));
    }
    figures.write(&mut report);
    let mut plan = setup.finish(rows, report)?;
    plan.report.pass_bound = setup.pass_bound(super::pass_bound::Feed::Plane(params.angle));
    Ok(plan)
}

/// One sample of a section, for the plane spacing.
#[derive(Debug, Clone, Copy)]
struct Station {
    face: usize,
    uv: [f64; 2],
}

struct IsoPlanar<'s, 'a> {
    setup: &'s IsoSetup<'a>,
    feed: Vec3,
    normal: Vec3,
}

impl IsoPlanar<'_, '_> {
    /// All rows, from the start side across the part.
    fn rows(&self, figures: &mut Figures) -> Result<Vec<Row>, PathError> {
        let [lo, hi] = self.extent();
        if hi - lo <= 2.0 * EDGE_INSET {
            let (row, _) = self.row(0.5 * (lo + hi))?;
            return Ok(vec![row]);
        }
        if let Some(step) = self.setup.params.stepover {
            return self.fixed_rows(lo + EDGE_INSET, hi - EDGE_INSET, step, figures);
        }
        let (mut m, end, sign) = match self.setup.params.start {
            StartSide::Min => (lo + EDGE_INSET, hi - EDGE_INSET, 1.0),
            StartSide::Max => (hi - EDGE_INSET, lo + EDGE_INSET, -1.0),
        };
        let mut rows: Vec<Row> = Vec::new();
        loop {
            let (row, stations) = self.row(m)?;
            if m == end
                && rows
                    .last()
                    .is_some_and(|prev| self.setup.covers(prev, &row))
            {
                return Ok(rows);
            }
            rows.push(row);
            if m == end {
                return Ok(rows);
            }
            let dm = self.spacing(m, sign, &stations, figures);
            m = if sign > 0.0 {
                (m + dm).min(end)
            } else {
                (m - dm).max(end)
            };
        }
    }

    /// Rows on planes exactly `step` apart, centred in `[lo, hi]` (module doc).
    fn fixed_rows(
        &self,
        lo: f64,
        hi: f64,
        step: f64,
        figures: &mut Figures,
    ) -> Result<Vec<Row>, PathError> {
        let n = ((hi - lo) / step).floor();
        let first = lo + 0.5 * ((hi - lo) - n * step);
        let mut planes: Vec<f64> = (0..=n as usize).map(|k| first + k as f64 * step).collect();
        let sign = match self.setup.params.start {
            StartSide::Min => 1.0,
            StartSide::Max => {
                planes.reverse();
                -1.0
            }
        };
        let mut rows = Vec::with_capacity(planes.len());
        for (k, &m) in planes.iter().enumerate() {
            let (row, stations) = self.row(m)?;
            if k + 1 < planes.len() {
                let geom: Vec<_> = stations
                    .iter()
                    .filter_map(|s| self.geometry(s, sign))
                    .collect();
                self.record(&geom, m + sign * step, figures);
            }
            rows.push(row);
        }
        Ok(rows)
    }

    /// `[min, max]` of `M . x` over the part, from a survey of every patch.
    fn extent(&self) -> [f64; 2] {
        let mut out = [f64::INFINITY, f64::NEG_INFINITY];
        for patch in &self.setup.part.patches {
            let [[u0, u1], [v0, v1]] = patch.domain();
            let n = EXTENT_SURVEY - 1;
            for i in 0..=n {
                for j in 0..=n {
                    let p = patch.eval(
                        u0 + (u1 - u0) * i as f64 / n as f64,
                        v0 + (v1 - v0) * j as f64 / n as f64,
                    );
                    let m = self.normal.dot(&p.coords);
                    out = [out[0].min(m), out[1].max(m)];
                }
            }
        }
        out
    }

    /// The pieces of the section at `m`, ordered along the feed, and the stations.
    fn row(&self, m: f64) -> Result<(Row, Vec<Station>), PathError> {
        let plane = Plane {
            normal: self.normal,
            offset: m,
        };
        let mut pieces: Vec<Pass> = Vec::new();
        for (face, patch) in self.setup.part.patches.iter().enumerate() {
            for curve in patch.intersect_plane(&plane, self.setup.step.tolerance)? {
                pieces.extend(self.pieces(face, patch, &curve, m));
            }
        }
        for p in &mut pieces {
            let (a, b) = (p.points[0].pose.cl, p.points[p.points.len() - 1].pose.cl);
            if self.feed.dot(&(b - a)) < 0.0 {
                p.points.reverse();
            }
        }
        pieces.sort_by(|a, b| {
            let ka = self.feed.dot(&a.points[0].pose.cl.coords);
            let kb = self.feed.dot(&b.points[0].pose.cl.coords);
            ka.total_cmp(&kb)
        });
        let stations = pieces
            .iter()
            .flat_map(|p| &p.points)
            .filter_map(|p| {
                p.contact.map(|c| Station {
                    face: c.face,
                    uv: c.uv,
                })
            })
            .collect();
        Ok((pieces, stations))
    }

    /// Forward-stepped, reachable pieces of one section curve.
    fn pieces(&self, face: usize, patch: &Patch, curve: &SectionCurve, m: f64) -> Vec<Pass> {
        let n = curve.samples.len();
        if n == 0 {
            return Vec::new();
        }
        let map = self.setup.cl_map(face);
        let last = if curve.closed { n } else { n - 1 };
        let f = |t: f64| {
            let k = (t.floor().max(0.0) as usize).min(last.saturating_sub(1));
            let (a, b) = (&curve.samples[k % n], &curve.samples[(k + 1) % n]);
            let s = if last == 0 { 0.0 } else { t - k as f64 };
            let uv = self.pull_back(patch, [a.u + s * (b.u - a.u), a.v + s * (b.v - a.v)], m);
            self.setup.reachable(&map, uv[0], uv[1])
        };
        sample_curve(&f, 0.0, last as f64, &self.setup.step)
            .into_iter()
            .map(|mut run| {
                self.even_end(&f, &mut run);
                Pass {
                    points: run.into_iter().map(|s| s.point).collect::<Vec<PathPoint>>(),
                    ..Pass::default()
                }
            })
            .collect()
    }

    /// Splits the last two steps of a run evenly (by chord length) when the
    /// last, the remainder up to the end of the curve, is under half the one before:
    /// a stub at the end of a pass (down to two samples 1e-13 mm apart where a section
    /// ends on a patch corner) gives five-axis positioning no feed direction and the
    /// machine a needless short move. Kept only when both new chords are within the
    /// chordal tolerance and the longest step (checked at their quarter points).
    fn even_end(&self, f: &impl Fn(f64) -> Option<PathPoint>, run: &mut [Sample]) {
        let n = run.len();
        if n < 3 {
            return;
        }
        let (a, b, c) = (&run[n - 3], &run[n - 2], &run[n - 1]);
        let chord = |p: &Sample, q: &Sample| (q.point.pose.cl - p.point.pose.cl).norm();
        if chord(b, c) >= 0.5 * chord(a, b) {
            return;
        }
        let Some(mid) = halfway(f, a, c) else { return };
        let opts = &self.setup.step;
        let within = |p: &Sample, q: &Sample| {
            chord(p, q) <= opts.max_step
                && [0.25, 0.5, 0.75].iter().all(|s| {
                    f(p.t + s * (q.t - p.t)).is_some_and(|m| {
                        point_segment_distance(&m.pose.cl, &p.point.pose.cl, &q.point.pose.cl)
                            <= opts.tolerance
                    })
                })
        };
        if within(a, &mid) && within(&mid, c) {
            run[n - 2] = mid;
        }
    }

    /// `uv` moved onto the plane `M . S = m` along the parameter gradient.
    fn pull_back(&self, patch: &Patch, uv: [f64; 2], m: f64) -> [f64; 2] {
        let mut uv = uv;
        for _ in 0..PULL_BACK_STEPS {
            let d = patch.derivs(uv[0], uv[1]);
            let g = self.normal.dot(&d.point.coords) - m;
            let grad = [self.normal.dot(&d.du), self.normal.dot(&d.dv)];
            let len2 = grad[0] * grad[0] + grad[1] * grad[1];
            if g.abs() < 1e-12 || len2 == 0.0 {
                break;
            }
            let (u, v) = patch.clamp_params(uv[0] - g * grad[0] / len2, uv[1] - g * grad[1] / len2);
            uv = [u, v];
        }
        uv
    }

    /// Spacing to the next plane (module doc); the flat-surface step where the plane
    /// has no station.
    fn spacing(&self, m: f64, sign: f64, stations: &[Station], figures: &mut Figures) -> f64 {
        let geom: Vec<_> = stations
            .iter()
            .filter_map(|s| self.geometry(s, sign))
            .collect();
        let first = geom
            .iter()
            .map(|g| g.side.step * self.normal.dot(&g.side.side).abs())
            .filter(|d| *d > 0.0)
            .fold(f64::INFINITY, f64::min);
        let start = if first.is_finite() {
            first
        } else {
            self.setup.side.step(0.0, 0.0)
        };
        let dm = fit_interval(start, |dm| {
            geom.iter()
                .filter_map(|g| self.crossing(g, m + sign * dm))
                .map(|c| c.across / c.allowed)
                .fold(0.0, f64::max)
        });
        let dm = if dm > 0.0 { dm } else { start };
        self.record(&geom, m + sign * dm, figures);
        dm
    }

    /// Side steps and predicted scallops from the stations `geom` to the plane `next`.
    fn record(&self, geom: &[Geometry<'_>], next: f64, figures: &mut Figures) {
        for c in geom.iter().filter_map(|g| self.crossing(g, next)) {
            figures.add_step(c.across, c.scallop);
        }
    }

    /// Frame and side geometry at a station; `side` turned toward the next plane.
    fn geometry(&self, s: &Station, sign: f64) -> Option<Geometry<'_>> {
        let patch = &self.setup.part.patches[s.face];
        let d = patch.derivs(s.uv[0], s.uv[1]);
        let n = crate::cl_curve::tool_side_normal(&d)?;
        let tangent = n.cross(&self.normal).try_normalize(0.0)?;
        let mut side = self.setup.side_at(&d, &tangent)?;
        if sign * self.normal.dot(&side.side) < 0.0 {
            side.side = -side.side;
        }
        Some(Geometry {
            patch,
            uv: s.uv,
            d,
            tangent,
            side,
        })
    }

    /// The point of plane `m` across the path from `g`, and the side steps allowed.
    fn crossing(&self, g: &Geometry<'_>, m: f64) -> Option<Crossing> {
        let section = PlaneEq {
            normal: g.tangent,
            offset: g.tangent.dot(&g.d.point.coords),
        };
        let next = PlaneEq {
            normal: self.normal,
            offset: m,
        };
        let Solved::Inside { d, .. } = two_planes(g.patch, g.uv, &section, &next) else {
            return None;
        };
        let q = self.setup.side_at(&d, &g.tangent)?;
        let chord = d.point - g.d.point;
        let across = chord.norm();
        let side = &self.setup.side;
        let both = |a: Option<f64>, b: Option<f64>| Some(a?.max(b?));
        // A convex ridge between the planes is cut by the two facing corners of a
        // bull end mill (side_step, "Convex ridges"), as in iso_parametric. A flat end
        // mill has no corner to cut it with: its ridges stay a known gap (see the
        // module doc).
        if side.corner() > 0.0 && corners_face(&g.side.normal, &q.normal, &chord) {
            return Some(Crossing {
                across,
                allowed: side
                    .corner_step(g.side.kappa)
                    .min(side.corner_step(q.kappa)),
                scallop: both(
                    side.corner_scallop(across, g.side.kappa),
                    side.corner_scallop(across, q.kappa),
                ),
            });
        }
        Some(Crossing {
            across,
            allowed: g.side.step.min(q.step),
            scallop: both(
                side.scallop(across, g.side.kappa, g.side.tilt),
                side.scallop(across, q.kappa, q.tilt),
            ),
        })
    }
}

/// The sample between `a` and `c` equally far from both (bisection on the curve
/// parameter: the parameter of a section's polyline can linger where two of its
/// samples nearly coincide).
fn halfway(f: &impl Fn(f64) -> Option<PathPoint>, a: &Sample, c: &Sample) -> Option<Sample> {
    let (pa, pc) = (a.point.pose.cl, c.point.pose.cl);
    let (mut lo, mut hi) = (a.t, c.t);
    let mut best = None;
    for _ in 0..HALFWAY_BISECTIONS {
        let t = 0.5 * (lo + hi);
        let point = f(t)?;
        let p = point.pose.cl;
        if (p - pa).norm() < (pc - p).norm() {
            lo = t;
        } else {
            hi = t;
        }
        best = Some(Sample { t, point });
    }
    best
}

/// A station's frame.
struct Geometry<'p> {
    patch: &'p Patch,
    uv: [f64; 2],
    d: swarf_geom::SurfaceDerivs,
    tangent: Vec3,
    side: crate::strategy::iso::setup::SideGeom,
}

/// Distance to the next plane's path at one station.
struct Crossing {
    across: f64,
    allowed: f64,
    scallop: Option<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::TestJob;

    /// Planes at `angle_deg` from +X, spaced for a scallop of 0.3 mm by a ball d = 8.
    fn job(angle_deg: f64) -> TestJob<IsoPlanarParams> {
        let mut j = TestJob::new("ball:d=8", IsoPlanarParams::new(0.3));
        j.angle = angle_deg.to_radians();
        j
    }

    fn plan(part: &Part, j: &TestJob<IsoPlanarParams>) -> Result<Plan, PathError> {
        super::plan(part, &j.cut, &j.params)
    }

    /// Height of `patch` over `(x, y)` by Newton on the XY map from the best node of a
    /// coarse grid; `None` outside its outline.
    fn height(patch: &Patch, x: f64, y: f64) -> Option<f64> {
        let n = 40;
        let mut best = (f64::INFINITY, [0.0, 0.0]);
        for i in 0..=n {
            for j in 0..=n {
                let uv = [i as f64 / n as f64, j as f64 / n as f64];
                let p = patch.eval(uv[0], uv[1]);
                let d = (p.x - x).hypot(p.y - y);
                if d < best.0 {
                    best = (d, uv);
                }
            }
        }
        let mut uv = best.1;
        for _ in 0..30 {
            let d = patch.derivs(uv[0], uv[1]);
            let (fx, fy) = (d.point.x - x, d.point.y - y);
            let det = d.du.x * d.dv.y - d.du.y * d.dv.x;
            uv[0] -= (fx * d.dv.y - fy * d.dv.x) / det;
            uv[1] -= (d.du.x * fy - d.du.y * fx) / det;
        }
        let p = patch.eval(uv[0], uv[1]);
        let inside = uv.iter().all(|t| (-1e-9..=1.0 + 1e-9).contains(t));
        (inside && (p.x - x).hypot(p.y - y) < 1e-6).then_some(p.z)
    }

    #[test]
    fn sections_cross_the_valley_of_two_patches_on_their_envelope() {
        let part = swarf_io::builtin_part("edge-convex").unwrap();
        let plan = plan(&part, &job(90.0)).unwrap();
        let points: Vec<_> = plan
            .toolpath
            .passes
            .iter()
            .flat_map(|p| &p.points)
            .collect();
        // Every CC point is on the upper envelope: no other patch above it by more
        // than the envelope's margin (0.05 mm) and its mesh's vertical error.
        for p in &points {
            let Some(c) = p.contact else { continue };
            let other = &part.patches[1 - c.face];
            if let Some(z) = height(other, c.point.x, c.point.y) {
                assert!(z <= c.point.z + 0.08, "{c:?} under the other patch at {z}");
            }
        }
        // Passes run along y across the crease: some hold contacts on both patches.
        let both = plan.toolpath.passes.iter().any(|p| {
            let faces: Vec<_> = p
                .points
                .iter()
                .filter_map(|q| q.contact.map(|c| c.face))
                .collect();
            faces.contains(&0) && faces.contains(&1)
        });
        assert!(both);
        // The ball cannot enter the crease: lifted points, reported as a region.
        assert!(plan.report.lifted_points > 0);
        assert!(plan.report.max_lift > 0.01);
        assert!(
            plan.report
                .uncovered
                .iter()
                .any(|u| u.reason.contains("lifted"))
        );
        // Passes are drive-plane sections: each at one x (up to the bridges).
        for pass in &plan.toolpath.passes {
            let xs: Vec<f64> = pass
                .points
                .iter()
                .filter_map(|q| q.contact.map(|c| c.point.x))
                .collect();
            let spread = xs.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                - xs.iter().copied().fold(f64::INFINITY, f64::min);
            assert!(spread < 1e-6, "{spread}");
        }
        let pred = plan.report.predicted_max_scallop.unwrap();
        assert!(pred <= 0.3 * (1.0 + 1e-3), "{pred}");
    }

    #[test]
    fn start_side_and_bad_angle() {
        let part = swarf_io::builtin_part("wave").unwrap();
        let mut max = job(0.0);
        max.start = StartSide::Max;
        let a = plan(&part, &max).unwrap();
        let first = a.toolpath.passes[0].points[0].contact.unwrap().point;
        assert!(first.y > 99.0, "{first:?}");
        let b = plan(&part, &job(0.0)).unwrap();
        let first = b.toolpath.passes[0].points[0].contact.unwrap().point;
        assert!(first.y < 1.0, "{first:?}");
        let mut j = job(0.0);
        j.angle = f64::NAN;
        let e = plan(&part, &j).unwrap_err().to_string();
        assert!(e.starts_with("angle"), "{e}");
    }
}
