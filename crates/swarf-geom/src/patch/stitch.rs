//! Crack-free triangulation of a rectangle subdivision of the parameter plane.
//!
//! Cells are rectangles addressed by integer keys: each knot span is `2^30` units long,
//! so equal keys mean equal parameters (computed one way, from the key) and one shared
//! vertex, and a cell splits by halving its integer width. A cell with no neighbour
//! corner inside its edges becomes two triangles (the shorter diagonal in 3D). A cell
//! whose edges hold corners of smaller neighbours (T-junctions, found by range queries
//! on the sorted corner sets of horizontal and vertical lines) becomes a fan from its
//! centre through every such corner, so both sides of every edge use the same vertices
//! and the mesh has no gaps (de Berg et al., Computational Geometry, ch. 14.3, do the
//! same for balanced quadtrees; a fan needs no balancing). Triangles run
//! counter-clockwise in `(u, v)`, so their normals follow `du x dv`; triangles that
//! collapse at a degenerate patch edge are dropped.

use super::Patch;
use crate::mesh::TriMesh;
use crate::solve::DEGENERATE_NORMAL_REL;
use std::collections::{BTreeSet, HashMap};

/// Bits of the dyadic offset inside one knot span (the deepest possible split level).
const KEY_BITS: u32 = 30;
/// One knot span in key units.
pub(super) const SPAN: u64 = 1 << KEY_BITS;
/// A rectangle of the parameter plane in key units: `lo` inclusive, `hi` exclusive.
#[derive(Debug, Clone, Copy)]
pub(super) struct Cell {
    pub(super) lo: [u64; 2],
    pub(super) hi: [u64; 2],
}

/// The non-empty knot spans in each direction and the key-to-parameter map.
pub(super) struct Spans(pub(super) [Vec<[f64; 2]>; 2]);

impl Spans {
    pub(super) fn new(patch: &Patch) -> Spans {
        Spans([0, 1].map(|dir| {
            let k = patch.knots(dir);
            let p = patch.degree()[dir];
            k[p..k.len() - p]
                .windows(2)
                .filter(|w| w[1] > w[0])
                .map(|w| [w[0], w[1]])
                .collect()
        }))
    }

    /// The parameter of `key` in direction `dir`; exact at span ends.
    pub(super) fn param(&self, dir: usize, key: u64) -> f64 {
        let spans = &self.0[dir];
        let n = spans.len() as u64;
        let (s, off) = if key >= n * SPAN {
            (n - 1, SPAN)
        } else {
            (key >> KEY_BITS, key & (SPAN - 1))
        };
        let [a, b] = spans[s as usize];
        match off {
            0 => a,
            SPAN => b,
            _ => a + (b - a) * (off as f64 / SPAN as f64),
        }
    }
}

/// Turns leaf cells into a shared-vertex mesh.
pub(super) struct Mesher<'a> {
    patch: &'a Patch,
    spans: &'a Spans,
    leaves: &'a [Cell],
    /// Leaf corners on horizontal lines, as `(v, u)`, and on vertical ones, as `(u, v)`.
    lines: [BTreeSet<(u64, u64)>; 2],
    index: HashMap<(u64, u64), u32>,
    mesh: TriMesh,
}

impl<'a> Mesher<'a> {
    pub(super) fn new(patch: &'a Patch, spans: &'a Spans, leaves: &'a [Cell]) -> Mesher<'a> {
        let mut lines = [BTreeSet::new(), BTreeSet::new()];
        for c in leaves {
            for (u, v) in [
                (c.lo[0], c.lo[1]),
                (c.hi[0], c.lo[1]),
                (c.lo[0], c.hi[1]),
                (c.hi[0], c.hi[1]),
            ] {
                lines[0].insert((v, u));
                lines[1].insert((u, v));
            }
        }
        Mesher {
            patch,
            spans,
            leaves,
            lines,
            index: HashMap::new(),
            mesh: TriMesh::default(),
        }
    }

    pub(super) fn run(mut self) -> TriMesh {
        for c in self.leaves {
            self.cell(c);
        }
        self.mesh
    }

    /// The vertex at key `(u, v)`, made on first use.
    fn vertex(&mut self, u: u64, v: u64) -> u32 {
        if let Some(i) = self.index.get(&(u, v)) {
            return *i;
        }
        let i = self.mesh.vertices.len() as u32;
        let p = self
            .patch
            .eval(self.spans.param(0, u), self.spans.param(1, v));
        self.mesh.vertices.push(p);
        self.index.insert((u, v), i);
        i
    }

    /// Boundary keys of `c` counter-clockwise from `(lo, lo)`, with T-junction corners.
    fn boundary(&self, c: &Cell) -> Vec<(u64, u64)> {
        let ([u0, v0], [u1, v1]) = (c.lo, c.hi);
        let inner = |set: &BTreeSet<(u64, u64)>, line: u64, a: u64, b: u64| {
            set.range((line, a + 1)..(line, b))
                .map(|k| k.1)
                .collect::<Vec<_>>()
        };
        let mut out = vec![(u0, v0)];
        out.extend(
            inner(&self.lines[0], v0, u0, u1)
                .into_iter()
                .map(|u| (u, v0)),
        );
        out.push((u1, v0));
        out.extend(
            inner(&self.lines[1], u1, v0, v1)
                .into_iter()
                .map(|v| (u1, v)),
        );
        out.push((u1, v1));
        out.extend(
            inner(&self.lines[0], v1, u0, u1)
                .into_iter()
                .rev()
                .map(|u| (u, v1)),
        );
        out.push((u0, v1));
        out.extend(
            inner(&self.lines[1], u0, v0, v1)
                .into_iter()
                .rev()
                .map(|v| (u0, v)),
        );
        out
    }

    fn cell(&mut self, c: &Cell) {
        let keys = self.boundary(c);
        let ring: Vec<u32> = keys.iter().map(|&(u, v)| self.vertex(u, v)).collect();
        if let [a, b, c2, d] = ring[..] {
            let pos = |i: u32| self.mesh.vertices[i as usize];
            if (pos(a) - pos(c2)).norm() <= (pos(b) - pos(d)).norm() {
                self.triangle([a, b, c2]);
                self.triangle([a, c2, d]);
            } else {
                self.triangle([a, b, d]);
                self.triangle([b, c2, d]);
            }
            return;
        }
        let centre = self.vertex((c.lo[0] + c.hi[0]) / 2, (c.lo[1] + c.hi[1]) / 2);
        for k in 0..ring.len() {
            self.triangle([centre, ring[k], ring[(k + 1) % ring.len()]]);
        }
    }

    /// Adds a triangle unless it has collapsed to (rounding noise around) zero area,
    /// as next to a degenerate patch edge, where its orientation would be noise.
    fn triangle(&mut self, t: [u32; 3]) {
        let p = t.map(|i| self.mesh.vertices[i as usize]);
        let (a, b) = (p[1] - p[0], p[2] - p[0]);
        let scale = a.norm_squared() + b.norm_squared();
        if a.cross(&b).norm() > DEGENERATE_NORMAL_REL * scale {
            self.mesh.triangles.push(t);
        }
    }
}
