//! Building the drop tree: the tiled layout, the vertices in first-use order, and
//! the nodes with their lids (see the parent module).

use super::{DropTree, FANOUT, Node};
use crate::drop::facet::BOUND_MIN_NZ;
use rayon::prelude::*;
use swarf_geom::mesh::index::layout::{round_down, round_up};
use swarf_geom::{Point3, TriMesh};

/// Smallest chunk of triangles per rayon task while building.
const PAR_CHUNK: usize = 4096;

impl DropTree {
    /// Builds the tree over the finite triangles of `mesh`.
    ///
    /// # Panics
    /// When the mesh has `u32::MAX` triangles or more, or an index is out of range.
    pub(crate) fn build(mesh: &TriMesh) -> DropTree {
        assert!(
            u32::try_from(mesh.len()).is_ok() && u32::try_from(mesh.vertices.len()).is_ok(),
            "drop tree: too many triangles or vertices"
        );
        let corners = |t: u32| mesh.triangles[t as usize].map(|k| mesh.vertices[k as usize]);
        let finite: Vec<u32> = (0..mesh.len())
            .into_par_iter()
            .with_min_len(PAR_CHUNK)
            .filter(|&t| mesh.usable(t))
            .map(|t| t as u32)
            .collect();
        if finite.is_empty() {
            return DropTree::default();
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for &t in &finite {
            for p in corners(t) {
                for a in 0..2 {
                    lo[a] = lo[a].min(p[a]);
                    hi[a] = hi[a].max(p[a]);
                }
            }
        }
        let mut keyed: Vec<Centre> = finite
            .par_iter()
            .with_min_len(PAR_CHUNK)
            .map(|&t| {
                let c = corners(t);
                let mid = |a: usize| {
                    0.5 * (c[0][a].min(c[1][a]).min(c[2][a]) + c[0][a].max(c[1][a]).max(c[2][a]))
                };
                (mid(0), mid(1), t)
            })
            .collect();
        drop(finite);
        let mut cap = 1;
        while cap * FANOUT < keyed.len() {
            cap *= FANOUT;
        }
        tile(&mut keyed, cap);
        let ids: Vec<u32> = keyed.par_iter().map(|&(_, _, t)| t).collect();
        drop(keyed);
        let (vertices, tris) = renumbered(mesh, &ids);
        let mut tree = DropTree {
            origin: lo,
            vertices,
            tris,
            ids,
            levels: Vec::new(),
        };
        let leaves: Vec<Node> = (0..tree.len().div_ceil(FANOUT))
            .into_par_iter()
            .with_min_len(PAR_CHUNK / FANOUT)
            .map(|i| {
                let range = i * FANOUT..((i + 1) * FANOUT).min(tree.len());
                let corners: Vec<[Point3; 3]> = range.map(|p| tree.corners(p)).collect();
                leaf(&corners, tree.origin)
            })
            .collect();
        tree.levels.push(leaves);
        while let Some(last) = tree.levels.last().filter(|l| l.len() > 1) {
            let up = last.par_chunks(FANOUT).map(merge).collect();
            tree.levels.push(up);
        }
        tree.ids.shrink_to_fit();
        tree.levels.iter_mut().for_each(Vec::shrink_to_fit);
        tree
    }
}

/// The vertices of the triangles `ids` in first-use order and the triangles' corner
/// indices into them.
fn renumbered(mesh: &TriMesh, ids: &[u32]) -> (Vec<Point3>, Vec<[u32; 3]>) {
    let mut renumber = vec![u32::MAX; mesh.vertices.len()];
    let mut vertices = Vec::new();
    let tris = ids
        .iter()
        .map(|&t| {
            mesh.triangles[t as usize].map(|k| {
                let slot = &mut renumber[k as usize];
                if *slot == u32::MAX {
                    *slot = vertices.len() as u32;
                    vertices.push(mesh.vertices[k as usize]);
                }
                *slot
            })
        })
        .collect();
    vertices.shrink_to_fit();
    (vertices, tris)
}

/// A triangle's XY box centre and mesh index, while the layout is made.
type Centre = (f64, f64, u32);

/// Lays out `items` (at most `FANOUT cap` of them) for a node whose children hold
/// `cap` each: halves across the longer side of their centres' extent, each half
/// across its own longer side (ties to the mesh index, so the layout is unique), and
/// so on down to single triangles: the children of every node are compact tiles.
fn tile(items: &mut [Centre], cap: usize) {
    if items.len() <= 1 {
        return;
    }
    let halve = |items: &mut [Centre], at: usize| {
        if at >= items.len() {
            return;
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for c in items.iter() {
            lo = [lo[0].min(c.0), lo[1].min(c.1)];
            hi = [hi[0].max(c.0), hi[1].max(c.1)];
        }
        if hi[0] - lo[0] >= hi[1] - lo[1] {
            items.select_nth_unstable_by(at, |a, b| a.0.total_cmp(&b.0).then(a.2.cmp(&b.2)));
        } else {
            items.select_nth_unstable_by(at, |a, b| a.1.total_cmp(&b.1).then(a.2.cmp(&b.2)));
        }
    };
    halve(items, 2 * cap);
    let (left, right) = items.split_at_mut((2 * cap).min(items.len()));
    halve(left, cap);
    halve(right, cap);
    if cap == 1 {
        return;
    }
    let sub = cap / FANOUT;
    let mut children: Vec<&mut [Centre]> = Vec::with_capacity(FANOUT);
    let mut rest = items;
    while !rest.is_empty() {
        let (child, tail) = rest.split_at_mut(cap.min(rest.len()));
        children.push(child);
        rest = tail;
    }
    if cap >= PAR_CHUNK {
        children.into_par_iter().for_each(|c| tile(c, sub));
    } else {
        children.into_iter().for_each(|c| tile(c, sub));
    }
}

/// The node of triangles' corners (XY relative to `origin`): box, top, and a lid
/// with the slope of their mean upward normal (weighted by area) through their
/// highest corner above it.
pub(super) fn leaf(tris: &[[Point3; 3]], origin: [f64; 2]) -> Node {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    let mut n = Point3::origin().coords;
    for [p0, p1, p2] in tris {
        for p in [p0, p1, p2] {
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
            }
        }
        let m = (p1 - p0).cross(&(p2 - p0));
        n = if m.z < 0.0 { n - m } else { n + m };
    }
    let mut node = Node {
        bbox: [
            round_down(lo[0] - origin[0]),
            round_down(lo[1] - origin[1]),
            round_up(hi[0] - origin[0]),
            round_up(hi[1] - origin[1]),
        ],
        zmax: round_up(hi[2]),
        slope: [f32::NAN; 2],
        lid: f64::INFINITY,
    };
    if n.z >= BOUND_MIN_NZ * n.norm() && n.z > 0.0 {
        node.slope = [(-n.x / n.z) as f32, (-n.y / n.z) as f32];
        let o = node.centre();
        let (a, b) = (f64::from(node.slope[0]), f64::from(node.slope[1]));
        let mut lid = f64::NEG_INFINITY;
        for p in tris.iter().flatten() {
            lid = lid.max(p.z - a * (p.x - origin[0] - o[0]) - b * (p.y - origin[1] - o[1]));
        }
        node.lid = lid;
    }
    node
}

/// The node holding `nodes`: the lid's slope the mean of theirs, through the highest
/// corner of their lids over their boxes (a lid is linear, so its box's corners bound
/// it).
fn merge(nodes: &[Node]) -> Node {
    let mut up = nodes.iter().skip(1).fold(nodes[0], |a, b| Node {
        bbox: [
            a.bbox[0].min(b.bbox[0]),
            a.bbox[1].min(b.bbox[1]),
            a.bbox[2].max(b.bbox[2]),
            a.bbox[3].max(b.bbox[3]),
        ],
        zmax: a.zmax.max(b.zmax),
        slope: [f32::NAN; 2],
        lid: f64::INFINITY,
    });
    if nodes.iter().all(|n| !n.slope[0].is_nan()) {
        let k = nodes.len() as f64;
        let mean = |i: usize| nodes.iter().map(|n| f64::from(n.slope[i])).sum::<f64>() / k;
        up.slope = [mean(0) as f32, mean(1) as f32];
        let o = up.centre();
        let (a, b) = (f64::from(up.slope[0]), f64::from(up.slope[1]));
        up.lid = nodes
            .iter()
            .flat_map(|n| {
                let [x0, y0, x1, y1] = n.bbox.map(f64::from);
                [[x0, y0], [x1, y0], [x0, y1], [x1, y1]]
                    .map(|q| n.lid_at(q) - a * (q[0] - o[0]) - b * (q[1] - o[1]))
            })
            .fold(f64::NEG_INFINITY, f64::max);
    }
    up
}
