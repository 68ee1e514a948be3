//! `swarf verify --part P --program PROG [--program PROG2 ...] -o DIR`: simulate a
//! program (or several in sequence on one stock, e.g. a finish then its cleanup, each
//! with its own `--tool`) on a dexel stock and measure the result against the design
//! ([`swarf_app::verify`]); writes `report.json`, `flagged.csv`, `deviation.png` and
//! `toolpath.png`. A program that stops mid-way still gets its partial report, then
//! the command fails.

use super::help::note;
use crate::progress::Bars;
use anyhow::{Result, bail};
use std::path::{Path, PathBuf};
use swarf_app::holder;
use swarf_app::verify::{GcodeSetup, SimSettings, VerifyRequest, verify_request_with};
use swarf_sim::report::text_summary;

/// Arguments of `swarf verify`.
#[derive(clap::Args)]
#[command(
    mut_arg("tol", |a| note(a, "(default: the tolerance the program states it was planned for by swarf, else 0.01)")),
    mut_arg("scallop", |a| note(a, "(default: the scallop the program states it was planned for by swarf, else 0)")),
    mut_arg("floor", |a| note(a, "(no floor check without it)")),
)]
pub struct Args {
    #[arg(long, help = super::help::part("Design part", super::help::Reads::Model))]
    part: String,
    /// NC program: G-code (.ngc, .nc, .tap, .gcode), APT CL (.cl, .apt, .cls) or pose
    /// CSV. Give it several times to run programs one after the other on the same
    /// stock (a finish, then its cleanup): one report for the result.
    #[arg(long, required = true)]
    program: Vec<PathBuf>,
    /// Tool spec, e.g. ball:d=8; the n-th --tool goes with the n-th --program, and
    /// a program that changes tools (T.. M6) takes one --tool per tool, in order. A
    /// program past the last --tool uses its own CUTTER record, else the last --tool
    /// (default: the program's CUTTER record).
    #[arg(long)]
    tool: Vec<String>,
    /// Tool library (TOML, see tooling/library.toml): each --tool is then a tool's
    /// name or T number in it (without --tool, each tool section's T word is looked
    /// up), and verify adds the holder and shank check of every tool section
    /// (holder.json: collisions, the shortest stick-out that clears).
    #[arg(long)]
    tool_library: Option<PathBuf>,
    /// Machine file (TOML) or builtin:NAME for five-axis G-code: the programs' X Y Z
    /// and rotary words are this machine's axes (every G-code program; not needed for
    /// APT CL or pose CSV).
    #[arg(long)]
    machine: Option<String>,
    /// Tool length from the spindle gauge line to the tip, mm (machines with head
    /// axes, whose programs position the head).
    #[arg(long, requires = "machine")]
    tool_length: Option<f64>,
    #[command(flatten)]
    gcode: GcodeArgs,
    #[command(flatten)]
    sim: SimArgs,
    /// When a program stops before its end, still write the reports (covering the
    /// motions before the stop); without it nothing is written and the previous
    /// reports stay whole.
    #[arg(long)]
    partial: bool,
    /// Output directory.
    #[arg(short = 'o', long = "out")]
    out: PathBuf,
}

/// How G-code programs are read.
#[derive(clap::Args, Clone)]
pub struct GcodeArgs {
    /// The language of G-code programs: linuxcnc (RS274/NGC as LinuxCNC 2.9 reads it:
    /// parameters, expressions, O-word subroutines and loops, canned cycles, cutter
    /// compensation, offsets), fanuc (Fanuc macro B: IF/GOTO, WHILE/DO, M98/M99, G65) or
    /// heidenhain (conversational, as swarf's Heidenhain post writes it; `.h` files are
    /// read so whatever this says).
    #[arg(long, default_value = "linuxcnc", value_parser = ["linuxcnc", "fanuc", "heidenhain"])]
    dialect: String,
    /// Tool table in LinuxCNC's format (`T1 P1 D6.35 Z50 ;comment`): cutter
    /// compensation radii (G41/G42 D) and tool length offsets (G43 H).
    #[arg(long)]
    tool_table: Option<PathBuf>,
    /// LinuxCNC parameter file (.var: `number value` lines): parameters at the start
    /// (work offsets #5221.., G28/G30 positions #5161.., #500..).
    #[arg(long)]
    params: Option<PathBuf>,
    /// Folder searched for subroutine files (`o<name> call` reads name.ngc; Fanuc
    /// M98 P1234 reads O1234.nc); give it several times; the program's own folder is
    /// searched last.
    #[arg(long)]
    sub_path: Vec<PathBuf>,
    /// Units of the tool table and the parameter file (LinuxCNC's standalone rs274
    /// is an inch machine).
    #[arg(long, default_value = "mm", value_parser = ["mm", "inch"])]
    machine_units: String,
}

impl Default for GcodeArgs {
    fn default() -> Self {
        GcodeArgs {
            dialect: "linuxcnc".into(),
            tool_table: None,
            params: None,
            sub_path: Vec::new(),
            machine_units: "mm".into(),
        }
    }
}

impl GcodeArgs {
    /// The reading setup these flags give, with the files they name read.
    ///
    /// # Errors
    /// A file that cannot be read or parsed, naming it.
    pub fn setup(&self) -> Result<GcodeSetup> {
        Ok(GcodeSetup::load(
            &self.dialect,
            &self.machine_units,
            self.tool_table.as_deref(),
            self.params.as_deref(),
            &self.sub_path,
        )?)
    }
}

/// Options shared by `verify`, `compare` and `view`; each command adds its defaults
/// to the help ([`super::help::note`]).
#[derive(clap::Args, Clone)]
pub struct SimArgs {
    /// Stock: box, box:TOP, offset:ALLOWANCE (mm above the design) or a mesh file.
    #[arg(long, default_value = "offset:0.5")]
    stock: String,
    /// Cell size, mm (default: 5 x the tolerance).
    #[arg(long)]
    cell: Option<f64>,
    /// Gouge / excess tolerance, mm.
    #[arg(long)]
    tol: Option<f64>,
    /// Material allowed above the design before it counts as excess (the scallop
    /// limit), mm.
    #[arg(long)]
    scallop: Option<f64>,
    /// Machine rapid rate for the time estimate, mm/min.
    #[arg(long)]
    rapid: Option<f64>,
    /// Distance bound for sampled motions (arcs, five-axis), mm (default: tol / 4).
    #[arg(long)]
    sample_tol: Option<f64>,
    /// Memory limit for the grid, MiB.
    #[arg(long, default_value_t = 4096)]
    max_memory: u64,
    /// How deviation is measured: `vertical` (along z) or `normal` (along the design
    /// normals, "mow the grass": the scallop height; the default).
    #[arg(long)]
    deviation: Option<String>,
    /// Sample five-axis motions by the first-order bound alone (the slow reference
    /// sweep; the default samples ball and bull cutters to a second-order bound where
    /// their flat top stays clear of the stock)
    #[arg(long)]
    first_order_sweep: bool,
    /// The lowest height the tool may reach, mm: every motion whose tool goes lower
    /// by more than the tolerance is reported.
    #[arg(long, allow_hyphen_values = true)]
    floor: Option<f64>,
}

impl SimArgs {
    /// The settings these flags give (stock and deviation parsed as Python's
    /// keywords are, so that both say the same of a bad value).
    ///
    /// # Errors
    /// A stock or deviation neither names.
    pub fn settings(&self) -> Result<SimSettings> {
        Ok(SimSettings {
            stock: self.stock.parse()?,
            cell: self.cell,
            tol: self.tol,
            scallop: self.scallop,
            rapid: self.rapid,
            sample_tol: self.sample_tol,
            max_memory: self.max_memory,
            deviation: self.deviation.as_deref().map(str::parse).transpose()?,
            first_order_sweep: self.first_order_sweep,
            floor: self.floor,
        })
    }
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    if let Some(l) = args.tool_length {
        super::check_flags(&[("--tool-length", l, swarf_geom::domain::TOOL_LENGTH)])?;
    }
    let sim = args.sim.settings()?;
    let gcode = args.gcode.setup()?;
    let tools = match &args.tool_library {
        Some(library) => holder::library_specs(&holder_request(args, library, &gcode, sim.tol))?,
        None => args.tool.clone(),
    };
    let req = VerifyRequest {
        part: &args.part,
        programs: &args.program,
        tools: &tools,
        gcode: &gcode,
        machine: args.machine.as_deref(),
        tool_length: args.tool_length,
        sim: &sim,
        out: &args.out,
        partial: args.partial,
    };
    // The holder check is staged with the reports: holder.json is written with them
    // or not at all.
    let holder = match &args.tool_library {
        Some(library) => Some(holder_check(args, library, &gcode, sim.tol)?),
        None => None,
    };
    let extra: Vec<(&str, Vec<u8>)> = holder
        .as_ref()
        .map(|(_, json)| ("holder.json", json.clone()))
        .into_iter()
        .collect();
    let done = verify_request_with(&req, &Bars::default(), &extra)?;
    for note in &done.notes {
        eprintln!("{note}");
    }
    print!("{}", text_summary(&done.verification, &done.context));
    for line in holder.iter().flat_map(|(lines, _)| lines) {
        println!("{line}");
    }
    match (&done.context.stopped, done.written) {
        (Some(stop), false) => bail!(
            "the program stopped at {stop}: no report was written and the previous reports \
             in {} are unchanged (--partial writes the report of the motions before the stop)",
            args.out.display()
        ),
        (Some(stop), true) => {
            println!("reports in {}", args.out.display());
            bail!("the program stopped at {stop}; the report covers the motions before it")
        }
        (None, _) => println!("reports in {}", args.out.display()),
    }
    Ok(())
}

/// What the holder check of `--tool-library` reads.
fn holder_request<'a>(
    args: &'a Args,
    library: &'a Path,
    gcode: &'a GcodeSetup,
    tol: Option<f64>,
) -> holder::HolderRequest<'a> {
    holder::HolderRequest {
        part: &args.part,
        programs: &args.program,
        library,
        tools: &args.tool,
        gcode,
        machine: args.machine.as_deref(),
        tool_length: args.tool_length,
        tol: tol.unwrap_or(0.01),
        spacing: holder::POSE_SPACING,
    }
}

/// The holder check of `--tool-library`: a summary per tool section of each program
/// and `holder.json`.
fn holder_check(
    args: &Args,
    library: &Path,
    gcode: &GcodeSetup,
    tol: Option<f64>,
) -> Result<(Vec<String>, Vec<u8>)> {
    let checks = holder::check_request(&holder_request(args, library, gcode, tol))?;
    let lines = checks.iter().map(holder::HolderCheck::summary).collect();
    Ok((lines, serde_json::to_vec_pretty(&checks)?))
}

#[cfg(test)]
mod tests;
