//! Steep-and-shallow finishing: a raster on the shallow areas, waterline passes on
//! the steep ones, with an overlap band between them (thesis 002 ch. 6: §6.1 the
//! classification, §6.2.1 finishing horizontal areas, §6.2.2 Z-slicing of steep
//! areas with trimming).
//!
//! The part is classified ([`crate::classify`]) with the steep angle `theta_s`. A
//! raster with XY spacing `s` leaves the scallop of passes `s / cos(theta)` apart on
//! a slope `theta` across it, and Z-levels `dz` apart leave that of passes
//! `dz / sin(theta)` apart: with both spacings from [`crate::slope_step`] for
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
use crate::params::{Finish, RasterParams, StartSide};
use crate::plan::{Plan, PlanReport};
use crate::slope_step::{raster_spacing, zlevel_spacing};
use crate::waterline::{Milling, WaterlineParams};
use swarf_geom::TriMesh;
use swarf_toolpath::{Pass, PathPoint};

/// Parameters of steep-and-shallow finishing.
#[derive(Debug, Clone, PartialEq)]
pub struct SteepShallowParams {
    /// Cutter, tolerance, feeds, linking.
    pub finish: Finish,
    /// Scallop limit everywhere, mm.
    pub scallop: f64,
    /// Slope from horizontal above which an area is steep, radians.
    pub steep_angle: f64,
    /// Slope below which an area is horizontal, radians (classification only).
    pub flat_angle: f64,
    /// Width of the band both strategies cut, mm.
    pub overlap: f64,
    /// Raster feed direction in the XY plane from +X, radians.
    pub angle: f64,
    /// Milling direction of the waterline loops.
    pub direction: Milling,
    /// Go-board cell and waterline drop-field step, mm (default: a quarter of the
    /// tool radius).
    pub sampling: Option<f64>,
}

impl SteepShallowParams {
    /// Scallop `h` (mm), steep above 40 and horizontal below 15 degrees, a 1 mm
    /// overlap, raster along +X, climb milling.
    pub fn new(finish: Finish, h: f64) -> SteepShallowParams {
        SteepShallowParams {
            finish,
            scallop: h,
            steep_angle: 40f64.to_radians(),
            flat_angle: 15f64.to_radians(),
            overlap: 1.0,
            angle: 0.0,
            direction: Milling::Climb,
            sampling: None,
        }
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
        let (nx, ny) = (grid.nx as i64, grid.ny as i64);
        let r = k.abs();
        let grow = k > 0;
        let steep = (0..nx * ny)
            .map(|c| {
                let (i, j) = (c % nx, c / nx);
                let mut any = false;
                let mut all = true;
                for dj in -r..=r {
                    for di in -r..=r {
                        let (a, b) = (i + di, j + dj);
                        let v = a >= 0 && b >= 0 && a < nx && b < ny && base[(b * nx + a) as usize];
                        any |= v;
                        all &= v;
                    }
                }
                if grow { any } else { all }
            })
            .collect();
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

/// Plans steep-and-shallow finishing over `mesh` (module doc).
///
/// # Units
/// mm, radians.
///
/// # Errors
/// [`PathError::InvalidParameter`] for a scallop outside `(0, tool radius)`, angles
/// out of range or a flat angle not below the steep angle, a negative overlap, and
/// as [`crate::classify::classify`], [`crate::raster::plan`] and
/// [`crate::waterline::plan`]; [`PathError::NoPath`] where neither makes a pass.
pub fn plan(mesh: &TriMesh, params: &SteepShallowParams) -> Result<Plan, PathError> {
    let tool = &params.finish.tool;
    if !(params.overlap.is_finite() && params.overlap >= 0.0) {
        return Err(PathError::InvalidParameter {
            field: "strategy.overlap".into(),
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
        },
    )?;
    let k = (params.overlap / cell).ceil() as i64;
    let (grown, shrunk) = (Zone::new(&classes.grid, k), Zone::new(&classes.grid, -k));
    let step = raster_spacing(tool, params.scallop, params.steep_angle)?;
    let dz = zlevel_spacing(tool, params.scallop, params.steep_angle)?;
    let mut passes = Vec::new();
    if classes.steep.cells > 0 {
        let wl = WaterlineParams {
            level_step: Some(dz),
            steep_angle: params.steep_angle,
            flat_angle: params.flat_angle,
            adaptive: false,
            sampling: Some(cell),
            direction: params.direction,
            ..WaterlineParams::new(params.finish.clone(), params.scallop)
        };
        let levels = crate::waterline::plan(mesh, &wl)?;
        passes.extend(trim(levels.toolpath.passes, |p| grown.contains(p)));
    }
    // Lines out to a tool radius past the mesh, so that the cutter reaches the
    // part's edges where the surface falls toward them.
    let b = mesh.aabb();
    let r = tool.radius();
    let raster = RasterParams {
        angle: params.angle,
        start: StartSide::Min,
        boundary: Some([b.min.x - r, b.min.y - r, b.max.x + r, b.max.y + r]),
        ..RasterParams::new(params.finish.clone(), step)
    };
    let rows = crate::raster::plan(mesh, &raster)?;
    let double_contacts = rows.double_contacts;
    passes.extend(trim(rows.toolpath.passes, |p| !shrunk.contains(p)));
    if passes.is_empty() {
        return Err(PathError::NoPath(
            "steep-shallow: neither the raster nor the levels touch the part".into(),
        ));
    }
    let report = PlanReport {
        predicted_max_scallop: Some(params.scallop),
        side_step_range: Some([dz.min(step), dz.max(step)]),
        ..PlanReport::default()
    };
    Ok(Plan::from_passes(
        passes,
        &params.finish,
        report,
        double_contacts,
    ))
}
