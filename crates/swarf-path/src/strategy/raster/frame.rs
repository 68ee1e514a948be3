//! Raster pass geometry: feed and side directions, the side offsets of the passes in
//! cutting order, and each pass's line clipped to the region (see [`crate::strategy::raster`]).

use crate::error::PathError;
use crate::params::StartSide;
use crate::stepping::raster_step::stepover_for_scallop;
use crate::stepping::slope_step::{check_slope, raster_spacing};
use crate::strategy::raster::RasterParams;
use crate::strategy::raster::pass::{Line, PassOut, Sampler};
use rayon::prelude::*;
use swarf_geom::TriMesh;
use swarf_tool::Cutter;
use swarf_tool::drop::DropScratch;

/// A given boundary is widened by this (relative to its largest coordinate) so that
/// passes on its edges survive rounding.
pub const BOUNDARY_SLACK: f64 = 1e-12;

/// Pass geometry: directions, side offsets in cutting order, extents along the feed.
pub(crate) struct Frame {
    d: [f64; 2],
    n: [f64; 2],
    /// Side offsets of the passes (`p . n`), in cutting order.
    pub(crate) offsets: Vec<f64>,
    /// The even side step, mm.
    pub(crate) spacing: f64,
    /// Range of `p . d` the passes may cover (before the boundary).
    along: [f64; 2],
    boundary: Option<[f64; 4]>,
}

impl Frame {
    /// The frame of `job`'s passes over `mesh` (see [`crate::strategy::raster`]).
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] for a stepover wider than the tool, a
    /// scallop the tool cannot leave or a slope limit outside `(0, pi/2)`.
    pub(crate) fn new(
        mesh: &TriMesh,
        tool: &Cutter,
        params: &RasterParams,
    ) -> Result<Frame, PathError> {
        let (sa, ca) = params.angle.sin_cos();
        let (d, n) = ([ca, sa], [-sa, ca]);
        let radius = tool.radius();
        if let Some(slope) = params.max_slope {
            check_slope("max_slope", slope)?;
        }
        let stepover = match (params.stepover, params.scallop) {
            (Some(s), _) => s,
            (None, Some(h)) => match params.max_slope {
                Some(slope) => raster_spacing(tool, h, slope)?,
                None => stepover_for_scallop(tool, h)?,
            },
            (None, None) => {
                return Err(PathError::InvalidParameter {
                    field: "strategy".into(),
                    message: "expected `scallop` (mm) or `stepover` (mm)".into(),
                });
            }
        };
        if !(stepover.is_finite() && stepover > 0.0 && stepover <= 2.0 * radius) {
            return Err(PathError::InvalidParameter {
                field: "stepover".into(),
                message: format!(
                    "{} mm: expected a stepover > 0 and at most the tool diameter {} mm",
                    swarf_geom::domain::show(stepover),
                    2.0 * radius
                ),
            });
        }
        let dot = |v: [f64; 2], x: f64, y: f64| v[0] * x + v[1] * y;
        let range = |v: [f64; 2]| -> [f64; 2] {
            let pts: Vec<[f64; 2]> = match params.boundary {
                Some(b) => vec![[b[0], b[1]], [b[2], b[1]], [b[2], b[3]], [b[0], b[3]]],
                None => finite_xy(mesh),
            };
            pts.iter().fold([f64::INFINITY, f64::NEG_INFINITY], |r, p| {
                let x = dot(v, p[0], p[1]);
                [r[0].min(x), r[1].max(x)]
            })
        };
        let side = range(n);
        let mesh_along = {
            let pts = finite_xy(mesh);
            pts.iter().fold([f64::INFINITY, f64::NEG_INFINITY], |r, p| {
                let x = dot(d, p[0], p[1]);
                [r[0].min(x), r[1].max(x)]
            })
        };
        let width = (side[1] - side[0]).max(0.0);
        let limit = range(d);
        let length = (mesh_along[1] - mesh_along[0]).min(limit[1] - limit[0]);
        check_work(width / stepover, length.max(0.0) + 2.0 * radius, radius)?;
        let k = (width / stepover).ceil().max(1.0) as usize;
        let spacing = if width > 0.0 {
            width / k as f64
        } else {
            stepover
        };
        let mut offsets: Vec<f64> = (0..=k)
            .map(|i| side[0] + width * i as f64 / k as f64)
            .collect();
        if params.start == StartSide::Max {
            offsets.reverse();
        }
        Ok(Frame {
            d,
            n,
            offsets,
            spacing,
            along: [mesh_along[0] - radius, mesh_along[1] + radius],
            boundary: params.boundary,
        })
    }

    /// Every row sampled by `sampler`, in parallel, collected in cutting order.
    pub(crate) fn rows(&self, sampler: &Sampler<'_>) -> Vec<PassOut> {
        self.offsets
            .par_iter()
            .map_init(DropScratch::default, |s, &c| match self.line(c) {
                Some(line) => sampler.run(&line, s),
                None => PassOut::default(),
            })
            .collect()
    }

    /// The pass line at side offset `c`, clipped to the boundary (`None` when the
    /// line misses it). The boundary is widened by [`BOUNDARY_SLACK`] (relative) so
    /// that a pass on its edge survives the rounding of `c`.
    pub(crate) fn line(&self, c: f64) -> Option<Line> {
        let origin = [c * self.n[0], c * self.n[1]];
        let [mut t0, mut t1] = self.along;
        if let Some(b) = self.boundary {
            let slack = BOUNDARY_SLACK * (1.0 + b.iter().fold(0.0f64, |m, v| m.max(v.abs())));
            for axis in 0..2 {
                let (lo, hi) = (b[axis] - slack, b[axis + 2] + slack);
                let (o, v) = (origin[axis], self.d[axis]);
                if v.abs() < 1e-12 {
                    if o < lo || o > hi {
                        return None;
                    }
                } else {
                    let (a, e) = ((lo - o) / v, (hi - o) / v);
                    t0 = t0.max(a.min(e));
                    t1 = t1.min(a.max(e));
                }
            }
        }
        (t0 <= t1).then_some(Line {
            origin,
            dir: self.d,
            t0,
            t1,
        })
    }
}

/// XY of the vertices of the finite triangles.
/// Most first drops of one raster (passes times drops along each, before
/// refinement): about 3 GB of samples and contacts.
pub const MAX_RASTER_DROPS: f64 = 5e7;

/// Refuses a raster of `passes` passes `length` mm long with a tool of `radius` mm
/// when its first drops would exceed [`MAX_RASTER_DROPS`], before any is allocated.
fn check_work(passes: f64, length: f64, radius: f64) -> Result<(), PathError> {
    let per_pass = length / (crate::strategy::raster::INIT_STEP_RADII * radius) + 1.0;
    let drops = (passes + 1.0) * per_pass;
    if drops <= MAX_RASTER_DROPS {
        return Ok(());
    }
    Err(PathError::InvalidParameter {
        field: "stepover".into(),
        message: format!(
            "{} passes of {} drops over a {} mm long part need {} drops, more than the \
             limit of {MAX_RASTER_DROPS:e}: expected a larger stepover or scallop, a \
             boundary, or a larger tool",
            swarf_geom::domain::show(passes.ceil() + 1.0),
            swarf_geom::domain::show(per_pass.ceil()),
            swarf_geom::domain::show(length),
            swarf_geom::domain::show(drops),
        ),
    })
}

fn finite_xy(mesh: &TriMesh) -> Vec<[f64; 2]> {
    (0..mesh.len())
        .filter(|&t| mesh.usable(t))
        .flat_map(|t| {
            mesh.triangles[t].map(|k| [mesh.vertices[k as usize].x, mesh.vertices[k as usize].y])
        })
        .collect()
}
