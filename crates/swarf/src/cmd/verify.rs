//! `swarf verify --part P --program PROG -o DIR`: simulate a program on a dexel stock
//! and measure it against the design; writes `report.json`, `flagged.csv`,
//! `deviation.png` and `toolpath.png`. A program that stops mid-way still gets its
//! partial report, then the command fails.
//!
//! Five-axis G-code (`X Y Z` and two rotary words) needs the machine it was posted
//! for: `--machine FILE` (or `builtin:NAME`) and, for machines with head axes,
//! `--tool-length MM`. The G-code's axis positions then go through the machine's
//! forward kinematics into part-frame poses ([`read_with_machine`]). APT CL and pose
//! CSV programs are in the part frame already: `--machine` is not needed for them, and
//! is ignored with a note.

use crate::load::{Model, load_model};
use anyhow::{Context, Result, bail};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use swarf_fiveaxis::job::load_machine;
use swarf_fiveaxis::machine::reader::MachineKinematics;
use swarf_fiveaxis::machine::{Machine, MachineKind};
use swarf_nc::read::{GcodeReadOptions, Program, ProgramFormat, read_program, read_program_with};
use swarf_sim::report::{ReportContext, flagged_csv, json_report, text_summary};
use swarf_sim::{Design, Progress, StockSpec, Verification, VerifyOptions};
use swarf_tool::Cutter;

/// Arguments of `swarf verify`.
#[derive(clap::Args)]
pub struct Args {
    /// Design part: a part file (.toml), a mesh (.stl, .obj) or a built-in part name.
    #[arg(long)]
    part: String,
    /// NC program: G-code (.ngc, .nc, .tap, .gcode), APT CL (.cl, .apt, .cls) or pose CSV.
    #[arg(long)]
    program: PathBuf,
    /// Tool spec, e.g. ball:d=8 (default: the program's CUTTER record).
    #[arg(long)]
    tool: Option<String>,
    /// Machine file (TOML) or builtin:NAME for five-axis G-code: the program's X Y Z
    /// and rotary words are this machine's axes (not needed for APT CL or pose CSV).
    #[arg(long)]
    machine: Option<String>,
    /// Tool length from the spindle gauge line to the tip, mm (machines with head
    /// axes, whose programs position the head).
    #[arg(long, requires = "machine")]
    tool_length: Option<f64>,
    #[command(flatten)]
    sim: SimArgs,
    /// Output directory.
    #[arg(short = 'o', long = "out")]
    out: PathBuf,
}

/// Options shared by `verify` and `compare`.
#[derive(clap::Args, Clone)]
pub struct SimArgs {
    /// Stock: box, box:TOP, offset:ALLOWANCE (mm above the design) or a mesh file.
    #[arg(long, default_value = "offset:0.5")]
    stock: String,
    /// Cell size, mm (default: 5 x the tolerance).
    #[arg(long)]
    cell: Option<f64>,
    /// Gouge / excess tolerance, mm (compare: default from each job).
    #[arg(long)]
    tol: Option<f64>,
    /// Material allowed above the design before it counts as excess (the scallop
    /// limit), mm (compare: default from each job).
    #[arg(long)]
    scallop: Option<f64>,
    /// Machine rapid rate for the time estimate, mm/min (compare: default from each job).
    #[arg(long)]
    rapid: Option<f64>,
    /// Distance bound for sampled motions (arcs, five-axis), mm (default: tol / 4).
    #[arg(long)]
    sample_tol: Option<f64>,
    /// Memory limit for the grid, MiB.
    #[arg(long, default_value_t = 4096)]
    max_memory: u64,
    /// How deviation is measured: `vertical` (along z) or `normal` (along the design
    /// normals, "mow the grass"; the scallop height of paper 004). Default: vertical
    /// for verify, normal for compare.
    #[arg(long, value_parser = ["vertical", "normal"])]
    deviation: Option<String>,
}

impl Default for SimArgs {
    /// The command-line defaults (for callers such as `swarf demo`).
    fn default() -> Self {
        SimArgs {
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

impl SimArgs {
    /// Defaults with cell size `cell`, measuring along the normals (for tests).
    #[cfg(test)]
    pub fn for_tests(cell: f64) -> SimArgs {
        SimArgs {
            cell: Some(cell),
            deviation: Some("normal".into()),
            ..SimArgs::default()
        }
    }

    /// Verification options, with the given defaults where an option is absent.
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

/// Parses `--stock`.
fn parse_stock(text: &str) -> Result<StockSpec> {
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

/// Progress bars on stderr, hidden when stderr is not a terminal.
pub struct Bars {
    bar: Mutex<Option<ProgressBar>>,
}

impl Default for Bars {
    fn default() -> Self {
        Bars {
            bar: Mutex::new(None),
        }
    }
}

impl Progress for Bars {
    fn begin(&self, stage: &str, total: u64) {
        let target = if std::io::stderr().is_terminal() {
            ProgressDrawTarget::stderr()
        } else {
            ProgressDrawTarget::hidden()
        };
        let bar = ProgressBar::with_draw_target(Some(total), target);
        if let Ok(style) = ProgressStyle::with_template("{msg:>16} [{bar:40}] {percent:>3}% {eta}")
        {
            bar.set_style(style.progress_chars("=> "));
        }
        bar.set_message(stage.to_string());
        if let Ok(mut b) = self.bar.lock() {
            *b = Some(bar);
        }
    }

    fn advance(&self, n: u64) {
        if let Ok(b) = self.bar.lock()
            && let Some(bar) = b.as_ref()
        {
            bar.inc(n);
        }
    }

    fn end(&self) {
        if let Ok(mut b) = self.bar.lock()
            && let Some(bar) = b.take()
        {
            bar.finish_and_clear();
        }
    }
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let model = load_model(&args.part)?;
    let opts = args.sim.options(0.01, 0.0, 5000.0, false)?;
    let machine = match &args.machine {
        Some(spec) if ProgramFormat::of(&args.program) == Some(ProgramFormat::Gcode) => {
            Some(machine_arg(spec)?)
        }
        Some(spec) => {
            eprintln!(
                "note: --machine {spec} ignored: {} is not G-code, its poses are in the \
                 part frame already",
                args.program.display()
            );
            None
        }
        None => None,
    };
    let tool_length = match (&machine, args.tool_length) {
        (Some(m), None) if m.kind != MachineKind::TableTable => bail!(
            "--tool-length: the machine {:?} has head axes: give the tool length from the \
             spindle gauge line to the tip, in mm",
            m.name
        ),
        (_, length) => length.unwrap_or(0.0),
    };
    let sample_tol = opts.sample_tol.unwrap_or(0.25 * opts.tol);
    let program = read_with_machine(&args.program, machine.as_ref(), tool_length, sample_tol)?;
    let cutter = match (&args.tool, &program.tool) {
        (Some(spec), _) => spec
            .parse::<Cutter>()
            .map_err(|e| anyhow::anyhow!("--tool {spec}: {e}"))?,
        (None, Some(t)) => *t,
        (None, None) => bail!(
            "{}: the program names no cutter (no APT CUTTER record): give the tool with --tool, e.g. --tool ball:d=8",
            program.source
        ),
    };
    let ctx = context(&args.part, &program, &cutter, &opts);
    let v = verify_and_write(&model, &program, &cutter, &opts, &args.out, "", &ctx)?;
    print!("{}", text_summary(&v, &ctx));
    println!("reports in {}", args.out.display());
    if let Some(stop) = &ctx.stopped {
        bail!("the program stopped at {stop}; the report covers the motions before it");
    }
    Ok(())
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
fn machine_arg(spec: &str) -> Result<Machine> {
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

/// Verifies and writes `{prefix}report.json`, `{prefix}flagged.csv`,
/// `{prefix}deviation.png` and `{prefix}toolpath.png` under `out`.
pub fn verify_and_write(
    model: &Model,
    program: &Program,
    cutter: &Cutter,
    opts: &VerifyOptions,
    out: &Path,
    prefix: &str,
    ctx: &ReportContext,
) -> Result<Verification> {
    let design = match model {
        Model::Patches(p) => Design::Part(p),
        Model::Mesh { mesh, .. } => Design::Mesh(mesh),
    };
    let bars = Bars::default();
    let v = swarf_sim::verify(design, program, cutter, opts, &bars)?;
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

    /// A ball raster over a plane with one CL point 0.05 mm too deep, then the same
    /// program cut off by a bad word: the gouge is reported with its line, and the
    /// stopped program still writes its report but fails.
    #[test]
    fn verify_finds_the_gouge_and_fails_on_a_stopped_program() {
        let dir = std::env::temp_dir().join(format!("swarf-verify-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let part = dir.join("plane.toml");
        std::fs::write(
            &part,
            "name = \"plane\"\nunits = \"mm\"\n[[patch]]\ndegree = [1, 1]\n\
             points = [[0, 0, 0], [0, 10, 0], [20, 0, 0], [20, 10, 0]]\n",
        )
        .unwrap();
        let mut g = String::from("G21 G90 G17\nG0 Z5\n");
        let mut gouge_line = 0;
        for k in 0..8 {
            let y = 0.625 + 1.25 * k as f64;
            g += &format!("G0 X-3 Y{y}\nG1 Z0 F100\n");
            for s in 0..=13 {
                let x = -3.0 + 2.0 * s as f64;
                let z = if k == 4 && s == 6 { -0.05 } else { 0.0 };
                g += &format!("G1 X{x} Y{y} Z{z} F300\n");
                if z < 0.0 {
                    gouge_line = g.lines().count();
                }
            }
            g += "G0 Z5\n";
        }
        let program = dir.join("raster.ngc");
        std::fs::write(&program, &g).unwrap();
        let args = |program: &Path, out: &str| Args {
            part: part.display().to_string(),
            program: program.to_path_buf(),
            tool: Some("ball:d=6".into()),
            machine: None,
            tool_length: None,
            sim: SimArgs {
                deviation: None,
                ..SimArgs::for_tests(0.05)
            },
            out: dir.join(out),
        };
        run(&args(&program, "ok")).unwrap();
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("ok/report.json")).unwrap())
                .unwrap();
        let worst = &report["deviation"]["gouges"][0];
        assert_eq!(worst["line"].as_u64(), Some(gouge_line as u64), "{worst}");
        assert!(
            (worst["worst"].as_f64().unwrap() + 0.05).abs() < 2e-3,
            "{worst}"
        );
        for f in ["flagged.csv", "deviation.png", "toolpath.png"] {
            assert!(dir.join("ok").join(f).exists(), "{f}");
        }
        let stopped = dir.join("stopped.ngc");
        let cut: String = g.lines().take(30).map(|l| format!("{l}\n")).collect();
        std::fs::write(&stopped, cut + "G1 X4 Y\n").unwrap();
        let err = run(&args(&stopped, "stop")).unwrap_err().to_string();
        assert!(err.contains("stopped.ngc:31"), "{err}");
        let report: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("stop/report.json")).unwrap())
                .unwrap();
        assert_eq!(report["complete"], serde_json::Value::Bool(false));
        let _ = std::fs::remove_dir_all(&dir);
    }

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
