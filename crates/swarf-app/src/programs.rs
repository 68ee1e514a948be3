//! The programs of a verification: reading them (five-axis G-code through the
//! machine it was posted for) and matching the `--tool` specs to them.
//!
//! Tools go with programs in order: the k-th `--tool` is the k-th program's cutter.
//! A program past the last `--tool` uses its own APT CUTTER record, or, without one,
//! the last `--tool` given (so one `--tool` serves several G-code programs cut with
//! the same tool). More tools than programs is an error, and so is a program with
//! neither a tool nor a CUTTER record.

use crate::error::{AppError, Context, Result, bail};
use std::path::{Path, PathBuf};
use swarf_fiveaxis::machine::reader::MachineKinematics;
use swarf_fiveaxis::machine::{Machine, MachineKind, load_machine};
use swarf_geom::domain::excerpt;
use swarf_io::Source;
use swarf_nc::Language;
use swarf_nc::read::{
    GcodeReadOptions, Program, ProgramFormat, ToolTable, parse_var_file, read_program_with,
};
use swarf_tool::Cutter;

/// How G-code is read: the language, the machine's units, tool table and parameter
/// file, and where subroutine files are (`--dialect`, `--machine-units`,
/// `--tool-table`, `--params`, `--sub-path`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct GcodeSetup {
    /// LinuxCNC's RS274/NGC, Fanuc macro B or Heidenhain conversational.
    pub dialect: Language,
    /// Tool table and parameter values are in inches.
    pub machine_inch: bool,
    /// The tool table (LinuxCNC's format), if given.
    pub tool_table: Option<ToolTable>,
    /// Parameter values at the start (a LinuxCNC var file).
    pub parameters: Vec<(usize, f64)>,
    /// Folders searched for subroutine files, in order.
    pub sub_path: Vec<PathBuf>,
}

impl GcodeSetup {
    /// Reads the tool table and parameter file named, if any; `dialect` is `linuxcnc`,
    /// `fanuc` or `heidenhain`, `machine_units` `mm` or `inch`.
    ///
    /// # Errors
    /// A file that cannot be read or parsed (naming it, with line and column); a
    /// folder of the search path that does not exist; an unknown dialect or unit.
    pub fn load(
        dialect: &str,
        machine_units: &str,
        tool_table: Option<&Path>,
        params: Option<&Path>,
        sub_path: &[PathBuf],
    ) -> Result<Self> {
        let Some(dialect) = Language::named(dialect) else {
            bail!("--dialect {dialect}: expected linuxcnc, fanuc or heidenhain");
        };
        let machine_inch = match machine_units {
            "mm" => false,
            "inch" => true,
            other => bail!("--machine-units {other}: expected mm or inch"),
        };
        let read = |flag: &str, p: &Path| {
            swarf_io::read_input_text(p).with_context(|| format!("{flag} {}", p.display()))
        };
        let tool_table = match tool_table {
            Some(p) => Some(ToolTable::parse(
                &read("--tool-table", p)?,
                &p.display().to_string(),
            )?),
            None => None,
        };
        let parameters = match params {
            Some(p) => parse_var_file(&read("--params", p)?, &p.display().to_string())?,
            None => Vec::new(),
        };
        if let Some(d) = sub_path.iter().find(|d| !d.is_dir()) {
            bail!("--sub-path {}: not a folder", d.display());
        }
        Ok(GcodeSetup {
            dialect,
            machine_inch,
            tool_table,
            parameters,
            sub_path: sub_path.to_vec(),
        })
    }

    /// The G-code reader's options for this setup.
    pub fn options(&self) -> GcodeReadOptions<'_> {
        GcodeReadOptions {
            language: self.dialect,
            tool_table: self.tool_table.as_ref(),
            machine_inch: self.machine_inch,
            parameters: &self.parameters,
            sub_path: &self.sub_path,
            ..GcodeReadOptions::default()
        }
    }
}

/// Reads the programs at `paths`, G-code ones through the machine `machine` names
/// (`--machine`) when given, with a tool `tool_length` long (`--tool-length`, mm;
/// machines with head axes) and five-axis moves split within `sample_tol` mm. The
/// notes say where the machine does not apply.
///
/// # Errors
/// A program or machine that cannot be read (naming its file); a head machine
/// without a tool length.
pub fn read_programs(
    paths: &[PathBuf],
    gcode: &GcodeSetup,
    machine: Option<&str>,
    tool_length: Option<f64>,
    sample_tol: f64,
) -> Result<(Vec<Program>, Vec<String>)> {
    let is_gcode = |p: &Path| ProgramFormat::of(p) == Some(ProgramFormat::Gcode);
    let mut notes = Vec::new();
    let machine = match machine {
        Some(spec) => {
            for p in paths.iter().filter(|p| !is_gcode(p)) {
                notes.push(format!(
                    "note: --machine {spec} ignored: {} is not G-code, its poses are in the \
                     part frame already",
                    p.display()
                ));
            }
            let any = paths.iter().any(|p| is_gcode(p));
            any.then(|| machine_arg(spec)).transpose()?
        }
        None => None,
    };
    let tool_length = match (&machine, tool_length) {
        (Some(m), None) if m.kind != MachineKind::TableTable => bail!(
            "--tool-length: the machine {:?} has head axes: give the tool length from the \
             spindle gauge line to the tip, in mm",
            m.name
        ),
        (_, length) => length.unwrap_or(0.0),
    };
    let programs = paths
        .iter()
        .map(|p| {
            let machine = machine.as_ref().filter(|_| is_gcode(p));
            read_with_machine(p, gcode, machine, tool_length, sample_tol)
        })
        .collect::<Result<Vec<_>>>()?;
    for p in &programs {
        notes.extend(p.messages.iter().map(|m| format!("{}: {}", p.source, m)));
    }
    Ok((programs, notes))
}

/// Parses the `--tool` specs, for `programs` programs.
///
/// # Errors
/// More tools than programs; a spec that does not parse, naming `--tool`, the spec
/// and (when there are several) its position.
pub fn parse_tools(specs: &[String], programs: usize) -> Result<Vec<Cutter>> {
    if specs.len() > programs {
        bail!(
            "--tool: {} tools for {} {}: each --tool goes with the --program at its \
             position",
            specs.len(),
            programs,
            if programs == 1 { "program" } else { "programs" }
        );
    }
    specs
        .iter()
        .enumerate()
        .map(|(k, spec)| {
            spec.parse::<Cutter>().map_err(|e| {
                let at = if specs.len() > 1 {
                    format!(" (tool {} of {})", k + 1, specs.len())
                } else {
                    String::new()
                };
                AppError::Message(format!("--tool {}{at}: {e}", excerpt(spec, 60)))
            })
        })
        .collect()
}

/// The cutter of each program: the tool given at its position; past the tools given,
/// the program's own APT CUTTER record, else the last tool given.
///
/// # Errors
/// A program with neither, naming its file.
pub fn stage_cutters(tools: &[Cutter], programs: &[Program]) -> Result<Vec<Cutter>> {
    programs
        .iter()
        .enumerate()
        .map(
            |(k, program)| match (tools.get(k), &program.tool, tools.last()) {
                (Some(t), _, _) | (None, Some(t), _) | (None, None, Some(t)) => Ok(*t),
                (None, None, None) => bail!(
                    "{}: the program names no cutter (no APT CUTTER record): give the tool \
                 with --tool, e.g. --tool ball:d=8",
                    program.source
                ),
            },
        )
        .collect()
}

/// Reads the program at `path`; a G-code program through `machine`'s forward
/// kinematics when given (five-axis moves split into motions within `tol` of the tool
/// tip's path), with a tool `tool_length` long from the gauge line to the tip
/// (machines with head axes), read as `gcode` says. APT CL and pose CSV programs are
/// read as they are.
///
/// # Units
/// mm.
///
/// # Errors
/// A program file that cannot be read; a tool length that is not a length.
pub fn read_with_machine(
    path: &Path,
    gcode: &GcodeSetup,
    machine: Option<&Machine>,
    tool_length: f64,
    tol: f64,
) -> Result<Program> {
    let Some(machine) = machine else {
        return Ok(read_program_with(path, &gcode.options())?);
    };
    let kinematics = MachineKinematics::new(machine.clone(), tool_length)?;
    let opts = GcodeReadOptions {
        kinematics: Some(&kinematics),
        kinematics_tol: tol,
        ..gcode.options()
    };
    Ok(read_program_with(path, &opts)?)
}

/// The machine `--machine` names: `builtin:NAME` or a machine file.
///
/// # Errors
/// A file that cannot be read or parsed; an unknown built-in name.
pub fn machine_arg(spec: &str) -> Result<Machine> {
    if let Source::Builtin(_) = Source::parse(spec, Path::new("")) {
        return Ok(load_machine(spec, Path::new(""))?);
    }
    let text = swarf_io::read_input_text(Path::new(spec))
        .with_context(|| format!("--machine {spec}: cannot read the machine file"))?;
    Ok(Machine::parse(&text, spec)?)
}

/// The header comment in which swarf's G-code states the scallop its plan allows
/// (the job's limit, else the plan's predicted largest): `(scallop limit H mm)`.
pub const SCALLOP_COMMENT: &str = "scallop limit ";

/// The largest planned scallop stated by the G-code programs at `paths`
/// ([`SCALLOP_COMMENT`], in the first [`MAX_HEADER_LINES`] lines, read alone);
/// `None` where none states one or a program cannot be read (reading it reports
/// that).
fn header_scallop(paths: &[PathBuf]) -> Option<f64> {
    paths
        .iter()
        .filter(|p| ProgramFormat::of(p) == Some(ProgramFormat::Gcode))
        .filter_map(|p| swarf_io::checked_open(p, swarf_io::max_input_bytes()).ok())
        .filter_map(|file| {
            std::io::BufRead::lines(std::io::BufReader::new(file))
                .take(MAX_HEADER_LINES)
                .map_while(Result::ok)
                .find_map(|l| {
                    let rest = l.trim().strip_prefix('(')?.strip_prefix(SCALLOP_COMMENT)?;
                    rest.strip_suffix(" mm)")?.trim().parse::<f64>().ok()
                })
                .filter(|h| h.is_finite() && *h >= 0.0)
        })
        .reduce(f64::max)
}

/// What programs say they were planned for: their plan records
/// ([`crate::plan_record`]), else, for a G-code program without one, the scallop its
/// header states ([`SCALLOP_COMMENT`]). The defaults of a verification of them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Planned {
    /// The largest scallop any of them was planned for, mm.
    pub scallop: Option<f64>,
    /// The smallest tolerance they were planned with, mm (records only).
    pub tolerance: Option<f64>,
    /// Their tools in program order, when every program has a record.
    pub tools: Vec<String>,
    /// The machine of the first record that names one, and its tool length.
    pub machine: Option<(String, Option<f64>)>,
    /// How many programs have a record.
    pub records: usize,
}

/// What `paths` say they were planned for ([`Planned`]).
///
/// # Errors
/// A record that cannot be read.
pub fn planned(paths: &[PathBuf]) -> Result<Planned> {
    let mut p = Planned::default();
    let mut tools = Vec::new();
    for path in paths {
        let Some(r) = crate::plan_record::read_record(path)? else {
            p.scallop = max(p.scallop, header_scallop(std::slice::from_ref(path)));
            continue;
        };
        p.records += 1;
        p.scallop = max(p.scallop, r.scallop());
        p.tolerance = match (p.tolerance, r.tolerance()) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        tools.extend(r.tool_specs());
        if p.machine.is_none() {
            p.machine = r.machine.map(|m| (m, r.tool_length));
        }
    }
    if p.records == paths.len() {
        p.tools = tools;
    }
    Ok(p)
}

fn max(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    match (a, b) {
        (Some(a), Some(b)) => Some(a.max(b)),
        (a, b) => a.or(b),
    }
}

/// Header lines searched for [`SCALLOP_COMMENT`].
pub const MAX_HEADER_LINES: usize = 40;

#[cfg(test)]
mod tests {
    use super::*;

    fn specs(s: &[&str]) -> Vec<String> {
        s.iter().map(|t| (*t).to_string()).collect()
    }

    #[test]
    fn tool_errors_name_the_flag_and_position() {
        let e = parse_tools(&specs(&["ball:d=x"]), 1)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--tool ball:d=x: "), "{e}");
        let e = parse_tools(&specs(&["ball:d=6", "ball:q=2"]), 2)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--tool ball:q=2 (tool 2 of 2): "), "{e}");
        let e = parse_tools(&specs(&["ball:d=6", "ball:d=2"]), 1)
            .unwrap_err()
            .to_string();
        assert!(e.contains("--tool: 2 tools for 1 program"), "{e}");
        let two = parse_tools(&specs(&["ball:d=6", "flat:d=2"]), 3).unwrap();
        assert_eq!(two[1], "flat:d=2".parse::<Cutter>().unwrap());
    }

    #[test]
    fn tools_go_with_programs_in_order_then_cutter_records_then_the_last_tool() {
        let cutter = |s: &str| s.parse::<Cutter>().unwrap();
        let mut with_record = Program::new("b.cl");
        with_record.tool = Some(cutter("bull:d=10,r=1"));
        let programs = [Program::new("a.ngc"), with_record, Program::new("c.ngc")];
        let given = [cutter("ball:d=6")];
        let got = stage_cutters(&given, &programs).unwrap();
        assert_eq!(got, [given[0], cutter("bull:d=10,r=1"), given[0]]);
        let given = [cutter("ball:d=6"), cutter("ball:d=4"), cutter("ball:d=2")];
        assert_eq!(stage_cutters(&given, &programs).unwrap(), given);
        let e = stage_cutters(&[], &programs).unwrap_err().to_string();
        assert!(e.starts_with("a.ngc: the program names no cutter"), "{e}");
    }

    #[test]
    fn a_missing_program_names_its_file() {
        let dir = std::env::temp_dir().join(format!("swarf-programs-{}", std::process::id()));
        let paths = [dir.join("there.cl"), dir.join("missing.ngc")];
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(&paths[0], "CUTTER/6\nGOTO/0,0,5\nGOTO/1,0,5\n").unwrap();
        let e = read_programs(&paths, &GcodeSetup::default(), None, None, 0.01)
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing.ngc"), "{e}");
        let _ = std::fs::remove_dir_all(&dir);
    }
}
