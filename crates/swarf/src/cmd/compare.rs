//! `swarf compare JOB...`: plan each job, verify its program and print paper 004's
//! Table 1 (and thesis 000's five-axis table) for them ([`swarf_app::compare`]).

use crate::cmd::verify::SimArgs;
use crate::progress::Bars;
use anyhow::{Result, bail};
use std::path::PathBuf;
use swarf_app::Outputs;
use swarf_app::compare::{compare_all, five_axis_markdown, markdown};

/// Arguments of `swarf compare`.
#[derive(clap::Args)]
#[command(
    mut_arg("tol", |a| super::help::note(a, "(default: each job's tolerance)")),
    mut_arg("scallop", |a| super::help::note(a, "(default: each job's scallop)")),
    mut_arg("rapid", |a| super::help::note(a, "(default: each job's rapid rate)")),
    mut_arg("floor", |a| super::help::note(a, "(default: each job's floor)")),
)]
pub struct Args {
    /// Job files (TOML) to plan and compare.
    #[arg(required = true)]
    jobs: Vec<PathBuf>,
    #[command(flatten)]
    sim: SimArgs,
    /// When a program stops before its end, still write the results (covering the
    /// motions before the stop); without it nothing is written and the previous
    /// results stay whole.
    #[arg(long)]
    partial: bool,
    /// Output directory.
    #[arg(short = 'o', long = "out", default_value = "swarf-compare")]
    out: PathBuf,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let mut out = Outputs::new(&args.out);
    let (rows, five) = compare_all(
        &args.jobs,
        &args.sim.settings()?,
        &mut out,
        &Bars::default(),
    )?;
    let stopped: Vec<&str> = rows
        .iter()
        .filter(|r| r.incomplete)
        .map(|r| r.job.as_str())
        .collect();
    let incomplete = !stopped.is_empty();
    if !incomplete || args.partial {
        out.commit()?;
    }
    print!("{}", markdown(&rows));
    if !five.is_empty() {
        println!();
        print!("{}", five_axis_markdown(&five));
    }
    if incomplete && !args.partial {
        bail!(
            "the program of {} stopped early: nothing was written and \
             the previous results in {} are unchanged (--partial writes them, covering the \
             motions before the stop)",
            stopped.join(", "),
            args.out.display()
        );
    }
    println!("tables and pictures in {}", args.out.display());
    if incomplete {
        bail!(
            "the program of {} stopped early; its row covers the motions before the stop",
            stopped.join(", ")
        );
    }
    Ok(())
}
