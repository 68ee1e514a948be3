//! Verifying a program against the design: the settings a user gives, the stock, the
//! machine a five-axis G-code program was posted for, and the reports and pictures
//! written for it.
//!
//! Five-axis G-code (`X Y Z` and two rotary words) needs the machine it was posted
//! for: `--machine FILE` (or `builtin:NAME`) and, for machines with head axes,
//! `--tool-length MM`. The G-code's axis positions then go through the machine's
//! forward kinematics into part-frame poses ([`read_with_machine`]). APT CL and pose
//! CSV programs are in the part frame already: the machine is not needed for them.

use crate::error::{AppError, Context, Result, bail};
use crate::model::{Model, load_model};
use std::path::Path;
use swarf_fiveaxis::machine::reader::MachineKinematics;
use swarf_fiveaxis::machine::{Machine, MachineKind, load_machine};
use swarf_nc::read::{GcodeReadOptions, Program, ProgramFormat, read_program, read_program_with};
use swarf_sim::report::{ReportContext, flagged_csv, json_report};
use swarf_sim::{Design, Progress, StockSpec, Verification, VerifyOptions};
use swarf_tool::Cutter;

/// Verification settings as a user gives them (`swarf verify` and `swarf compare`
/// flags): each absent one takes a default from the job or the command.
#[derive(Debug, Clone, PartialEq)]
pub struct SimSettings {
    /// Stock: box, box:TOP, offset:ALLOWANCE (mm above the design) or a mesh file.
    pub stock: String,
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
    /// How deviation is measured: `vertical` (along z) or `normal` (along the design
    /// normals, "mow the grass"; the scallop height of paper 004). Default: vertical
    /// for verify, normal for compare.
    pub deviation: Option<String>,
}

impl Default for SimSettings {
    /// The command-line defaults (for callers such as `swarf demo`).
    fn default() -> Self {
        SimSettings {
            stock: "offset:0.5".into(),
            cell: None,
            tol: None,
            scallop: None,
            rapid: None,
            sample_tol: None,
            max_memory: 4096,
            deviation: None,
        }
    }
}

impl SimSettings {
    /// Defaults with cell size `cell` (mm), measuring along the normals.
    pub fn normal_with_cell(cell: f64) -> SimSettings {
        SimSettings {
            cell: Some(cell),
            deviation: Some("normal".into()),
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
        for (flag, v) in [
            ("--cell", self.cell),
            ("--tol", self.tol),
            ("--sample-tol", self.sample_tol),
        ] {
            if let Some(x) = v
                && !(x.is_finite() && x > 0.0)
            {
                bail!("{flag}: expected a finite number > 0 mm, found {x}");
            }
        }
        Ok(VerifyOptions {
            cell: self.cell,
            tol: self.tol.unwrap_or(tol),
            allowed_excess: self.scallop.unwrap_or(scallop),
            stock: parse_stock(&self.stock)?,
            max_bytes: self.max_memory.saturating_mul(1 << 20),
            sample_tol: self.sample_tol,
            rapid_rate: self.rapid.unwrap_or(rapid),
            along_normals: self
                .deviation
                .as_deref()
                .map_or(along_normals, |d| d == "normal"),
            ..VerifyOptions::default()
        })
    }
}

/// Parses `--stock`: `box`, `box:TOP`, `offset:ALLOWANCE` or a mesh file.
///
/// # Errors
/// Anything else, naming `--stock`.
pub fn parse_stock(text: &str) -> Result<StockSpec> {
    let number = |s: &str, what: &str| -> Result<f64> {
        s.trim()
            .parse::<f64>()
            .ok()
            .filter(|v| v.is_finite())
            .with_context(|| format!("--stock {text}: {what} {s:?} is not a finite number"))
    };
    if text == "box" {
        return Ok(StockSpec::Box { top: None });
    }
    if let Some(top) = text.strip_prefix("box:") {
        return Ok(StockSpec::Box {
            top: Some(number(top, "top")?),
        });
    }
    if let Some(a) = text.strip_prefix("offset:") {
        let allowance = number(a, "allowance")?;
        if allowance < 0.0 {
            bail!("--stock {text}: the allowance must be >= 0 mm");
        }
        return Ok(StockSpec::Offset { allowance });
    }
    let path = Path::new(text);
    match path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase)
    {
        Some(e) if e == "stl" || e == "obj" => Ok(StockSpec::Mesh(swarf_io::read_mesh(path)?)),
        _ => bail!("--stock {text}: expected box, box:TOP, offset:ALLOWANCE or a .stl / .obj mesh"),
    }
}

/// A verification as `swarf verify` asks for it.
#[derive(Debug, Clone, Copy)]
pub struct VerifyRequest<'a> {
    /// Design part: a part file, a mesh or a built-in part name.
    pub part: &'a str,
    /// NC program: G-code, APT CL or pose CSV.
    pub program: &'a Path,
    /// Tool spec (default: the program's CUTTER record).
    pub tool: Option<&'a str>,
    /// Machine file or `builtin:NAME` for five-axis G-code.
    pub machine: Option<&'a str>,
    /// Spindle gauge line to tool tip, mm (machines with head axes).
    pub tool_length: Option<f64>,
    /// Verification settings.
    pub sim: &'a SimSettings,
    /// Output directory.
    pub out: &'a Path,
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
}

/// Reads and verifies the program of `req`, writing the reports and pictures under
/// `req.out` ([`verify_and_write`]).
///
/// # Errors
/// A part, machine or program that cannot be read; a head machine without a tool
/// length; a program that names no cutter when no tool is given; the errors of
/// [`verify_and_write`].
pub fn verify_request(req: &VerifyRequest<'_>, progress: &dyn Progress) -> Result<Verified> {
    let model = load_model(req.part)?;
    let opts = req.sim.options(0.01, 0.0, 5000.0, false)?;
    let mut notes = Vec::new();
    let machine = match req.machine {
        Some(spec) if ProgramFormat::of(req.program) == Some(ProgramFormat::Gcode) => {
            Some(machine_arg(spec)?)
        }
        Some(spec) => {
            notes.push(format!(
                "note: --machine {spec} ignored: {} is not G-code, its poses are in the \
                 part frame already",
                req.program.display()
            ));
            None
        }
        None => None,
    };
    let tool_length = match (&machine, req.tool_length) {
        (Some(m), None) if m.kind != MachineKind::TableTable => bail!(
            "--tool-length: the machine {:?} has head axes: give the tool length from the \
             spindle gauge line to the tip, in mm",
            m.name
        ),
        (_, length) => length.unwrap_or(0.0),
    };
    let sample_tol = opts.sample_tol.unwrap_or(0.25 * opts.tol);
    let program = read_with_machine(req.program, machine.as_ref(), tool_length, sample_tol)?;
    let cutter = match (req.tool, &program.tool) {
        (Some(spec), _) => spec
            .parse::<Cutter>()
            .map_err(|e| AppError::Message(format!("--tool {spec}: {e}")))?,
        (None, Some(t)) => *t,
        (None, None) => bail!(
            "{}: the program names no cutter (no APT CUTTER record): give the tool with --tool, e.g. --tool ball:d=8",
            program.source
        ),
    };
    let context = context(req.part, &program, &cutter, &opts);
    let verification = verify_and_write(
        &model,
        &program,
        &cutter,
        &opts,
        Destination {
            dir: req.out,
            prefix: "",
        },
        &context,
        progress,
    )?;
    Ok(Verified {
        verification,
        context,
        notes,
    })
}

/// Reads the program at `path`; a G-code program through `machine`'s forward
/// kinematics when given (five-axis moves split into motions within `tol` of the tool
/// tip's path), with a tool `tool_length` long from the gauge line to the tip
/// (machines with head axes). APT CL and pose CSV programs are read as they are.
///
/// # Units
/// mm.
///
/// # Errors
/// A program file that cannot be read; a tool length that is not a length.
pub fn read_with_machine(
    path: &Path,
    machine: Option<&Machine>,
    tool_length: f64,
    tol: f64,
) -> Result<Program> {
    let Some(machine) = machine else {
        return Ok(read_program(path)?);
    };
    let kinematics = MachineKinematics::new(machine.clone(), tool_length)?;
    let opts = GcodeReadOptions {
        kinematics: Some(&kinematics),
        kinematics_tol: tol,
        ..GcodeReadOptions::default()
    };
    Ok(read_program_with(path, &opts)?)
}

/// The machine `--machine` names: `builtin:NAME` or a machine file.
///
/// # Errors
/// A file that cannot be read or parsed; an unknown built-in name.
pub fn machine_arg(spec: &str) -> Result<Machine> {
    if spec.starts_with("builtin:") {
        return Ok(load_machine(spec, Path::new(""))?);
    }
    let text = std::fs::read_to_string(spec)
        .with_context(|| format!("--machine {spec}: cannot read the machine file"))?;
    Ok(Machine::parse(&text, spec)?)
}

/// What the report says about the inputs.
pub fn context(
    part: &str,
    program: &Program,
    cutter: &Cutter,
    opts: &VerifyOptions,
) -> ReportContext {
    ReportContext {
        part: part.to_string(),
        program: program.source.clone(),
        tool: cutter.to_string(),
        stock: opts.stock.describe(),
        warnings: program
            .warnings
            .iter()
            .map(|w| program.located(w))
            .collect(),
        stopped: program.stopped.as_ref().map(|d| program.located(d)),
    }
}

/// Where a verification's files go: `dir/{prefix}report.json`, ...
#[derive(Debug, Clone, Copy)]
pub struct Destination<'a> {
    /// Output directory (created when missing).
    pub dir: &'a Path,
    /// Prefix of every file name.
    pub prefix: &'a str,
}

/// Verifies and writes `{prefix}report.json`, `{prefix}flagged.csv`,
/// `{prefix}deviation.png` and `{prefix}toolpath.png` under `to.dir`.
///
/// # Errors
/// A verification that cannot run (grid too large, ...); an output that cannot be
/// written.
pub fn verify_and_write(
    model: &Model,
    program: &Program,
    cutter: &Cutter,
    opts: &VerifyOptions,
    to: Destination<'_>,
    ctx: &ReportContext,
    progress: &dyn Progress,
) -> Result<Verification> {
    let (out, prefix) = (to.dir, to.prefix);
    let design = match model {
        Model::Patches(p) => Design::Part(p),
        Model::Mesh { mesh, .. } => Design::Mesh(mesh),
    };
    let v = swarf_sim::verify(design, program, cutter, opts, progress)?;
    std::fs::create_dir_all(out)
        .with_context(|| format!("{}: cannot create the output directory", out.display()))?;
    let file = |name: &str| out.join(format!("{prefix}{name}"));
    let json = serde_json::to_string_pretty(&json_report(&v, ctx))? + "\n";
    swarf_io::write_atomic(&file("report.json"), json.as_bytes())?;
    swarf_io::write_atomic(&file("flagged.csv"), flagged_csv(&v).as_bytes())?;
    let name = Path::new(&ctx.program)
        .file_name()
        .map_or(ctx.program.clone(), |n| n.to_string_lossy().into_owned());
    let mode = if v.along_normals {
        "normal"
    } else {
        "vertical"
    };
    let title = format!(
        "{mode} deviation: {name}, {}, tol {} mm",
        ctx.tool, v.deviation.summary.tol
    );
    swarf_io::write_atomic(
        &file("deviation.png"),
        &swarf_report::picture::deviation_png(&v, &title)?,
    )?;
    let title = format!("tool path: {name}, {}", ctx.tool);
    let png = swarf_report::picture::toolpath_png(&v, &program.motions, &title)?;
    swarf_io::write_atomic(&file("toolpath.png"), &png)?;
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
