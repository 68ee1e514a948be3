//! `swarf inspect PART`: a summary of a part or mesh.

use crate::load::{Model, load_model};
use anyhow::Result;
use serde::Serialize;
use swarf_geom::{Aabb, Patch, TriMesh};

/// Arguments of `swarf inspect`.
#[derive(clap::Args)]
pub struct Args {
    /// Part file (.toml), mesh (.stl, .obj) or built-in part name (die, wave, edge-convex, edge-concave).
    part: String,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// Samples per direction for the curvature survey.
const CURVATURE_SAMPLES: usize = 101;
/// Chordal tolerance of the tessellation whose vertices bound the patch, mm.
const BOX_TOL: f64 = 1e-3;

/// Summary of one patch.
#[derive(Serialize)]
pub struct PatchSummary {
    index: usize,
    kind: String,
    degree: [usize; 2],
    control_points: [usize; 2],
    domain: [[f64; 2]; 2],
    bbox_min: [f64; 3],
    bbox_max: [f64; 3],
    k1: [f64; 2],
    k2: [f64; 2],
}

/// Summarises a patch: its box from a fine tessellation (vertices lie on the surface)
/// and the range of its principal curvatures over a parameter grid.
pub fn summarise_patch(index: usize, patch: &Patch) -> Result<PatchSummary> {
    let mesh = patch.tessellate(BOX_TOL)?;
    let bbox = Aabb::from_points(&mesh.vertices);
    let [[u0, u1], [v0, v1]] = patch.domain();
    let mut k1 = [f64::INFINITY, f64::NEG_INFINITY];
    let mut k2 = k1;
    let n = CURVATURE_SAMPLES - 1;
    for i in 0..=n {
        for j in 0..=n {
            let u = u0 + (u1 - u0) * i as f64 / n as f64;
            let v = v0 + (v1 - v0) * j as f64 / n as f64;
            if let Some(c) = patch.derivs(u, v).curvature() {
                k1 = [k1[0].min(c.k1), k1[1].max(c.k1)];
                k2 = [k2[0].min(c.k2), k2[1].max(c.k2)];
            }
        }
    }
    Ok(PatchSummary {
        index,
        kind: format!("{:?}", patch.kind()),
        degree: patch.degree(),
        control_points: patch.count(),
        domain: patch.domain(),
        bbox_min: bbox.min.coords.into(),
        bbox_max: bbox.max.coords.into(),
        k1,
        k2,
    })
}

/// Runs the subcommand.
pub fn run(args: &Args) -> Result<()> {
    match load_model(&args.part)? {
        Model::Patches(part) => {
            let patches: Vec<PatchSummary> = part
                .patches
                .iter()
                .enumerate()
                .map(|(i, p)| summarise_patch(i, p))
                .collect::<Result<_>>()?;
            if args.json {
                let v = serde_json::json!({ "name": part.name, "patches": patches });
                println!("{}", serde_json::to_string_pretty(&v)?);
            } else {
                print!("{}", patch_text(&part.name, &patches));
            }
        }
        Model::Mesh { name, mesh } => print_mesh(&name, &mesh, args.json)?,
    }
    Ok(())
}

fn fmt3(v: [f64; 3]) -> String {
    format!("({:.3}, {:.3}, {:.3})", v[0], v[1], v[2])
}

/// The text form of a part summary.
pub fn patch_text(name: &str, patches: &[PatchSummary]) -> String {
    let mut s = format!("part {name}: {} patch(es), units mm\n", patches.len());
    for p in patches {
        s += &format!(
            "  patch {}: {}, degree {}x{}, {}x{} control points, u in [{}, {}], v in [{}, {}]\n",
            p.index,
            p.kind,
            p.degree[0],
            p.degree[1],
            p.control_points[0],
            p.control_points[1],
            p.domain[0][0],
            p.domain[0][1],
            p.domain[1][0],
            p.domain[1][1]
        );
        s += &format!(
            "    bounding box {} .. {} mm\n",
            fmt3(p.bbox_min),
            fmt3(p.bbox_max)
        );
        s += &format!(
            "    principal curvature k1 in [{:.6}, {:.6}], k2 in [{:.6}, {:.6}] 1/mm \
             (positive bends toward the normal du x dv)\n",
            p.k1[0], p.k1[1], p.k2[0], p.k2[1]
        );
    }
    s
}

fn print_mesh(name: &str, mesh: &TriMesh, json: bool) -> Result<()> {
    let bbox = mesh.aabb();
    let report = mesh.validate();
    if json {
        let v = serde_json::json!({
            "name": name,
            "triangles": mesh.triangles.len(),
            "vertices": mesh.vertices.len(),
            "bbox_min": <[f64; 3]>::from(bbox.min.coords),
            "bbox_max": <[f64; 3]>::from(bbox.max.coords),
            "non_finite": report.non_finite,
            "degenerate": report.degenerate,
            "duplicate": report.duplicate,
        });
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        println!(
            "mesh {name}: {} triangles, {} vertices\n  bounding box {} .. {} mm",
            mesh.triangles.len(),
            mesh.vertices.len(),
            fmt3(bbox.min.coords.into()),
            fmt3(bbox.max.coords.into())
        );
        if report.is_clean() {
            println!("  no degenerate, non-finite or duplicate triangles");
        } else {
            println!("{report}");
        }
    }
    Ok(())
}
