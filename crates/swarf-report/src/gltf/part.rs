//! The design as a mesh: a triangle mesh as it is (a mesh part), or the patches of a
//! part tessellated within a chordal tolerance by the geometry kernel
//! ([`swarf_geom::Part::tessellate`]) before they come here. Vertex normals are the
//! area-weighted means of the normals of the triangles around each vertex.

use super::glb::{Glb, TRIANGLES, linear};
use swarf_geom::TriMesh;

/// The design's colour (sRGB).
const GREY: [u8; 3] = [170, 175, 185];

/// Area-weighted unit vertex normals of `mesh` (+z where a vertex has none).
pub fn vertex_normals(mesh: &TriMesh) -> Vec<[f64; 3]> {
    let mut acc = vec![[0.0f64; 3]; mesh.vertices.len()];
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
        let n = (b - a).cross(&(c - a));
        for &i in t {
            for k in 0..3 {
                acc[i as usize][k] += n[k];
            }
        }
    }
    acc.into_iter()
        .map(|n| {
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            if len > 0.0 && len.is_finite() {
                n.map(|c| c / len)
            } else {
                [0.0, 0.0, 1.0]
            }
        })
        .collect()
}

/// Adds `mesh` to `glb` as the node `part`; its index.
///
/// # Units
/// mm.
pub fn add_part(glb: &mut Glb, mesh: &TriMesh) -> usize {
    if mesh.triangles.is_empty() {
        return glb.empty_node("part");
    }
    let pos: Vec<f32> = mesh
        .vertices
        .iter()
        .flat_map(|p| [p.x, p.y, p.z])
        .map(|c| c as f32)
        .collect();
    let nrm: Vec<f32> = vertex_normals(mesh)
        .into_iter()
        .flatten()
        .map(|c| c as f32)
        .collect();
    let idx: Vec<u32> = mesh.triangles.iter().flatten().copied().collect();
    let p = glb.floats(&pos, "VEC3", 3);
    let n = glb.floats(&nrm, "VEC3", 3);
    let i = glb.indices(&idx);
    let [r, g, b] = GREY.map(linear);
    let mat = glb.material("part", [r, g, b, 1.0], 0.1);
    glb.mesh_node(
        "part",
        &[("POSITION", p), ("NORMAL", n)],
        Some(i),
        TRIANGLES,
        mat,
    )
}
