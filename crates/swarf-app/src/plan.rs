//! Planning a job: its strategy's parameters from the job file, the strategy run on
//! the part (or on its tessellation, for the raster), the clearance plane above the
//! planned path, and the pass bound of the iso strategies.

use crate::job::Job;
use swarf_geom::{Part, TriMesh};
use swarf_path::pass_bound::{Feed, PassBound, pass_bound};
use swarf_path::side_step::SideStep;
use swarf_path::{PathError, Plan, StrategyKind};

/// What a job plans on.
#[derive(Debug, Clone, Copy)]
pub enum PlanInput<'a> {
    /// Parametric patches (all strategies; raster runs on their tessellation).
    Part(&'a Part),
    /// A triangle mesh (raster only).
    Mesh(&'a TriMesh),
}

/// The pass bound of an iso job on `part` (empty for raster, or without a usable
/// scallop height: the strategy has already rejected those).
fn bound_for(job: &Job, part: &Part) -> Vec<PassBound> {
    let feed = match job.strategy.kind {
        StrategyKind::Raster
        | StrategyKind::Cleanup
        | StrategyKind::Waterline
        | StrategyKind::SteepShallow
        | StrategyKind::DropSpin
        | StrategyKind::Roughing => return Vec::new(),
        StrategyKind::IsoParametric | StrategyKind::IsoScallop => Feed::Param(job.param_dir()),
        StrategyKind::IsoPlanar => Feed::Plane(job.angle_rad()),
    };
    match job.strategy.scallop.map(|h| SideStep::new(&job.tool, h)) {
        Some(Ok(side)) => pass_bound(part, &side, feed),
        _ => Vec::new(),
    }
}

/// Z-level roughing of `mesh` from a box over its XY extent, its top at the job's
/// `stock_top` (default 1 mm above the part).
fn roughing(job: &Job, mesh: &TriMesh) -> Result<Plan, PathError> {
    let b = mesh.aabb();
    let top = job.strategy.stock_top.unwrap_or(b.max.z + 1.0);
    let (min, max) = ([b.min.x, b.min.y], [b.max.x, b.max.y]);
    let material = move |x: f64, y: f64| {
        if x >= min[0] && x <= max[0] && y >= min[1] && y <= max[1] {
            top
        } else {
            f64::NEG_INFINITY
        }
    };
    let stock = swarf_path::roughing::RoughingStock {
        min,
        max,
        top,
        material: &material,
    };
    Ok(swarf_path::roughing::plan(mesh, &stock, &job.roughing_params())?.0)
}

/// The job's lead arcs and ramps ([`swarf_path::leads`]) on every pass of a
/// finishing plan, gouge-checked by drops on the part (tessellated for a
/// parametric part); roughing enters by its own ramps.
fn add_job_leads(job: &Job, input: PlanInput<'_>, plan: &mut Plan) -> Result<(), PathError> {
    let l = &job.linking;
    let leads = swarf_path::leads::Leads {
        arc_radius: l.lead_radius,
        ramp_angle: l.ramp_angle.map(f64::to_radians),
        ramp_height: l.approach,
    };
    if !leads.any() || job.strategy.kind == StrategyKind::Roughing {
        return leads.check();
    }
    let tessellated;
    let mesh = match input {
        PlanInput::Mesh(mesh) => mesh,
        PlanInput::Part(part) => {
            tessellated = part.tessellate(job.strategy.tolerance * 0.1)?;
            &tessellated
        }
    };
    let dropper = swarf_tool::drop::MeshDropper::new(mesh, &job.tool);
    swarf_path::leads::add_leads(&mut plan.toolpath.passes, &dropper, &leads)?;
    let top = swarf_toolpath::top_z(&plan.toolpath.passes);
    plan.toolpath.linking = job.linking.for_top(top);
    Ok(())
}

/// Plans `job` on `input`.
///
/// # Errors
/// [`PathError::NoPath`] when a strategy cannot make any pass (or an iso strategy is
/// given a mesh), [`PathError::InvalidParameter`] for parameters the strategy cannot use.
pub fn plan(job: &Job, input: PlanInput<'_>) -> Result<Plan, PathError> {
    let start = std::time::Instant::now();
    let mut plan = match (job.strategy.kind, input) {
        (StrategyKind::Raster, PlanInput::Mesh(mesh)) => {
            swarf_path::raster::plan(mesh, &job.raster_params())?
        }
        (StrategyKind::Raster, PlanInput::Part(part)) => {
            let mesh = part.tessellate(job.strategy.tolerance * 0.1)?;
            swarf_path::raster::plan(&mesh, &job.raster_params())?
        }
        (StrategyKind::Waterline, PlanInput::Mesh(mesh)) => {
            swarf_path::waterline::plan(mesh, &job.waterline_params())?
        }
        (StrategyKind::Waterline, PlanInput::Part(part)) => {
            let mesh = part.tessellate(job.strategy.tolerance * 0.1)?;
            swarf_path::waterline::plan(&mesh, &job.waterline_params())?
        }
        (StrategyKind::SteepShallow, PlanInput::Mesh(mesh)) => {
            swarf_path::steep_shallow::plan(mesh, &job.steep_shallow_params())?
        }
        (StrategyKind::SteepShallow, PlanInput::Part(part)) => {
            let mesh = part.tessellate(job.strategy.tolerance * 0.1)?;
            swarf_path::steep_shallow::plan(&mesh, &job.steep_shallow_params())?
        }
        (StrategyKind::Roughing, PlanInput::Mesh(mesh)) => roughing(job, mesh)?,
        (StrategyKind::Roughing, PlanInput::Part(part)) => {
            roughing(job, &part.tessellate(job.strategy.tolerance * 0.1)?)?
        }
        (StrategyKind::Cleanup, _) => {
            return Err(PathError::NoPath(
                "a cleanup job is planned with its parent (swarf plan, crate::cleanup)".into(),
            ));
        }
        (StrategyKind::DropSpin, _) => {
            return Err(PathError::NoPath(
                "a drop-spin job is planned by swarf-fiveaxis (swarf plan, crate::drop_spin)"
                    .into(),
            ));
        }
        (kind, PlanInput::Mesh(_)) => {
            return Err(PathError::NoPath(format!(
                "strategy {kind:?} plans on parametric patches; a mesh part needs strategy \"raster\", \"waterline\" or \"steep-shallow\""
            )));
        }
        (StrategyKind::IsoParametric, PlanInput::Part(part)) => {
            swarf_path::iso_parametric::plan(part, &job.iso_params())?
        }
        (StrategyKind::IsoPlanar, PlanInput::Part(part)) => {
            swarf_path::iso_planar::plan(part, &job.iso_params())?
        }
        (StrategyKind::IsoScallop, PlanInput::Part(part)) => {
            swarf_path::iso_scallop::plan(part, &job.iso_params())?
        }
    };
    add_job_leads(job, input, &mut plan)?;
    plan.report.lifted_points = plan.toolpath.lifted_count();
    if let PlanInput::Part(part) = input {
        plan.report.pass_bound = bound_for(job, part);
    }
    plan.report.elapsed_s = start.elapsed().as_secs_f64();
    Ok(plan)
}
