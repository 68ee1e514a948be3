//! `swarf classify PART [--steep-angle DEG] [--flat-angle DEG] [--cell MM] -o DIR`:
//! the steep, horizontal and other areas of a part ([`swarf_app::classify`]);
//! writes `classify.json` and `classify.png`.

use anyhow::Result;
use std::path::PathBuf;
use swarf_app::classify::{ClassifyRequest, classify_request};
use swarf_path::classify::{ClassifyParams, SurfaceClass};

/// Arguments of `swarf classify`.
#[derive(clap::Args)]
pub struct Args {
    #[arg(help = super::help::part("The part", super::help::Reads::Model))]
    part: String,
    /// Facets sloping more than this from horizontal are steep, degrees.
    #[arg(long, default_value_t = ClassifyParams::default().steep_angle.to_degrees().round())]
    steep_angle: f64,
    /// Facets sloping less than this are horizontal, degrees.
    #[arg(long, default_value_t = ClassifyParams::default().flat_angle.to_degrees().round())]
    flat_angle: f64,
    /// Side of the Go-board cells, mm.
    #[arg(long, default_value_t = ClassifyParams::default().cell)]
    cell: f64,
    /// Chordal tolerance for tessellating a parametric part, mm.
    #[arg(long, default_value_t = 0.01)]
    tol: f64,
    /// Output directory.
    #[arg(short = 'o', long = "out")]
    out: PathBuf,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    use swarf_geom::domain::{CELL, TOLERANCE};
    super::check_flags(&[
        ("--steep-angle", args.steep_angle, super::STEEP_DEG),
        ("--flat-angle", args.flat_angle, super::SLOPE_DEG),
        ("--cell", args.cell, CELL),
        ("--tol", args.tol, TOLERANCE),
    ])?;
    if args.steep_angle <= args.flat_angle {
        anyhow::bail!(
            "--steep-angle {}: expected more than --flat-angle {} degrees",
            args.steep_angle,
            args.flat_angle
        );
    }
    let req = ClassifyRequest {
        part: &args.part,
        params: ClassifyParams {
            steep_angle: args.steep_angle.to_radians(),
            flat_angle: args.flat_angle.to_radians(),
            cell: args.cell,
            feed_angle: None,
        },
        tol: args.tol,
        out: &args.out,
    };
    let c = classify_request(&req)?;
    for class in SurfaceClass::ALL {
        let r = c.region(class);
        println!(
            "{}: {:.1} mm² seen from above, {:.1} mm² of surface, {} triangles, {} cells",
            class.name(),
            r.xy_area,
            r.surface_area,
            r.triangles,
            r.cells
        );
    }
    if c.degenerate + c.facing_down > 0 {
        println!(
            "left out: {} degenerate triangles, {} facing down",
            c.degenerate, c.facing_down
        );
    }
    println!("classify.json and classify.png in {}", args.out.display());
    Ok(())
}
