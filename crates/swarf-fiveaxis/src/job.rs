//! Five-axis jobs: what `swarf plan` does after the 3-axis plan of a job that has a
//! `positioning` table or an `output.machine` ([`swarf_path::job`]).
//!
//! 1. **CC paths.** The planned passes keep the contact each pose was planned from
//!    (the 3-axis gouge lift moves a pose's tip, never its contact). A point without
//!    a contact (a bridge across a gap between two pieces of a row, placed by a
//!    vertical drop) splits its pass there; runs of fewer than two contacts are
//!    dropped, as no feed direction can be taken from them ([`cc_paths`]). A contact
//!    within [`MIN_CC_GAP`] of the one before replaces it (section curves can end in
//!    two samples a few 1e-13 mm apart, whose chord gives no feed direction).
//! 2. **Positioning** ([`crate::positioning`]): the inclined tool or the gouge-free
//!    lead, with the sectioning gouge report. The positioned passes replace the
//!    3-axis ones, in the same order and directions (zigzag kept).
//! 3. **Linking** ([`linking`]). A tool tilted by `alpha` from `+z` reaches at most
//!    `R sin(alpha)` below its tip (`R` the largest cutting radius: every profile
//!    point has `z >= 0` and `rho <= R`). The part lies below the top of its control
//!    box (the patches are in the convex hull of their control points). Retracts and
//!    rapids carry the tool at the orientation of a pass end; with the tip at `top +
//!    max over pass ends of R sin(alpha)`, `top` the higher of the part's top and the
//!    highest tip, the whole tool is above the part. The job's clearance is raised to
//!    that height when below it; by default it is that height plus
//!    [`swarf_path::job::DEFAULT_CLEARANCE_MARGIN`].
//! 4. **Post** ([`write_job_gcode`]): the machine named by `output.machine`
//!    ([`load_machine`]: a file relative to the job file, or `builtin:NAME` for the
//!    machines shipped in `machines/`), G93 or G94, the tool length for machines with
//!    head axes, through [`write_gcode_5x`].
//!
//! The 3-axis plan's figures that describe the vertical tool (its lifts and predicted
//! scallop) are cleared from a positioned plan's report; the sectioning report says
//! what the tilted tool does.

use crate::error::FiveAxisError;
use crate::machine::{Machine, MachineKind};
use crate::positioning::{PositioningReport, position_with_progress};
use crate::post::{FeedMode, PostOptions, write_gcode_5x};
use std::path::Path;
use swarf_geom::Part;
use swarf_nc::{Dialect, Units};
use swarf_path::job::{OutputDialect, OutputFeedMode, OutputUnits};
use swarf_path::{Job, PathError, Plan, PlanInput};
use swarf_toolpath::{Contact, Linking, Pass, Toolpath};

/// The machine files shipped with swarf (`machines/*.toml`), by built-in name.
pub const BUILTIN_MACHINES: [(&str, &str); 3] = [
    (
        "xyzac-trunnion",
        include_str!("../../../machines/xyzac-trunnion.toml"),
    ),
    (
        "xyzbc-head",
        include_str!("../../../machines/xyzbc-head.toml"),
    ),
    (
        "xyzbc-table-head",
        include_str!("../../../machines/xyzbc-table-head.toml"),
    ),
];

/// Consecutive contacts closer than this are merged by [`cc_paths`], mm.
pub const MIN_CC_GAP: f64 = 1e-6;

/// The contacts of every pass of `toolpath`, split where a point has none (module
/// doc); runs of fewer than two contacts are left out.
pub fn cc_paths(toolpath: &Toolpath) -> Vec<Vec<Contact>> {
    let mut out = Vec::new();
    for pass in &toolpath.passes {
        let mut run: Vec<Contact> = Vec::new();
        for p in &pass.points {
            match p.contact {
                Some(c) => {
                    if let Some(last) = run.last_mut()
                        && (c.point - last.point).norm() < MIN_CC_GAP
                    {
                        *last = c;
                    } else {
                        run.push(c);
                    }
                }
                None => {
                    if run.len() > 1 {
                        out.push(std::mem::take(&mut run));
                    }
                    run.clear();
                }
            }
        }
        if run.len() > 1 {
            out.push(run);
        }
    }
    out
}

/// The CC paths of `job`'s 3-axis plan on `part` ([`cc_paths`] of its passes): what
/// [`position_plan`] positions, for callers that position them themselves.
///
/// # Errors
/// The planning errors of [`swarf_path::plan()`].
pub fn planned_cc_paths(job: &Job, part: &Part) -> Result<Vec<Vec<Contact>>, PathError> {
    let plan = swarf_path::plan(job, PlanInput::Part(part))?;
    Ok(cc_paths(&plan.toolpath))
}

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
    let (passes, report) = position_with_progress(
        &job.tool,
        part,
        &cc,
        positioning,
        job.strategy.tolerance,
        progress,
    )?;
    plan.toolpath.linking = linking(job, part, &passes);
    plan.toolpath.passes = passes;
    plan.report.lifted_points = 0;
    plan.report.max_lift = 0.0;
    plan.report.predicted_max_scallop = None;
    Ok(Some(report))
}

/// The linking of positioned `passes` on `part` (module doc).
pub fn linking(job: &Job, part: &Part, passes: &[Pass]) -> Linking {
    let r = job.tool.radius();
    let tips = passes
        .iter()
        .flat_map(|p| &p.points)
        .map(|p| p.pose.cl.z)
        .fold(f64::NEG_INFINITY, f64::max);
    let top = part.control_box().max.z.max(tips);
    let below = passes
        .iter()
        .flat_map(|p| [p.points.first(), p.points.last()])
        .flatten()
        .map(|p| r * (1.0 - p.pose.axis.z.clamp(-1.0, 1.0).powi(2)).sqrt())
        .fold(0.0, f64::max);
    job.linking_for(top + below)
}

/// The machine `spec` names: `builtin:NAME` (one of [`BUILTIN_MACHINES`]) or a
/// machine file, relative to `job_dir` unless absolute.
///
/// # Errors
/// [`FiveAxisError::Machine`] for an unknown built-in name, a file that cannot be
/// read, or a machine file that does not parse (with its line and field).
pub fn load_machine(spec: &str, job_dir: &Path) -> Result<Machine, FiveAxisError> {
    if let Some(name) = spec.strip_prefix("builtin:") {
        let name = name.strip_suffix(".toml").unwrap_or(name);
        let Some((_, text)) = BUILTIN_MACHINES.iter().find(|(n, _)| *n == name) else {
            let names: Vec<_> = BUILTIN_MACHINES.iter().map(|(n, _)| *n).collect();
            return Err(FiveAxisError::Machine {
                file: spec.to_string(),
                message: format!(
                    "no built-in machine of that name (built-in machines: {})",
                    names.join(", ")
                ),
            });
        };
        return Machine::parse(text, &format!("{name}.toml (built in)"));
    }
    let path = job_dir.join(spec);
    let text = std::fs::read_to_string(&path).map_err(|e| FiveAxisError::Machine {
        file: path.display().to_string(),
        message: format!("cannot read the machine file (output.machine): {e}"),
    })?;
    Machine::parse(&text, &path.display().to_string())
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
        dialect: match job.output.dialect {
            OutputDialect::Linuxcnc => Dialect::Linuxcnc,
            OutputDialect::Fanuc => Dialect::Fanuc,
        },
        units: match job.output.units {
            OutputUnits::Mm => Units::Mm,
            OutputUnits::Inch => Units::Inch,
        },
        comments,
        feed_mode: match job.output.feed_mode {
            OutputFeedMode::InverseTime => FeedMode::InverseTime,
            OutputFeedMode::UnitsPerMinute => FeedMode::UnitsPerMinute,
        },
        tool_length,
        path_tol: job.strategy.tolerance,
        ..PostOptions::default()
    })
}

/// `toolpath` as five-axis G-code for `machine`, with the job's post options.
///
/// # Errors
/// As [`post_options`] and [`write_gcode_5x`] (an unreachable pose names the pass,
/// the point and the axis).
pub fn write_job_gcode(
    job: &Job,
    machine: &Machine,
    toolpath: &Toolpath,
    comments: Vec<String>,
) -> Result<String, FiveAxisError> {
    let opts = post_options(job, machine, comments)?;
    write_gcode_5x(machine, toolpath, &opts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::{Point3, Vec3};
    use swarf_tool::Pose;
    use swarf_toolpath::PathPoint;

    fn point(x: f64, contact: bool) -> PathPoint {
        let p = Point3::new(x, 0.0, 1.0);
        PathPoint {
            pose: Pose::vertical(p),
            contact: contact.then_some(Contact {
                point: p,
                normal: Vec3::z(),
                face: 0,
                uv: [0.0; 2],
            }),
            lifted: 0.0,
        }
    }

    #[test]
    fn cc_paths_split_at_bridges_and_drop_short_runs() {
        let pass = |flags: &[bool]| Pass {
            points: flags
                .iter()
                .enumerate()
                .map(|(i, &c)| point(i as f64, c))
                .collect(),
        };
        let tp = Toolpath {
            passes: vec![
                pass(&[true, true, false, false, true, true, true]),
                pass(&[true, false, true]),
                Pass {
                    points: [0.0, 1.0, 1.0 + 1e-9, 2.0, 2.0 + 1e-13]
                        .into_iter()
                        .map(|x| point(x, true))
                        .collect(),
                },
            ],
            feeds: Default::default(),
            linking: Default::default(),
        };
        let cc = cc_paths(&tp);
        let xs: Vec<Vec<f64>> = cc
            .iter()
            .map(|r| r.iter().map(|c| c.point.x).collect())
            .collect();
        assert_eq!(
            xs,
            vec![
                vec![0.0, 1.0],
                vec![4.0, 5.0, 6.0],
                vec![0.0, 1.0 + 1e-9, 2.0 + 1e-13]
            ]
        );
    }

    /// The clearance clears a tilted bull `d = 20, r = 4` over a plane at z = 20: the
    /// lowest point of the tool at the clearance plane (sampled on its profile in the
    /// plane of the tilt) is 5 mm above the part, and no more than the bound's slack
    /// (`R sin(alpha)`) higher.
    #[test]
    fn clearance_is_above_the_part_under_the_whole_tilted_tool() {
        let job = Job::parse(
            "part = \"x\"\ntool = \"bull:d=20,r=4\"\n[strategy]\nkind = \"iso-planar\"\nstepover = 2\n",
            "job.toml",
        )
        .unwrap();
        let p = |x: f64, y: f64| Point3::new(x, y, 20.0);
        let part = Part {
            name: "plane".into(),
            patches: vec![
                swarf_geom::Patch::bezier(
                    [1, 1],
                    vec![p(0.0, 0.0), p(0.0, 9.0), p(9.0, 0.0), p(9.0, 9.0)],
                )
                .unwrap(),
            ],
        };
        let a = 30f64.to_radians();
        let axis = Vec3::new(a.sin(), 0.0, a.cos());
        let at = |z: f64| {
            PathPoint::new(Pose {
                cl: Point3::new(0.0, 0.0, z),
                axis,
            })
        };
        let profile = job.tool.profile();
        let lowest = |tip: f64| {
            (0..=2000)
                .map(|k| profile.point_at(k as f64 / 2000.0).0)
                .map(|q| tip + q.z * a.cos() - q.rho * a.sin())
                .fold(f64::INFINITY, f64::min)
        };
        for (tip, top) in [(10.0, 20.0), (30.0, 30.0)] {
            let passes = vec![Pass {
                points: vec![at(tip), at(tip)],
            }];
            let l = linking(&job, &part, &passes);
            let low = lowest(l.clearance);
            assert!(low >= top + 5.0 - 1e-9, "{low} vs {top}");
            assert!(low <= top + 5.0 + 10.0 * a.sin(), "{low} vs {top}");
        }
    }

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
        let plan = swarf_path::plan(&job, swarf_path::PlanInput::Part(&part)).unwrap();
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
    fn machines_resolve_and_head_machines_need_a_tool_length() {
        let dir = Path::new(".");
        for (name, _) in BUILTIN_MACHINES {
            load_machine(&format!("builtin:{name}"), dir).unwrap();
        }
        let e = load_machine("builtin:hexapod", dir)
            .unwrap_err()
            .to_string();
        assert!(e.contains("xyzac-trunnion"), "{e}");
        let e = load_machine("no/such/machine.toml", dir)
            .unwrap_err()
            .to_string();
        assert!(e.contains("output.machine"), "{e}");
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
