//! Five-axis jobs: what [`crate::plan_job()`] does after the 3-axis plan of a job that
//! has a `positioning` table or an `output.machine` ([`crate::job`]).
//!
//! 1. **CC paths** of the plan ([`swarf_fiveaxis::cc_paths`]).
//! 2. **Positioning** ([`swarf_fiveaxis::positioning`]): the inclined tool or the
//!    gouge-free lead, with the sectioning gouge report. The positioned passes replace
//!    the 3-axis ones, in the same order and directions (zigzag kept), relinked above
//!    the tilted tool ([`swarf_fiveaxis::cc_paths::linking`]), after they are cut
//!    where the tool's lowest point would go below the floor
//!    ([`crate::plan::clip_plan`], the floor alone: a tilted tool reaches further
//!    than its radius from its tip, so the stock's footprint does not bound its
//!    tip); the sectioning check is then run again on what is left.
//! 3. **Holder avoidance** ([`avoid_holder`]) for a library tool: poses whose shank
//!    or holder meets the part are tilted clear.
//! 4. **Post** ([`write_job_gcode`]): the machine named by `output.machine`
//!    ([`load_machine`]: a file relative to the job file, or `builtin:NAME` for the
//!    machines shipped in `machines/`), G93 or G94, the tool length for machines with
//!    head axes, through [`post_5x`].
//!
//! The 3-axis plan's figures that describe the vertical tool (its lifts and predicted
//! scallop) are cleared from a positioned plan's report; the sectioning report says
//! what the tilted tool does.

use crate::error::Result;
use crate::holder::avoid::{Avoidance, Limits, avoid};
use crate::job::Job;
use crate::model::Model;
use swarf_fiveaxis::FiveAxisError;
use swarf_fiveaxis::cc_paths::{cc_paths, linking};
use swarf_fiveaxis::machine::{Machine, MachineKind};
use swarf_fiveaxis::positioning::spec::DEFAULT_MAX_RATE;
use swarf_fiveaxis::positioning::{
    Positioning, PositioningReport, position_with_progress, recheck,
};
use swarf_fiveaxis::post::{Post5x, PostOptions, post_5x};
use swarf_geom::Part;
use swarf_nc::Post;
use swarf_path::Plan;
use swarf_tool::holder::tilted::TiltSearch;
use swarf_toolpath::Toolpath;
use swarf_toolpath::reach::Reach;

#[cfg(doc)]
use swarf_fiveaxis::machine::load_machine;

/// Positions the planned passes of `plan` as `job.positioning` asks (module doc) and
/// relinks them; `None` (and `plan` untouched) for a job without positioning.
/// `progress(done, total)` counts passes.
///
/// # Errors
/// [`FiveAxisError::InvalidParameter`] when the plan has no CC path; the errors of
/// [`position_with_progress`] (a gouge-free lead that cannot be found names the pass,
/// the point and the CC point).
pub fn position_plan(
    job: &Job,
    part: &Part,
    plan: &mut Plan,
    progress: &dyn Fn(usize, usize),
) -> Result<Option<PositioningReport>, FiveAxisError> {
    let Some(positioning) = &job.positioning else {
        return Ok(None);
    };
    let cc = cc_paths(&plan.toolpath);
    if cc.is_empty() {
        return Err(FiveAxisError::parameter(
            "positioning",
            "the strategy gave no pass with two or more contact points to position",
        ));
    }
    let (passes, mut report) =
        position_with_progress(&job.tool, part, &cc, positioning, job.tolerance(), progress)?;
    plan.toolpath.passes = passes;
    if let Some(reach) = &job.reach {
        let floor = Reach {
            floor: reach.floor,
            footprint: None,
        };
        let clipped = crate::plan::clip_plan(job, &floor, plan)
            .map_err(|e| FiveAxisError::parameter("stock.floor", e.to_string()))?;
        if clipped {
            report.poses = plan.toolpath.passes.iter().map(|p| p.points.len()).sum();
            recheck(&job.tool, part, &plan.toolpath.passes, &mut report)?;
        }
    }
    plan.toolpath.linking = linking(&job.cutting(), part, &plan.toolpath.passes);
    plan.report.lifted_points = 0;
    plan.report.max_lift = 0.0;
    plan.report.predicted_max_scallop = None;
    Ok(Some(report))
}

/// Tilts the positioned passes of `plan` clear of the job's library tool's shank
/// and holder on the part's triangles ([`crate::holder::avoid`]) under the
/// positioning's limits (its `max_rate`, the default rate for an inclined tool; a
/// gouge-free lead's `max_alpha`), relinks them above the tilted tool and runs the
/// positioning's gouge check on them again (`report`). `None` (and `plan`
/// untouched) for a job without positioning or library tool, or when nothing was
/// tilted.
///
/// # Errors
/// The part's tessellation; as [`avoid`] and [`recheck`].
pub fn avoid_holder(
    job: &Job,
    model: &Model,
    plan: &mut Plan,
    report: Option<&mut PositioningReport>,
) -> crate::error::Result<Option<Avoidance>> {
    let (Model::Patches(part), Some(tool)) = (model, &job.library_tool) else {
        return Ok(None);
    };
    let limits = match job.positioning {
        None => return Ok(None),
        Some(Positioning::Inclined { .. }) => Limits {
            max_rate: DEFAULT_MAX_RATE.to_radians(),
            max_tilt: TiltSearch::default().max_tilt,
            max_lean: None,
        },
        Some(Positioning::GougeFree {
            max_alpha,
            max_rate,
            ..
        }) => Limits {
            max_rate: max_rate.to_radians(),
            max_tilt: TiltSearch::default().max_tilt,
            max_lean: Some(max_alpha.to_radians()),
        },
    };
    let mesh = model.triangles(job.tolerance())?;
    let avoided = avoid(&mesh, tool, &mut plan.toolpath, &limits)?;
    if avoided.is_some() {
        plan.toolpath.linking = linking(&job.cutting(), part, &plan.toolpath.passes);
        if let Some(r) = report {
            recheck(&job.tool, part, &plan.toolpath.passes, r)?;
        }
    }
    Ok(avoided)
}

/// The five-axis post options for `job` on `machine`, with header `comments`.
///
/// # Errors
/// [`FiveAxisError::InvalidParameter`] naming `output.tool_length` when a machine with
/// head axes has no tool length.
pub fn post_options(
    job: &Job,
    machine: &Machine,
    comments: Vec<String>,
) -> Result<PostOptions, FiveAxisError> {
    let tool_length = match (machine.kind, job.output.tool_length) {
        (_, Some(l)) => l,
        (MachineKind::TableTable, None) => 0.0,
        (kind, None) => {
            return Err(FiveAxisError::parameter(
                "output.tool_length",
                format!(
                    "machine {:?} ({kind:?}) turns the head: its kinematics need the tool length (spindle gauge line to tip, mm)",
                    machine.name
                ),
            ));
        }
    };
    Ok(PostOptions {
        units: job.output.units,
        comments,
        feed_mode: job.output.feed_mode,
        tool_length,
        path_tol: job.tolerance(),
        ..PostOptions::default()
    })
}

/// `toolpath` as five-axis G-code for `machine`, with the job's post options, and
/// what the post did (the rotary ranges among it).
///
/// # Errors
/// As [`post_options`] and [`post_5x`] (an unreachable pose names the pass, the
/// point and the axis).
pub fn write_job_gcode(
    job: &Job,
    machine: &Machine,
    post: &Post,
    toolpath: &Toolpath,
    comments: Vec<String>,
) -> Result<Post5x, FiveAxisError> {
    let opts = PostOptions {
        post: post.clone(),
        ..post_options(job, machine, comments)?
    };
    post_5x(machine, toolpath, &opts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;
    use swarf_fiveaxis::machine::load_machine;
    use swarf_fiveaxis::post::FeedMode;
    use swarf_geom::Vec3;

    /// The 3-axis gouge lift moves a pose's tip, not its contact: positioning gets
    /// the CC points as planned (a ball in the crease of the concave edge part, where
    /// it is lifted: tip = contact + r n - r z, raised by the lift).
    #[test]
    fn lifted_points_keep_their_contacts() {
        let part = swarf_io::builtin_part("edge-concave").unwrap();
        let job = Job::parse(
            "part = \"x\"\ntool = \"ball:d=16\"\n[strategy]\nkind = \"iso-planar\"\nstepover = 4\nangle = 90\n",
            "job.toml",
        )
        .unwrap();
        let plan = crate::plan::plan(&job, crate::plan::PlanInput::Part(&part)).unwrap();
        let lifted: Vec<_> = plan
            .toolpath
            .passes
            .iter()
            .flat_map(|p| &p.points)
            .filter(|p| p.lifted > 1e-3)
            .collect();
        assert!(lifted.len() > 5, "{}", lifted.len());
        for p in lifted {
            let c = p.contact.unwrap();
            let planned = c.point + 8.0 * c.normal - 8.0 * Vec3::z();
            let tip = p.pose.cl - p.lifted * Vec3::z();
            assert!((tip - planned).norm() < 1e-9, "{tip} vs {planned}");
            let on = part.patches[c.face].eval(c.uv[0], c.uv[1]);
            assert!((on - c.point).norm() < 1e-9);
        }
    }

    #[test]
    fn head_machines_need_a_tool_length() {
        let dir = Path::new(".");
        let job = Job::parse(
            "part = \"x\"\ntool = \"ball:d=8\"\n[strategy]\nkind = \"iso-planar\"\nscallop = 0.1\n",
            "job.toml",
        )
        .unwrap();
        let head = load_machine("builtin:xyzbc-head", dir).unwrap();
        let e = post_options(&job, &head, Vec::new())
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("output.tool_length"), "{e}");
        let trunnion = load_machine("builtin:xyzac-trunnion", dir).unwrap();
        let o = post_options(&job, &trunnion, Vec::new()).unwrap();
        assert_eq!(o.feed_mode, FeedMode::InverseTime);
    }
}
