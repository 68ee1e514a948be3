//! `swarf drop --mesh M.stl --tool SPEC --points P.csv [-o OUT.csv] [--contact]`:
//! drop-cutter at many points.
//!
//! Output: CSV with the header `x,y,z` (with `--contact` also the triangle index, the
//! feature touched and the CC point: `x,y,z,tri,feature,cx,cy,cz`), one line per input
//! point in input order; `z` is the tool tip height. A point where the cutter reaches
//! no triangle (off the mesh) gets empty fields after `x,y`. Numbers are written in
//! the shortest form that reads back to the same f64, so the output is exact and
//! byte-identical whatever the number of threads. Throughput goes to stderr.

use anyhow::{Context, Result, bail};
use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;
use swarf_tool::Cutter;
use swarf_tool::drop::{DropResult, MeshDropper, drop_points_threads};

/// Arguments of `swarf drop`.
#[derive(clap::Args)]
pub struct Args {
    /// Triangle mesh (.stl or .obj), mm.
    #[arg(long)]
    mesh: PathBuf,
    /// Cutter spec, e.g. `ball:d=8`, `bull:d=10,r=2`, `cone:d=10,angle=90`.
    #[arg(long)]
    tool: String,
    /// Points CSV: `x,y` per line (mm); an optional header line and `#` comments.
    #[arg(long)]
    points: PathBuf,
    /// Output CSV (default: standard output).
    #[arg(
        short = 'o',
        long = "out",
        visible_alias = "output",
        value_name = "FILE"
    )]
    output: Option<PathBuf>,
    /// Add the touched triangle, feature and CC point to each line.
    #[arg(long)]
    contact: bool,
    /// Worker threads (default: one per core).
    #[arg(long)]
    threads: Option<usize>,
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    let cutter: Cutter = args
        .tool
        .parse()
        .with_context(|| format!("--tool {:?}", swarf_geom::domain::excerpt(&args.tool, 60)))?;
    if let Some(n) = args.threads {
        super::check_flags(&[("--threads", n as f64, swarf_geom::domain::THREADS)])?;
    }
    let start = Instant::now();
    let mesh = swarf_io::read_mesh(&args.mesh)?;
    let points = swarf_io::read_xy_points(&args.points)?;
    let loaded = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let dropper = MeshDropper::new(&mesh, &cutter);
    if dropper.is_empty() {
        bail!("{}: no triangle has finite corners", args.mesh.display());
    }
    let skipped = mesh.len() - dropper.len();
    if skipped > 0 {
        eprintln!("swarf drop: {skipped} triangles with non-finite corners ignored");
    }
    let built = start.elapsed().as_secs_f64();
    let start = Instant::now();
    let (results, threads) = drop_points_threads(&dropper, &points, args.threads);
    let dropped = start.elapsed().as_secs_f64();
    let hits = results.iter().filter(|r| r.is_some()).count();
    eprintln!(
        "swarf drop: {} points ({hits} with contact) on {} triangles, {threads} threads: \
         {dropped:.3} s, {:.0} points/s (read {loaded:.3} s, index {built:.3} s)",
        points.len(),
        dropper.len(),
        points.len() as f64 / dropped.max(1e-9)
    );
    let write = |w: &mut dyn Write| write_csv(w, &points, &results, args.contact);
    match &args.output {
        Some(path) => swarf_io::write_atomic_with(path, write)?,
        None => {
            let stdout = std::io::stdout();
            let mut out = std::io::BufWriter::new(stdout.lock());
            write(&mut out)
                .and_then(|()| out.flush())
                .context("standard output")?;
        }
    }
    Ok(())
}

/// The CSV described in the module doc.
fn write_csv(
    w: &mut dyn Write,
    points: &[[f64; 2]],
    results: &[Option<DropResult>],
    contact: bool,
) -> std::io::Result<()> {
    let header = if contact {
        "x,y,z,tri,feature,cx,cy,cz"
    } else {
        "x,y,z"
    };
    writeln!(w, "{header}")?;
    for (k, (p, r)) in points.iter().zip(results).enumerate() {
        let numbers = r.iter().flat_map(|r| [r.z, r.cc.x, r.cc.y, r.cc.z]);
        if !p.iter().copied().chain(numbers).all(f64::is_finite) {
            return Err(std::io::Error::other(format!(
                "point {}: a result that is not a finite number",
                k + 1
            )));
        }
        write!(w, "{},{},", p[0], p[1])?;
        match (r, contact) {
            (Some(r), false) => writeln!(w, "{}", r.z)?,
            (Some(r), true) => writeln!(
                w,
                "{},{},{},{},{},{}",
                r.z, r.tri, r.feature, r.cc.x, r.cc.y, r.cc.z
            )?,
            (None, false) => writeln!(w)?,
            (None, true) => writeln!(w, ",,,,,")?,
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;
    use swarf_geom::{Point3, TriMesh};

    /// The CSV for `points` dropped on `mesh` with `threads` threads.
    fn csv_for(
        mesh: &swarf_geom::TriMesh,
        spec: &str,
        points: &[[f64; 2]],
        threads: usize,
        contact: bool,
    ) -> String {
        let dropper = MeshDropper::new(mesh, &spec.parse().unwrap());
        let (results, _) = drop_points_threads(&dropper, points, Some(threads));
        let mut out = Vec::new();
        write_csv(&mut out, points, &results, contact).unwrap();
        String::from_utf8(out).unwrap()
    }

    fn mesh() -> TriMesh {
        let p = |x: f64, y: f64| Point3::new(x, y, 0.1 * x + 0.05 * y * y);
        let mut soup = Vec::new();
        for j in 0..20 {
            for i in 0..20 {
                let (x, y) = (f64::from(i), f64::from(j));
                soup.push([p(x, y), p(x + 1.0, y), p(x + 1.0, y + 1.0)]);
                soup.push([p(x, y), p(x + 1.0, y + 1.0), p(x, y + 1.0)]);
            }
        }
        TriMesh::from_triangles(&soup)
    }

    #[test]
    fn output_is_identical_for_any_thread_count() {
        let m = mesh();
        let pts: Vec<[f64; 2]> = (0..3000)
            .map(|k| {
                let k = f64::from(k);
                [
                    (k * 0.618_033_9) % 26.0 - 3.0,
                    (k * 0.414_213_5) % 26.0 - 3.0,
                ]
            })
            .collect();
        let one = csv_for(&m, "bull:d=6,r=1", &pts, 1, true);
        let two = csv_for(&m, "bull:d=6,r=1", &pts, 2, true);
        let three = csv_for(&m, "bull:d=6,r=1", &pts, 3, true);
        assert_eq!(one, two);
        assert_eq!(one, three);
        assert!(one.starts_with("x,y,z,tri,feature,cx,cy,cz\n"));
        assert!(one.contains(",,,,,\n"), "some points are off the mesh");
    }

    #[test]
    fn off_mesh_points_have_empty_z() {
        let csv = csv_for(&mesh(), "ball:d=2", &[[5.5, 5.5], [40.0, 40.0]], 1, false);
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines[0], "x,y,z");
        assert!(lines[1].starts_with("5.5,5.5,") && lines[1].len() > 8);
        assert_eq!(lines[2], "40,40,");
    }

    #[test]
    fn bad_inputs_are_errors_naming_the_file_or_line() {
        let dir = std::env::temp_dir().join(format!("swarf-drop-test-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let pts = dir.join("p.csv");
        std::fs::write(&pts, "x,y\n1,2\n3,oops\n").unwrap();
        let stl = dir.join("m.stl");
        let mut out = swarf_io::OutputSet::new();
        swarf_io::write_stl(&mut out, &stl, &mesh(), "m").unwrap();
        out.commit().unwrap();
        let args = |mesh: &Path, tool: &str| Args {
            mesh: mesh.to_path_buf(),
            tool: tool.into(),
            points: pts.clone(),
            output: Some(dir.join("out.csv")),
            contact: false,
            threads: Some(1),
        };
        let e = format!("{:#}", run(&args(&stl, "ball:d=8")).unwrap_err());
        assert!(e.contains("p.csv") && e.contains("line 3"), "{e}");
        let e = format!("{:#}", run(&args(&stl, "ball:d=-8")).unwrap_err());
        assert!(e.contains("--tool"), "{e}");
        let e = format!(
            "{:#}",
            run(&args(&dir.join("none.stl"), "ball:d=8")).unwrap_err()
        );
        assert!(e.contains("none.stl"), "{e}");
        std::fs::write(&pts, "1,2\n").unwrap();
        let empty = dir.join("empty.stl");
        let mut out = swarf_io::OutputSet::new();
        swarf_io::write_stl(&mut out, &empty, &TriMesh::default(), "e").unwrap();
        out.commit().unwrap();
        let e = format!("{:#}", run(&args(&empty, "ball:d=8")).unwrap_err());
        assert!(e.contains("empty.stl: a mesh with no triangle"), "{e}");
        run(&args(&stl, "ball:d=8")).unwrap();
        let out = std::fs::read_to_string(dir.join("out.csv")).unwrap();
        assert!(out.starts_with("x,y,z\n1,2,"), "{out}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
