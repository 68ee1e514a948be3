//! What the three iso strategies share: validated parameters, the side-step model,
//! the forward-step options, the side geometry at a CC point, and the end of planning
//! (clipping to trimmed faces, boundary passes where the rows leave too much on an edge, whole-part gouge check,
//! joining and ordering rows, the report).
//!
//! A fixed `stepover` (iso-planar) replaces the scallop limit: the side-step
//! model then takes the height a ball of the tool's radius leaves at that stepover on
//! a plane ([`nominal_scallop`]) and serves the predicted-scallop figures only (exact
//! for a ball, the effective-radius approximation of [`crate::stepping::side_step`] otherwise),
//! and no boundary passes are added: the cross feed is what the job asked for.
//!
//! Side geometry (paper 004, iso-parametric section): at a CC point with unit normal
//! `N` (toward the tool) and unit path tangent `T`, the side direction is
//! `B = N x T`; the side step follows from the normal curvature along `B`
//! ([`crate::stepping::side_step`]) and the tilt of `N` from the tool axis seen in the section
//! normal to `T`, `atan2(|B.z|, N.z)`.

use crate::cl_curve::{ClMap, tool_side_curvature, tool_side_normal};
use crate::envelope::Envelope;
use crate::error::PathError;
use crate::gouge::GougeCheck;
use crate::ordering::{Joining, Row, order_rows};
use crate::params::{Cutting, Finish, ParamDir, StartSide};
use crate::plan::{Plan, PlanReport};
use crate::stepping::forward_step::{OUTPUT_ROUNDING, StepOptions};
use crate::stepping::side_step::SideStep;
use crate::strategy::iso::boundary::boundary_passes;
use crate::strategy::iso::trim_clip::{clip_rows, inside};
use crate::uncovered::{Marked, regions};
use swarf_geom::{Part, Point3, SurfaceDerivs, Vec3};
use swarf_tool::drop::DropScratch;
use swarf_toolpath::{PathPoint, Toolpath, top_z};

/// A CC point is hidden under another patch when the envelope (tessellated within the
/// tolerance) is above it by more than this many tolerances...
const ENVELOPE_MARGIN_TOLS: f64 = 4.0;
/// ... and at least this much, mm (steep slopes magnify the mesh's vertical error).
const ENVELOPE_MARGIN_MIN: f64 = 0.05;

/// Side geometry at a CC point (module doc).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SideGeom {
    /// Unit normal toward the tool.
    pub normal: Vec3,
    /// Unit side direction `N x T`.
    pub side: Vec3,
    /// Normal curvature along `side`, 1/mm, positive concave as the tool sees it.
    pub kappa: f64,
    /// Tilt of the normal from the axis in the section normal to `T`, radians.
    pub tilt: f64,
    /// The side step allowed by the scallop limit, mm.
    pub step: f64,
}

/// What the three iso strategies take, from the job's cutting and each one's own
/// parameters ([`super::IsoParams`], [`super::planar::IsoPlanarParams`]).
#[derive(Debug, Clone, Copy)]
pub struct IsoJob<'a> {
    /// Tool, feeds, linking.
    pub cutting: &'a Cutting,
    /// Tolerance and zigzag.
    pub finish: Finish,
    /// Scallop height limit, mm.
    pub scallop: Option<f64>,
    /// Fixed distance between drive planes, mm (iso-planar).
    pub stepover: Option<f64>,
    /// The parameter the passes follow (iso-parametric, iso-scallop).
    pub direction: ParamDir,
    /// Side the first pass starts on.
    pub start: StartSide,
    /// Which iso strategy, as a job names it (for messages).
    pub kind: &'static str,
}

/// The shared planning context of one iso job on one part.
pub struct IsoSetup<'a> {
    /// The part.
    pub part: &'a Part,
    /// The strategy's parameters.
    pub params: IsoJob<'a>,
    /// The side-step model.
    pub side: SideStep,
    /// Forward-step options.
    pub step: StepOptions,
    /// Whole-part gouge check.
    pub gouge: GougeCheck,
    /// The upper envelope, for parts of several patches.
    pub envelope: Option<Envelope>,
}

impl<'a> IsoSetup<'a> {
    /// Validates the job's parameters for `part` and prepares the whole-part queries.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] naming `scallop` or `tolerance`; [`PathError::NoPath`] for a part without patches;
    /// [`PathError::Geom`] when the part cannot be tessellated.
    pub fn new(part: &'a Part, params: IsoJob<'a>) -> Result<IsoSetup<'a>, PathError> {
        let h =
            match (params.scallop, params.stepover) {
                (Some(h), _) => h,
                (None, Some(step)) => nominal_scallop(params.cutting.tool.radius(), step)
                    .ok_or_else(|| PathError::InvalidParameter {
                        field: "stepover".into(),
                        message: format!(
                            "expected 0 < stepover < tool diameter {} mm, found {} mm",
                            2.0 * params.cutting.tool.radius(),
                            swarf_geom::domain::show(step)
                        ),
                    })?,
                (None, None) => {
                    return Err(PathError::InvalidParameter {
                        field: "scallop".into(),
                        message: "required by the iso strategies (scallop height limit, mm)".into(),
                    });
                }
            };
        let side = SideStep::new(&params.cutting.tool, h)?;
        if part.patches.is_empty() {
            return Err(PathError::NoPath(format!(
                "part {:?} has no patches",
                part.name
            )));
        }
        let tolerance = params.finish.tolerance;
        let gouge = GougeCheck::new(part, &params.cutting.tool, tolerance)?;
        let envelope = if part.patches.len() > 1 {
            let mesh = part.tessellate(tolerance)?;
            Some(Envelope::new(
                mesh,
                (ENVELOPE_MARGIN_TOLS * tolerance).max(ENVELOPE_MARGIN_MIN),
            ))
        } else {
            None
        };
        Ok(IsoSetup {
            part,
            params,
            side,
            step: StepOptions {
                tolerance: (tolerance - OUTPUT_ROUNDING).max(0.5 * tolerance),
                max_step: params.cutting.tool.radius(),
            },
            gouge,
            envelope,
        })
    }

    /// The least number of full-length passes any family along `feed` needs on each
    /// patch at the scallop limit ([`super::pass_bound`]; none for a fixed
    /// stepover).
    pub fn pass_bound(&self, feed: super::pass_bound::Feed) -> Vec<super::pass_bound::PassBound> {
        match self.params.scallop {
            Some(_) => super::pass_bound::pass_bound(self.part, &self.side, feed),
            None => Vec::new(),
        }
    }

    /// The CC -> CL map of patch `face`.
    pub fn cl_map(&self, face: usize) -> ClMap<'a> {
        ClMap::new(&self.part.patches[face], face, &self.params.cutting.tool)
    }

    /// The CL point at `(u, v)` of `map`'s patch, `None` where undefined or hidden
    /// under another patch.
    pub fn reachable(&self, map: &ClMap<'_>, u: f64, v: f64) -> Option<PathPoint> {
        let p = map.at(u, v)?;
        match (&self.envelope, &p.contact) {
            (Some(env), Some(c)) if env.hides(&c.point) => None,
            _ => Some(p),
        }
    }

    /// Side geometry at `d` for the path tangent `tangent` (module doc); `None` at a
    /// degenerate point.
    pub fn side_at(&self, d: &SurfaceDerivs, tangent: &Vec3) -> Option<SideGeom> {
        let normal = tool_side_normal(d)?;
        let t = (tangent - normal * normal.dot(tangent)).try_normalize(1e-300)?;
        let side = normal.cross(&t);
        let kappa = tool_side_curvature(d, &side)?;
        let tilt = side.z.abs().atan2(normal.z);
        Some(SideGeom {
            normal,
            side,
            kappa,
            tilt,
            step: self.side.step(kappa, tilt),
        })
    }

    /// True when the tools of `current` leave at most `h` at every CC point of `last`
    /// inside its face (so the boundary row `last` need not be cut): each tool is taken as the ball of
    /// the least effective radius touching its CC point, and the material at a point
    /// is where the ray along its normal first enters one of them.
    pub fn covers(&self, current: &Row, last: &Row) -> bool {
        let r = self.side.min_effective_radius();
        let h = self.side.h();
        let centres: Vec<_> = current
            .iter()
            .flat_map(|p| &p.points)
            .filter_map(|p| p.contact.map(|c| c.point + r * c.normal))
            .collect();
        let targets: Vec<_> = last
            .iter()
            .flat_map(|p| &p.points)
            .filter(|p| inside(self.part, p))
            .filter_map(|p| p.contact)
            .collect();
        !centres.is_empty()
            && targets.iter().all(|c| {
                centres
                    .iter()
                    .map(|centre| ray_sphere(&c.point, &c.normal, centre, r))
                    .fold(f64::INFINITY, f64::min)
                    <= h
            })
    }

    /// Gouge-checks, joins and orders `rows` (in side order from the start side) and
    /// completes `report` with the lifts and the regions the cutter could not reach.
    ///
    /// # Errors
    /// [`PathError::NoPath`] when there is no pass, or when every CL point had to be
    /// lifted (the tool is too large for any valid position on this part).
    pub fn finish(&self, rows: Vec<Row>, mut report: PlanReport) -> Result<Plan, PathError> {
        let mut rows = clip_rows(self, rows);
        let total: usize = rows.iter().flatten().map(|p| p.points.len()).sum();
        if total == 0 {
            return Err(PathError::NoPath(format!(
                "{}: no CC point of part {:?} can be reached by the tool",
                self.params.kind, self.part.name
            )));
        }
        if self.params.stepover.is_none() {
            let extra = boundary_passes(self, &rows);
            if !extra.is_empty() {
                rows.push(extra);
            }
        }
        let stats = self.gouge.apply(&mut rows);
        if stats.lifted == total {
            return Err(PathError::NoPath(format!(
                "tool {} is too large for any valid position on part {:?}: every CL point had to be lifted off its contact",
                self.params.cutting.tool, self.part.name
            )));
        }
        report.lifted_points = stats.lifted;
        report.max_lift = stats.max_lift;
        report.uncovered.extend(self.lifted_regions(&rows));
        let scratch = std::cell::RefCell::new(DropScratch::default());
        let join = Joining {
            max_gap: 2.0 * self.params.cutting.tool.radius(),
            step: self.step.max_step,
            drop: |x: f64, y: f64| self.gouge.drop_z(x, y, &mut scratch.borrow_mut()),
        };
        let passes = order_rows(rows, self.params.finish.zigzag, &join);
        let top = top_z(&passes);
        Ok(Plan {
            toolpath: Toolpath {
                passes,
                feeds: self.params.cutting.feeds,
                linking: self.params.cutting.linking_for(top),
            },
            report,
            double_contacts: Vec::new(),
        })
    }

    fn lifted_regions(&self, rows: &[Row]) -> Vec<crate::plan::Uncovered> {
        let marked: Vec<Marked> = rows
            .iter()
            .flatten()
            .flat_map(|p| &p.points)
            .filter(|p| p.lifted > 0.0)
            .filter_map(|p| {
                let c = p.contact?;
                Some(Marked {
                    face: c.face,
                    uv: c.uv,
                    value: p.lifted,
                })
            })
            .collect();
        regions(self.part, &marked, |n, worst| {
            format!(
                "concave or crowded region the cutter cannot enter at its CC points: {n} CL points lifted to avoid gouging, by up to {worst:.4} mm"
            )
        })
    }
}

/// The scallop a ball of radius `r` leaves on a plane between passes `step` apart,
/// `r - sqrt(r^2 - step^2 / 4)` (mm): the side-step model's height for a fixed
/// stepover, which it uses for the predicted-scallop figures only. `None` unless
/// `0 < step < 2 r`.
pub fn nominal_scallop(r: f64, step: f64) -> Option<f64> {
    (step.is_finite() && step > 0.0 && step < 2.0 * r)
        .then(|| r - (r * r - 0.25 * step * step).sqrt())
        .filter(|h| *h > 0.0)
}

/// First `t >= 0` where `p + t n` (unit `n`) is inside the sphere; 0 when `p` is.
fn ray_sphere(p: &Point3, n: &Vec3, centre: &Point3, r: f64) -> f64 {
    let m = p - centre;
    let c = m.norm_squared() - r * r;
    if c <= 0.0 {
        return 0.0;
    }
    let b = m.dot(n);
    let disc = b * b - c;
    if disc < 0.0 {
        return f64::INFINITY;
    }
    let t = -b - disc.sqrt();
    if t >= 0.0 { t } else { f64::INFINITY }
}

/// Iterations fitting an interval between paths to the side steps allowed.
const FIT_ITERATIONS: usize = 40;
/// A fitted interval uses the allowed side step to within this fraction (below).
const FIT_SLACK: f64 = 1e-4;

/// The interval between two paths, fitted from the first-order guess `start` so that
/// `ratio(interval)` (the largest distance across the paths over the side step allowed
/// there, over all samples) is at most 1 and within [`FIT_SLACK`] of it: scaled by
/// `1 / ratio` (the distance is nearly proportional to the interval), bisected inside
/// the bracket once one is known. Returns the largest interval seen with a ratio of
/// at most 1 (or 0 when nothing is measured: `ratio` returns 0).
pub fn fit_interval(start: f64, ratio: impl Fn(f64) -> f64) -> f64 {
    let (mut good, mut bad) = (0.0f64, f64::INFINITY);
    let mut ds = start;
    for _ in 0..FIT_ITERATIONS {
        let r = ratio(ds);
        if r.is_nan() {
            bad = bad.min(ds);
        } else if r <= 1.0 {
            good = good.max(ds);
            if r > 1.0 - FIT_SLACK || r <= 0.0 {
                return ds;
            }
        } else {
            bad = bad.min(ds);
        }
        let scaled = if r.is_finite() && r > 0.0 {
            ds / if r > 1.0 {
                r * (1.0 + 0.5 * FIT_SLACK)
            } else {
                r
            }
        } else {
            0.5 * ds
        };
        ds = if scaled > good && scaled < bad {
            scaled
        } else if bad.is_finite() {
            0.5 * (good + bad)
        } else {
            scaled
        };
    }
    if good > 0.0 { good } else { ds }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fitted_interval_meets_the_limit_from_either_side() {
        // Distance across grows like d + d^3 / 10; allowed 1.
        let ratio = |d: f64| d + d * d * d / 10.0;
        for start in [0.1, 0.9, 1.0, 3.0, 100.0] {
            let d = fit_interval(start, ratio);
            let r = ratio(d);
            assert!(
                r <= 1.0 && r > 1.0 - 2.0 * FIT_SLACK,
                "start {start}: {d} -> {r}"
            );
        }
        // Nothing measured: the start is kept.
        assert_eq!(fit_interval(2.0, |_| 0.0), 2.0);
        // A ratio that jumps above the limit past 0.5 (a ridge): stays below it.
        let d = fit_interval(1.0, |d| if d > 0.5 { 3.0 } else { d });
        assert!(d <= 0.5 && d > 0.49, "{d}");
    }
}
