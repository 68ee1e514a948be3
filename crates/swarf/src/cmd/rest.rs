//! `swarf rest (--reference TOOL | --job PARENT.toml) [--part P] -o DIR`: the rest
//! material a finishing tool or job leaves, as regions ([`swarf_app::rest`]); writes
//! `rest.json`, `rest.csv` and `rest.png`. No rest is not an error: it says so.

use anyhow::Result;
use std::path::PathBuf;
use swarf_app::rest::{RestRequest, rest_request};
use swarf_rest::RegionParams;
use swarf_rest::RestSource;

/// Arguments of `swarf rest`.
#[derive(clap::Args)]
pub struct Args {
    #[arg(long, help = format!(
        "{} (default: the parent job's part)",
        super::help::part("Design part", super::help::Reads::Model)
    ))]
    part: Option<String>,
    /// The tool that finished (a reference tool), e.g. ball:d=12.
    #[arg(long, conflicts_with = "job")]
    reference: Option<String>,
    /// The finishing job whose rest to find (its tool is the reference).
    #[arg(long)]
    job: Option<PathBuf>,
    /// Where the rest comes from: crease scans with the reference tool, the double
    /// contacts a raster parent job records, or the dexel stock after the parent
    /// job's program.
    #[arg(long, default_value = "reference", value_parser = ["reference", "contacts", "stock"])]
    source: String,
    /// Rest thinner than this is left, mm.
    #[arg(long, default_value_t = RegionParams::default().threshold)]
    threshold: f64,
    /// Regions closer than this are merged, mm.
    #[arg(long, default_value_t = RegionParams::default().merge)]
    merge: f64,
    /// Outward offset of the regions, mm.
    #[arg(long, default_value_t = RegionParams::default().overlap)]
    overlap: f64,
    /// Regions with a smaller raw area are dropped, mm².
    #[arg(long, default_value_t = RegionParams::default().min_area)]
    min_area: f64,
    /// Concave corners of the boundaries are rounded to at least this radius, mm.
    #[arg(long, default_value_t = RegionParams::default().smoothness)]
    smoothness: f64,
    /// Machining tolerance, mm.
    #[arg(long, default_value_t = 0.01)]
    tol: f64,
    /// Output directory.
    #[arg(short = 'o', long = "out")]
    out: PathBuf,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let source = match args.source.as_str() {
        "contacts" => RestSource::Contacts,
        "stock" => RestSource::Stock,
        _ => RestSource::Reference,
    };
    let req = RestRequest {
        part: args.part.as_deref(),
        reference: args.reference.as_deref(),
        job: args.job.as_deref(),
        source,
        params: RegionParams {
            threshold: args.threshold,
            merge: args.merge,
            overlap: args.overlap,
            min_area: args.min_area,
            smoothness: args.smoothness,
        },
        tol: args.tol,
        out: &args.out,
    };
    let found = rest_request(&req)?;
    let regions = &found.detection.regions;
    if regions.is_empty() {
        println!(
            "no rest after {} ({}): nothing to clean up",
            found.reference, found.source
        );
    }
    for (k, r) in regions.iter().enumerate() {
        println!(
            "region {}: {:.1} mm² (raw {:.1} mm²), deepest {:.3} mm at ({:.2}, {:.2}, {:.2}), {} samples",
            k + 1,
            r.area,
            r.raw_area,
            r.depth,
            r.deepest.x,
            r.deepest.y,
            r.deepest.z,
            r.pairs.len()
        );
    }
    println!("rest.json, rest.csv and rest.png in {}", args.out.display());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use clap::Parser;

    #[derive(clap::Parser)]
    struct Cli {
        #[command(flatten)]
        args: Args,
    }

    fn run_with(words: &[&str]) -> Result<()> {
        let cli = Cli::try_parse_from(std::iter::once("rest").chain(words.iter().copied()))?;
        run(&cli.args)
    }

    #[test]
    fn rest_of_the_v_grooves_and_bad_input() {
        let dir = std::env::temp_dir().join(format!("swarf-rest-cli-{}", std::process::id()));
        let out = dir.to_str().unwrap();
        run_with(&["--part", "v-grooves", "--reference", "ball:d=12", "-o", out]).unwrap();
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("rest.json")).unwrap()).unwrap();
        assert_eq!(json["regions"].as_array().unwrap().len(), 3);
        let csv = std::fs::read_to_string(dir.join("rest.csv")).unwrap();
        assert!(csv.starts_with("region,ring,x,y\n") && csv.lines().count() > 30);
        assert!(
            std::fs::read(dir.join("rest.png"))
                .unwrap()
                .starts_with(b"\x89PNG")
        );
        // Errors name what is wrong.
        let e = run_with(&[
            "--part",
            "v-grooves",
            "--reference",
            "ball:d=12",
            "--merge",
            "0",
            "-o",
            out,
        ]);
        let e = e.unwrap_err().to_string();
        assert!(e.contains("--merge: expected a merge distance"), "{e}");
        let e = run_with(&["--part", "v-grooves", "--reference", "ball:x=1", "-o", out]);
        assert!(e.unwrap_err().to_string().contains("--reference"));
        let e = run_with(&["--part", "v-grooves", "-o", out]);
        assert!(e.unwrap_err().to_string().contains("--reference"));
        let e = run_with(&[
            "--part",
            "v-grooves",
            "--reference",
            "ball:d=12",
            "--source",
            "stock",
            "-o",
            out,
        ]);
        assert!(e.unwrap_err().to_string().contains("parent --job"));
        let e = run_with(&["--job", "/nonexistent/finish.toml", "-o", out]);
        assert!(e.unwrap_err().to_string().contains("finish.toml"));
        std::fs::remove_dir_all(&dir).ok();
    }
}
