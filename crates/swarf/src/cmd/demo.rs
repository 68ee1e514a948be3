//! `swarf demo [--out DIR]`: the main job on the built-in shared parts.
//!
//! Inspects and tessellates every built-in part, then plans the shipped example jobs
//! (paper 004's experiment on wave.toml) and writes everything under `--out`.

use super::inspect::{patch_text, summarise_patch};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};

/// Arguments of `swarf demo`.
#[derive(clap::Args)]
pub struct Args {
    /// Output directory.
    #[arg(long, default_value = "swarf-demo")]
    out: PathBuf,
}

/// Chordal tolerance of the demo tessellations, mm.
const DEMO_TOL: f64 = 0.01;

/// The example jobs shipped in `jobs/`, embedded so that the demo needs no files
/// (their parts are built-in). Outputs go to `--out` under the names the jobs give.
const JOBS: [(&str, &str); 3] = [
    (
        "wave-iso-parametric.toml",
        include_str!("../../../../jobs/wave-iso-parametric.toml"),
    ),
    (
        "wave-iso-planar.toml",
        include_str!("../../../../jobs/wave-iso-planar.toml"),
    ),
    (
        "wave-iso-scallop.toml",
        include_str!("../../../../jobs/wave-iso-scallop.toml"),
    ),
];

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    std::fs::create_dir_all(&args.out)
        .with_context(|| format!("{}: cannot create the output directory", args.out.display()))?;
    for (name, _) in swarf_io::builtin_parts() {
        let part = swarf_io::builtin_part(name).context("built-in part does not load")?;
        let summaries = part
            .patches
            .iter()
            .enumerate()
            .map(|(i, p)| summarise_patch(i, p))
            .collect::<Result<Vec<_>>>()?;
        print!("{}", patch_text(&part.name, &summaries));
        let mesh = part.tessellate(DEMO_TOL)?;
        let path = args.out.join(format!("{name}.stl"));
        swarf_io::write_stl(&path, &mesh, name)?;
        println!(
            "  tessellated within {DEMO_TOL} mm: {} triangles -> {}",
            mesh.triangles.len(),
            path.display()
        );
    }
    for (name, text) in JOBS {
        let job = swarf_path::Job::parse(text, name)?;
        let summary = super::plan::plan_job(&job, Path::new("."), &args.out)?;
        println!(
            "{name}: {} passes, {:.0} mm cutting, {:.1} min, predicted scallop <= {:.4} mm -> {}",
            summary["passes"],
            summary["cutting_length_mm"].as_f64().unwrap_or(f64::NAN),
            summary["estimated_time_s"].as_f64().unwrap_or(f64::NAN) / 60.0,
            summary["report"]["predicted_max_scallop"]
                .as_f64()
                .unwrap_or(f64::NAN),
            args.out.display()
        );
    }
    Ok(())
}
