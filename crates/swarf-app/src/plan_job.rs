//! `plan_job`: a job planned end to end. Loads its part, plans it, positions it for a
//! five-axis job (a `positioning` table, [`crate::five_axis`]) and writes every
//! requested output: G-code (three-axis, or five-axis for `output.machine`), APT CL,
//! pose CSV, double contacts and the JSON summary.

use crate::cleanup::{plan_cleanup_job, rest_json, stage_file, steep_json};
use crate::drop_spin::{contacts_csv, drop_spin_json, plan_drop_spin};
use crate::error::{AppError, Result, bail};
use crate::five_axis::{avoid_holder, position_plan, write_job_gcode};
use crate::gate::{self, Gate, stock_spec};
use crate::holder::HolderCheck;
use crate::holder::avoid::Avoidance;
use crate::holder::path::{check_path, gcode_line, refusal};
use crate::job::{Job, Output};
use crate::model::{Model, load_model_with};
use crate::outputs::Outputs;
use crate::plan::{PlanInput, plan};
use crate::plan_record::{OperationRecord, PlanRecord, ToolRecord, record_name};
use crate::plan_summary::{RotaryRanges, SummaryParts, header_comments, summary_json};
use crate::report::Reporter;
use crate::strategy::Strategy;
use std::path::Path;
use swarf_fiveaxis::machine::{Machine, load_machine};
use swarf_fiveaxis::positioning::{Positioning, PositioningReport};
use swarf_geom::TriMesh;
use swarf_geom::domain::excerpt;
use swarf_io::Source;
use swarf_nc::read::GcodeReadOptions;
use swarf_nc::{GcodeOptions, Post};
use swarf_path::Plan;
use swarf_sim::StockSpec;
use swarf_tool::library::LibraryTool;
use swarf_toolpath::{Toolpath, motion_stats};

/// Loads the job's part, plans it (and positions it, for a five-axis job) and stages
/// every requested output in `out` (relative to its directory). Returns the JSON
/// summary.
///
/// # Errors
/// A part or machine that cannot be read; the planning, positioning and post
/// errors; an output that cannot be written.
pub fn plan_job(
    job: &Job,
    job_dir: &Path,
    out: &mut Outputs,
    reporter: &dyn Reporter,
) -> Result<serde_json::Value> {
    let model = load_model_with(&part_arg(job, job_dir), &job.load_options())?;
    plan_model(job, &model, job_dir, out, reporter)
}

/// [`plan_job`] on the job's part already loaded as `model` (a caller that verifies
/// the program against the same part reads it once).
///
/// # Errors
/// As [`plan_job`].
pub fn plan_model(
    job: &Job,
    model: &Model,
    job_dir: &Path,
    out: &mut Outputs,
    reporter: &dyn Reporter,
) -> Result<serde_json::Value> {
    plan_model_toolpath(job, model, job_dir, out, reporter).map(|p| p.summary)
}

/// A planned job as values: its JSON summary and the tool path its program cuts.
#[derive(Debug, Clone)]
pub struct Planned {
    /// The JSON summary (as [`plan_job`] returns it).
    pub summary: serde_json::Value,
    /// The tool path the job's program cuts (a cleanup job's last stage; a five-axis
    /// job's positioned poses).
    pub toolpath: Toolpath,
}

/// [`plan_model`], also returning the tool path (for callers that use the plan as
/// data, such as the Python package).
///
/// # Errors
/// As [`plan_job`].
pub fn plan_model_toolpath(
    job: &Job,
    model: &Model,
    job_dir: &Path,
    out: &mut Outputs,
    reporter: &dyn Reporter,
) -> Result<Planned> {
    let job = &match job.material_top {
        Some(_) => job.clone(),
        None => job.on_stock(model, job_dir)?,
    };
    let machine = job
        .output
        .machine
        .as_deref()
        .map(|spec| {
            load_machine(spec, job_dir).map_err(|e| {
                AppError::Message(format!("output.machine = {:?}: {e}", excerpt(spec, 80)))
            })
        })
        .transpose()?;
    let spec = job.output.post_spec();
    let post = Post::load(spec, job_dir)
        .map_err(|e| AppError::Message(format!("output.post = {:?}: {e}", excerpt(spec, 80))))?;
    let post = &post;
    let gate_stock = match job.gate {
        Gate::Skip => None,
        _ => Some(stock_spec(job, job_dir)?),
    };
    let gate_stock = gate_stock.as_ref();
    match &job.strategy {
        Strategy::Cleanup(_) => {
            return cleanup_outputs(
                job,
                model,
                job_dir,
                (machine.as_ref(), post, gate_stock),
                out,
            );
        }
        Strategy::DropSpin(_) => {
            return drop_spin_outputs(job, model, (machine.as_ref(), post, gate_stock), out);
        }
        _ => {}
    }
    let (name, mut plan) = match model {
        Model::Patches(part) => (part.name.clone(), plan(job, PlanInput::Part(part))?),
        Model::Mesh { name, mesh } => (name.clone(), plan(job, PlanInput::Mesh(mesh))?),
    };
    let mut positioning = match (model, &job.positioning) {
        (_, None) => None,
        (Model::Patches(part), Some(_)) => {
            let start = std::time::Instant::now();
            let report = position_plan(job, part, &mut plan, &|done, total| {
                reporter.passes(done, total);
            });
            reporter.passes_done();
            let report = report?;
            plan.report.elapsed_s += start.elapsed().as_secs_f64();
            report
        }
        (Model::Mesh { .. }, Some(_)) => {
            bail!("positioning: five-axis positioning needs a parametric part (.toml), not a mesh")
        }
    };
    let avoidance = avoid_holder(job, model, &mut plan, positioning.as_mut())?;
    let notes: Vec<String> = avoidance.iter().map(Avoidance::note).collect();
    let written = Written {
        part_name: &name,
        model,
        machine: machine.as_ref(),
        post,
        positioning: positioning.as_ref(),
        avoidance: avoidance.as_ref(),
        notes: &notes,
        gate_stock,
    };
    let summary = write_outputs(job, &plan, &written, out)?;
    Ok(Planned {
        summary,
        toolpath: plan.toolpath,
    })
}

/// What a job's outputs say besides its plan.
struct Written<'a> {
    part_name: &'a str,
    /// The part (the holder check of a library tool runs on its triangles).
    model: &'a Model,
    machine: Option<&'a Machine>,
    /// The post of the G-code.
    post: &'a Post,
    positioning: Option<&'a PositioningReport>,
    /// What holder avoidance tilted.
    avoidance: Option<&'a Avoidance>,
    /// Extra header comments of the program.
    notes: &'a [String],
    /// The stock the verification gate simulates the program on (`None`: the gate
    /// is skipped).
    gate_stock: Option<&'a StockSpec>,
}

/// Plans a drop-spin job ([`crate::drop_spin`]) and writes its outputs, the
/// contacts CSV among them; the summary has its zones and station reports.
fn drop_spin_outputs(
    job: &Job,
    model: &Model,
    (machine, post, gate_stock): (Option<&Machine>, &Post, Option<&StockSpec>),
    out: &mut Outputs,
) -> Result<Planned> {
    let Model::Patches(part) = model else {
        bail!(
            "strategy.kind: drop-spin needs a parametric part (.toml) with two faces, not a mesh"
        );
    };
    let ds = plan_drop_spin(job, part, machine)?;
    if let Some(rel) = &job.output.contacts {
        out.write(
            rel,
            contacts_csv(&ds.passes.poses, crate::drop_spin::params_of(job)?.faces).as_bytes(),
        )?;
    }
    let written = Written {
        part_name: &part.name,
        model,
        machine,
        post,
        positioning: None,
        avoidance: None,
        notes: &[],
        gate_stock,
    };
    let mut quiet = job.clone();
    let summary_file = quiet.output.summary.take();
    let mut s = write_outputs(&quiet, &ds.plan, &written, out)?;
    s["drop_spin"] = drop_spin_json(&ds.passes);
    if let Some(rel) = &summary_file {
        out.write_json(rel, &s)?;
    }
    Ok(Planned {
        summary: s,
        toolpath: ds.plan.toolpath,
    })
}

/// Plans a cleanup job ([`crate::cleanup`]) and writes each stage's outputs (stage
/// `k` of several to `.k` files, the last to the job's own); the summary has the
/// last stage's figures, its rest regions, and every stage's summary when there are
/// several.
fn cleanup_outputs(
    job: &Job,
    model: &Model,
    job_dir: &Path,
    (machine, post, gate_stock): (Option<&Machine>, &Post, Option<&StockSpec>),
    out: &mut Outputs,
) -> Result<Planned> {
    let mut stages = plan_cleanup_job(job, model, job_dir, Some(out))?;
    let name = match model {
        Model::Patches(part) => part.name.clone(),
        Model::Mesh { name, .. } => name.clone(),
    };
    let n = stages.len();
    let mut summaries = Vec::with_capacity(n);
    for (k, stage) in stages.iter().enumerate() {
        let mut staged = job.clone();
        staged.tool = stage.tool;
        if staged.tool != job.tool {
            // A chain's intermediate tool is not the library's.
            staged.library_tool = None;
        }
        if k + 1 < n {
            let o = &mut staged.output;
            for f in [&mut o.gcode, &mut o.cl, &mut o.csv, &mut o.summary] {
                *f = f.as_deref().map(|f| stage_file(f, k + 1));
            }
        }
        let summary_file = staged.output.summary.take();
        let written = Written {
            part_name: &name,
            model,
            machine,
            post,
            positioning: None,
            avoidance: None,
            notes: &stage.notes,
            gate_stock,
        };
        let mut s = write_outputs(&staged, &stage.plan, &written, out)?;
        s["reference_tool"] = serde_json::json!(stage.reference.to_string());
        s["rest_source"] = serde_json::json!(stage.source);
        s["rest"] = rest_json(&stage.detection);
        if let Some(rest) = &stage.steep {
            s["steep_rest"] = steep_json(rest);
        }
        if !stage.notes.is_empty() {
            s["notes"] = serde_json::json!(stage.notes);
        }
        if let Some(rel) = summary_file {
            out.write_json(rel, &s)?;
        }
        summaries.push(s);
    }
    let mut last = summaries.pop().unwrap_or_default();
    if !summaries.is_empty() {
        summaries.push(last.clone());
        last["stages"] = serde_json::Value::Array(summaries);
    }
    let toolpath = match stages.pop() {
        Some(stage) => stage.plan.toolpath,
        None => bail!("strategy.kind: the cleanup job planned no stage"),
    };
    Ok(Planned {
        summary: last,
        toolpath,
    })
}

/// The job's part as a `load_model` argument: built-in or absolute as given, else
/// relative to the job's directory.
pub fn part_arg(job: &Job, job_dir: &Path) -> String {
    match Source::parse(&job.part, job_dir) {
        Source::Builtin(_) => job.part.clone(),
        Source::File(path) => path.display().to_string(),
    }
}

/// The job's 3-axis program: `moves` through `post`, with arcs when the job asks.
fn three_axis_gcode(
    job: &Job,
    post: &Post,
    moves: &[swarf_toolpath::Move],
    comments: Vec<String>,
) -> Result<String> {
    let mut opts = GcodeOptions {
        post: post.clone(),
        units: job.output.units,
        comments,
        arc_tolerance: job.output.arc_tolerance_mm(),
        ..GcodeOptions::default()
    };
    if let Some(tool) = &job.library_tool {
        opts.tool_number = tool.number;
    }
    Ok(swarf_nc::write_gcode(moves, &job.feeds, &opts)?)
}

fn write_outputs(
    job: &Job,
    plan: &Plan,
    written: &Written<'_>,
    out: &mut Outputs,
) -> Result<serde_json::Value> {
    let Written {
        part_name,
        model,
        machine,
        post,
        positioning,
        avoidance,
        notes,
        gate_stock: _,
    } = *written;
    let holder = match &job.library_tool {
        Some(tool) => {
            let mesh = model.triangles(job.tolerance())?;
            let name = job.name.as_deref().unwrap_or(part_name);
            let check = check_path(&mesh, &plan.toolpath, tool, name)?;
            Some((tool, mesh, check))
        }
        None => None,
    };
    let moves = plan.toolpath.moves();
    let stats = motion_stats(&moves, job.feeds.rapid);
    let strategy = job.strategy.kind().to_string();
    let comments = header_comments(job, plan, part_name, &strategy, notes);
    let read = GcodeReadOptions {
        language: post.reader(),
        ..GcodeReadOptions::default()
    };
    let (rotary, program, gate) =
        gated_program(job, plan, written, (&moves, &read), comments, out)?;
    if let Some((tool, mesh, check)) = &holder {
        let program = program.as_deref().map(|text| (text, &read));
        refuse_collisions(job, plan, program, (tool, mesh, check))?;
    }
    if let Some(rel) = &job.output.cl {
        let text = swarf_nc::write_cl(&moves, &job.feeds, &job.tool, part_name, job.output.units)?;
        out.write(rel, text.as_bytes())?;
    }
    if let Some(rel) = &job.output.csv {
        let text = swarf_nc::write_pose_csv(&plan.toolpath, job.output.units)?;
        out.write(rel, text.as_bytes())?;
    }
    if let (Some(rel), Some(text)) = (&job.output.double_contacts, plan.double_contacts_csv()) {
        out.write(rel, text.as_bytes())?;
    }
    write_records(&job_record(job, plan, written), &job.output, out)?;
    let summary = summary_json(&SummaryParts {
        job,
        plan,
        part_name,
        stats: &stats,
        machine: machine.map(|m| (m, rotary)),
        positioning,
        holder: holder
            .as_ref()
            .map(|(tool, _, check)| (*tool, check, avoidance)),
        gate: gate.as_ref(),
    })?;
    if let Some(rel) = &job.output.summary {
        out.write_json(rel, &summary)?;
    }
    Ok(summary)
}

/// Writes the program ([`write_program`]) through the verification gate
/// ([`crate::gate`]): simulated on the job's stock as it would be written (a
/// five-axis or machine program: from its poses), its verdict in its header,
/// refused when unsafe unless the job allows it.
///
/// # Errors
/// As [`write_program`]; the gate's refusal.
fn gated_program(
    job: &Job,
    plan: &Plan,
    written: &Written<'_>,
    (moves, read): (&[swarf_toolpath::Move], &GcodeReadOptions<'_>),
    mut comments: Vec<String>,
    out: &mut Outputs,
) -> Result<(
    Option<RotaryRanges>,
    Option<String>,
    Option<gate::GateReport>,
)> {
    let stock = written.gate_stock;
    // Without a machine the program is three-axis G-code (a tilted path without one
    // writes none: `output.machine`); with one, the gate simulates the poses.
    let first = match (&job.output.gcode, stock) {
        (Some(_), Some(_)) if written.machine.is_none() => Some(three_axis_gcode(
            job,
            written.post,
            moves,
            comments.clone(),
        )?),
        _ => None,
    };
    let scallop = planned_scallop(job, plan).unwrap_or(0.0);
    let simulated = (moves, first.as_deref(), read);
    let mut gate = gate::run(job, written.model, simulated, stock, scallop)?;
    comments.push(gate::comment(gate.as_ref()));
    let program = write_program(job, plan, written, moves, comments, out)?;
    let text = program.three_axis.as_deref();
    gate::conclude(job, gate.as_mut(), (moves, text, read), &program.move_lines)?;
    Ok((program.rotary, program.three_axis, gate))
}

/// The plan record of `job`'s program (`crate::plan_record`): its tool, what it was
/// planned for, the machine and the post.
fn job_record(job: &Job, plan: &Plan, written: &Written<'_>) -> PlanRecord {
    let number = job.library_tool.as_ref().map_or(1, |t| t.number);
    let tool = ToolRecord {
        number,
        cutter: job.tool.to_string(),
        name: job.library_tool.as_ref().map(|t| t.name.clone()),
    };
    let op = OperationRecord {
        name: job
            .name
            .clone()
            .unwrap_or_else(|| written.part_name.to_string()),
        strategy: job.strategy.kind().into(),
        tool: number,
        scallop: planned_scallop(job, plan),
        tolerance: job.tolerance(),
    };
    let mut record = PlanRecord::new(
        &job.part,
        job.output.units,
        vec![tool],
        vec![op],
        job.output.post_spec(),
    );
    record.machine = written.machine.and(job.output.machine.clone());
    record.tool_length = job.output.tool_length;
    record
}

/// The scallop a job's program is planned for, mm: the job's limit, else what its
/// strategy predicts.
pub(crate) fn planned_scallop(job: &Job, plan: &Plan) -> Option<f64> {
    job.strategy.scallop().or(plan.report.predicted_max_scallop)
}

/// Writes `record` beside each program `output` names (one record for the programs
/// that share a stem), listing them.
///
/// # Errors
/// A record that cannot be staged.
pub(crate) fn write_records(record: &PlanRecord, output: &Output, out: &mut Outputs) -> Result<()> {
    let programs: Vec<&String> = [&output.gcode, &output.cl, &output.csv]
        .into_iter()
        .flatten()
        .collect();
    let mut names: Vec<String> = programs.iter().map(|p| record_name(p)).collect();
    names.sort();
    names.dedup();
    for name in names {
        let mut r = record.clone();
        r.programs = programs
            .iter()
            .filter(|p| record_name(p) == name)
            .map(|p| p.to_string())
            .collect();
        out.write_json(&name, &r)?;
    }
    Ok(())
}

/// Writes the program `output.gcode` asks for: five-axis for `output.machine`
/// (with the rotary axes' ranges), else three-axis (returned as text, the T number
/// the library tool's).
fn write_program(
    job: &Job,
    plan: &Plan,
    written: &Written<'_>,
    moves: &[swarf_toolpath::Move],
    comments: Vec<String>,
    out: &mut Outputs,
) -> Result<WrittenProgram> {
    let Some(rel) = &job.output.gcode else {
        return Ok(WrittenProgram::default());
    };
    if let Some(m) = written.machine {
        let post =
            write_job_gcode(job, m, written.post, &plan.toolpath, comments).map_err(|e| {
                let spec = job.output.machine.as_deref().unwrap_or_default();
                AppError::Message(format!("output.machine = {spec:?} ({}): {e}", m.name))
            })?;
        out.write(rel, post.gcode.as_bytes())?;
        return Ok(WrittenProgram {
            rotary: post.rotary_ranges,
            three_axis: None,
            move_lines: post.move_lines,
        });
    }
    let text = three_axis_gcode(job, written.post, moves, comments)?;
    out.write(rel, text.as_bytes())?;
    Ok(WrittenProgram {
        three_axis: Some(text),
        ..WrittenProgram::default()
    })
}

/// The G-code [`write_program`] wrote.
#[derive(Default)]
struct WrittenProgram {
    /// The rotary axes' ranges of a five-axis program.
    rotary: Option<RotaryRanges>,
    /// The three-axis program's text.
    three_axis: Option<String>,
    /// A five-axis program's line of the end of each move (empty otherwise).
    move_lines: Vec<usize>,
}

/// Refuses a path whose shank or holder reaches into the part (module doc of
/// [`crate::holder::path`]): the first collision's pass, pose and G-code line (when
/// `program` is the three-axis G-code written), the shortest stick-out that clears,
/// and for a tilted pose the extra tilt that clears.
fn refuse_collisions(
    job: &Job,
    plan: &Plan,
    program: Option<(&str, &GcodeReadOptions<'_>)>,
    (tool, mesh, check): (&LibraryTool, &TriMesh, &HolderCheck),
) -> Result<()> {
    let Some(first) = check.collisions.first() else {
        return Ok(());
    };
    let mut check = check.clone();
    if let Some((text, read)) = program {
        check.collisions[0].line = gcode_line(text, read, &plan.toolpath, first);
    }
    let max_tilt = match job.positioning {
        Some(Positioning::GougeFree { max_alpha, .. }) => Some(max_alpha.to_radians()),
        _ => None,
    };
    Err(AppError::Message(refusal(mesh, tool, &check, max_tilt)?))
}
