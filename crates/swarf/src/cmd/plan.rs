//! `swarf plan JOB.toml`: plan a job and write its outputs.

use crate::load::{Model, load_model};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use swarf_nc::{Dialect, GcodeOptions, Units};
use swarf_path::job::{OutputDialect, OutputUnits};
use swarf_path::plan::{Plan, PlanInput};
use swarf_path::{Job, motion_stats};

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
    let text = std::fs::read_to_string(&args.job)
        .with_context(|| format!("{}: cannot read the job file", args.job.display()))?;
    let job = Job::parse(&text, &args.job.display().to_string())?;
    let job_dir = args.job.parent().unwrap_or(Path::new("."));
    let out_dir = args.out.clone().unwrap_or_else(|| job_dir.to_path_buf());
    let summary = plan_job(&job, job_dir, &out_dir)?;
    println!("{summary}");
    Ok(())
}

/// Loads the job's part, plans it and writes every requested output under `out_dir`.
/// Returns the JSON summary.
pub fn plan_job(job: &Job, job_dir: &Path, out_dir: &Path) -> Result<serde_json::Value> {
    let part_arg = if job.part.starts_with("builtin:") || Path::new(&job.part).is_absolute() {
        job.part.clone()
    } else {
        job_dir.join(&job.part).display().to_string()
    };
    let model = load_model(&part_arg)?;
    let (name, plan) = match &model {
        Model::Patches(part) => (
            part.name.clone(),
            swarf_path::plan::plan(job, PlanInput::Part(part))?,
        ),
        Model::Mesh { name, mesh } => (
            name.clone(),
            swarf_path::plan::plan(job, PlanInput::Mesh(mesh))?,
        ),
    };
    write_outputs(job, &name, &plan, out_dir)
}

fn units(job: &Job) -> Units {
    match job.output.units {
        OutputUnits::Mm => Units::Mm,
        OutputUnits::Inch => Units::Inch,
    }
}

fn write_outputs(
    job: &Job,
    part_name: &str,
    plan: &Plan,
    out_dir: &Path,
) -> Result<serde_json::Value> {
    let moves = plan.toolpath.moves();
    let stats = motion_stats(&moves, job.feeds.rapid);
    let strategy = serde_json::to_value(job.strategy.kind)?;
    let strategy = strategy.as_str().unwrap_or("?").to_string();
    let out = |rel: &str| out_dir.join(rel);
    if let Some(rel) = &job.output.gcode {
        let opts = GcodeOptions {
            dialect: match job.output.dialect {
                OutputDialect::Linuxcnc => Dialect::Linuxcnc,
                OutputDialect::Fanuc => Dialect::Fanuc,
            },
            units: units(job),
            comments: vec![
                format!("swarf {}", env!("CARGO_PKG_VERSION")),
                format!("part {part_name}"),
                format!("tool {}", job.tool),
                format!("strategy {strategy}"),
            ],
            ..GcodeOptions::default()
        };
        let text = swarf_nc::write_gcode(&moves, &job.feeds, &opts)?;
        swarf_io::write_atomic(&out(rel), text.as_bytes())?;
    }
    if let Some(rel) = &job.output.cl {
        let text = swarf_nc::write_cl(&moves, &job.feeds, &job.tool, part_name, units(job))?;
        swarf_io::write_atomic(&out(rel), text.as_bytes())?;
    }
    if let Some(rel) = &job.output.csv {
        let text = swarf_nc::write_pose_csv(&plan.toolpath, units(job));
        swarf_io::write_atomic(&out(rel), text.as_bytes())?;
    }
    if let (Some(rel), Some(text)) = (&job.output.double_contacts, plan.double_contacts_csv()) {
        swarf_io::write_atomic(&out(rel), text.as_bytes())?;
    }
    let summary = serde_json::json!({
        "job": job.name,
        "part": part_name,
        "tool": job.tool.to_string(),
        "strategy": strategy,
        "passes": plan.toolpath.passes.len(),
        "poses": plan.toolpath.pose_count(),
        "cutting_length_mm": stats.cutting_length,
        "approach_length_mm": stats.approach_length,
        "rapid_length_mm": stats.rapid_length,
        "estimated_time_s": stats.time_s,
        "lifted_points": plan.toolpath.lifted_count(),
        "report": plan.report,
    });
    if let Some(rel) = &job.output.summary {
        let text = serde_json::to_string_pretty(&summary)? + "\n";
        swarf_io::write_atomic(&out(rel), text.as_bytes())?;
    }
    Ok(summary)
}
