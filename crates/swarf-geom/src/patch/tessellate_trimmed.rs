//! Tessellation of a trimmed face: the patch's adaptive cells, cut by its trimming
//! loops.
//!
//! The points are the corners of the cells that [`Patch::tessellate`] would mesh
//! (placed by the same chordal bound, see [`super::tessellate`]) that lie inside the
//! face, plus the trimming loops' own points. A constrained Delaunay triangulation in
//! `(u, v)` (the `spade` crate: exact predicates, constraint edges kept) joins them with
//! every loop edge present (in `(u, v)` scaled so the median cell is square), and the
//! triangles inside the loops are kept (even-odd, by crossings of constraint edges). A triangle inside the face lies within a cell's circumcircle or spans from a
//! loop point to nearby cell corners, so the cells' bound holds up to the spread of the
//! loop's points; loop edges whose 3D chord strays more than `tol` from the surface
//! are split in `(u, v)` until it does not (readers sample edges in 3D, so this is rare;
//! points that two faces' loops share stay shared, so the seam between them is closed
//! within the readers' edge tolerance).

use super::Patch;
use super::stitch::Spans;
use crate::error::GeomError;
use crate::math::Point3;
use crate::mesh::TriMesh;
use crate::trim::{Trim, Uv};
use spade::{ConstrainedDelaunayTriangulation, Point2, Triangulation};

/// Deepest bisection of one loop edge.
const MAX_EDGE_SPLITS: u32 = 16;

impl Patch {
    /// A triangle mesh within `tol` of the face: this patch inside `trim`. Triangles run
    /// counter-clockwise in `(u, v)`, so normals follow `du x dv`.
    ///
    /// # Units
    /// `tol` in mm.
    ///
    /// # Errors
    /// As [`Patch::tessellate`]; [`GeomError::InvalidPatch`] naming `trim` when the
    /// triangulation cannot hold the loops (loop edges that meet, which [`Trim::new`]
    /// refuses, or parameters out of the triangulator's range).
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Patch, Point3, trim::Trim};
    /// let flat = Patch::bezier([1, 1], vec![
    ///     Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 10.0, 0.0),
    ///     Point3::new(10.0, 0.0, 0.0), Point3::new(10.0, 10.0, 0.0),
    /// ]).unwrap();
    /// // The lower-left triangle of the square.
    /// let trim = Trim::new(vec![vec![[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]]).unwrap();
    /// let mesh = flat.tessellate_trimmed(&trim, 0.01).unwrap();
    /// let area: f64 = mesh.triangles.iter().map(|t| {
    ///     let [a, b, c] = t.map(|i| mesh.vertices[i as usize]);
    ///     0.5 * (b - a).cross(&(c - a)).norm()
    /// }).sum();
    /// assert!((area - 50.0).abs() < 1e-9);
    /// ```
    pub fn tessellate_trimmed(&self, trim: &Trim, tol: f64) -> Result<TriMesh, GeomError> {
        let tol = GeomError::check_positive("tol", tol)?;
        let spans = Spans::new(self);
        let leaves = self.refine(&spans, tol)?;
        let mut keys: Vec<[u64; 2]> = leaves
            .iter()
            .flat_map(|c| [c.lo, [c.hi[0], c.lo[1]], c.hi, [c.lo[0], c.hi[1]]])
            .collect();
        keys.sort_unstable();
        keys.dedup();
        let mut uv: Vec<Uv> = Vec::new();
        let mut edges: Vec<[usize; 2]> = Vec::new();
        for l in trim.loops() {
            let first = uv.len();
            for k in 0..l.len() {
                uv.push(l[k]);
                self.split_edge(l[k], l[(k + 1) % l.len()], tol, 0, &mut uv);
            }
            let n = uv.len() - first;
            edges.extend((0..n).map(|k| [first + k, first + (k + 1) % n]));
        }
        // Corners on the domain's edges are left to the loops: a loop along an edge
        // (a seam of a closed surface, a face that reaches its patch's edge) carries
        // that edge's points, and a corner between them would be a T-junction with
        // the face across.
        let [[u0, u1], [v0, v1]] = self.domain();
        uv.extend(
            keys.iter()
                .map(|k| [spans.param(0, k[0]), spans.param(1, k[1])])
                .filter(|p| p[0] > u0 && p[0] < u1 && p[1] > v0 && p[1] < v1)
                .filter(|p| trim.contains(p[0], p[1])),
        );
        let scale = metric_scale(&spans, &leaves);
        let vertices: Vec<Point2<f64>> = uv
            .iter()
            .map(|p| Point2::new(p[0] * scale[0], p[1] * scale[1]))
            .collect();
        let mut conflicts = 0usize;
        let cdt = Cdt::try_bulk_load_cdt(vertices, edges, |_| conflicts += 1)
            .map_err(|e| GeomError::patch("trim", format!("cannot triangulate the face: {e}")))?;
        if conflicts > 0 {
            return Err(GeomError::patch(
                "trim",
                format!(
                    "{conflicts} loop edges meet another: expected loops that do not intersect"
                ),
            ));
        }
        let mut mesh = TriMesh {
            vertices: cdt
                .vertices()
                .map(|v| {
                    let p = v.position();
                    self.eval(p.x / scale[0], p.y / scale[1])
                })
                .collect(),
            triangles: Vec::new(),
        };
        let inside = inside_faces(&cdt);
        for f in cdt.inner_faces() {
            if inside[f.fix().index()] {
                let t = f.vertices().map(|v| v.fix().index() as u32);
                if !collapsed(&mesh.vertices, t) {
                    mesh.triangles.push(t);
                }
            }
        }
        Ok(mesh)
    }

    /// Pushes the points that split the loop edge `a`-`b` (exclusive of both ends)
    /// until the surface at each piece's middle is within `tol` of its 3D chord.
    fn split_edge(&self, a: Uv, b: Uv, tol: f64, depth: u32, out: &mut Vec<Uv>) {
        if depth >= MAX_EDGE_SPLITS {
            return;
        }
        let m = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        let (pa, pb, pm) = (
            self.eval(a[0], a[1]),
            self.eval(b[0], b[1]),
            self.eval(m[0], m[1]),
        );
        if (pm - Point3::from(0.5 * (pa.coords + pb.coords))).norm() <= tol {
            return;
        }
        self.split_edge(a, m, tol, depth + 1, out);
        out.push(m);
        self.split_edge(m, b, tol, depth + 1, out);
    }
}

type Cdt = ConstrainedDelaunayTriangulation<Point2<f64>>;

/// Per face (by index), whether it is inside the loops: a walk from the outer face
/// that flips at every constraint edge it crosses (the even-odd rule of
/// [`Trim::contains`], decided by the triangulation's topology rather than by a point
/// test, so slivers along a loop are classified by the side they are on).
fn inside_faces(cdt: &Cdt) -> Vec<bool> {
    let mut parity: Vec<Option<bool>> = vec![None; cdt.num_all_faces()];
    let outer = cdt.outer_face();
    parity[outer.fix().index()] = Some(false);
    let mut stack = Vec::new();
    if let Some(start) = outer.adjacent_edge() {
        let mut e = start;
        loop {
            cross(cdt, e.fix(), false, &mut parity, &mut stack);
            e = e.next();
            if e == start {
                break;
            }
        }
    }
    while let Some(f) = stack.pop() {
        let from = parity[f.index()].unwrap_or(false);
        for e in cdt.face(f).adjacent_edges() {
            cross(cdt, e.fix(), from, &mut parity, &mut stack);
        }
    }
    parity.into_iter().map(|p| p.unwrap_or(false)).collect()
}

/// Steps across edge `e` from a face of parity `from` into the face on its other
/// side, if that face has no parity yet.
fn cross(
    cdt: &Cdt,
    e: spade::handles::FixedDirectedEdgeHandle,
    from: bool,
    parity: &mut [Option<bool>],
    stack: &mut Vec<spade::handles::FixedFaceHandle<spade::handles::InnerTag>>,
) {
    let e = cdt.directed_edge(e);
    let next = e.rev().face();
    let k = next.fix().index();
    if parity[k].is_none() {
        parity[k] = Some(from ^ cdt.is_constraint_edge(e.as_undirected().fix()));
        if let Some(inner) = next.as_inner() {
            stack.push(inner.fix());
        }
    }
}

/// Factors that make the median cell square: the triangulation runs in the space
/// where the cells' error bound is about isotropic, so its triangles span about one
/// cell in each direction.
fn metric_scale(spans: &Spans, leaves: &[super::stitch::Cell]) -> [f64; 2] {
    [0, 1].map(|d| {
        let mut w: Vec<f64> = leaves
            .iter()
            .map(|c| spans.param(d, c.hi[d]) - spans.param(d, c.lo[d]))
            .filter(|w| *w > 0.0)
            .collect();
        w.sort_by(f64::total_cmp);
        w.get(w.len() / 2).map_or(1.0, |m| 1.0 / m)
    })
}

/// A triangle whose 3D corners coincide (at a degenerate patch edge).
fn collapsed(v: &[Point3], t: [u32; 3]) -> bool {
    let [a, b, c] = t.map(|i| v[i as usize]);
    (b - a).cross(&(c - a)).norm_squared() == 0.0
}

#[cfg(test)]
mod tests;
