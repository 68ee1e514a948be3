//! `swarf inspect PART`: a summary of a part or mesh ([`swarf_app::inspect`]).

use anyhow::{Context, Result};
use swarf_app::load_model;

/// Arguments of `swarf inspect`.
#[derive(clap::Args)]
pub struct Args {
    /// Part file (.toml, .step, .stp, .igs, .iges), mesh (.stl, .obj) or built-in part name (die, wave, edge-convex, edge-concave).
    part: String,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let model = load_model(&args.part)?;
    let text = swarf_app::inspect::inspect(&model, args.json).with_context(|| args.part.clone())?;
    print!("{text}");
    Ok(())
}
