//! `swarf batch SWEEP.toml --scheduler ADDRESS|local --out DIR`: a sweep of jobs
//! planned or compared on Dask, by the Python package (`python3 -m swarf.batch`,
//! its `batch` extra installed): the table (Parquet, CSV) and the plots in `DIR`.
//!
//! The command line only finds the interpreter and checks that it has what a batch
//! needs, so that a missing piece is named before anything runs; the Python side
//! does the work.

use anyhow::{Result, bail};
use std::ffi::OsString;
use std::path::PathBuf;
use std::process::Command;

/// The interpreter's environment variable.
const PYTHON_VAR: &str = "SWARF_PYTHON";

/// Imports what a batch needs; prints the first module missing and exits 3.
const PROBE: &str = r"import importlib, sys
for m in ('swarf', 'swarf.batch', 'dask.distributed', 'pandas', 'pyarrow'):
    try:
        importlib.import_module(m)
    except ImportError as e:
        print(m, e.name or m)
        sys.exit(3)
";

/// Arguments of `swarf batch`.
#[derive(clap::Args)]
pub struct Args {
    /// The sweep file (TOML: `[batch]`, `jobs`, `[base]` and `[sweep]`).
    sweep: PathBuf,
    /// A Dask scheduler's address (`tcp://host:8786`), or `local` for a cluster of
    /// this machine's cores.
    #[arg(long, default_value = "local")]
    scheduler: String,
    /// The results folder: a path, or an fsspec URL every worker can reach.
    #[arg(short = 'o', long = "out")]
    out: String,
    /// Run a sweep of up to this many tasks (default: the sweep's `max_tasks`, else
    /// 1000).
    #[arg(long)]
    max_tasks: Option<u64>,
    /// Workers of the local cluster (default: one per core).
    #[arg(long)]
    workers: Option<u32>,
    /// Write the table only, no plots.
    #[arg(long)]
    no_plots: bool,
    /// No progress bar.
    #[arg(long)]
    quiet: bool,
    /// The Python interpreter (default: `$SWARF_PYTHON`, else `python3`).
    #[arg(long)]
    python: Option<PathBuf>,
}

/// Runs the subcommand.
///
/// # Errors
/// No interpreter, or one without the package, its native module or the batch
/// extra's modules (each named); a batch that failed or was interrupted.
pub fn run(args: &Args) -> Result<()> {
    let python = args
        .python
        .clone()
        .or_else(|| std::env::var_os(PYTHON_VAR).map(PathBuf::from))
        .unwrap_or_else(|| PathBuf::from("python3"));
    let shown = python.display();
    let probe = match Command::new(&python).args(["-c", PROBE]).output() {
        Ok(p) => p,
        Err(e) => bail!(
            "swarf batch runs on Python, but the interpreter `{shown}` cannot be started ({e}); \
             install Python 3.9 or later, or name one with --python or {PYTHON_VAR}"
        ),
    };
    if !probe.status.success() {
        let said = String::from_utf8_lossy(&probe.stdout);
        let mut words = said.split_whitespace();
        let (Some(wanted), Some(missing)) = (words.next(), words.next()) else {
            bail!(
                "`{shown}` could not check for the swarf package: {}",
                String::from_utf8_lossy(&probe.stderr).trim()
            );
        };
        let how = if wanted.starts_with("swarf") {
            "install the package with its batch extra: pip install './python[batch]'"
        } else {
            "install the package's batch extra: pip install 'swarf[batch]' (dask[distributed], pandas, pyarrow, matplotlib, fsspec)"
        };
        bail!("`{shown}` cannot import `{wanted}` (module `{missing}` is missing); {how}");
    }
    let status = Command::new(&python)
        .args(["-m", "swarf.batch"])
        .args(python_args(args))
        .status()?;
    match status.code() {
        Some(0) => Ok(()),
        Some(130) => bail!(
            "interrupted: the finished tasks are kept in {}; rerun to do the rest",
            args.out
        ),
        Some(code) => bail!("the batch ended with exit status {code} (its messages are above)"),
        None => bail!("the batch's Python process was killed by a signal"),
    }
}

/// The arguments of `python -m swarf.batch`.
fn python_args(args: &Args) -> Vec<OsString> {
    let mut v: Vec<OsString> = vec![
        args.sweep.clone().into(),
        "--scheduler".into(),
        args.scheduler.clone().into(),
        "--out".into(),
        args.out.clone().into(),
    ];
    if let Some(n) = args.max_tasks {
        v.extend(["--max-tasks".into(), n.to_string().into()]);
    }
    if let Some(n) = args.workers {
        v.extend(["--workers".into(), n.to_string().into()]);
    }
    if args.no_plots {
        v.push("--no-plots".into());
    }
    if args.quiet {
        v.push("--quiet".into());
    }
    v
}
