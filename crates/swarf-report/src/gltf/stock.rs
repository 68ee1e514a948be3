//! The simulated dexel stock as a mesh: one vertex per kept cell centre at the
//! machined height, two triangles per lattice quad whose corners all hold material,
//! coloured per vertex on the deviation scale of the PNG heat map
//! ([`crate::picture::Scale::colour`], converted to linear light as glTF requires).
//!
//! Large grids are decimated: every `stride`-th cell in x and y is kept (and the
//! last), the least stride whose lattice has at most
//! [`StockMeshOptions::max_vertices`] vertices. Each vertex shows the most extreme
//! deviation among the cells nearest to it (as a PNG pixel does, so a gouge one cell
//! wide still shows), and carries that cell (`_CELL`: i, j), its deviation
//! (`_DEVIATION`, mm), the program line that last lowered it (`_LINE`, -1: none) and
//! its state (`_STATE`: 0 measured, 1 no stock measured, 2 off the part).
//!
//! The height error of the decimated surface is computed, not estimated: every cell
//! with material is located in its lattice quad, the surface height there is
//! interpolated on the quad's triangle, and the largest difference from the cell's
//! own height is stated ([`StockMesh::height_error`]). Cells whose quad has a corner
//! without material are not covered by any triangle and are counted apart.

use super::glb::{Glb, TRIANGLES, linear};
use crate::picture::{Scale, limits};
use serde_json::json;
use swarf_sim::Verification;
use swarf_sim::dexel::NO_MOTION;

/// Options of the stock mesh.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StockMeshOptions {
    /// Most vertices of the lattice (decimation above it).
    pub max_vertices: usize,
}

impl Default for StockMeshOptions {
    fn default() -> Self {
        StockMeshOptions {
            max_vertices: 250_000,
        }
    }
}

/// What the stock mesh holds, and its error.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct StockMesh {
    /// Cells kept per lattice step in x and y (1: every cell).
    pub stride: usize,
    /// Vertices.
    pub vertices: usize,
    /// Triangles.
    pub triangles: usize,
    /// Largest height difference between a covered cell and the mesh above its
    /// centre, mm (0 with stride 1).
    pub height_error: f64,
    /// Cells with material that no triangle covers.
    pub uncovered_cells: usize,
    /// Colour scale: deviation of the darkest red, mm (negative).
    pub scale_below: f64,
    /// Colour scale: deviation of the darkest blue, mm.
    pub scale_above: f64,
}

/// The kept indices `0, s, 2s, ...` and `n - 1`.
pub fn lattice(n: usize, s: usize) -> Vec<usize> {
    let mut v: Vec<usize> = (0..n).step_by(s.max(1)).collect();
    if n > 0 && v.last() != Some(&(n - 1)) {
        v.push(n - 1);
    }
    v
}

/// The least stride whose lattice has at most `max_vertices` vertices.
pub fn stride_for(nx: usize, ny: usize, max_vertices: usize) -> usize {
    let mut s = ((nx * ny) as f64 / max_vertices.max(4) as f64)
        .sqrt()
        .floor()
        .max(1.0) as usize;
    while lattice(nx, s).len() * lattice(ny, s).len() > max_vertices.max(4) {
        s += 1;
    }
    s
}

/// The cells `[lo, hi)` nearest to lattice point `a`.
fn block(lat: &[usize], a: usize, n: usize) -> (usize, usize) {
    let lo = if a == 0 {
        0
    } else {
        (lat[a - 1] + lat[a]) / 2 + 1
    };
    let hi = if a + 1 == lat.len() {
        n
    } else {
        (lat[a] + lat[a + 1]) / 2 + 1
    };
    (lo, hi)
}

/// Per-vertex attributes being gathered.
#[derive(Default)]
struct Vertices {
    index: Vec<u32>,
    pos: Vec<f32>,
    colour: Vec<f32>,
    deviation: Vec<f32>,
    line: Vec<f32>,
    cell: Vec<f32>,
    state: Vec<f32>,
}

/// The vertices of the lattice `(xs, ys)`: positions, colours and cell attributes
/// (module doc); `index` maps lattice points to vertices (`u32::MAX`: no material).
fn vertices(v: &Verification, xs: &[usize], ys: &[usize], scale: &Scale) -> Vertices {
    let (g, z) = (&v.grid, v.stock.heights());
    let (dev, design) = (&v.deviation.values, &v.design.heights);
    let mut out = Vertices::default();
    for (b, &j) in ys.iter().enumerate() {
        for (a, &i) in xs.iter().enumerate() {
            let k = j * g.nx + i;
            if !z[k].is_finite() {
                out.index.push(u32::MAX);
                continue;
            }
            out.index.push((out.pos.len() / 3) as u32);
            out.pos.extend([g.x(i), g.y(j), z[k]].map(|c| c as f32));
            let ((i0, i1), (j0, j1)) = (block(xs, a, g.nx), block(ys, b, g.ny));
            let (mut pick, mut at, mut any_design) = (f64::NAN, k, false);
            for jj in j0..j1 {
                for ii in i0..i1 {
                    let kk = jj * g.nx + ii;
                    any_design |= design[kk].is_finite();
                    let d = dev[kk];
                    if d.is_finite() && (pick.is_nan() || d.abs() > pick.abs()) {
                        (pick, at) = (d, kk);
                    }
                }
            }
            let rgb = scale.colour(pick, any_design);
            out.colour.extend(rgb.map(linear));
            out.deviation
                .push(if pick.is_finite() { pick as f32 } else { 0.0 });
            out.state.push(if pick.is_finite() {
                0.0
            } else if any_design {
                1.0
            } else {
                2.0
            });
            out.cell.extend([(at % g.nx) as f32, (at / g.nx) as f32]);
            let m = v.stock.last_motion()[at];
            let line = (m != NO_MOTION).then(|| v.lines.get(m as usize)).flatten();
            out.line.push(line.map_or(-1.0, |&l| l as f32));
        }
    }
    out
}

/// Unit normals of the lattice's vertices from differences to their neighbours.
fn normals(pos: &[f32], index: &[u32], w: usize) -> Vec<f32> {
    let h = index.len() / w.max(1);
    let at = |a: usize, b: usize| -> Option<[f32; 3]> {
        let k = *index.get(b * w + a)?;
        (k != u32::MAX).then(|| [0, 1, 2].map(|c| pos[3 * k as usize + c]))
    };
    let mut out = Vec::with_capacity(pos.len());
    for b in 0..h {
        for a in 0..w {
            let Some(p) = at(a, b) else { continue };
            let slope = |lo: Option<[f32; 3]>, hi: Option<[f32; 3]>, c: usize| {
                let (l, r) = (lo.unwrap_or(p), hi.unwrap_or(p));
                if r[c] != l[c] {
                    (r[2] - l[2]) / (r[c] - l[c])
                } else {
                    0.0
                }
            };
            let left = a.checked_sub(1).and_then(|a| at(a, b));
            let down = b.checked_sub(1).and_then(|b| at(a, b));
            let dx = slope(left, (a + 1 < w).then(|| at(a + 1, b)).flatten(), 0);
            let dy = slope(down, (b + 1 < h).then(|| at(a, b + 1)).flatten(), 1);
            let n = (dx * dx + dy * dy + 1.0).sqrt();
            out.extend([-dx / n, -dy / n, 1.0 / n]);
        }
    }
    out
}

/// The triangles of the lattice (two per quad with material at all four corners,
/// split along the diagonal from its low corner; counter-clockwise from above).
fn triangles(index: &[u32], w: usize) -> Vec<u32> {
    let h = index.len() / w.max(1);
    let mut out = Vec::new();
    for b in 0..h.saturating_sub(1) {
        for a in 0..w.saturating_sub(1) {
            let q = [
                index[b * w + a],
                index[b * w + a + 1],
                index[(b + 1) * w + a + 1],
                index[(b + 1) * w + a],
            ];
            if q.contains(&u32::MAX) {
                continue;
            }
            out.extend([q[0], q[1], q[2], q[0], q[2], q[3]]);
        }
    }
    out
}

/// The largest height error of the lattice surface over the cells it covers, and
/// the cells with material it does not cover (module doc).
pub fn height_error(v: &Verification, xs: &[usize], ys: &[usize]) -> (f64, usize) {
    let (g, z) = (&v.grid, v.stock.heights());
    let (mut worst, mut uncovered) = (0.0f64, 0usize);
    let span = |lat: &[usize], i: usize| {
        let a = lat
            .partition_point(|&c| c <= i)
            .saturating_sub(1)
            .min(lat.len().saturating_sub(2));
        (
            a,
            if lat.len() > 1 {
                (i as f64 - lat[a] as f64) / (lat[a + 1] - lat[a]) as f64
            } else {
                0.0
            },
        )
    };
    for j in 0..g.ny {
        let (b, v_) = span(ys, j);
        for i in 0..g.nx {
            let zc = z[j * g.nx + i];
            if !zc.is_finite() {
                continue;
            }
            let (a, u) = span(xs, i);
            let corner = |da: usize, db: usize| {
                let (ii, jj) = (xs.get(a + da), ys.get(b + db));
                ii.zip(jj).map_or(f64::NAN, |(&ii, &jj)| z[jj * g.nx + ii])
            };
            let [z00, z10, z11, z01] = [corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)];
            let zm = if u >= v_ {
                z00 + u * (z10 - z00) + v_ * (z11 - z10)
            } else {
                z00 + v_ * (z01 - z00) + u * (z11 - z01)
            };
            if zm.is_finite() {
                worst = worst.max((zm - zc).abs());
            } else {
                uncovered += 1;
            }
        }
    }
    (worst, uncovered)
}

/// Adds the stock of `v` to `glb` as the node `stock` (module doc); what it holds.
///
/// # Units
/// mm.
pub fn add_stock(glb: &mut Glb, v: &Verification, opts: &StockMeshOptions) -> StockMesh {
    let g = &v.grid;
    let stride = stride_for(g.nx, g.ny, opts.max_vertices);
    let (xs, ys) = (lattice(g.nx, stride), lattice(g.ny, stride));
    let scale = limits(v);
    let (below, above) = (scale.below, scale.above);
    let vx = vertices(v, &xs, &ys, &scale);
    let nrm = normals(&vx.pos, &vx.index, xs.len());
    let tri = triangles(&vx.index, xs.len());
    let (height_error, uncovered_cells) = height_error(v, &xs, &ys);
    let mesh = StockMesh {
        stride,
        vertices: vx.pos.len() / 3,
        triangles: tri.len() / 3,
        height_error,
        uncovered_cells,
        scale_below: -below,
        scale_above: above,
    };
    let mat = glb.material("stock", [1.0, 1.0, 1.0, 1.0], 0.0);
    if mesh.triangles == 0 {
        glb.empty_node("stock");
        return mesh;
    }
    let attributes = [
        ("POSITION", glb.floats(&vx.pos, "VEC3", 3)),
        ("NORMAL", glb.floats(&nrm, "VEC3", 3)),
        ("COLOR_0", glb.floats(&vx.colour, "VEC3", 3)),
        ("_DEVIATION", glb.floats(&vx.deviation, "SCALAR", 1)),
        ("_LINE", glb.floats(&vx.line, "SCALAR", 1)),
        ("_CELL", glb.floats(&vx.cell, "VEC2", 2)),
        ("_STATE", glb.floats(&vx.state, "SCALAR", 1)),
    ];
    let idx = glb.indices(&tri);
    let node = glb.mesh_node("stock", &attributes, Some(idx), TRIANGLES, mat);
    let s = &v.deviation.summary;
    glb.set_node(
        node,
        "extras",
        json!({
            "grid": { "origin_mm": g.origin, "cell_mm": g.cell, "nx": g.nx, "ny": g.ny },
            "mesh": mesh,
            "tolerance_mm": s.tol,
            "allowed_excess_mm": s.allowed_excess,
            "deviation_mode": if v.along_normals { "normal" } else { "vertical" },
        }),
    );
    mesh
}
