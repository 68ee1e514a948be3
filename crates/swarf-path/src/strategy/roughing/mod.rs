//! Z-level roughing: the stock cleared level by level down to the part plus an
//! allowance, each level by rings that grow outwards one stepover at a time.
//!
//! At a level `z` the tool tip may stand where the cutter's drop height onto the part
//! is at most `z - allowance` (thesis 002 §6.2.2, the Z-slice of the tool offset
//! surface; the waterline contour of [`crate::strategy::waterline`], exact to its tolerance).
//! Ring `k` is the boundary of that region offset inwards by `d_k` (polygon buffers;
//! the offset of the tool-centre region by `d` is the region of the cutter widened
//! by `d`), `d_k` the sum of the stepovers of the rings outside it. The rings are
//! cut from the innermost outwards (`regions.rs`), so each removes a band one
//! stepover `s` wide: on a straight stretch the cutter's engagement angle is
//! `acos(1 - s / R)` (R the cutter radius). The tool enters a
//! level at each innermost ring by ramping down along that ring's own loop at the
//! ramp angle (a helix when the ring is round), from the level above, which was
//! cleared (the allowed region only shrinks downwards). So every pass starts clear
//! of material with nothing above it, and its link comes down to the approach above
//! its start ([`swarf_toolpath::Pass::clear_from`]), not above the stock.
//!
//! The stock bounds the work: a skirt of vertical walls one clearance outside the
//! stock's XY box joins the part, so every level is a closed pocket and the rings
//! stop at the stock's side; a ring that passes no material (the in-process stock,
//! [`RoughingStock::material`], is lower than the level within the tool's reach) is
//! not cut, and one that meets material in stretches only is cut in those, each a
//! pass that starts and ends clear of material (`material.rs`). That makes rest
//! roughing of an already roughed stock the same operation, cutting only where the
//! previous tool left material. Levels are `step_down` apart from the stock's top, with one more level
//! on every flat of the part (its height plus the allowance), so no floor keeps more
//! than the allowance.
//!
//! Rings of plain offset roughing have sharp corners where the pocket has (the
//! offset of a corner is a corner), and a tool turning one meets far more material
//! than on a straight stretch. Adaptive roughing rounds them and steps over less, so
//! that the engagement holds in right-angled corners too (`corners.rs`), each ring
//! with the stepover of its own corner radius. The step from a ring out to the
//! next is spread along the ring just cut ([`BLEND_SLOPE`]): a step straight
//! across the band would meet its whole width at once. The engagement measured on
//! the simulated stock (swarf-sim's `engagement`) checks it.

mod corners;
mod cut;
mod levels;
mod material;
mod moves;
mod regions;

use crate::error::PathError;
use crate::params::{Cutting, Finish};
use crate::plan::{Plan, PlanReport};
use crate::strategy::waterline::{Milling, Waterline, WaterlineParams};
use cut::cut_level;
use regions::{Region, Ring, link_parents};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use swarf_geom::domain::SAMPLE;
use swarf_geom::domain::show;
use swarf_geom::{Point3, TriMesh};
use swarf_tool::{Cutter, Pose};
use swarf_toolpath::{Pass, PathPoint};

/// Most rings one level may need.
pub const MAX_RINGS: usize = 2_000;
/// Gap between the stock's side and the skirt that bounds the tool, mm.
pub const SKIRT_GAP: f64 = 1.0;
/// Points closer than this are one, mm.
pub(crate) const SAME_POINT: f64 = 1e-9;
/// Slope of the step out to the next ring across the band (gap over length).
pub const BLEND_SLOPE: f64 = 0.125;
/// Points of that step (at least).
pub(crate) const BLEND_SAMPLES: usize = 16;
/// Material higher than the level by less than this is not cut, mm.
pub const MATERIAL_EPS: f64 = 1e-6;

/// Z-level roughing parameters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct RoughingParams {
    /// Chord tolerance of the rings (and zigzag, unused: rings are cut one way).
    #[serde(flatten)]
    pub finish: Finish,
    /// Material left on the part, mm.
    #[schemars(extend("unit" = "mm", "domain" = "0 to 100 mm"))]
    pub allowance: f64,
    /// Largest depth of one level, mm.
    #[schemars(extend("unit" = "mm", "domain" = "more than 0, at most 1000 mm"))]
    pub step_down: f64,
    /// Largest radial engagement angle on a straight stretch, degrees; sets the
    /// stepover `R (1 - cos)`.
    #[serde(with = "swarf_geom::units::serde_degrees")]
    #[schemars(with = "f64", extend("unit" = "degrees", "domain" = "1 to 90 degrees"))]
    pub max_engagement: f64,
    /// Ramp angle of the entries, degrees.
    #[serde(with = "swarf_geom::units::serde_degrees")]
    #[schemars(with = "f64", extend("unit" = "degrees", "domain" = "0.1 to 45 degrees"))]
    pub ramp_angle: f64,
    /// Drop-field grid step, mm (default: a quarter of the tool radius).
    #[schemars(extend("unit" = "mm", "domain" = SAMPLE.to_string()))]
    pub sampling: Option<f64>,
    /// Round the inner rings' corners and step over so that the engagement holds
    /// in right-angled corners too (`corners.rs`); false: plain offset rings, sharp
    /// corners, the straight-stretch stepover.
    pub adaptive: bool,
    /// Radius the inner rings' corners are rounded to, mm (default: the tool
    /// radius).
    #[schemars(extend("unit" = "mm", "domain" = "0.05 to 100 tool radii"))]
    pub corner_radius: Option<f64>,
}

impl Default for RoughingParams {
    /// 0.5 mm allowance, 2 mm levels, 60 degrees of engagement, a 3 degree ramp,
    /// adaptive rings.
    fn default() -> Self {
        RoughingParams {
            finish: Finish::default(),
            allowance: 0.5,
            step_down: 2.0,
            max_engagement: 60f64.to_radians(),
            ramp_angle: 3f64.to_radians(),
            sampling: None,
            adaptive: true,
            corner_radius: None,
        }
    }
}

impl RoughingParams {
    /// The radius the inner rings' corners are rounded to for a tool of `radius`,
    /// mm.
    pub fn rho(&self, radius: f64) -> f64 {
        self.corner_radius.unwrap_or(radius)
    }

    /// The stepover of a tool of `radius` from the largest engagement, mm: on
    /// straight stretches for plain offset rings; for adaptive ones, in
    /// right-angled corners rounded to `rho` (a ring's opening radius; `None`, a
    /// ring too narrow to open: the smallest radius tried).
    pub fn stepover(&self, radius: f64, rho: Option<f64>) -> f64 {
        let r = radius;
        if self.adaptive {
            let rho = rho.unwrap_or_else(|| corners::smallest(self.rho(r)));
            corners::stepover(rho, r, self.max_engagement)
        } else {
            r * (1.0 - self.max_engagement.cos())
        }
    }

    /// Checks the parameters for `tool`.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] naming the field: a parameter outside its
    /// domain, a cutter that is not a flat, bull or ball end.
    pub fn validate(&self, tool: &Cutter) -> Result<(), PathError> {
        self.finish.validate()?;
        crate::params::in_domain("sampling", self.sampling, SAMPLE)?;
        check_params(self, tool)
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
    /// Top of the material to remove at `(x, y)`, mm (`-inf` where there is none:
    /// no stock, or none above the part plus the allowance).
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
    /// Smallest and largest stepover of the rings, mm.
    pub stepover: [f64; 2],
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
    cutting: &Cutting,
    params: &RoughingParams,
) -> Result<(Plan, RoughingReport), PathError> {
    let tool = &cutting.tool;
    check(params, tool, stock)?;
    let radius = tool.radius();
    let skirted = skirted(mesh, stock, radius);
    let levels = levels::levels(mesh, stock.top, params.allowance, params.step_down)?;
    let rings = Rings::new(&skirted, tool, params)?;
    let mut report = RoughingReport {
        levels: levels.clone(),
        stepover: [f64::INFINITY, 0.0],
        ..RoughingReport::default()
    };
    let mut passes: Vec<Pass> = Vec::new();
    let mut above = stock.top;
    for &z in &levels {
        let regions = rings.level(z, &mut report.stepover)?;
        cut_level(
            &regions,
            z,
            above,
            stock,
            (radius, params.ramp_angle),
            &mut passes,
            &mut report,
        );
        above = z;
    }
    if passes.is_empty() {
        return Err(PathError::NoPath(format!(
            "roughing: no level between {:.3} and {:.3} mm has material to cut",
            levels.last().copied().unwrap_or(stock.top),
            stock.top
        )));
    }
    // Each pass starts clear of material, under levels already cleared (module doc).
    for p in &mut passes {
        p.clear_from = p.points.first().map(|q| q.pose.cl.z);
    }
    let plan_report = PlanReport {
        side_step_range: Some(report.stepover),
        ..PlanReport::default()
    };
    Ok((
        Plan::from_passes(passes, cutting, plan_report, Vec::new()),
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

fn check(
    params: &RoughingParams,
    tool: &Cutter,
    stock: &RoughingStock<'_>,
) -> Result<(), PathError> {
    check_params(params, tool)?;
    let ok = stock.min.iter().chain(&stock.max).all(|v| v.is_finite())
        && stock.min[0] < stock.max[0]
        && stock.min[1] < stock.max[1]
        && stock.top.is_finite();
    if !ok {
        return Err(PathError::InvalidParameter {
            field: "stock".into(),
            message: "expected a finite box with min below max".into(),
        });
    }
    Ok(())
}

/// The parameters' domains and the cutter's shape.
fn check_params(params: &RoughingParams, tool: &Cutter) -> Result<(), PathError> {
    let bad = |field: &str, message: String| PathError::InvalidParameter {
        field: field.into(),
        message,
    };
    if !matches!(
        tool,
        Cutter::Flat { .. } | Cutter::Ball { .. } | Cutter::Bull { .. }
    ) {
        return Err(bad(
            "tool",
            format!("{tool}: roughing needs a flat, bull or ball end mill"),
        ));
    }
    if !(params.allowance.is_finite() && params.allowance >= 0.0 && params.allowance <= 100.0) {
        return Err(bad(
            "allowance",
            format!("{} mm: expected 0 to 100 mm", show(params.allowance)),
        ));
    }
    if !(params.step_down.is_finite() && params.step_down > 0.0 && params.step_down <= 1000.0) {
        return Err(bad(
            "step_down",
            format!(
                "{} mm: expected more than 0, at most 1000 mm",
                show(params.step_down)
            ),
        ));
    }
    let deg = swarf_geom::units::shown_degrees;
    if !(params.max_engagement >= 1f64.to_radians()
        && params.max_engagement <= std::f64::consts::FRAC_PI_2)
    {
        return Err(bad(
            "max_engagement",
            format!(
                "{} degrees: expected 1 to 90 degrees",
                deg(params.max_engagement)
            ),
        ));
    }
    let r = tool.radius();
    if let Some(rho) = params.corner_radius
        && !(rho >= 0.05 * r && rho <= 100.0 * r)
    {
        return Err(bad(
            "corner_radius",
            format!(
                "{} mm: expected 0.05 to 100 tool radii ({} to {} mm)",
                show(rho),
                0.05 * r,
                100.0 * r
            ),
        ));
    }
    if !(params.ramp_angle >= 0.1f64.to_radians() && params.ramp_angle <= 45f64.to_radians()) {
        return Err(bad(
            "ramp_angle",
            format!(
                "{} degrees: expected 0.1 to 45 degrees",
                deg(params.ramp_angle)
            ),
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
    radius: f64,
    waterline: Waterline<'a>,
}

impl<'a> Rings<'a> {
    fn new(
        mesh: &'a TriMesh,
        tool: &Cutter,
        params: &'a RoughingParams,
    ) -> Result<Rings<'a>, PathError> {
        let wp = WaterlineParams {
            finish: params.finish,
            sampling: params.sampling,
            ..WaterlineParams::new(0.1)
        };
        Ok(Rings {
            params,
            radius: tool.radius(),
            waterline: Waterline::new(mesh, tool, &wp)?,
        })
    }

    /// Every ring's regions at tip height `z`, parents linked; `range` widened to
    /// the rings' stepovers.
    fn level(&self, z: f64, range: &mut [f64; 2]) -> Result<Vec<Region>, PathError> {
        let loops = self
            .waterline
            .level(z - self.params.allowance, Milling::Climb)
            .loops;
        let loops: Vec<Ring> = loops
            .iter()
            .map(|lp| lp.iter().map(|p| [p.pose.cl.x, p.pose.cl.y]).collect())
            .collect();
        let a0 = regions::allowed(loops);
        let radius = self.radius;
        let rho = self.params.adaptive.then(|| self.params.rho(radius));
        let mut all: Vec<Region> = Vec::new();
        let mut first_of = Vec::new();
        let (mut d, mut step) = (0.0, 0.0);
        let mut steps = Vec::new();
        for k in 0..=MAX_RINGS {
            if k == MAX_RINGS {
                return Err(PathError::InvalidParameter {
                    field: "max_engagement".into(),
                    message: format!(
                        "a stepover of {step:.4} mm needs more than {MAX_RINGS} rings on a \
                         level: expected a larger engagement"
                    ),
                });
            }
            let mut found = regions::ring_regions(&a0, k, d, rho);
            if let Some(rho) = rho
                && k > 0
            {
                let outer = &all[first_of[k - 1]..];
                let margin = corners::smallest(rho);
                found.retain(|g| g.rho.is_some() || !regions::covered(g, outer, radius, margin));
            }
            first_of.push(all.len());
            if found.is_empty() {
                break;
            }
            step = found
                .iter()
                .map(|g| self.params.stepover(radius, g.rho))
                .fold(f64::INFINITY, f64::min);
            steps.push(step);
            range[0] = range[0].min(step);
            range[1] = range[1].max(step);
            d += step;
            all.extend(found);
        }
        first_of.push(all.len());
        link_parents(&mut all, &first_of);
        regions::add_ridges(&mut all, &steps);
        Ok(all)
    }
}

pub(crate) fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

pub(crate) fn pass_of(pts: &[[f64; 3]]) -> Pass {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_parameters_name_their_field_and_read_as_given() {
        let material = |_: f64, _: f64| 10.0;
        let stock = RoughingStock {
            min: [0.0, 0.0],
            max: [10.0, 10.0],
            top: 10.0,
            material: &material,
        };
        let tool = Cutter::flat(10.0, None).unwrap();
        let params = RoughingParams::default();
        assert!(check(&params, &tool, &stock).is_ok());
        let message = |p: RoughingParams| check(&p, &tool, &stock).unwrap_err().to_string();
        let e = message(RoughingParams {
            step_down: 1e300,
            ..params
        });
        assert!(e.contains("step_down") && e.contains("1e300 mm"), "{e}");
        let e = message(RoughingParams {
            max_engagement: 95f64.to_radians(),
            ..params
        });
        assert!(
            e.contains("max_engagement") && e.contains("95 degrees"),
            "{e}"
        );
        let e = message(RoughingParams {
            corner_radius: Some(0.1),
            ..params
        });
        assert!(
            e.contains("corner_radius") && e.contains("0.25 to 500 mm"),
            "{e}"
        );
        let e = message(RoughingParams {
            ramp_angle: f64::NAN,
            ..params
        });
        assert!(e.contains("ramp_angle") && e.contains("NaN degrees"), "{e}");
        let flat = RoughingStock {
            max: [0.0, 10.0],
            ..stock
        };
        let e = check(&params, &tool, &flat).unwrap_err().to_string();
        assert!(e.contains("stock") && e.contains("min below max"), "{e}");
    }
}
