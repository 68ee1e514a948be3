//! `swarf dsm PART --tool bull:d=12,r=2 --station 50 [--offset W] [--faces 0,1]
//! [--along DEG] [--footprints N]`: the drop-and-spin method at one footprint or
//! along one reference line across the common edge of two faces, as JSON on stdout
//! ([`swarf_app::dsm`]).

use anyhow::Result;
use swarf_app::dsm::{DsmRequest, dsm_report};
use swarf_tool::Cutter;

/// Arguments of `swarf dsm`.
#[derive(clap::Args)]
pub struct Args {
    #[arg(help = super::help::part("The part", super::help::Reads::Patches))]
    part: String,
    /// The cutter: a bull (`bull:d=12,r=2,length=30`) or a ball.
    #[arg(long)]
    tool: Cutter,
    /// The two faces (patch indices): dropped on the first, spun onto the second.
    #[arg(long, value_delimiter = ',', default_values_t = [0, 1])]
    faces: Vec<usize>,
    /// The edge's overall direction in XY, degrees from +X.
    #[arg(long, default_value_t = 0.0)]
    along: f64,
    /// Position of the reference line along that direction, mm.
    #[arg(long)]
    station: f64,
    /// One footprint: its offset from the edge toward the second face, mm (default:
    /// the whole zone on the reference line).
    #[arg(long, allow_negative_numbers = true)]
    offset: Option<f64>,
    /// Footprints across the zone, its ends included.
    #[arg(long, default_value_t = 5)]
    footprints: usize,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let [a, b] = args.faces[..] else {
        anyhow::bail!("--faces: expected two patch indices, as 0,1");
    };
    use swarf_geom::domain::{COORDINATE, Domain};
    super::check_flags(&[
        (
            "--along",
            args.along,
            Domain::new(-360.0, 360.0, "degrees", "a direction"),
        ),
        ("--station", args.station, COORDINATE),
        ("--offset", args.offset.unwrap_or(0.0), COORDINATE),
        (
            "--footprints",
            args.footprints as f64,
            Domain::new(1.0, 1000.0, "", "a count"),
        ),
    ])?;
    let req = DsmRequest {
        part: args.part.clone(),
        tool: args.tool,
        faces: [a, b],
        along: args.along,
        station: args.station,
        offset: args.offset,
        footprints: args.footprints,
    };
    let report = dsm_report(&req)?;
    print!("{}", swarf_io::json::to_pretty(&report)?);
    Ok(())
}
