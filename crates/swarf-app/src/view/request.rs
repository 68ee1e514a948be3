//! `swarf view`'s request: what to show (a program on a part, a job, a sequence
//! job), read or planned, verified, and written as one set with its view
//! ([`super::write_staged_view`]). A program that changes tools, and a sequence,
//! are verified as one stage per tool on one stock; the stock after each stage but
//! the last is verified again on the stages up to it, for the view of each
//! operation.

use super::{StagedView, ViewWritten, check_view_inputs, write_staged_view};
use crate::error::{AppError, Result, bail};
use crate::model::Model;
use crate::outputs::Outputs;
use crate::sequence::Sequence;
use crate::stock::StockKind;
use std::path::Path;
use swarf_nc::read::Program;
use swarf_report::gltf::StockMeshOptions;
use swarf_sim::{Stage, StockSpec, VerifyOptions};
use swarf_tool::Cutter;

/// A view as `swarf view` asks for it: a part and a program, or a job.
#[derive(Debug, Clone, Copy)]
pub struct ViewRequest<'a> {
    /// What to show.
    pub source: ViewSource<'a>,
    /// Verification settings (cell size, tolerance, stock, ...).
    pub sim: &'a crate::verify::SimSettings,
    /// The stock mesh's vertex budget.
    pub stock: StockMeshOptions,
    /// The view folder.
    pub out: &'a Path,
}

/// What `swarf view` shows.
#[derive(Debug, Clone, Copy)]
pub enum ViewSource<'a> {
    /// A program on a part.
    Program {
        /// The design: a part file, a mesh or a built-in part.
        part: &'a str,
        /// The NC program (G-code, APT CL or pose CSV).
        program: &'a Path,
        /// Tool spec (default: the program's CUTTER record).
        tool: Option<&'a str>,
        /// Machine for five-axis G-code.
        machine: Option<&'a str>,
    },
    /// A job file (a job or a sequence job), planned first.
    Job(&'a Path),
}

/// What `swarf view` did: the view and the notes for the user.
#[derive(Debug)]
pub struct Viewed {
    /// The view.
    pub written: ViewWritten,
    /// Deviation range and cells, for the console.
    pub summary: String,
    /// Notes for the user.
    pub notes: Vec<String>,
}

/// What is shown: the design, the programs (one per tool) with their cutters and
/// names, the program's file and text where it was planned here, and how it is
/// verified.
struct Shown {
    model: Model,
    programs: Vec<Program>,
    cutters: Vec<Cutter>,
    names: Vec<String>,
    source: Option<(String, String)>,
    opts: VerifyOptions,
    part: String,
    notes: Vec<String>,
}

/// Verifies what `req` names and writes its view folder (with the verification's
/// report, flagged cells and pictures beside the view's files) as one set.
///
/// # Errors
/// Inputs that cannot be read; a program with no moves or away from the part
/// ([`check_view_inputs`]); a program that stops before its end; the verification's
/// and [`write_staged_view`]'s errors.
pub fn view_request(
    req: &ViewRequest<'_>,
    progress: &dyn crate::report::Reporter,
) -> Result<Viewed> {
    let mut out = Outputs::new(req.out);
    let shown = match req.source {
        ViewSource::Program {
            part,
            program,
            tool,
            machine,
        } => read_program_input(req, part, program, tool, machine)?,
        ViewSource::Job(path) => {
            let text = swarf_io::read_input_text(path)?;
            if Sequence::is_sequence(&text) {
                plan_sequence_input(req, path, &text, &mut out)?
            } else {
                plan_job_input(req, path, &text, &mut out, progress)?
            }
        }
    };
    for (p, c) in shown.programs.iter().zip(&shown.cutters) {
        check_view_inputs(&shown.model, p, c)?;
    }
    let stages: Vec<Stage<'_>> = shown
        .programs
        .iter()
        .zip(&shown.cutters)
        .map(|(program, cutter)| Stage { program, cutter })
        .collect();
    let ctx = crate::verify::context(&shown.part, &stages, &shown.opts);
    if let Some(stop) = &ctx.stopped {
        bail!(
            "{}: the program stops before its end ({stop}): nothing written",
            stages[0].program.source
        );
    }
    let (model, opts) = (&shown.model, &shown.opts);
    let v = crate::verify::verify_and_write(model, &stages, opts, (&mut out, ""), &ctx, progress)?;
    let design = || crate::verify::design_of(model);
    let after = (1..stages.len())
        .map(|k| swarf_sim::verify_stages(design(), &stages[..k], opts, progress))
        .collect::<std::result::Result<Vec<_>, _>>()?;
    let input = StagedView {
        model,
        tol: opts.tol,
        stages: &stages,
        names: &shown.names,
        source: shown.source.as_ref().map(|(f, t)| (f.as_str(), t.as_str())),
        verification: &v,
        after: &after,
    };
    let written = write_staged_view(&mut out, "", &input, &req.stock)?;
    out.commit()?;
    let summary = swarf_sim::report::text_summary(&v, &ctx);
    Ok(Viewed {
        written,
        summary,
        notes: shown.notes,
    })
}

/// The stages of `program` (one per tool it uses) with their cutters: `tool` for a
/// program of one tool, else the tools its plan record names, in order.
fn stages_of(program: Program, tools: &[String]) -> Result<(Vec<Program>, Vec<Cutter>)> {
    let programs = program.split_by_tool();
    let tools = crate::programs::parse_tools(tools, programs.len())?;
    if programs.len() > 1 && tools.len() < programs.len() {
        bail!(
            "{}: the program changes tools {} times but {} tool(s) are known for it (no plan \
             record?): plan it with swarf (its plan record names each tool), or verify it with a \
             `swarf verify --tool` for each tool",
            programs[0].source,
            programs.len() - 1,
            tools.len()
        );
    }
    let cutters = crate::programs::stage_cutters(&tools, &programs)?;
    Ok((programs, cutters))
}

fn read_program_input(
    req: &ViewRequest<'_>,
    part: &str,
    program: &Path,
    tool: Option<&str>,
    machine: Option<&str>,
) -> Result<Shown> {
    let model = crate::model::load_model(part)?;
    model.check_covers_xy(part)?;
    let paths = [program.to_path_buf()];
    let planned = crate::programs::planned(&paths)?;
    let tools: Vec<String> = match tool {
        Some(t) => vec![t.to_string()],
        None => planned.tools.clone(),
    };
    let opts = req.sim.program_options(&planned)?;
    let gcode = crate::programs::GcodeSetup::default();
    let (mut programs, notes) =
        crate::programs::read_programs(&paths, &gcode, machine, None, opts.sample_tol())?;
    let (programs, cutters) = stages_of(programs.remove(0), &tools)?;
    let names = tool_names(&programs);
    Ok(Shown {
        model,
        programs,
        cutters,
        names,
        source: None,
        opts,
        part: part.to_string(),
        notes,
    })
}

/// The names of the stages of a program: its T words (none for one stage).
fn tool_names(programs: &[Program]) -> Vec<String> {
    if programs.len() < 2 {
        return Vec::new();
    }
    programs
        .iter()
        .map(|p| {
            p.tools
                .first()
                .map_or_else(String::new, |t| format!("T{}", t.number))
        })
        .collect()
}

fn plan_job_input(
    req: &ViewRequest<'_>,
    path: &Path,
    text: &str,
    out: &mut Outputs,
    reporter: &dyn crate::report::Reporter,
) -> Result<Shown> {
    let mut job = crate::Job::parse(text, &path.display().to_string())?;
    let stem = path
        .file_stem()
        .map_or_else(|| "job".into(), |s| s.to_string_lossy().into_owned());
    let (program_file, five) = crate::compare::for_measurement(&mut job, &stem);
    let job_dir = path.parent().unwrap_or(Path::new("."));
    let part = crate::plan_job::part_arg(&job, job_dir);
    let model = crate::model::load_model_with(&part, &job.load_options())?;
    crate::plan_job::plan_model(&job, &model, job_dir, out, reporter)?;
    let program = out.read_program(&program_file)?;
    let scallop = job.strategy.scallop().unwrap_or(0.0);
    let mut opts = req
        .sim
        .options(job.tolerance(), scallop, job.feeds.rapid, true)?;
    if five {
        opts.cell = opts.cell.or(Some(crate::compare::FIVE_AXIS_CELL));
        opts.sample_tol = opts
            .sample_tol
            .or(Some(crate::compare::FIVE_AXIS_SAMPLE_TOL));
    }
    Ok(Shown {
        model,
        programs: vec![program],
        cutters: vec![job.tool],
        names: Vec::new(),
        source: None,
        opts,
        part,
        notes: Vec::new(),
    })
}

/// A sequence job planned into `out` (unsafe programs written, so that they can be
/// seen), its program read back and cut into its operations, verified on the
/// sequence's stock at its cell and tolerance unless the flags say otherwise.
fn plan_sequence_input(
    req: &ViewRequest<'_>,
    path: &Path,
    text: &str,
    out: &mut Outputs,
) -> Result<Shown> {
    let job_dir = path.parent().unwrap_or(Path::new("."));
    let mut seq = Sequence::parse(text, &path.display().to_string(), job_dir)?;
    seq.gate = crate::gate::Gate::AllowUnsafe;
    let stem = path
        .file_stem()
        .map_or_else(|| "sequence".into(), |s| s.to_string_lossy().into_owned());
    let file = seq
        .output
        .gcode
        .get_or_insert_with(|| format!("{stem}.ngc"))
        .clone();
    let report = crate::sequence::plan_sequence(&seq, job_dir, out)?;
    let spec = seq.output.post.as_deref().unwrap_or("linuxcnc");
    let post = swarf_nc::Post::load(spec, job_dir)
        .map_err(|e| AppError::Message(format!("output.post = {spec:?}: {e}")))?;
    let read = swarf_nc::read::GcodeReadOptions {
        language: post.reader(),
        ..swarf_nc::read::GcodeReadOptions::default()
    };
    let program = swarf_nc::read::parse_gcode(&report.program, &file, &read)?;
    let first = &seq.operations[0].job;
    let part = crate::plan_job::part_arg(first, job_dir);
    let model = crate::model::load_model_with(&part, &first.load_options())?;
    let scallop = seq
        .operations
        .iter()
        .filter_map(|o| o.job.strategy.scallop())
        .fold(0.0, f64::max);
    let rapid = first.feeds.rapid;
    let mut opts = req.sim.options(seq.stock.tol, scallop, rapid, true)?;
    opts.cell = req.sim.cell.or(Some(seq.stock.cell));
    let [bottom, top] = model.z_range()?;
    opts.stock = match seq.stock.kind {
        StockKind::Box => StockSpec::Box {
            top: Some(seq.stock.top(top, None)?),
        },
        StockKind::Offset => StockSpec::Offset {
            allowance: seq.stock.allowance,
        },
        StockKind::Mesh => match seq.stock.mesh(job_dir)? {
            Some(mesh) => StockSpec::Mesh(mesh),
            None => StockSpec::Box { top: None },
        },
    };
    opts.floor = opts.floor.or(Some(seq.stock.floor(bottom, top)?));
    let programs = program.split_by_tool();
    if programs.len() != seq.operations.len() {
        bail!(
            "{file}: the program reads back as {} tool(s) for {} operations",
            programs.len(),
            seq.operations.len()
        );
    }
    Ok(Shown {
        model,
        programs,
        cutters: seq.operations.iter().map(|o| o.job.tool).collect(),
        names: seq.operations.iter().map(|o| o.name.clone()).collect(),
        source: Some((file, report.program)),
        opts,
        part,
        notes: Vec::new(),
    })
}
