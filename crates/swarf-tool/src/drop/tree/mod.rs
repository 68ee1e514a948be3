//! The drop tree: a mesh's triangles in a hierarchy of XY boxes, tops and lids, for
//! drop-cutter queries whose cost grows with the depth of the hierarchy, not with the
//! number of triangles under the cutter.
//!
//! Layout ([`build`]): the triangles are tiled top-down like a k-d tree of their XY
//! box centres, each node's range halved across the longer side of its extent and
//! each half again, into [`FANOUT`] children of `F^k` triangles each (ties to the
//! mesh index, so the layout is unique and does not depend on threads). Level 0
//! groups [`FANOUT`] consecutive triangles into a node, level `k + 1` groups
//! [`FANOUT`] consecutive nodes of level `k`, up to one root, so children are found
//! by position and no pointers are stored. A node holds the XY box of what is under
//! it and its highest z (`f32`, rounded outward), and a lid: a
//! plane that everything under it lies below (for a leaf, the slope of its triangles'
//! mean normal through their highest corner above it; for a node above, the mean of
//! its children's slopes through the highest of their lids' box corners, as a lid is
//! linear). Nodes holding a face steeper than [`super::facet::BOUND_MIN_NZ`] allows
//! have no lid.
//!
//! A query ([`DropTree::search`]) is best-first branch and bound. A cutter whose
//! lower surface is `tip + h(rho)`, `h` convex and increasing, puts its tip at most at
//! the largest `f(q) = z(q) - h(|q - c|)` over what it touches. Two bounds hold for a
//! node: `z_max - h(rho_min)` (`rho_min` the distance from the axis to its box), and
//! the tangent bound of its lid: with `L` the lid, `L(q) - h(|q - c|)` is concave, so
//! below its tangent plane at the box centre `o`, whose largest value over the box is
//! `L(o) - h(|o - c|) + |g_x| w + |g_y| d` (`g` the gradient at `o`, `w`, `d` the
//! box's half sides). The first is first order in the box size, the second second
//! order near the contact (where `g` vanishes), which is what keeps the nodes a
//! query opens about the same at any density. Both are taken with the margin of
//! [`super::facet::BOUND_MARGIN_REL`] on the lid's. Nodes and triangles wait in one
//! binary heap in descending bound (equal bounds in a fixed order); the search
//! expands a node into its children, hands a triangle to the caller, and stops at the
//! first item the caller no longer wants ([`Search::wants`]). Every bound is at least
//! the drop of anything under its node, so nothing that could win or tie is skipped:
//! the heights and the winning triangle are the flat scan's, bit for bit.
//!
//! Why not a crate: the R-trees and BVHs of crates.io answer intersection and
//! nearest-neighbour queries; this search needs bounds that depend on the cutter's
//! profile and the tie rule of the drop, inside the traversal.
//!
//! Memory: corners are kept as three `u32` indices into a copy of the vertices in
//! first-use order (neighbours stay together in memory), with the mesh index of each
//! triangle and about `40 / (F - 1)` bytes of nodes per triangle:
//! [`DropTree::estimate_bytes`] gives the total before anything is built. Triangles
//! with a non-finite corner are not stored and never touched.

mod build;

use super::Envelope;
use super::facet::BOUND_MARGIN_REL;
use build::leaf;
use std::collections::BinaryHeap;
use swarf_geom::{Point3, TriMesh};

/// Children per node.
pub(crate) const FANOUT: usize = 4;

/// A node: the XY box `[x0, y0, x1, y1]` of what it holds relative to the tree's
/// origin and its highest z, rounded outward, and a lid above everything it holds:
/// `z <= lid + slope[0] (x - xc) + slope[1] (y - yc)` about the box centre
/// `(xc, yc)` (slopes `NaN` where it holds a face steeper than the plane bound
/// allows).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Node {
    bbox: [f32; 4],
    zmax: f32,
    slope: [f32; 2],
    lid: f64,
}

impl Node {
    fn centre(&self) -> [f64; 2] {
        [
            0.5 * (f64::from(self.bbox[0]) + f64::from(self.bbox[2])),
            0.5 * (f64::from(self.bbox[1]) + f64::from(self.bbox[3])),
        ]
    }

    /// The lid's height at `q` (relative to the origin).
    fn lid_at(&self, q: [f64; 2]) -> f64 {
        let o = self.centre();
        self.lid
            + f64::from(self.slope[0]) * (q[0] - o[0])
            + f64::from(self.slope[1]) * (q[1] - o[1])
    }
}

/// The cutter's lower surface as a search bounds it.
pub(crate) trait Lower {
    /// `h(rho)`, mm: convex and non-decreasing within the reach.
    fn height(&self, rho: f64) -> f64;
    /// `h(rho)` and `h'(rho)` (a subgradient at a joint; infinite beyond the
    /// reach).
    fn height_slope(&self, rho: f64) -> (f64, f64);
}

impl Lower for Envelope {
    #[inline]
    fn height(&self, rho: f64) -> f64 {
        Envelope::height(self, rho)
    }

    #[inline]
    fn height_slope(&self, rho: f64) -> (f64, f64) {
        Envelope::height_slope(self, rho)
    }
}

/// A flat disc of this radius (0: a needle).
pub(crate) struct Flat(pub(crate) f64);

impl Lower for Flat {
    fn height(&self, _: f64) -> f64 {
        0.0
    }

    fn height_slope(&self, rho: f64) -> (f64, f64) {
        (0.0, if rho <= self.0 { 0.0 } else { f64::INFINITY })
    }
}

/// A heap item: the bound's order key and what it is: `level << 40 | index`, level 0
/// a triangle position, level `k` a node of `levels[k - 1]`.
pub(crate) type Item = (u64, u64);

/// Where an item's level starts in its last field.
const LEVEL_SHIFT: u32 = 40;

/// The index bits of an item's last field.
const INDEX_MASK: u64 = (1 << LEVEL_SHIFT) - 1;

/// What a search asks of its caller.
pub(crate) trait Search {
    /// True while an item whose bound is `ub` (mm) may still change the result;
    /// the first `false` ends the search.
    fn wants(&self, ub: f64) -> bool;
    /// Visits the triangle at tree position `pos`.
    fn visit(&mut self, pos: usize);
}

/// Triangles of a mesh in a hierarchy of boxes and tops (module doc).
#[derive(Debug, Clone, Default)]
pub(crate) struct DropTree {
    origin: [f64; 2],
    vertices: Vec<Point3>,
    tris: Vec<[u32; 3]>,
    pub(crate) ids: Vec<u32>,
    levels: Vec<Vec<Node>>,
}

/// `f64` to a `u64` with the same order (for finite and infinite values).
pub(crate) fn order_key(v: f64) -> u64 {
    let b = v.to_bits();
    if b >> 63 == 1 { !b } else { b | (1 << 63) }
}

/// The inverse of [`order_key`].
pub(crate) fn from_order_key(k: u64) -> f64 {
    f64::from_bits(if k >> 63 == 1 { k & !(1 << 63) } else { !k })
}

impl DropTree {
    /// Heap bytes [`DropTree::build`] will hold for `mesh` (an upper bound, before
    /// anything is allocated): vertices, triangle indices and mesh indices, nodes.
    pub(crate) fn estimate_bytes(mesh: &TriMesh) -> usize {
        let t = mesh.len();
        let nodes = t.div_ceil(FANOUT - 1) + 1;
        mesh.vertices.len().min(3 * t) * std::mem::size_of::<Point3>()
            + t * (12 + 4)
            + nodes * std::mem::size_of::<Node>()
    }

    /// Number of stored triangles.
    pub(crate) fn len(&self) -> usize {
        self.tris.len()
    }

    /// Heap bytes held.
    pub(crate) fn memory_bytes(&self) -> usize {
        self.vertices.capacity() * std::mem::size_of::<Point3>()
            + self.tris.capacity() * 12
            + self.ids.capacity() * 4
            + self
                .levels
                .iter()
                .map(|l| l.capacity() * std::mem::size_of::<Node>())
                .sum::<usize>()
    }

    /// The corners of the triangle at tree position `pos`.
    #[inline]
    pub(crate) fn corners(&self, pos: usize) -> [Point3; 3] {
        self.tris[pos].map(|k| self.vertices[k as usize])
    }

    /// The node of the triangle at tree position `pos`: its box, top and plane.
    fn tri_node(&self, pos: usize) -> Node {
        leaf(&[self.corners(pos)], self.origin)
    }

    /// Best-first search (module doc) about `(x, y)` within `radius`: items whose
    /// box is farther are skipped, the others bounded by the lesser of
    /// `z_max - h(rho_min)` and the tangent bound of their lid, and offered to
    /// `search` in descending bound. `scratch` is working memory.
    pub(crate) fn search<S: Search>(
        &self,
        xy: [f64; 2],
        radius: f64,
        lower: &impl Lower,
        scratch: &mut Vec<Item>,
        search: &mut S,
    ) {
        let Some(top) = self.levels.last() else {
            return;
        };
        let c = [xy[0] - self.origin[0], xy[1] - self.origin[1]];
        if !(c[0].is_finite() && c[1].is_finite()) || radius.is_nan() || radius < 0.0 {
            return;
        }
        let bound = |n: &Node, search: &S| node_bound(n, c, radius, lower, |ub| search.wants(ub));
        let mut heap = BinaryHeap::from(std::mem::take(scratch));
        heap.clear();
        let offer = |heap: &mut BinaryHeap<Item>, search: &S, n: &Node, what: u64| {
            if let Some(ub) = bound(n, search)
                && search.wants(ub)
            {
                heap.push((order_key(ub), what));
            }
        };
        let depth = self.levels.len() as u64;
        for (i, n) in top.iter().enumerate() {
            offer(&mut heap, search, n, depth << LEVEL_SHIFT | i as u64);
        }
        while let Some((key, what)) = heap.pop() {
            if !search.wants(from_order_key(key)) {
                break;
            }
            let (level, i) = ((what >> LEVEL_SHIFT) as usize, (what & INDEX_MASK) as usize);
            if level == 0 {
                search.visit(i);
                continue;
            }
            let below = level - 1;
            let count = if below == 0 {
                self.len()
            } else {
                self.levels[below - 1].len()
            };
            for j in i * FANOUT..((i + 1) * FANOUT).min(count) {
                let n = if below == 0 {
                    self.tri_node(j)
                } else {
                    self.levels[below - 1][j]
                };
                offer(
                    &mut heap,
                    search,
                    &n,
                    (below as u64) << LEVEL_SHIFT | j as u64,
                );
            }
        }
        *scratch = heap.into_vec();
    }
}

/// The lesser of a node's two bounds (module doc) for a cutter `lower` of reach
/// `radius` at `c` (relative to the origin); `None` when its box is out of reach or
/// its first bound is already not `wanted`.
fn node_bound(
    n: &Node,
    c: [f64; 2],
    radius: f64,
    lower: &impl Lower,
    wanted: impl Fn(f64) -> bool,
) -> Option<f64> {
    let r2 = radius * radius;
    let dx = (f64::from(n.bbox[0]) - c[0])
        .max(c[0] - f64::from(n.bbox[2]))
        .max(0.0);
    let dy = (f64::from(n.bbox[1]) - c[1])
        .max(c[1] - f64::from(n.bbox[3]))
        .max(0.0);
    let d2 = dx * dx + dy * dy;
    if d2 > r2 {
        return None;
    }
    let top = f64::from(n.zmax) - lower.height(d2.sqrt());
    if n.slope[0].is_nan() || !wanted(top) {
        return Some(top);
    }
    // f(q) = lid(q) - h(|q - c|) is concave: below its tangent plane at the
    // box centre, whose largest value over the box is at a corner.
    let o = n.centre();
    let v = [o[0] - c[0], o[1] - c[1]];
    let rho = (v[0] * v[0] + v[1] * v[1]).sqrt();
    let (h, slope) = lower.height_slope(rho);
    let k = if rho > 0.0 { slope / rho } else { 0.0 };
    let g = [
        f64::from(n.slope[0]) - k * v[0],
        f64::from(n.slope[1]) - k * v[1],
    ];
    let half = [
        0.5 * (f64::from(n.bbox[2]) - f64::from(n.bbox[0])),
        0.5 * (f64::from(n.bbox[3]) - f64::from(n.bbox[1])),
    ];
    let rise = g[0].abs() * half[0] + g[1].abs() * half[1];
    let f0 = n.lid - h;
    let scale = 1.0 + n.lid.abs() + f0.abs() + rise + rho;
    let tangent = f0 + rise + BOUND_MARGIN_REL * scale;
    Some(if tangent.is_nan() {
        top
    } else {
        top.min(tangent)
    })
}

#[cfg(test)]
mod tests;
