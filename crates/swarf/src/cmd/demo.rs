//! `swarf demo [--out DIR]`: the main job on the built-in shared parts
//! ([`swarf_app::demo`]).

use crate::progress::Bars;
use anyhow::Result;
use std::path::PathBuf;

/// Arguments of `swarf demo`.
#[derive(clap::Args)]
pub struct Args {
    /// Output directory.
    #[arg(short = 'o', long = "out", default_value = "swarf-demo")]
    out: PathBuf,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let mut stdout = std::io::stdout();
    swarf_app::demo::demo(&args.out, &mut stdout, &Bars::default())?;
    Ok(())
}
