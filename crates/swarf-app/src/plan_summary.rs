//! The JSON summary of a planned job and its program's header comments
//! ([`crate::plan_job`]): the plan's figures, the machine and the rotary ranges,
//! the positioning, the holder check and the verification gate's verdict.

use crate::error::{AppError, Result};
use crate::gate::GateReport;
use crate::holder::HolderCheck;
use crate::holder::avoid::Avoidance;
use crate::job::Job;
use crate::plan_job::planned_scallop;
use crate::programs::SCALLOP_COMMENT;
use swarf_fiveaxis::machine::Machine;
use swarf_fiveaxis::positioning::{Positioning, PositioningReport};
use swarf_path::Plan;
use swarf_tool::library::LibraryTool;
use swarf_toolpath::MotionStats;

/// The ranges of a five-axis program's two rotary axes, radians.
pub(crate) type RotaryRanges = [[f64; 2]; 2];

/// What a job's summary is made of.
pub(crate) struct SummaryParts<'a> {
    pub job: &'a Job,
    pub plan: &'a Plan,
    pub part_name: &'a str,
    /// The program's lengths and time.
    pub stats: &'a MotionStats,
    /// The machine of five-axis G-code, and the rotary ranges of the program written.
    pub machine: Option<(&'a Machine, Option<RotaryRanges>)>,
    pub positioning: Option<&'a PositioningReport>,
    /// The library tool, its shank and holder check and what avoidance tilted.
    pub holder: Option<(&'a LibraryTool, &'a HolderCheck, Option<&'a Avoidance>)>,
    /// The verification gate's verdict (`None`: skipped).
    pub gate: Option<&'a GateReport>,
}

/// The JSON summary `swarf plan` prints and writes.
///
/// # Errors
/// A figure that is not finite; a holder check that does not serialise.
pub(crate) fn summary_json(parts: &SummaryParts<'_>) -> Result<serde_json::Value> {
    let SummaryParts {
        job,
        plan,
        part_name,
        stats,
        machine,
        positioning,
        holder,
        gate,
    } = *parts;
    let numbers = [
        stats.cutting_length,
        stats.approach_length,
        stats.rapid_length,
        stats.time_s,
    ];
    swarf_io::json::check_finite(&(numbers, &plan.report))
        .map_err(|e| AppError::Message(format!("the plan's summary: {e}")))?;
    let mut summary = serde_json::json!({
        "job": job.name,
        "part": part_name,
        "tool": job.tool.to_string(),
        "strategy": job.strategy.kind(),
        "passes": plan.toolpath.passes.len(),
        "poses": plan.toolpath.pose_count(),
        "cutting_length_mm": stats.cutting_length,
        "approach_length_mm": stats.approach_length,
        "rapid_length_mm": stats.rapid_length,
        "estimated_time_s": stats.time_s,
        "lifted_points": plan.toolpath.lifted_count(),
        "report": plan.report,
    });
    if let Some((m, rotary)) = machine {
        summary["machine"] = serde_json::json!(m.name);
        if let Some(ranges) = rotary {
            summary["rotary_ranges_deg"] = rotary_json(m, ranges);
        }
    }
    if let Some(p) = positioning {
        summary["positioning"] = serde_json::to_value(p)?;
    }
    if let Some((tool, check, avoidance)) = holder {
        summary["holder"] = holder_json(tool, check)?;
        if let Some(a) = avoidance {
            summary["holder"]["avoidance"] = serde_json::to_value(a)?;
        }
    }
    summary["verification"] = match gate {
        Some(g) => serde_json::to_value(g)?,
        None => serde_json::json!({ "skipped": "--no-verify" }),
    };
    Ok(summary)
}

/// The summary's `holder` section: the check's figures and the tool.
fn holder_json(tool: &LibraryTool, check: &HolderCheck) -> Result<serde_json::Value> {
    let mut h = serde_json::to_value(check.cleared()?)?;
    h["number"] = serde_json::json!(tool.number);
    h["name"] = serde_json::json!(tool.name);
    Ok(h)
}

/// The program's header comments.
pub(crate) fn header_comments(
    job: &Job,
    plan: &Plan,
    part_name: &str,
    strategy: &str,
    notes: &[String],
) -> Vec<String> {
    let mut comments = vec![
        format!("swarf {}", env!("CARGO_PKG_VERSION")),
        format!("part {part_name}"),
        format!("tool {}", job.tool),
        format!("strategy {strategy}"),
    ];
    if plan.toolpath.passes.is_empty() {
        comments.push("no passes: nothing to cut".into());
    }
    if let Some(h) = planned_scallop(job, plan) {
        comments.push(format!("{SCALLOP_COMMENT}{h} mm"));
    }
    comments.extend(notes.iter().cloned());
    if let Some(p) = &job.positioning {
        comments.push(format!("positioning {}", describe(p)));
    }
    comments
}

/// The rotary axes' ranges by name, degrees.
fn rotary_json(m: &Machine, ranges: [[f64; 2]; 2]) -> serde_json::Value {
    let names = m.rotary_names();
    let deg = |r: [f64; 2]| [r[0].to_degrees(), r[1].to_degrees()];
    serde_json::json!({
        names[0].to_string(): deg(ranges[0]),
        names[1].to_string(): deg(ranges[1]),
    })
}

/// The positioning as one line for the G-code header (degrees, mm).
fn describe(p: &Positioning) -> String {
    match *p {
        Positioning::Inclined {
            alpha,
            tilt,
            sections,
        } => format!("inclined, lead {alpha} deg, tilt {tilt} deg, sections {sections} mm"),
        Positioning::GougeFree {
            max_alpha,
            sections,
            tilt,
            max_rate,
            ..
        } => format!(
            "gouge-free, lead <= {max_alpha} deg, <= {max_rate} deg/mm, tilt {tilt} deg, sections {sections} mm"
        ),
    }
}
