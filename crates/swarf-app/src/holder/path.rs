//! The holder and shank check of a planned job's path (`swarf plan` with a library
//! tool, [`crate::job`]): every pose of every pass, and points about
//! [`POSE_SPACING`] apart between them, checked as [`super::check_program`] checks
//! a program's (vertical poses with the shortest stick-out, tilted poses in their
//! own frame), each collision named by its pass and pose and, when the job writes
//! three-axis G-code, the line that commands it.
//!
//! A tilted pose that collides (five-axis) is also searched for the extra tilt that
//! clears ([`clearing_tilt`]): the axis turned about the tool tip away from where
//! the holder or shank touches the part, `a(t) = a cos t + d sin t` with `d` the
//! direction from the contact to the tip, normal to `a`. A positioned ball-end
//! path is tilted clear first ([`super::avoid`]); what still collides is refused,
//! naming that tilt.

use super::{HolderCheck, LineCollision, POSE_SPACING, check_poses};
use crate::error::Result;
use swarf_geom::TriMesh;
use swarf_geom::math::slerp;
use swarf_nc::read::{GcodeReadOptions, parse_gcode};
use swarf_tool::Pose;
use swarf_tool::holder::tilted::{Tilt, TiltSearch, clearing_tilt};
use swarf_tool::library::LibraryTool;
use swarf_toolpath::Toolpath;

/// A motion's end within this of a pose is the motion that commands it (the
/// program's words are rounded to 1e-4 mm), mm.
const LINE_MATCH: f64 = 1e-3;

/// The poses of the passes of `toolpath`: each point, and points about `spacing`
/// apart on the straight segments between consecutive points (axes interpolated
/// by the one slerp), each tagged with its pass and the pose it leads to.
pub fn path_poses(toolpath: &Toolpath, spacing: f64) -> Vec<(Pose, [usize; 2])> {
    let mut out = Vec::new();
    for (p, pass) in toolpath.passes.iter().enumerate() {
        for (k, point) in pass.points.iter().enumerate() {
            if k > 0 {
                let a = pass.points[k - 1].pose;
                let b = point.pose;
                let n = ((b.cl - a.cl).norm() / spacing.max(1e-3)).ceil() as usize;
                for i in 1..n {
                    let f = i as f64 / n as f64;
                    let cl = a.cl + f * (b.cl - a.cl);
                    let axis = slerp(&a.axis, &b.axis, f);
                    if let Some(pose) = Pose::new(cl, axis) {
                        out.push((pose, [p, k]));
                    }
                }
            }
            out.push((point.pose, [p, k]));
        }
    }
    out
}

/// Checks the shank and holder of `tool` at the poses of `toolpath` against `mesh`
/// (module doc); `name` names the path in the summary.
///
/// # Errors
/// A shank or holder segment the kernel refuses.
pub fn check_path(
    mesh: &TriMesh,
    toolpath: &Toolpath,
    tool: &LibraryTool,
    name: &str,
) -> Result<HolderCheck> {
    let tagged = path_poses(toolpath, POSE_SPACING);
    let poses: Vec<(Pose, usize)> = tagged
        .iter()
        .enumerate()
        .map(|(i, (pose, _))| (*pose, i))
        .collect();
    let check = check_poses(mesh, &poses, tool)?;
    Ok(
        check.into_check(name.to_string(), tool, poses.len(), |i, c| LineCollision {
            pass: Some(tagged[i].1),
            ..c
        }),
    )
}

/// The line of the first motion of the G-code `text` (read as `read` says) that
/// ends at the collision's pass pose of `toolpath`.
pub fn gcode_line(
    text: &str,
    read: &GcodeReadOptions<'_>,
    toolpath: &Toolpath,
    c: &LineCollision,
) -> Option<usize> {
    let [p, k] = c.pass?;
    let cl = toolpath.passes.get(p)?.points.get(k)?.pose.cl;
    let program = parse_gcode(text, "the job's program", read).ok()?;
    program
        .motions
        .iter()
        .find(|m| (m.end.cl - cl).norm() < LINE_MATCH)
        .map(|m| m.line)
}

/// The smallest extra tilt that clears the collision `c` of `tool`'s shank and
/// holder with `mesh` (module doc); [`Tilt::Fails`] when none up to `search`'s
/// largest does.
///
/// # Errors
/// A shank or holder segment the kernel refuses.
pub fn collision_tilt(
    mesh: &TriMesh,
    tool: &LibraryTool,
    c: &LineCollision,
    search: &TiltSearch,
) -> Result<Tilt> {
    let pose = Pose {
        cl: c.cl,
        axis: c.axis,
    };
    Ok(clearing_tilt(
        &tool.assembly,
        mesh,
        &pose,
        &(c.cl - c.contact),
        search,
    )?)
}

/// The refusal of a path that collides: the check's summary and, for a tilted
/// first collision, the tilt that clears it (degrees at this edge).
///
/// # Errors
/// A shank or holder segment the kernel refuses.
pub fn refusal(
    mesh: &TriMesh,
    tool: &LibraryTool,
    check: &HolderCheck,
    max_tilt: Option<f64>,
) -> Result<String> {
    let mut s = check.summary();
    let Some(first) = check.collisions.first() else {
        return Ok(s);
    };
    if (swarf_tool::Pose {
        cl: first.cl,
        axis: first.axis,
    })
    .is_vertical()
    {
        return Ok(s);
    }
    let search = TiltSearch::default();
    s += &match collision_tilt(mesh, tool, first, &search)? {
        Tilt::Clear => String::new(),
        Tilt::Clears { tilt, axis, .. } => {
            let mut t = format!(
                "\nholder: tilting the axis at {} a further {:.3} deg away from the part, to \
                 ({:.4}, {:.4}, {:.4}), clears it",
                first.place(),
                tilt.to_degrees(),
                axis.x,
                axis.y,
                axis.z
            );
            if let Some(limit) = max_tilt {
                t += &format!(
                    "; the positioning allows leads up to {:.3} deg",
                    limit.to_degrees()
                );
            }
            t
        }
        Tilt::Fails => format!(
            "\nholder: no extra tilt up to {:.0} deg clears {}",
            search.max_tilt.to_degrees(),
            first.place()
        ),
    };
    Ok(s)
}
