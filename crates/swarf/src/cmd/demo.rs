//! `swarf demo [--out DIR]`: the main job on the built-in shared parts.
//!
//! Inspects and tessellates every built-in part, then plans the shipped example jobs
//! (paper 004's experiment on wave.toml) and writes everything under `--out`.

use super::inspect::{patch_text, summarise_patch};
use anyhow::{Context, Result};
use std::path::PathBuf;

/// Arguments of `swarf demo`.
#[derive(clap::Args)]
pub struct Args {
    /// Output directory.
    #[arg(long, default_value = "swarf-demo")]
    out: PathBuf,
}

/// Chordal tolerance of the demo tessellations, mm.
const DEMO_TOL: f64 = 0.01;

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
    Ok(())
}
