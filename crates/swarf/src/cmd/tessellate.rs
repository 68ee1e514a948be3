//! `swarf tessellate PART --tol T -o part.stl`.

use anyhow::Result;
use std::path::PathBuf;
use swarf_app::load_part;

/// Arguments of `swarf tessellate`.
#[derive(clap::Args)]
pub struct Args {
    #[arg(help = format!(
        "{}; trimmed faces are meshed inside their loops",
        super::help::part("The part", super::help::Reads::Patches)
    ))]
    part: String,
    /// Chordal tolerance, mm: every point of the mesh is within this of the surface.
    #[arg(long, default_value_t = 0.01)]
    tol: f64,
    /// Output binary STL.
    #[arg(
        short = 'o',
        long = "out",
        visible_alias = "output",
        value_name = "FILE"
    )]
    output: PathBuf,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    super::check_flags(&[("--tol", args.tol, swarf_geom::domain::TOLERANCE)])?;
    let part = load_part(&args.part)?;
    let mesh = part.tessellate(args.tol)?;
    let mut out = swarf_io::OutputSet::new();
    swarf_io::write_stl(&mut out, &args.output, &mesh, &part.name)?;
    out.commit()?;
    eprintln!(
        "{}: {} triangles within {} mm -> {}",
        part.name,
        mesh.triangles.len(),
        args.tol,
        args.output.display()
    );
    Ok(())
}
