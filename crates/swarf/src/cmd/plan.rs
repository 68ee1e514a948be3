//! `swarf plan JOB.toml`: plan a job and write its outputs ([`swarf_app::plan_job()`]),
//! or a sequence of operations on one stock ([`swarf_app::sequence`]).

use crate::progress::Bars;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use swarf_app::Job;
use swarf_app::gate::Gate;
use swarf_app::sequence::{Sequence, plan_sequence};

/// Arguments of `swarf plan`.
#[derive(clap::Args)]
pub struct Args {
    /// Job file (TOML): one job (part, tool, strategy, feeds, linking, outputs) or a
    /// sequence of operations on one stock (`[[operation]]` tables).
    job: PathBuf,
    /// Directory for the outputs (default: beside the job file).
    #[arg(long, short = 'o')]
    out: Option<PathBuf>,
    /// Write a program that fails its verification on the job's stock (a rapid in
    /// material, a gouge beyond the tolerance), labelled so in its header and
    /// summary, instead of refusing it.
    #[arg(long, conflicts_with = "no_verify")]
    allow_unsafe: bool,
    /// Do not verify the program on the job's stock before writing it (faster; the
    /// header says it was not verified).
    #[arg(long)]
    no_verify: bool,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let text = swarf_io::read_input_text(&args.job)
        .with_context(|| format!("{}: cannot read the job file", args.job.display()))?;
    let job_dir = args.job.parent().unwrap_or(Path::new("."));
    let out_dir = args.out.clone().unwrap_or_else(|| job_dir.to_path_buf());
    let mut out = swarf_app::Outputs::new(&out_dir);
    if Sequence::is_sequence(&text) {
        let mut seq = Sequence::parse(&text, &args.job.display().to_string(), job_dir)?;
        seq.gate = gate(args);
        let report = plan_sequence(&seq, job_dir, &mut out)
            .with_context(|| format!("{}: planning the sequence", args.job.display()))?;
        out.commit()?;
        for line in report.lines() {
            println!("{line}");
        }
        return Ok(());
    }
    let mut job = Job::parse_in(&text, &args.job.display().to_string(), job_dir)?;
    job.gate = gate(args);
    let summary = swarf_app::plan_job(&job, job_dir, &mut out, &Bars::default())
        .with_context(|| format!("{}: planning the job", args.job.display()))?;
    out.commit()?;
    println!("{summary}");
    Ok(())
}

/// The gate the flags ask for.
fn gate(args: &Args) -> Gate {
    match (args.allow_unsafe, args.no_verify) {
        (_, true) => Gate::Skip,
        (true, _) => Gate::AllowUnsafe,
        _ => Gate::Verify,
    }
}
