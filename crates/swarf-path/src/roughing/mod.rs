//! Z-level roughing: the stock cleared level by level down to the part plus an
//! allowance, each level by rings that grow outwards one stepover at a time.
//!
//! At a level `z` the tool tip may stand where the cutter's drop height onto the part
//! is at most `z - allowance` (thesis 002 §6.2.2, the Z-slice of the tool offset
//! surface; the waterline contour of [`crate::waterline`], exact to its tolerance).
//! Ring `k` is the boundary of that region offset inwards by `k s` (polygon buffers;
//! the offset of the tool-centre region by `d` is the region of the cutter widened
//! by `d`). The rings are cut from the innermost outwards (`regions.rs`), so each
//! removes a band one stepover `s` wide: on a straight stretch the cutter's
//! engagement angle is `acos(1 - s / R)` (R the cutter radius). The tool enters a
//! level at each innermost ring by ramping down along that ring's own loop at the
//! ramp angle (a helix when the ring is round), from the level above, which was
//! cleared (the allowed region only shrinks downwards).
//!
//! The stock bounds the work: a skirt of vertical walls one clearance outside the
//! stock's XY box joins the part, so every level is a closed pocket and the rings
//! stop at the stock's side; a ring that passes no material (the in-process stock,
//! [`RoughingStock::material`], is lower than the level within the tool's reach) is
//! not cut, which makes rest roughing of an already roughed stock the same
//! operation. Levels are `step_down` apart from the stock's top, with one more level
//! on every flat of the part (its height plus the allowance), so no floor keeps more
//! than the allowance.
//!
//! Rings of plain offset roughing have sharp corners where the pocket has (the
//! offset of a corner is a corner), and a tool turning one meets far more material
//! than on a straight stretch. Adaptive roughing rounds them and steps over less, so
//! that the engagement holds in right-angled corners too (`corners.rs`); the
//! engagement measured on the simulated stock (swarf-sim's `engagement`) checks it.

mod corners;
mod levels;
mod regions;

use crate::error::PathError;
use crate::params::Finish;
use crate::plan::{Plan, PlanReport};
use crate::waterline::{Milling, Waterline, WaterlineParams};
use regions::{Region, Ring, cutting_order, link_parents};
use swarf_geom::{Point3, TriMesh};
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Pass, PathPoint};

/// Most rings one level may need.
pub const MAX_RINGS: usize = 2_000;
/// Gap between the stock's side and the skirt that bounds the tool, mm.
pub const SKIRT_GAP: f64 = 1.0;
/// Points closer than this are one, mm.
const SAME_POINT: f64 = 1e-9;
/// How far ahead (in tool radii) the step to the next ring lands.
pub const LINK_LEAD: f64 = 2.0;
/// Material higher than the level by less than this is not cut, mm.
pub const MATERIAL_EPS: f64 = 1e-6;

/// Z-level roughing parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughingParams {
    /// Cutter (flat, bull or ball end), chord tolerance of the rings, feeds, linking.
    pub finish: Finish,
    /// Material left on the part, mm (>= 0).
    pub allowance: f64,
    /// Largest depth of one level, mm (> 0).
    pub step_down: f64,
    /// Largest radial engagement angle on a straight stretch, radians (0 to 90
    /// degrees); sets the stepover `R (1 - cos)`.
    pub max_engagement: f64,
    /// Ramp angle of the entry, radians (0 to 45 degrees).
    pub ramp_angle: f64,
    /// Drop-field grid step, mm (default: a quarter of the tool radius).
    pub sampling: Option<f64>,
    /// Round the inner rings' corners and step over so that the engagement holds
    /// in right-angled corners too (`corners.rs`); false: plain offset rings, sharp
    /// corners, the straight-stretch stepover.
    pub adaptive: bool,
    /// Radius the inner rings' corners are rounded to, mm (default: the tool
    /// radius).
    pub corner_radius: Option<f64>,
}

impl RoughingParams {
    /// 0.5 mm allowance, 2 mm levels, 60 degrees of engagement, a 3 degree ramp.
    pub fn new(finish: Finish) -> RoughingParams {
        RoughingParams {
            finish,
            allowance: 0.5,
            step_down: 2.0,
            max_engagement: 60f64.to_radians(),
            ramp_angle: 3f64.to_radians(),
            sampling: None,
            adaptive: true,
            corner_radius: None,
        }
    }

    /// The radius the inner rings' corners are rounded to, mm.
    pub fn rho(&self) -> f64 {
        self.corner_radius.unwrap_or(self.finish.tool.radius())
    }

    /// The stepover from the largest engagement, mm: on straight stretches for
    /// plain offset rings, in right-angled rounded corners for adaptive ones.
    pub fn stepover(&self) -> f64 {
        let r = self.finish.tool.radius();
        if self.adaptive {
            corners::stepover(self.rho(), r, self.max_engagement)
        } else {
            r * (1.0 - self.max_engagement.cos())
        }
    }
}

/// The stock to rough: its XY box, its top, and the height of material at a point.
pub struct RoughingStock<'a> {
    /// Lower XY corner of the stock's box, mm.
    pub min: [f64; 2],
    /// Upper XY corner, mm.
    pub max: [f64; 2],
    /// Highest point of the stock, mm.
    pub top: f64,
    /// Top of the material at `(x, y)`, mm (`-inf` where there is none).
    pub material: &'a (dyn Fn(f64, f64) -> f64 + Sync),
}

/// Figures of a roughing plan.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RoughingReport {
    /// Tip heights of the levels, from the top, mm.
    pub levels: Vec<f64>,
    /// Rings cut (over all levels).
    pub rings: usize,
    /// Entries (ramps into a level, each ending with one round at the level): the
    /// index of the pass each begins, and how many of the pass's first points it
    /// takes.
    pub entries: Vec<(usize, usize)>,
    /// Stepover, mm.
    pub stepover: f64,
}

/// Plans Z-level roughing of `stock` down to `mesh` plus the allowance (module doc).
///
/// # Units
/// mm, radians.
///
/// # Errors
/// [`PathError::InvalidParameter`] naming the field for a parameter outside its
/// domain or a cutter that is not a flat, bull or ball end; [`PathError::NoPath`]
/// when no level has material to cut.
pub fn plan(
    mesh: &TriMesh,
    stock: &RoughingStock<'_>,
    params: &RoughingParams,
) -> Result<(Plan, RoughingReport), PathError> {
    check(params, stock)?;
    let skirted = skirted(mesh, stock, params.finish.tool.radius());
    let levels = levels::levels(mesh, stock.top, params.allowance, params.step_down)?;
    let s = params.stepover();
    let rings = Rings::new(&skirted, params, s)?;
    let mut report = RoughingReport {
        levels: levels.clone(),
        stepover: s,
        ..RoughingReport::default()
    };
    let mut passes: Vec<Pass> = Vec::new();
    let mut above = stock.top;
    for &z in &levels {
        let regions = rings.level(z)?;
        cut_level(&regions, z, above, stock, params, &mut passes, &mut report);
        above = z;
    }
    if passes.is_empty() {
        return Err(PathError::NoPath(format!(
            "roughing: no level between {:.3} and {:.3} mm has material to cut",
            levels.last().copied().unwrap_or(stock.top),
            stock.top
        )));
    }
    let plan_report = PlanReport {
        side_step_range: Some([s, s]),
        ..PlanReport::default()
    };
    Ok((
        Plan::from_passes(passes, &params.finish, plan_report, Vec::new()),
        report,
    ))
}

/// Which of `moves` (a roughing plan's [`swarf_toolpath::Toolpath::moves`]) belong
/// to the entries of `report`: the ramps and their round at the level, slots by
/// design, whose engagement is not the clearing's.
pub fn entry_moves(moves: &[swarf_toolpath::Move], report: &RoughingReport) -> Vec<bool> {
    let mut seen = std::collections::BTreeMap::new();
    moves
        .iter()
        .map(|m| {
            m.pass.is_some_and(|p| {
                let i = seen.entry(p).or_insert(0usize);
                *i += 1;
                report.entries.iter().any(|&(q, n)| q == p && *i < n)
            })
        })
        .collect()
}

fn check(params: &RoughingParams, stock: &RoughingStock<'_>) -> Result<(), PathError> {
    let bad = |field: &str, message: String| PathError::InvalidParameter {
        field: field.into(),
        message,
    };
    if !matches!(
        params.finish.tool,
        Cutter::Flat { .. } | Cutter::Ball { .. } | Cutter::Bull { .. }
    ) {
        return Err(bad(
            "tool",
            format!(
                "{}: roughing needs a flat, bull or ball end mill",
                params.finish.tool
            ),
        ));
    }
    if !(params.allowance.is_finite() && params.allowance >= 0.0 && params.allowance <= 100.0) {
        return Err(bad(
            "strategy.allowance",
            format!("{} mm: expected 0 to 100 mm", params.allowance),
        ));
    }
    if !(params.step_down.is_finite() && params.step_down > 0.0 && params.step_down <= 1000.0) {
        return Err(bad(
            "strategy.step_down",
            format!(
                "{} mm: expected more than 0, at most 1000 mm",
                params.step_down
            ),
        ));
    }
    let deg = crate::params::degrees;
    if !(params.max_engagement >= 1f64.to_radians()
        && params.max_engagement <= std::f64::consts::FRAC_PI_2)
    {
        return Err(bad(
            "strategy.max_engagement",
            format!(
                "{} degrees: expected 1 to 90 degrees",
                deg(params.max_engagement)
            ),
        ));
    }
    let r = params.finish.tool.radius();
    if let Some(rho) = params.corner_radius
        && !(rho >= 0.05 * r && rho <= 100.0 * r)
    {
        return Err(bad(
            "strategy.corner_radius",
            format!(
                "{rho} mm: expected 0.05 to 100 tool radii ({} to {} mm)",
                0.05 * r,
                100.0 * r
            ),
        ));
    }
    if !(params.ramp_angle >= 0.1f64.to_radians() && params.ramp_angle <= 45f64.to_radians()) {
        return Err(bad(
            "strategy.ramp_angle",
            format!(
                "{} degrees: expected 0.1 to 45 degrees",
                deg(params.ramp_angle)
            ),
        ));
    }
    let ok = stock.min.iter().chain(&stock.max).all(|v| v.is_finite())
        && stock.min[0] < stock.max[0]
        && stock.min[1] < stock.max[1]
        && stock.top.is_finite();
    if !ok {
        return Err(bad(
            "stock",
            "expected a finite box with min below max".into(),
        ));
    }
    Ok(())
}

/// The part with four vertical walls [`SKIRT_GAP`] plus the tool radius outside the
/// stock's box, from below the part to above the stock.
fn skirted(mesh: &TriMesh, stock: &RoughingStock<'_>, radius: f64) -> TriMesh {
    let g = SKIRT_GAP + radius;
    let (x0, y0, x1, y1) = (
        stock.min[0] - g,
        stock.min[1] - g,
        stock.max[0] + g,
        stock.max[1] + g,
    );
    let lo = mesh.aabb().min.z.min(stock.top) - 1.0;
    let hi = stock.top + 1.0;
    let corners = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    let mut walls = Vec::with_capacity(8);
    for k in 0..4 {
        let (a, b) = (corners[k], corners[(k + 1) % 4]);
        let p = |c: [f64; 2], z: f64| Point3::new(c[0], c[1], z);
        walls.push([p(a, lo), p(b, lo), p(b, hi)]);
        walls.push([p(a, lo), p(b, hi), p(a, hi)]);
    }
    let mut out = mesh.clone();
    out.append(&TriMesh::from_triangles(&walls));
    out
}

/// The level contours of the cutter over the skirted part, and the rings in them.
struct Rings<'a> {
    params: &'a RoughingParams,
    stepover: f64,
    waterline: Waterline<'a>,
}

impl<'a> Rings<'a> {
    fn new(
        mesh: &'a TriMesh,
        params: &'a RoughingParams,
        stepover: f64,
    ) -> Result<Rings<'a>, PathError> {
        let mut wp = WaterlineParams::new(params.finish.clone(), 0.1);
        wp.sampling = params.sampling;
        Ok(Rings {
            params,
            stepover,
            waterline: Waterline::new(mesh, &wp)?,
        })
    }

    /// Every ring's regions at tip height `z`, parents linked.
    fn level(&self, z: f64) -> Result<Vec<Region>, PathError> {
        let loops = self
            .waterline
            .level(z - self.params.allowance, Milling::Climb)
            .loops;
        let loops: Vec<Ring> = loops
            .iter()
            .map(|lp| lp.iter().map(|p| [p.pose.cl.x, p.pose.cl.y]).collect())
            .collect();
        let a0 = regions::allowed(loops);
        let rho = self.params.adaptive.then(|| self.params.rho());
        let mut all: Vec<Region> = Vec::new();
        let mut first_of = Vec::new();
        for k in 0..=MAX_RINGS {
            if k == MAX_RINGS {
                return Err(PathError::InvalidParameter {
                    field: "strategy.max_engagement".into(),
                    message: format!(
                        "a stepover of {:.4} mm needs more than {MAX_RINGS} rings on a level: \
                         expected a larger engagement",
                        self.stepover
                    ),
                });
            }
            first_of.push(all.len());
            let found = regions::ring_regions(&a0, k, self.stepover * k as f64, rho);
            if found.is_empty() {
                break;
            }
            all.extend(found);
        }
        first_of.push(all.len());
        link_parents(&mut all, &first_of);
        Ok(all)
    }
}

/// Cuts one level's regions in order (module doc of [`regions`]), appending passes.
fn cut_level(
    regions: &[Region],
    z: f64,
    above: f64,
    stock: &RoughingStock<'_>,
    params: &RoughingParams,
    passes: &mut Vec<Pass>,
    report: &mut RoughingReport,
) {
    let radius = params.finish.tool.radius();
    let mut current: Option<Vec<[f64; 3]>> = None;
    let mut last_cut: Option<usize> = None;
    for (i, fresh) in cutting_order(regions) {
        let region = &regions[i];
        let live: Vec<&Ring> = region
            .loops
            .iter()
            .filter(|lp| touches_material(lp, z, radius, stock))
            .collect();
        if live.is_empty() {
            continue;
        }
        let from_child = last_cut.is_some_and(|c| regions[c].parent == Some(i));
        last_cut = Some(i);
        let fresh_entry = fresh || !from_child || current.is_none();
        if fresh_entry {
            if let Some(pts) = current.take() {
                passes.push(pass_of(&pts));
            }
            let mut pts = Vec::new();
            ramp_entry(live[0], above, z, params.ramp_angle, &mut pts);
            report.entries.push((passes.len(), pts.len()));
            current = Some(pts);
        }
        let entered = fresh_entry;
        let pts = current.get_or_insert_with(Vec::new);
        for lp in live.into_iter().skip(usize::from(entered)) {
            let start = nearest(lp, link_aim(pts, radius));
            pts.extend(
                lp[start..]
                    .iter()
                    .chain(&lp[..=start])
                    .map(|p| [p[0], p[1], z]),
            );
            report.rings += 1;
        }
    }
    if let Some(pts) = current {
        passes.push(pass_of(&pts));
    }
}

/// Where the next ring starts: nearest the point [`LINK_LEAD`] radii ahead of the
/// tool along its last move, so that the step out to the next ring runs forwards
/// at a slant rather than square into the band.
fn link_aim(pts: &[[f64; 3]], radius: f64) -> [f64; 2] {
    let n = pts.len();
    let Some(&last) = pts.last() else {
        return [0.0, 0.0];
    };
    let before = pts[..n - 1]
        .iter()
        .rev()
        .find(|p| (p[0] - last[0]).hypot(p[1] - last[1]) > 1e-9);
    let Some(b) = before else {
        return [last[0], last[1]];
    };
    let len = (last[0] - b[0]).hypot(last[1] - b[1]);
    let k = LINK_LEAD * radius / len;
    [
        last[0] + k * (last[0] - b[0]),
        last[1] + k * (last[1] - b[1]),
    ]
}

/// Whether material stands above `z` within the tool's reach of some point of `lp`
/// (checked at the loop's points and at eight points round each, at half and all of
/// the radius).
fn touches_material(lp: &Ring, z: f64, radius: f64, stock: &RoughingStock<'_>) -> bool {
    let level = z + MATERIAL_EPS;
    lp.iter().any(|p| {
        (stock.material)(p[0], p[1]) > level
            || (0..16).any(|k| {
                let a = std::f64::consts::TAU * (k % 8) as f64 / 8.0;
                let r = if k < 8 { 0.5 } else { 0.98 } * radius;
                (stock.material)(p[0] + r * a.cos(), p[1] + r * a.sin()) > level
            })
    })
}

/// The ramp into a level along `lp`: from `above` down to `z` at `angle` from the
/// horizontal, going round the loop as often as it takes, then once more round it
/// at the level.
fn ramp_entry(lp: &Ring, above: f64, z: f64, angle: f64, pts: &mut Vec<[f64; 3]>) {
    let slope = angle.tan();
    let n = lp.len();
    let mut h = above.max(z);
    let push = |p: [f64; 3], pts: &mut Vec<[f64; 3]>| {
        let same = pts.last().is_some_and(|q: &[f64; 3]| {
            (q[0] - p[0]).hypot(q[1] - p[1]).hypot(q[2] - p[2]) < SAME_POINT
        });
        if !same {
            pts.push(p);
        }
    };
    push([lp[0][0], lp[0][1], h], pts);
    let length: f64 = (0..n).map(|i| dist(lp[i], lp[(i + 1) % n])).sum();
    if length < 1e-6 {
        push([lp[0][0], lp[0][1], z], pts);
        return;
    }
    let mut i = 0;
    while h > z {
        let (a, b) = (lp[i % n], lp[(i + 1) % n]);
        let drop = dist(a, b) * slope;
        if h - drop <= z {
            let t = (h - z) / drop;
            let reach = [a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), z];
            push(reach, pts);
            // One whole round at the level, back to where the ramp reached it: the
            // last round of the ramp left a wedge above the level all the way.
            let j = i % n;
            for p in lp[j + 1..].iter().chain(&lp[..=j]) {
                push([p[0], p[1], z], pts);
            }
            push(reach, pts);
            return;
        }
        h -= drop;
        push([b[0], b[1], h], pts);
        i += 1;
    }
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

/// Index of the point of `lp` nearest `q`.
fn nearest(lp: &[[f64; 2]], q: [f64; 2]) -> usize {
    lp.iter()
        .enumerate()
        .map(|(i, p)| (i, dist(*p, q)))
        .min_by(|a, b| a.1.total_cmp(&b.1).then(a.0.cmp(&b.0)))
        .map_or(0, |(i, _)| i)
}

fn pass_of(pts: &[[f64; 3]]) -> Pass {
    let mut points: Vec<PathPoint> = Vec::with_capacity(pts.len());
    for p in pts {
        if let Some(last) = points.last()
            && (last.pose.cl - Point3::new(p[0], p[1], p[2])).norm() < SAME_POINT
        {
            continue;
        }
        points.push(PathPoint::new(Pose::vertical(Point3::new(
            p[0], p[1], p[2],
        ))));
    }
    Pass {
        points,
        ..Pass::default()
    }
}
