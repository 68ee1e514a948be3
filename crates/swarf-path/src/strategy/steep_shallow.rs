//! Steep-and-shallow finishing: a raster on the shallow areas, waterline passes on
//! the steep ones, with an overlap band between them (thesis 002 ch. 6: §6.1 the
//! classification, §6.2.1 finishing horizontal areas, §6.2.2 Z-slicing of steep
//! areas with trimming).
//!
//! The part is classified ([`crate::classify`]) with the steep angle `theta_s`. A
//! raster with XY spacing `s` leaves the scallop of passes `s / cos(theta)` apart on
//! a slope `theta` across it, and Z-levels `dz` apart leave that of passes
//! `dz / sin(theta)` apart: with both spacings from [`crate::stepping::slope_step`] for
//! `theta_s` (a ball's `2 cos(theta_s) sqrt(2Rh - h^2)` and
//! `2 sin(theta_s) sqrt(2Rh - h^2)`), the raster keeps the scallop within `h` on
//! every slope up to `theta_s` and the levels on every slope from `theta_s` up, so
//! the whole part is covered within `h`.
//!
//! Trimming is by contact: a raster point stays where its CC point is outside the
//! steep cells shrunk by the overlap, a waterline point where its CC point is inside
//! the steep cells grown by the overlap (cells of the classification's Go board,
//! grown and shrunk by whole cells, at least the overlap). Passes are split where
//! points are dropped; the waterline pieces are cut first, level by level from the
//! top, then the raster, whose lines reach a tool radius past the mesh so that the
//! cutter reaches edges the surface falls toward. A part without steep cells gets the raster alone, one
//! without shallow cells the levels alone.

use crate::classify::{ClassGrid, ClassifyParams, SurfaceClass, classify};
use crate::error::PathError;
use crate::params::{
    Cutting, Finish, StartSide, check_angle, check_open_angle, check_scallop, in_domain,
};
use crate::plan::{Plan, PlanReport};
use crate::strategy::raster::RasterParams;
use crate::strategy::waterline::{Milling, WaterlineParams};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use swarf_geom::TriMesh;
use swarf_geom::domain::{ALLOWANCE, SAMPLE, SCALLOP};
use swarf_tool::Cutter;
use swarf_toolpath::{Pass, PathPoint};

/// Parameters of steep-and-shallow finishing.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SteepShallowParams {
    /// Tolerance and zigzag.
    #[serde(flatten)]
    pub finish: Finish,
    /// Scallop limit everywhere, mm: both spacings follow from it (required).
    #[schemars(extend("unit" = "mm", "domain" = format!("{SCALLOP}, below the tool radius")))]
    pub scallop: Option<f64>,
    /// Slope from horizontal above which an area is steep, degrees.
    #[serde(with = "swarf_geom::units::serde_degrees")]
    #[schemars(with = "f64", extend("unit" = "degrees", "domain" = "(flat_angle, 90)"))]
    pub steep_angle: f64,
    /// Slope below which an area is horizontal, degrees (classification only).
    #[serde(with = "swarf_geom::units::serde_degrees")]
    #[schemars(with = "f64", extend("unit" = "degrees", "domain" = "(0, steep_angle)"))]
    pub flat_angle: f64,
    /// Width of the band both strategies cut, mm.
    #[schemars(extend("unit" = "mm", "domain" = ALLOWANCE.to_string()))]
    pub overlap: f64,
    /// Raster feed direction in the XY plane, degrees from +X.
    #[serde(with = "swarf_geom::units::serde_degrees")]
    #[schemars(with = "f64", extend("unit" = "degrees"))]
    pub angle: f64,
    /// Milling direction of the waterline loops.
    pub direction: Milling,
    /// Go-board cell and waterline drop-field step, mm (default: a quarter of the
    /// tool radius).
    #[schemars(extend("unit" = "mm", "domain" = SAMPLE.to_string()))]
    pub sampling: Option<f64>,
}

impl Default for SteepShallowParams {
    /// No scallop yet; steep above 40 and horizontal below 15 degrees, a 1 mm
    /// overlap, raster along +X, climb milling.
    fn default() -> Self {
        SteepShallowParams {
            finish: Finish::default(),
            scallop: None,
            steep_angle: 40f64.to_radians(),
            flat_angle: 15f64.to_radians(),
            overlap: 1.0,
            angle: 0.0,
            direction: Milling::Climb,
            sampling: None,
        }
    }
}

impl SteepShallowParams {
    /// Scallop `h` (mm) and the defaults.
    pub fn new(h: f64) -> SteepShallowParams {
        SteepShallowParams {
            scallop: Some(h),
            ..SteepShallowParams::default()
        }
    }

    /// Checks the parameters for `tool`.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] naming the field: a tolerance, scallop,
    /// angle, overlap or sampling out of range; no scallop; a flat angle not below
    /// the steep angle.
    pub fn validate(&self, tool: &Cutter) -> Result<(), PathError> {
        self.finish.validate()?;
        check_scallop(self.scallop, tool)?;
        if self.scallop.is_none() {
            return Err(PathError::InvalidParameter {
                field: "scallop".into(),
                message: "steep-shallow needs the scallop height limit, mm (both spacings follow from it)".into(),
            });
        }
        check_angle(self.angle)?;
        in_domain("sampling", self.sampling, SAMPLE)?;
        in_domain("overlap", Some(self.overlap), ALLOWANCE)?;
        check_open_angle("steep_angle", Some(self.steep_angle), "an angle")?;
        check_open_angle("flat_angle", Some(self.flat_angle), "an angle")?;
        if self.flat_angle >= self.steep_angle {
            return Err(PathError::InvalidParameter {
                field: "steep_angle".into(),
                message: format!(
                    "{} degrees is not above flat_angle ({} degrees): expected flat_angle < steep_angle",
                    swarf_geom::units::shown_degrees(self.steep_angle),
                    swarf_geom::units::shown_degrees(self.flat_angle)
                ),
            });
        }
        Ok(())
    }
}

/// Steep cells of the Go board, grown or shrunk by whole cells.
struct Zone {
    grid: ClassGrid,
    steep: Vec<bool>,
}

impl Zone {
    /// The steep cells of `grid` grown (`k > 0`) or shrunk (`k < 0`) by `|k|` cells.
    fn new(grid: &ClassGrid, k: i64) -> Zone {
        let base: Vec<bool> = grid
            .classes
            .iter()
            .map(|c| *c == Some(SurfaceClass::Steep))
            .collect();
        // A square window is a row window then a column window.
        let rows = window(&base, grid.nx, grid.ny, k, [1, grid.nx]);
        let steep = window(&rows, grid.nx, grid.ny, k, [grid.nx, 1]);
        Zone {
            grid: grid.clone(),
            steep,
        }
    }

    fn contains(&self, p: &PathPoint) -> bool {
        let Some(c) = p.contact else {
            return false;
        };
        let g = &self.grid;
        let i = ((c.point.x - g.origin[0]) / g.cell).floor();
        let j = ((c.point.y - g.origin[1]) / g.cell).floor();
        if !(i >= 0.0 && j >= 0.0 && i < g.nx as f64 && j < g.ny as f64) {
            return false;
        }
        self.steep[j as usize * g.nx + i as usize]
    }
}

/// Each cell of the `nx` x `ny` board `cells` (row-major) set to whether any
/// (`k > 0`) or every (`k < 0`) cell within `|k|` of it along one axis is set; `stride`
/// is `[step along the axis, step across it]` in cell indices (`[1, nx]` along x).
/// Cells past the board count as unset.
fn window(cells: &[bool], nx: usize, ny: usize, k: i64, stride: [usize; 2]) -> Vec<bool> {
    let (len, lines) = if stride[0] == 1 { (nx, ny) } else { (ny, nx) };
    let r = k.unsigned_abs() as usize;
    let mut out = vec![false; cells.len()];
    for line in 0..lines {
        let at = |t: usize| cells[t * stride[0] + line * stride[1]];
        for t in 0..len {
            let (lo, hi) = (t.saturating_sub(r), t + r);
            out[t * stride[0] + line * stride[1]] = if k > 0 {
                (lo..=hi.min(len - 1)).any(at)
            } else {
                t >= r && hi < len && (lo..=hi).all(at)
            };
        }
    }
    out
}

/// The runs of `passes` whose points `keep` holds (runs of one point dropped).
fn trim(passes: Vec<Pass>, keep: impl Fn(&PathPoint) -> bool) -> Vec<Pass> {
    let mut out = Vec::new();
    for pass in passes {
        let mut run: Vec<PathPoint> = Vec::new();
        let n = pass.points.len();
        // A closed loop is rotated to start at a dropped point, so no run wraps.
        let closed = n > 2 && pass.points[0].pose == pass.points[n - 1].pose;
        let start = if closed {
            pass.points.iter().position(|p| !keep(p)).unwrap_or(0)
        } else {
            0
        };
        let order: Vec<&PathPoint> = if closed && start > 0 {
            pass.points[start..n - 1]
                .iter()
                .chain(&pass.points[..=start])
                .collect()
        } else {
            pass.points.iter().collect()
        };
        for p in order {
            if keep(p) {
                run.push(*p);
            } else if !run.is_empty() {
                push_run(&mut out, std::mem::take(&mut run));
            }
        }
        push_run(&mut out, run);
    }
    out
}

fn push_run(out: &mut Vec<Pass>, points: Vec<PathPoint>) {
    if points.len() > 1 {
        out.push(Pass {
            points,
            ..Pass::default()
        });
    }
}

/// The waterline passes of `wl` over `mesh` kept where their contacts lie in the
/// steep cells of `grid` grown by `overlap` (mm; module doc), and the range of
/// Z-level side steps they were spaced by.
///
/// # Errors
/// As [`crate::strategy::waterline::plan`].
pub fn steep_levels(
    mesh: &TriMesh,
    grid: &ClassGrid,
    cutting: &Cutting,
    wl: &WaterlineParams,
    overlap: f64,
) -> Result<(Vec<Pass>, Option<[f64; 2]>), PathError> {
    let grown = Zone::new(grid, (overlap / grid.cell).ceil() as i64);
    let levels = crate::strategy::waterline::plan(mesh, cutting, wl)?;
    Ok((
        trim(levels.toolpath.passes, |p| grown.contains(p)),
        levels.report.side_step_range,
    ))
}

/// Plans steep-and-shallow finishing over `mesh` (module doc).
///
/// # Units
/// mm, radians.
///
/// # Errors
/// [`PathError::InvalidParameter`] for a scallop outside `(0, tool radius)`, angles
/// out of range or a flat angle not below the steep angle, a negative overlap, and
/// as [`crate::classify::classify`], [`crate::strategy::raster::plan`] and
/// [`crate::strategy::waterline::plan`]; [`PathError::NoPath`] where neither makes a pass.
pub fn plan(
    mesh: &TriMesh,
    cutting: &Cutting,
    params: &SteepShallowParams,
) -> Result<Plan, PathError> {
    let tool = &cutting.tool;
    let Some(scallop) = params.scallop else {
        return Err(PathError::InvalidParameter {
            field: "scallop".into(),
            message: "steep-shallow needs the scallop height limit, mm".into(),
        });
    };
    if !(params.overlap.is_finite() && params.overlap >= 0.0) {
        return Err(PathError::InvalidParameter {
            field: "overlap".into(),
            message: format!(
                "expected a length of 0 mm or more, found {}",
                params.overlap
            ),
        });
    }
    let cell = params.sampling.unwrap_or(0.25 * tool.radius());
    let classes = classify(
        mesh,
        &ClassifyParams {
            steep_angle: params.steep_angle,
            flat_angle: params.flat_angle,
            cell,
            feed_angle: None,
        },
    )?;
    let shrunk = Zone::new(&classes.grid, -((params.overlap / cell).ceil() as i64));
    let mut passes = Vec::new();
    let mut steps = Vec::new();
    if classes.steep.cells > 0 {
        let wl = WaterlineParams {
            steep_angle: params.steep_angle,
            flat_angle: params.flat_angle,
            adaptive: false,
            sampling: Some(cell),
            direction: params.direction,
            finish: params.finish,
            ..WaterlineParams::new(scallop)
        };
        let (levels, range) = steep_levels(mesh, &classes.grid, cutting, &wl, params.overlap)?;
        passes.extend(levels);
        steps.extend(range.into_iter().flatten());
    }
    // Lines out to a tool radius past the mesh, so that the cutter reaches the
    // part's edges where the surface falls toward them.
    let b = mesh.aabb();
    let r = tool.radius();
    let raster = RasterParams {
        scallop: Some(scallop),
        stepover: None,
        max_slope: Some(params.steep_angle),
        angle: params.angle,
        start: StartSide::Min,
        boundary: Some([b.min.x - r, b.min.y - r, b.max.x + r, b.max.y + r]),
        finish: params.finish,
        ..RasterParams::default()
    };
    let rows = crate::strategy::raster::plan(mesh, cutting, &raster)?;
    steps.extend(rows.report.side_step_range.into_iter().flatten());
    let double_contacts = rows.double_contacts;
    passes.extend(trim(rows.toolpath.passes, |p| !shrunk.contains(p)));
    if passes.is_empty() {
        return Err(PathError::NoPath(
            "steep-shallow: neither the raster nor the levels touch the part".into(),
        ));
    }
    let report = PlanReport {
        predicted_max_scallop: Some(scallop),
        side_step_range: PlanReport::step_range(&steps),
        ..PlanReport::default()
    };
    Ok(Plan::from_passes(passes, cutting, report, double_contacts))
}
