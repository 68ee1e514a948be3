//! `swarf plan JOB.toml`: plan a job and write its outputs ([`swarf_app::plan_job()`]),
//! or a sequence of operations on one stock ([`swarf_app::sequence`]).

use crate::progress::Bars;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use swarf_app::Job;
use swarf_app::sequence::{Sequence, plan_sequence};

/// Arguments of `swarf plan`.
#[derive(clap::Args)]
pub struct Args {
    /// Job file (TOML): part, tool, strategy, feeds, linking, outputs.
    job: PathBuf,
    /// Directory for the outputs (default: beside the job file).
    #[arg(long)]
    out: Option<PathBuf>,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let text = swarf_io::read_input_text(&args.job)
        .with_context(|| format!("{}: cannot read the job file", args.job.display()))?;
    let job_dir = args.job.parent().unwrap_or(Path::new("."));
    let out_dir = args.out.clone().unwrap_or_else(|| job_dir.to_path_buf());
    let mut out = swarf_app::Outputs::new(&out_dir);
    if Sequence::is_sequence(&text) {
        let seq = Sequence::parse(&text, &args.job.display().to_string(), job_dir)?;
        let report = plan_sequence(&seq, job_dir, &mut out)
            .with_context(|| format!("{}: planning the sequence", args.job.display()))?;
        out.commit()?;
        for line in report.lines() {
            println!("{line}");
        }
        return Ok(());
    }
    let job = Job::parse_in(&text, &args.job.display().to_string(), job_dir)?;
    let summary = swarf_app::plan_job(&job, job_dir, &mut out, &Bars::default())
        .with_context(|| format!("{}: planning the job", args.job.display()))?;
    out.commit()?;
    println!("{summary}");
    Ok(())
}
