//! `swarf plan JOB.toml`: plan a job and write its outputs ([`swarf_app::plan_job()`]),
//! or a sequence of operations on one stock ([`swarf_app::sequence`]).

use crate::progress::Bars;
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use swarf_app::Job;
use swarf_app::sequence::{Sequence, SequenceReport, plan_sequence};

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
        let seq = Sequence::parse(&text, &args.job.display().to_string())?;
        let report = plan_sequence(&seq, job_dir, &mut out)
            .with_context(|| format!("{}: planning the sequence", args.job.display()))?;
        out.commit()?;
        print_sequence(&report);
        return Ok(());
    }
    let job = Job::parse(&text, &args.job.display().to_string())?;
    let summary = swarf_app::plan_job(&job, job_dir, &mut out, &Bars::default())
        .with_context(|| format!("{}: planning the job", args.job.display()))?;
    out.commit()?;
    println!("{summary}");
    Ok(())
}

/// One line per operation, then the whole program's time.
fn print_sequence(r: &SequenceReport) {
    for op in &r.operations {
        let eng = op.engagement.as_ref().map_or(String::new(), |e| {
            format!(
                ", engagement max {:.0} deg, {:.1} % over {:.0} deg",
                e.max_deg,
                100.0 * e.over_limit,
                e.limit_deg + 5.0
            )
        });
        println!(
            "T{} {} ({}, {}): {} motions, {:.0} mm, {:.0} s{eng}; after it: {} gouge cells, \
             {} cells more than {:.3} mm above the part",
            op.number,
            op.name,
            op.strategy,
            op.tool,
            op.motions,
            op.cutting_length_mm,
            op.time_s,
            op.gouge_cells,
            op.rest_cells,
            op.rest_limit_mm
        );
    }
    println!("whole program: {:.0} s", r.time_s);
}
