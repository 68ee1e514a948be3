//! Verifying a program against the design: the settings a user gives, the stock, the
//! machine a five-axis G-code program was posted for, and the reports and pictures
//! written for it.
//!
//! Five-axis G-code (`X Y Z` and two rotary words) needs the machine it was posted
//! for: `--machine FILE` (or `builtin:NAME`) and, for machines with head axes,
//! `--tool-length MM`. The G-code's axis positions then go through the machine's
//! forward kinematics into part-frame poses ([`read_with_machine`]). APT CL and pose
//! CSV programs are in the part frame already: the machine is not needed for them.
//!
//! Several programs run one after the other on one stock (a finish, then the cleanup
//! of what its tool left, each with its own tool: [`swarf_sim::stage`]) and give one
//! report. The tools are matched to the programs in order ([`stage_cutters`]); the
//! machine applies to every G-code program.

use crate::error::{AppError, Result, bail};
use crate::model::{Model, load_model};
use crate::outputs::Outputs;
pub use crate::programs::{GcodeSetup, machine_arg, parse_tools, read_with_machine, stage_cutters};
use crate::programs::{Planned, planned, read_programs};
use std::path::{Path, PathBuf};
use swarf_geom::domain::excerpt;
use swarf_nc::read::{Motion, Program};
use swarf_sim::report::{ReportContext, flagged_csv, json_report};
use swarf_sim::{Design, Progress, Stage, StockSpec, Verification, VerifyOptions};
use swarf_tool::Cutter;

/// Verification settings as a user gives them (`swarf verify` and `swarf compare`
/// flags): each absent one takes a default from the job or the command.
#[derive(Debug, Clone, PartialEq)]
pub struct SimSettings {
    /// Stock: box, box:TOP, offset:ALLOWANCE (mm above the design) or a mesh file.
    pub stock: StockChoice,
    /// Cell size, mm (default: 5 x the tolerance).
    pub cell: Option<f64>,
    /// Gouge / excess tolerance, mm (compare: default from each job).
    pub tol: Option<f64>,
    /// Material allowed above the design before it counts as excess (the scallop
    /// limit), mm (compare: default from each job).
    pub scallop: Option<f64>,
    /// Machine rapid rate for the time estimate, mm/min (compare: default from each job).
    pub rapid: Option<f64>,
    /// Distance bound for sampled motions (arcs, five-axis), mm (default: tol / 4).
    pub sample_tol: Option<f64>,
    /// Memory limit for the grid, MiB.
    pub max_memory: u64,
    /// How deviation is measured (default: along the normals).
    pub deviation: Option<Deviation>,
    /// Sample five-axis motions by the first-order bound alone: the slow reference
    /// sweep the default (second-order where it applies) is checked against.
    pub first_order_sweep: bool,
    /// The lowest height the tool may reach, mm: motions that go lower are reported
    /// ([`swarf_sim::floor`]; compare: default each job's floor).
    pub floor: Option<f64>,
}

impl Default for SimSettings {
    /// The command-line defaults (for callers such as `swarf demo`).
    fn default() -> Self {
        SimSettings {
            stock: StockChoice::Offset { allowance: 0.5 },
            cell: None,
            tol: None,
            scallop: None,
            rapid: None,
            sample_tol: None,
            max_memory: 4096,
            deviation: None,
            first_order_sweep: false,
            floor: None,
        }
    }
}

/// Tolerance of a verification when neither `--tol` nor a plan record gives one, mm.
pub const DEFAULT_TOL: f64 = 0.01;

impl SimSettings {
    /// The options of verifying programs planned as `planned` says: each flag
    /// given, else what the plan records (or the G-code headers) say, else the
    /// defaults ([`DEFAULT_TOL`], no excess allowed, the default rapid rate,
    /// measured along the normals).
    ///
    /// # Errors
    /// As [`SimSettings::options`].
    pub fn program_options(&self, planned: &Planned) -> Result<VerifyOptions> {
        self.options(
            planned.tolerance.unwrap_or(DEFAULT_TOL),
            planned.scallop.unwrap_or(0.0),
            swarf_toolpath::Feeds::default().rapid,
            true,
        )
    }

    /// Defaults with cell size `cell` (mm), measuring along the normals.
    pub fn normal_with_cell(cell: f64) -> SimSettings {
        SimSettings {
            cell: Some(cell),
            deviation: Some(Deviation::Normal),
            ..SimSettings::default()
        }
    }

    /// Verification options, with the given defaults where an option is absent.
    ///
    /// # Errors
    /// A cell, tolerance or sampling bound that is not a positive length; a bad
    /// stock.
    pub fn options(
        &self,
        tol: f64,
        scallop: f64,
        rapid: f64,
        along_normals: bool,
    ) -> Result<VerifyOptions> {
        use swarf_geom::domain::{CELL, COORDINATE, RATE, SAMPLE, SCALLOP, TOLERANCE};
        for (flag, v, domain) in [
            ("--cell", self.cell, CELL),
            ("--tol", self.tol, TOLERANCE),
            ("--sample-tol", self.sample_tol, SAMPLE),
            ("--rapid", self.rapid, RATE),
            ("--floor", self.floor, COORDINATE),
        ] {
            if let Some(x) = v {
                domain.check_named(flag, x).map_err(AppError::Message)?;
            }
        }
        if let Some(h) = self.scallop
            && h != 0.0
        {
            SCALLOP
                .check(h)
                .map_err(|m| AppError::Message(format!("--scallop: {m} (or 0)")))?;
        }
        if !(1..=1 << 20).contains(&self.max_memory) {
            bail!(
                "--max-memory: expected a memory limit from 1 to 1048576 MiB, found {}",
                self.max_memory
            );
        }
        Ok(VerifyOptions {
            cell: self.cell,
            tol: self.tol.unwrap_or(tol),
            allowed_excess: self.scallop.unwrap_or(scallop),
            stock: self.stock.load()?,
            max_bytes: self.max_memory.saturating_mul(1 << 20),
            sample_tol: self.sample_tol,
            rapid_rate: self.rapid.unwrap_or(rapid),
            along_normals: self
                .deviation
                .map_or(along_normals, |d| d == Deviation::Normal),
            first_order: self.first_order_sweep,
            floor: self.floor,
            ..VerifyOptions::default()
        })
    }
}

/// The stock a verification starts from, as a user names it: `box`, `box:TOP`,
/// `offset:ALLOWANCE` (mm above the design) or a mesh file (read when the
/// verification starts, [`StockChoice::load`]).
#[derive(Debug, Clone, PartialEq)]
pub enum StockChoice {
    /// A block over the design, its top at `top` (default: above the program).
    Box {
        /// The block's top, mm.
        top: Option<f64>,
    },
    /// The design raised by an allowance.
    Offset {
        /// Material above the design, mm.
        allowance: f64,
    },
    /// A mesh's upper envelope (STL or OBJ).
    Mesh(PathBuf),
}

impl std::str::FromStr for StockChoice {
    type Err = AppError;

    /// `box`, `box:TOP`, `offset:ALLOWANCE` or a `.stl` / `.obj` file.
    fn from_str(text: &str) -> Result<StockChoice> {
        let number = |s: &str, what: &str, domain: swarf_geom::domain::Domain| -> Result<f64> {
            let v: f64 = s.trim().parse().map_err(|_| {
                AppError::Message(format!(
                    "--stock {}: {what} {:?} is not a number",
                    excerpt(text, 60),
                    excerpt(s, 40)
                ))
            })?;
            domain
                .check(v)
                .map_err(|m| AppError::Message(format!("--stock: {what}: {m}")))
        };
        if text == "box" {
            return Ok(StockChoice::Box { top: None });
        }
        if let Some(top) = text.strip_prefix("box:") {
            return Ok(StockChoice::Box {
                top: Some(number(top, "top", swarf_geom::domain::COORDINATE)?),
            });
        }
        if let Some(a) = text.strip_prefix("offset:") {
            let allowance = number(a, "allowance", swarf_geom::domain::ALLOWANCE)?;
            return Ok(StockChoice::Offset { allowance });
        }
        let path = Path::new(text);
        match swarf_io::ModelFormat::of(path) {
            f if f.is_mesh() => Ok(StockChoice::Mesh(path.to_path_buf())),
            _ => bail!(
                "--stock {}: expected box, box:TOP, offset:ALLOWANCE or a .stl / .obj mesh",
                excerpt(text, 60)
            ),
        }
    }
}

impl StockChoice {
    /// The stock the simulator starts from (a mesh read now).
    ///
    /// # Errors
    /// A mesh file that cannot be read.
    pub fn load(&self) -> Result<StockSpec> {
        Ok(match self {
            StockChoice::Box { top } => StockSpec::Box { top: *top },
            StockChoice::Offset { allowance } => StockSpec::Offset {
                allowance: *allowance,
            },
            StockChoice::Mesh(path) => StockSpec::Mesh(swarf_io::read_mesh(path)?),
        })
    }
}

/// Parses `--stock` and reads its mesh ([`StockChoice`]).
///
/// # Errors
/// Anything else, naming `--stock`; a mesh that cannot be read.
pub fn parse_stock(text: &str) -> Result<StockSpec> {
    text.parse::<StockChoice>()?.load()
}

/// How deviation is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Deviation {
    /// Along z.
    Vertical,
    /// Along the design normals ("mow the grass"; the scallop height of paper 004).
    Normal,
}

impl std::str::FromStr for Deviation {
    type Err = AppError;

    /// `vertical` or `normal`.
    fn from_str(s: &str) -> Result<Deviation> {
        match s {
            "vertical" => Ok(Deviation::Vertical),
            "normal" => Ok(Deviation::Normal),
            other => bail!(
                "--deviation {}: expected normal or vertical",
                excerpt(other, 40)
            ),
        }
    }
}

/// A verification as `swarf verify` asks for it.
#[derive(Debug, Clone, Copy)]
pub struct VerifyRequest<'a> {
    /// Design part: a part file, a mesh or a built-in part name.
    pub part: &'a str,
    /// NC programs, run in this order on one stock (e.g. a finish, then its cleanup):
    /// G-code, APT CL or pose CSV. At least one.
    pub programs: &'a [PathBuf],
    /// Tool specs matched to the programs in order ([`stage_cutters`]): none, one per
    /// program, or fewer (the programs after them use their own APT CUTTER record,
    /// else the last tool given).
    pub tools: &'a [String],
    /// How G-code is read (dialect, tool table, parameters, subroutine folders).
    pub gcode: &'a GcodeSetup,
    /// Machine file or `builtin:NAME` for five-axis G-code (every G-code program).
    pub machine: Option<&'a str>,
    /// Spindle gauge line to tool tip, mm (machines with head axes).
    pub tool_length: Option<f64>,
    /// Verification settings.
    pub sim: &'a SimSettings,
    /// Output directory.
    pub out: &'a Path,
    /// Write the reports of a program that stopped before its end (they cover the
    /// motions before the stop); without it such a run writes nothing and the
    /// previous reports stay whole.
    pub partial: bool,
}

/// What a verification gave, with what its report says about the inputs and the
/// notes for the user (options that did not apply).
#[derive(Debug)]
pub struct Verified {
    /// The verification.
    pub verification: Verification,
    /// The report's context.
    pub context: ReportContext,
    /// Notes for the user.
    pub notes: Vec<String>,
    /// Whether the reports were written (not when a program stopped early without
    /// [`VerifyRequest::partial`]).
    pub written: bool,
}

/// Reads and verifies the programs of `req`, in order on one stock, writing the
/// reports and pictures under `req.out` as one set ([`verify_and_write`]). A program
/// that stops mid-way is simulated up to where it stopped; the programs after it are
/// not (a note says so), [`Verified::context`] holds where it stopped, and the
/// reports are written only with [`VerifyRequest::partial`].
///
/// # Errors
/// No program; more tools than programs; a tool spec that does not parse (naming
/// `--tool` and its position); a part, machine or program that cannot be read
/// (naming its file); a head machine without a tool length; a program with no cutter
/// (neither a tool nor a CUTTER record); the errors of [`verify_and_write`].
pub fn verify_request(req: &VerifyRequest<'_>, progress: &dyn Progress) -> Result<Verified> {
    verify_request_with(req, progress, &[])
}

/// [`verify_request`] with `extra` files (name relative to `req.out`, bytes) staged
/// in the same output set, written with the reports or not at all.
///
/// # Errors
/// As [`verify_request`].
pub fn verify_request_with(
    req: &VerifyRequest<'_>,
    progress: &dyn Progress,
    extra: &[(&str, Vec<u8>)],
) -> Result<Verified> {
    let mut out = Outputs::new(req.out);
    let mut done = verify_with(req, |model, stages, opts, context| {
        verify_and_write(model, stages, opts, (&mut out, ""), context, progress)
    })?;
    done.written = done.context.stopped.is_none() || req.partial;
    if done.written {
        for (name, bytes) in extra {
            out.write(name, bytes)?;
        }
        out.commit()?;
    }
    Ok(done)
}

/// [`verify_request`] without writing anything (`req.out` and `req.partial` are not
/// used): the verification as values, for callers that take the report and the
/// deviation grid as data (the Python package). The report is
/// [`swarf_sim::report::json_report`] of the result and its context, as in
/// `report.json`.
///
/// # Errors
/// As [`verify_request`], less the outputs.
pub fn verify_in_memory(req: &VerifyRequest<'_>, progress: &dyn Progress) -> Result<Verified> {
    verify_with(req, |model, stages, opts, _| {
        Ok(swarf_sim::verify_stages(
            design_of(model),
            stages,
            opts,
            progress,
        )?)
    })
}

/// The design a model gives the verifier.
pub(crate) fn design_of(model: &Model) -> Design<'_> {
    match model {
        Model::Patches(p) => Design::Part(p),
        Model::Mesh { mesh, .. } => Design::Mesh(mesh),
    }
}

/// The programs cut into one stage per tool (a program that changes tools gives a
/// stage per tool, [`swarf_nc::read::Program::split_by_tool`]) and the `--tool` of
/// each stage, in order.
///
/// # Errors
/// More `--tool`s than stages; a program that changes tools without a `--tool` for
/// each of its tools (the last `--tool` would stand for them wrongly); a bad spec.
fn split_by_tool(programs: Vec<Program>, specs: &[String]) -> Result<(Vec<Program>, Vec<Cutter>)> {
    let changing: Vec<String> = programs
        .iter()
        .filter(|p| p.tools.len() > 1)
        .map(|p| {
            let t: Vec<String> = p
                .tools
                .iter()
                .map(|t| format!("T{} at line {}", t.number, t.line))
                .collect();
            format!("{} ({})", p.source, t.join(", "))
        })
        .collect();
    let programs: Vec<Program> = programs
        .into_iter()
        .flat_map(Program::split_by_tool)
        .collect();
    let tools = parse_tools(specs, programs.len())?;
    if !changing.is_empty() && tools.len() < programs.len() {
        bail!(
            "--tool: {} for {} tools: {} changes tools; give a --tool for each tool, in the \
             order the programs cut with them",
            tools.len(),
            programs.len(),
            changing.join("; ")
        );
    }
    Ok((programs, tools))
}

/// Reads the programs of `req` and runs `verify` on them (module doc of
/// [`verify_request`]); [`Verified::written`] is left false.
fn verify_with<F>(req: &VerifyRequest<'_>, verify: F) -> Result<Verified>
where
    F: FnOnce(&Model, &[Stage<'_>], &VerifyOptions, &ReportContext) -> Result<Verification>,
{
    if req.programs.is_empty() {
        bail!("--program: give at least one NC program to verify");
    }
    let model = load_model(req.part)?;
    model.check_covers_xy(req.part)?;
    let planned = planned(req.programs)?;
    let opts = req.sim.program_options(&planned)?;
    let (machine, tool_length) = match (req.machine, &planned.machine) {
        (Some(m), _) => (Some(m), req.tool_length),
        (None, Some((m, l))) => (Some(m.as_str()), req.tool_length.or(*l)),
        (None, None) => (None, req.tool_length),
    };
    let (programs, mut notes) = read_programs(
        req.programs,
        req.gcode,
        machine,
        tool_length,
        opts.sample_tol(),
    )?;
    let specs = if req.tools.is_empty() {
        &planned.tools
    } else {
        req.tools
    };
    let (mut programs, tools) = split_by_tool(programs, specs)?;
    let stated = if planned.records > 0 {
        "its plan record"
    } else {
        "its header"
    };
    match (req.sim.scallop, planned.scallop) {
        (Some(_), _) => {}
        (None, Some(h)) => notes.push(format!(
            "note: scallop allowance {h} mm, as the program states it was planned ({stated}; --scallop to change)"
        )),
        (None, None) => notes.push(
            "note: no --scallop and no planned scallop in the program: any material more than \
             the tolerance above the design counts as excess"
                .to_string(),
        ),
    }
    if let Some(k) = programs.iter().position(|p| p.stopped.is_some())
        && k + 1 < programs.len()
    {
        let skipped: Vec<String> = programs.drain(k + 1..).map(|p| p.source).collect();
        notes.push(format!(
            "note: {} not simulated: {} stopped before its end",
            skipped.join(", "),
            programs[k].source
        ));
    }
    let cutters = stage_cutters(&tools, &programs)?;
    let stages: Vec<Stage<'_>> = programs
        .iter()
        .zip(&cutters)
        .map(|(program, cutter)| Stage { program, cutter })
        .collect();
    let context = context(req.part, &stages, &opts);
    // A grid that cannot be laid over the design is the part's doing: name it.
    let verification = verify(&model, &stages, &opts, &context).map_err(|e| match e {
        AppError::Sim(
            swarf_sim::SimError::GridTooLarge { .. }
            | swarf_sim::SimError::NoMemory { .. }
            | swarf_sim::SimError::Empty(_),
        ) => AppError::Message(format!("{}: {e}", req.part)),
        e => e,
    })?;
    Ok(Verified {
        verification,
        context,
        notes,
        written: false,
    })
}

/// What the report says about the inputs: with several stages, the programs and
/// tools joined by " + ", and every program's warnings.
pub fn context(part: &str, stages: &[Stage<'_>], opts: &VerifyOptions) -> ReportContext {
    let joined =
        |f: &dyn Fn(&Stage<'_>) -> String| stages.iter().map(f).collect::<Vec<_>>().join(" + ");
    ReportContext {
        part: part.to_string(),
        program: joined(&|s| s.program.source.clone()),
        tool: joined(&|s| s.cutter.to_string()),
        stock: opts.stock.describe(),
        warnings: stages
            .iter()
            .flat_map(|s| s.program.warnings.iter().map(|w| s.program.located(w)))
            .collect(),
        stopped: stages.iter().find_map(|s| {
            let p = s.program;
            p.stopped.as_ref().map(|d| p.located(d))
        }),
    }
}

/// Verifies `stages` (programs run in order on one stock, each with its cutter) and
/// stages `{prefix}report.json`, `{prefix}flagged.csv`, `{prefix}deviation.png` and
/// `{prefix}toolpath.png` in `to = (outputs, prefix)`.
///
/// # Errors
/// No stage; a verification that cannot run (grid too large, ...); an output that
/// cannot be written.
pub fn verify_and_write(
    model: &Model,
    stages: &[Stage<'_>],
    opts: &VerifyOptions,
    to: (&mut Outputs, &str),
    ctx: &ReportContext,
    progress: &dyn Progress,
) -> Result<Verification> {
    let (out, prefix) = to;
    let v = swarf_sim::verify_stages(design_of(model), stages, opts, progress)?;
    let file = |name: &str| format!("{prefix}{name}");
    out.write_json(file("report.json"), &json_report(&v, ctx))?;
    out.write(file("flagged.csv"), flagged_csv(&v).as_bytes())?;
    let name = stages
        .iter()
        .map(|s| {
            let source = &s.program.source;
            Path::new(source)
                .file_name()
                .map_or(source.clone(), |n| n.to_string_lossy().into_owned())
        })
        .collect::<Vec<_>>()
        .join(" + ");
    let mode = if v.along_normals {
        "normal"
    } else {
        "vertical"
    };
    let title = format!(
        "{mode} deviation: {name}, {}, tol {} mm",
        ctx.tool, v.deviation.summary.tol
    );
    out.write(
        file("deviation.png"),
        &swarf_report::picture::deviation_png(&v, &title)?,
    )?;
    let title = format!("tool path: {name}, {}", ctx.tool);
    let motions: Vec<Motion> = stages
        .iter()
        .flat_map(|s| s.program.motions.iter().copied())
        .collect();
    let png = swarf_report::picture::toolpath_png(&v, &motions, &title)?;
    out.write(file("toolpath.png"), &png)?;
    Ok(v)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stock_specs() {
        assert_eq!(parse_stock("box").unwrap(), StockSpec::Box { top: None });
        assert_eq!(
            parse_stock("box:12.5").unwrap(),
            StockSpec::Box { top: Some(12.5) }
        );
        assert_eq!(
            parse_stock("offset:0.5").unwrap(),
            StockSpec::Offset { allowance: 0.5 }
        );
        for bad in ["offset:-1", "offset:x", "box:nan", "cylinder", "stock.step"] {
            assert!(parse_stock(bad).is_err(), "{bad}");
        }
    }
}
