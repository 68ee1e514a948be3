//! `swarf inspect PART`: a summary of a part or mesh ([`swarf_app::inspect`]).

use anyhow::{Context, Result};
use swarf_app::load_model;

/// Arguments of `swarf inspect`.
#[derive(clap::Args)]
pub struct Args {
    #[arg(help = super::help::part("The part", super::help::Reads::Model))]
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
