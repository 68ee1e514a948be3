//! Planning entry point: runs a job's strategy on a part or a mesh.

use crate::error::PathError;
use crate::job::{Job, StrategyKind};
use crate::pass_bound::{Feed, PassBound, pass_bound};
use crate::side_step::SideStep;
use serde::{Deserialize, Serialize};
use swarf_geom::{Part, Point3, TriMesh};
use swarf_toolpath::Toolpath;

/// What a job plans on.
#[derive(Debug, Clone, Copy)]
pub enum PlanInput<'a> {
    /// Parametric patches (all strategies; raster runs on their tessellation).
    Part(&'a Part),
    /// A triangle mesh (raster only).
    Mesh(&'a TriMesh),
}

/// A region a strategy could not cover, and why.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Uncovered {
    /// Where: e.g. `patch 0, u in [0.2, 0.3], v in [0.9, 1.0]` or an XY box.
    pub region: String,
    /// Why it was left.
    pub reason: String,
}

/// A place where the cutter touches the part at two or more separated points at once
/// (a valley it cannot enter; thesis 002 §5.1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct DoubleContact {
    /// The CL point (tool tip) of the pose.
    pub cl: Point3,
    /// The separated contact points.
    pub contacts: Vec<Point3>,
}

/// Figures a strategy reports beside its tool path.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct PlanReport {
    /// Largest scallop height the strategy predicts from its own geometry, mm.
    pub predicted_max_scallop: Option<f64>,
    /// Smallest and largest side step used, mm.
    pub side_step_range: Option<[f64; 2]>,
    /// Number of CL points the gouge check lifted, and the largest lift, mm.
    pub lifted_points: usize,
    /// Largest lift applied by the gouge check, mm.
    pub max_lift: f64,
    /// Regions left uncovered, with reasons.
    pub uncovered: Vec<Uncovered>,
    /// Iso strategies: per patch, the least number of full-length passes any pass
    /// family along the job's feed direction needs at its scallop height, and the
    /// column that needs them ([`crate::pass_bound`]).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub pass_bound: Vec<PassBound>,
    /// Planning wall time, s (not part of deterministic outputs).
    #[serde(skip)]
    pub elapsed_s: f64,
}

/// A planned job: the tool path and what the strategy reports about it.
#[derive(Debug, Clone, PartialEq)]
pub struct Plan {
    /// The tool path.
    pub toolpath: Toolpath,
    /// The strategy's figures.
    pub report: PlanReport,
    /// Double contacts found while planning (raster strategy).
    pub double_contacts: Vec<DoubleContact>,
}

impl Plan {
    /// Double contacts as CSV (`x,y,z,cx,cy,cz` per contact point; the CL point
    /// repeated for each of its contacts), or `None` when the strategy records none.
    pub fn double_contacts_csv(&self) -> Option<String> {
        if self.double_contacts.is_empty() {
            return None;
        }
        let mut s = String::from("x,y,z,cx,cy,cz\n");
        for d in &self.double_contacts {
            for c in &d.contacts {
                s += &format!(
                    "{:.6},{:.6},{:.6},{:.6},{:.6},{:.6}\n",
                    d.cl.x, d.cl.y, d.cl.z, c.x, c.y, c.z
                );
            }
        }
        Some(s)
    }
}

/// The pass bound of an iso job on `part` (empty for raster, or without a usable
/// scallop height: the strategy has already rejected those).
fn bound_for(job: &Job, part: &Part) -> Vec<PassBound> {
    let feed = match job.strategy.kind {
        StrategyKind::Raster => return Vec::new(),
        StrategyKind::IsoParametric | StrategyKind::IsoScallop => {
            Feed::Param(job.strategy.direction)
        }
        StrategyKind::IsoPlanar => Feed::Plane(job.angle_rad()),
    };
    match job.strategy.scallop.map(|h| SideStep::new(&job.tool, h)) {
        Some(Ok(side)) => pass_bound(part, &side, feed),
        _ => Vec::new(),
    }
}

/// Plans `job` on `input`.
///
/// # Errors
/// [`PathError::NoPath`] when a strategy cannot make any pass (or an iso strategy is
/// given a mesh), [`PathError::InvalidParameter`] for parameters the strategy cannot use.
pub fn plan(job: &Job, input: PlanInput<'_>) -> Result<Plan, PathError> {
    let start = std::time::Instant::now();
    let mut plan = match (job.strategy.kind, input) {
        (StrategyKind::Raster, PlanInput::Mesh(mesh)) => crate::raster::plan(mesh, job)?,
        (StrategyKind::Raster, PlanInput::Part(part)) => {
            let mesh = part.tessellate(job.strategy.tolerance * 0.1)?;
            crate::raster::plan(&mesh, job)?
        }
        (kind, PlanInput::Mesh(_)) => {
            return Err(PathError::NoPath(format!(
                "strategy {kind:?} plans on parametric patches; a mesh part needs strategy \"raster\""
            )));
        }
        (StrategyKind::IsoParametric, PlanInput::Part(part)) => {
            crate::iso_parametric::plan(part, job)?
        }
        (StrategyKind::IsoPlanar, PlanInput::Part(part)) => crate::iso_planar::plan(part, job)?,
        (StrategyKind::IsoScallop, PlanInput::Part(part)) => crate::iso_scallop::plan(part, job)?,
    };
    let top = plan
        .toolpath
        .passes
        .iter()
        .flat_map(|p| &p.points)
        .map(|p| p.pose.cl.z)
        .fold(f64::NEG_INFINITY, f64::max);
    if top.is_finite() {
        plan.toolpath.linking = job.linking_for(top);
    }
    plan.report.lifted_points = plan.toolpath.lifted_count();
    if let PlanInput::Part(part) = input {
        plan.report.pass_bound = bound_for(job, part);
    }
    plan.report.elapsed_s = start.elapsed().as_secs_f64();
    Ok(plan)
}
