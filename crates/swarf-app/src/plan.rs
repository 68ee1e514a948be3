//! Planning a job: its strategy run on the part (or on its tessellation, for the
//! strategies that plan on meshes: [`crate::strategy`]), its leads, and the
//! clearance plane above the planned path. The passes are cut to where the tool may
//! go ([`swarf_toolpath::reach`]: above the floor, within reach of the stock)
//! before the leads are added. The strategies' errors name fields
//! inside their table; here they are placed in it (`strategy.scallop`,
//! `linking.lead_radius`).

use crate::job::Job;
use crate::strategy::place;
use swarf_geom::{Part, TriMesh};
use swarf_path::{PathError, Plan};
use swarf_toolpath::reach::Reach;

/// What a job plans on.
#[derive(Debug, Clone, Copy)]
pub enum PlanInput<'a> {
    /// Parametric patches (all strategies; those that plan on meshes run on their
    /// tessellation).
    Part(&'a Part),
    /// A triangle mesh (the strategies that plan on meshes).
    Mesh(&'a TriMesh),
}

/// `e` with its field placed in `table`.
pub fn in_table(table: &str, e: PathError) -> PathError {
    match e {
        PathError::InvalidParameter { field, message } => PathError::InvalidParameter {
            field: place(table, &field),
            message,
        },
        other => other,
    }
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
    if !leads.any() || !job.strategy.leads() {
        return leads.check();
    }
    let tessellated;
    let mesh = match input {
        PlanInput::Mesh(mesh) => mesh,
        PlanInput::Part(part) => {
            tessellated = part.tessellate(job.tolerance() * 0.1)?;
            &tessellated
        }
    };
    let dropper = swarf_tool::drop::MeshDropper::new(mesh, &job.tool);
    swarf_path::leads::add_leads(&mut plan.toolpath.passes, &dropper, &leads)?;
    let top = swarf_toolpath::top_z(&plan.toolpath.passes);
    plan.toolpath.linking = job.cutting().linking_for(top);
    Ok(())
}

/// `plan`'s passes cut to where `job`'s tool may go ([`Job::reach`]), with what was
/// cut in its report; nothing to do before the job is on its stock, nor for a
/// five-axis job before it is positioned (its vertical tips are not where the
/// positioned tool goes: [`crate::five_axis::position_plan`] cuts the positioned
/// passes to the floor).
///
/// # Errors
/// [`PathError::NoPath`] when no pass is left.
pub fn clip_to_reach(job: &Job, plan: &mut Plan) -> Result<(), PathError> {
    let (Some(reach), None) = (&job.reach, &job.positioning) else {
        return Ok(());
    };
    clip_plan(job, reach, plan).map(|_| ())
}

/// `plan`'s passes of `job`'s tool cut to `reach` ([`swarf_toolpath::reach`]), with
/// what was cut added to its report; whether any pose was cut.
///
/// # Errors
/// [`PathError::NoPath`] when no pass is left.
pub fn clip_plan(job: &Job, reach: &Reach, plan: &mut Plan) -> Result<bool, PathError> {
    if plan.toolpath.passes.is_empty() {
        return Ok(false);
    }
    let passes = std::mem::take(&mut plan.toolpath.passes);
    let (passes, clipped) = swarf_toolpath::reach::clip(passes, reach, &job.tool.profile());
    if passes.is_empty() {
        return Err(PathError::NoPath(format!(
            "every pass lies below stock.floor ({:.3} mm) or out of the tool's reach of the \
             stock",
            reach.floor
        )));
    }
    plan.toolpath.passes = passes;
    plan.report.clipped_points += clipped.points;
    plan.report.split_passes += clipped.splits;
    Ok(clipped.points > 0)
}

/// Plans `job` on `input`.
///
/// # Errors
/// [`PathError::NoPath`] when a strategy cannot make any pass (or an iso strategy is
/// given a mesh), [`PathError::InvalidParameter`] for parameters the strategy cannot
/// use, naming the field as the job does.
pub fn plan(job: &Job, input: PlanInput<'_>) -> Result<Plan, PathError> {
    let start = std::time::Instant::now();
    let mut plan = job
        .strategy
        .plan(&job.cutting(), input)
        .map_err(|e| in_table("strategy", e))?;
    clip_to_reach(job, &mut plan)?;
    add_job_leads(job, input, &mut plan).map_err(|e| in_table("linking", e))?;
    plan.report.lifted_points = plan.toolpath.lifted_count();
    plan.report.elapsed_s = start.elapsed().as_secs_f64();
    Ok(plan)
}
