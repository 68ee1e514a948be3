//! The `swarf` command-line tool: a thin clap layer over swarf-app.
//!
//! Every subcommand lives in its own file under `cmd/`; errors are reported with
//! their context (file, line, field) and a non-zero exit status.

mod cmd;
mod progress;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// The version `swarf --version` prints: the package's, and the git commit it was
/// built from (`unknown` when built without git, as from a source tarball).
const VERSION: &str = concat!(
    env!("CARGO_PKG_VERSION"),
    " (commit ",
    env!("SWARF_COMMIT"),
    ")"
);

/// swarf: tool paths for sculptured surfaces, checked before a part is ever cut.
#[derive(Parser)]
#[command(name = "swarf", version = VERSION, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Summarise a part: patches, degrees, bounding box, principal curvatures.
    Inspect(cmd::inspect::Args),
    /// Evaluate a patch at (u, v): point, derivatives, normal, principal curvatures (JSON).
    Eval(cmd::eval::Args),
    /// Tessellate a part into a binary STL within a chordal tolerance.
    Tessellate(cmd::tessellate::Args),
    /// Plan a job (finishing, roughing, cleanup, five-axis, or a sequence of
    /// operations), verify its program on the job's stock, and write G-code, CL, CSV,
    /// summary.
    Plan(cmd::plan::Args),
    /// Simulate an NC program (or several in sequence, each with its tool) on a dexel
    /// stock and measure gouge, excess and scallops against the design; writes a JSON
    /// report, a CSV of flagged cells and pictures.
    Verify(Box<cmd::verify::Args>),
    /// Find the rest material a finishing tool or job leaves: regions as JSON, their
    /// boundaries as CSV, and a picture over the part.
    Rest(cmd::rest::Args),
    /// Classify a part's surface into steep, horizontal and other areas (Zhu 1998,
    /// §6.1): areas as JSON and a picture over the part.
    Classify(cmd::classify::Args),
    /// Plan jobs, verify their programs and print a table of machining time, scallop,
    /// remaining material and gouges for them (Shokrollahi & Shojaei's Table 1).
    Compare(cmd::compare::Args),
    /// Drop a cutter onto a triangle mesh at many XY points (CSV in, CSV out).
    Drop(cmd::drop::Args),
    /// Drop-and-spin five-axis positioning at the common edge of two faces (Sharma et
    /// al. 2019): the edge, the spin zone and both spins at a footprint or across a
    /// reference line, as JSON.
    Dsm(cmd::dsm::Args),
    /// Run the main job on the built-in shared parts and write the results.
    Demo(cmd::demo::Args),
    /// Verify a program (or a job's) and write its 3D view: GLB files of the part,
    /// tool path, cutter and stock coloured by deviation, and the viewer page.
    View(Box<cmd::view::Args>),
    /// Plan or compare the jobs of a sweep on Dask (the Python package's
    /// `swarf.batch`): a table of rows (Parquet, CSV) and plots in the results folder.
    Batch(cmd::batch::Args),
}

/// Ends the process quietly when standard output is a closed pipe (`swarf plan ... |
/// head`), as command-line tools do, instead of panicking on the failed write: the
/// default action of SIGPIPE, which Rust's runtime sets to ignored.
#[cfg(unix)]
fn quiet_broken_pipe() {
    // SAFETY: called first in main, before any thread exists; SIG_DFL is a valid
    // disposition for SIGPIPE.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
}

#[cfg(not(unix))]
fn quiet_broken_pipe() {}

fn main() -> ExitCode {
    quiet_broken_pipe();
    let cli = Cli::parse();
    // One command per process: no output may replace a file it read.
    swarf_io::track_inputs();
    let result = match cli.command {
        Command::Inspect(a) => cmd::inspect::run(&a),
        Command::Eval(a) => cmd::eval::run(&a),
        Command::Tessellate(a) => cmd::tessellate::run(&a),
        Command::Plan(a) => cmd::plan::run(&a),
        Command::Demo(a) => cmd::demo::run(&a),
        Command::Drop(a) => cmd::drop::run(&a),
        Command::Dsm(a) => cmd::dsm::run(&a),
        Command::Verify(a) => cmd::verify::run(&a),
        Command::Compare(a) => cmd::compare::run(&a),
        Command::Rest(a) => cmd::rest::run(&a),
        Command::Classify(a) => cmd::classify::run(&a),
        Command::View(a) => cmd::view::run(&a),
        Command::Batch(a) => cmd::batch::run(&a),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("swarf: error: {e:#}");
            ExitCode::FAILURE
        }
    }
}
