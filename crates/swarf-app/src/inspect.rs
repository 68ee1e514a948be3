//! `swarf inspect PART`: a summary of a part (patches, degrees, box, principal
//! curvatures) or of a mesh (counts, box, defects), as text or JSON.

use crate::error::Result;
use crate::model::Model;
use serde::Serialize;
use swarf_geom::{Aabb, Patch, TriMesh};

/// Samples per direction for the curvature survey.
const CURVATURE_SAMPLES: usize = 101;
/// Chordal tolerance of the tessellation whose vertices bound the patch, mm.
const BOX_TOL: f64 = 1e-3;

/// Summary of one patch (lengths mm, curvatures 1/mm).
#[derive(Serialize)]
pub struct PatchSummary {
    /// Patch index.
    pub index: usize,
    /// Bezier, B-spline or NURBS.
    pub kind: String,
    /// Degrees in u and v.
    pub degree: [usize; 2],
    /// Control points in u and v.
    pub control_points: [usize; 2],
    /// Parameter domain.
    pub domain: [[f64; 2]; 2],
    /// Box corner, mm.
    pub bbox_min: [f64; 3],
    /// Box corner, mm.
    pub bbox_max: [f64; 3],
    /// Range of the first principal curvature, 1/mm.
    pub k1: [f64; 2],
    /// Range of the second principal curvature, 1/mm.
    pub k2: [f64; 2],
}

/// Summarises a patch: its box from a fine tessellation (vertices lie on the surface)
/// and the range of its principal curvatures over a parameter grid.
///
/// # Errors
/// A patch that cannot be tessellated.
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

/// The summary of `model` as text, or as JSON when `json`.
///
/// # Errors
/// A patch that cannot be tessellated.
pub fn inspect(model: &Model, json: bool) -> Result<String> {
    match model {
        Model::Patches(part) => {
            let patches: Vec<PatchSummary> = part
                .patches
                .iter()
                .enumerate()
                .map(|(i, p)| summarise_patch(i, p))
                .collect::<Result<_>>()?;
            if json {
                let v = serde_json::json!({ "name": part.name, "patches": patches });
                Ok(serde_json::to_string_pretty(&v)? + "\n")
            } else {
                Ok(patch_text(&part.name, &patches))
            }
        }
        Model::Mesh { name, mesh } => mesh_text(name, mesh, json),
    }
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

fn mesh_text(name: &str, mesh: &TriMesh, json: bool) -> Result<String> {
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
        Ok(serde_json::to_string_pretty(&v)? + "\n")
    } else {
        let mut s = format!(
            "mesh {name}: {} triangles, {} vertices\n  bounding box {} .. {} mm\n",
            mesh.triangles.len(),
            mesh.vertices.len(),
            fmt3(bbox.min.coords.into()),
            fmt3(bbox.max.coords.into())
        );
        if report.is_clean() {
            s += "  no degenerate, non-finite or duplicate triangles\n";
        } else {
            s += &format!("{report}\n");
        }
        Ok(s)
    }
}
