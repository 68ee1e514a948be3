//! Drop-cutter on a whole mesh: the highest triangle contact under the cutter.
//!
//! The drop height is the maximum over the triangles within reach of their own drop
//! ([`super::kernel`]). Most of them cannot win, and proving that is cheaper than
//! dropping onto them: the cutter's lower surface is `tip + h(rho)` with `h`
//! increasing, so a triangle whose XY box is `rho_min` from the axis and whose top is
//! `z_max` puts the tip at most at `ub = z_max - h(rho_min)`. The same bound holds
//! for a box of triangles with the top of the highest, so the search runs best first
//! down the drop tree (`super::tree`): boxes and triangles in descending `ub` from
//! one heap, stopping at the first whose bound is below the best height found so
//! far, and whole boxes of triangles that cannot win are dismissed at once. Each
//! visit is [`super::kernel::triangle_drop_above`] with the best height as floor,
//! which settles most triangles with their plane's drop alone. The search starts from
//! the triangle that won the previous drop of the same scratch (neighbouring points
//! of a raster or grid row touch the same or a nearby triangle), so the best height
//! is near the answer from the start.
//!
//! Ties: the highest contact wins; equal heights go to the lowest triangle index, so
//! the result does not depend on the visiting order or on threads. Nothing is
//! allocated per query: callers pass a [`DropScratch`] they reuse (one per thread).
//!
//! For double-contact detection, [`MeshDropper::drop_with_contacts`] keeps every
//! triangle contact within a tolerance of the top (its bound is relaxed by the same
//! tolerance).

use super::facet::barycentric_xy;
use super::kernel::triangle_drop_above;
use super::tree::{DropTree, Flat, Item, Search};
use super::{DropCutter, Feature};
use crate::cutter::Cutter;
use swarf_geom::{Point3, TriMesh};

/// The result of a drop: tip height and the winning contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DropResult {
    /// Tool tip height (the CL point's z), mm.
    pub z: f64,
    /// Index of the touched triangle in the mesh.
    pub tri: u32,
    /// The feature touched.
    pub feature: Feature,
    /// The CC point, mm.
    pub cc: Point3,
}

/// Reusable per-thread working memory for drops. It also remembers the triangle of
/// the last drop, tried first on the next one: neighbouring points (a raster, a grid
/// row) usually touch the same or a nearby triangle, so the search starts with a
/// height close to the answer and prunes almost everything else. Results never
/// depend on it (module doc).
#[derive(Debug, Default, Clone)]
pub struct DropScratch {
    heap: Vec<Item>,
    near: Vec<DropResult>,
    hint: Option<u32>,
}

/// The best contact so far and the tree position it came from.
type Best = Option<(DropResult, usize)>;

/// The contacts of one drop within a tolerance of its height.
pub type TopContacts = Vec<DropResult>;

/// A mesh prepared for drops of one cutter.
///
/// # Example
/// ```
/// use swarf_geom::{Point3, TriMesh};
/// use swarf_tool::drop::{MeshDropper, DropScratch};
/// let p = |x: f64, y: f64| Point3::new(x, y, 2.0);
/// let mesh = TriMesh::from_triangles(&[[p(-9.0, -9.0), p(9.0, -9.0), p(0.0, 9.0)]]);
/// let dropper = MeshDropper::new(&mesh, &"bull:d=10,r=2".parse().unwrap());
/// let mut scratch = DropScratch::default();
/// assert_eq!(dropper.drop(0.0, 0.0, &mut scratch).unwrap().z, 2.0);
/// assert!(dropper.drop(50.0, 0.0, &mut scratch).is_none());
/// ```
#[derive(Debug, Clone)]
pub struct MeshDropper {
    tool: DropCutter,
    tree: DropTree,
}

impl MeshDropper {
    /// Prepares `mesh` for drops of `cutter`. Triangles with a non-finite corner are
    /// ignored (see [`swarf_geom::TriMesh::validate`] to report them).
    ///
    /// # Panics
    /// When the mesh has `u32::MAX` triangles or more, or a vertex index is out of
    /// range (a `TriMesh` built with [`TriMesh::new`] has none).
    pub fn new(mesh: &TriMesh, cutter: &Cutter) -> MeshDropper {
        MeshDropper {
            tool: DropCutter::new(cutter),
            tree: DropTree::build(mesh),
        }
    }

    /// The prepared cutter.
    pub fn tool(&self) -> &DropCutter {
        &self.tool
    }

    /// Number of triangles that drops can touch (the finite ones).
    pub fn len(&self) -> usize {
        self.tree.len()
    }

    /// True when no triangle can be touched.
    pub fn is_empty(&self) -> bool {
        self.tree.len() == 0
    }

    /// Heap bytes [`MeshDropper::new`] will hold for `mesh`, estimated before
    /// anything is built (an upper bound of [`MeshDropper::memory_bytes`]), for
    /// memory caps checked before allocation.
    pub fn estimate_bytes(mesh: &TriMesh) -> usize {
        DropTree::estimate_bytes(mesh)
    }

    /// Heap bytes held (the tree: vertices, triangle indices, nodes), for memory
    /// reports.
    pub fn memory_bytes(&self) -> usize {
        self.tree.memory_bytes()
    }

    /// Drops the cutter at `(x, y)`: the tip height and contact, or `None` where no
    /// triangle is within reach (off the mesh) or `x`, `y` is not finite.
    ///
    /// # Units
    /// mm.
    pub fn drop(&self, x: f64, y: f64, scratch: &mut DropScratch) -> Option<DropResult> {
        self.run(&self.tool, x, y, 0.0, scratch, false)
    }

    /// As [`MeshDropper::drop`] for another cutter `tool` over the same mesh and tree
    /// (the pieces of a shank and holder, [`crate::holder`], share one tree).
    ///
    /// # Units
    /// mm.
    pub fn drop_tool(
        &self,
        tool: &DropCutter,
        x: f64,
        y: f64,
        scratch: &mut DropScratch,
    ) -> Option<DropResult> {
        self.run(tool, x, y, 0.0, scratch, false)
    }

    /// As [`MeshDropper::drop`], and fills `contacts` with every triangle contact
    /// within `tol` (mm) of the top, in ascending triangle order (the winner
    /// included).
    pub fn drop_with_contacts(
        &self,
        x: f64,
        y: f64,
        tol: f64,
        scratch: &mut DropScratch,
        contacts: &mut TopContacts,
    ) -> Option<DropResult> {
        contacts.clear();
        let best = self.run(&self.tool, x, y, tol.max(0.0), scratch, true)?;
        contacts.extend(scratch.near.iter().filter(|c| c.z >= best.z - tol));
        contacts.sort_by_key(|c| c.tri);
        Some(best)
    }

    /// Height of the mesh itself at `(x, y)`: the highest triangle whose XY projection
    /// holds the point (a drop of a needle); `None` off the mesh. Its working memory
    /// is one heap per thread, kept between calls (callers probe single points
    /// without a scratch of their own).
    ///
    /// # Units
    /// mm.
    pub fn surface_z(&self, x: f64, y: f64) -> Option<f64> {
        thread_local! {
            static HEAP: std::cell::RefCell<Vec<Item>> = const { std::cell::RefCell::new(Vec::new()) };
        }
        let mut needle = Point {
            tree: &self.tree,
            xy: [x, y],
            best: None,
        };
        HEAP.with_borrow_mut(|heap| {
            self.tree.search([x, y], 0.0, &Flat(0.0), heap, &mut needle);
        });
        needle.best
    }

    fn run(
        &self,
        tool: &DropCutter,
        x: f64,
        y: f64,
        slack: f64,
        scratch: &mut DropScratch,
        keep: bool,
    ) -> Option<DropResult> {
        scratch.near.clear();
        let hint = scratch
            .hint
            .take()
            .map(|e| e as usize)
            .filter(|&e| e < self.tree.len());
        let mut s = Descent {
            tree: &self.tree,
            tool,
            xy: [x, y],
            slack,
            best: None,
            near: keep.then_some(&mut scratch.near),
            hint,
        };
        if let Some(e) = hint {
            s.consider(e, f64::NEG_INFINITY);
        }
        self.tree.search(
            [x, y],
            tool.radius(),
            tool.envelope(),
            &mut scratch.heap,
            &mut s,
        );
        scratch.hint = s.best.map(|b| b.1 as u32);
        s.best.map(|b| b.0)
    }
}

/// One drop's search: the best contact so far and the contacts near the top.
struct Descent<'a> {
    tree: &'a DropTree,
    tool: &'a DropCutter,
    xy: [f64; 2],
    slack: f64,
    best: Best,
    near: Option<&'a mut Vec<DropResult>>,
    hint: Option<usize>,
}

impl Descent<'_> {
    /// The height below which nothing is wanted.
    fn floor(&self) -> f64 {
        self.best.map_or(f64::NEG_INFINITY, |b| b.0.z - self.slack)
    }

    /// Drops onto the triangle at tree position `e` at or above `floor`; keeps the
    /// better of it and the best (ties to the lower triangle index) and records it in
    /// the near contacts.
    fn consider(&mut self, e: usize, floor: f64) {
        let Some(c) = triangle_drop_above(self.tool, self.xy, &self.tree.corners(e), floor) else {
            return;
        };
        let r = DropResult {
            z: c.z,
            tri: self.tree.ids[e],
            feature: c.feature,
            cc: c.cc,
        };
        if let Some(near) = self.near.as_deref_mut() {
            near.push(r);
        }
        if self
            .best
            .is_none_or(|(b, _)| r.z > b.z || (r.z == b.z && r.tri < b.tri))
        {
            self.best = Some((r, e));
        }
    }
}

impl Search for Descent<'_> {
    fn wants(&self, ub: f64) -> bool {
        ub >= self.floor()
    }

    fn visit(&mut self, pos: usize) {
        if Some(pos) != self.hint {
            self.consider(pos, self.floor());
        }
    }
}

/// The search of [`MeshDropper::surface_z`]: the highest triangle holding a point.
struct Point<'a> {
    tree: &'a DropTree,
    xy: [f64; 2],
    best: Option<f64>,
}

impl Search for Point<'_> {
    fn wants(&self, ub: f64) -> bool {
        self.best.is_none_or(|b| ub >= b)
    }

    fn visit(&mut self, pos: usize) {
        let t = self.tree.corners(pos);
        if let Some(l) = barycentric_xy(&t, self.xy) {
            let z = l[0] * t[0].z + l[1] * t[1].z + l[2] * t[2].z;
            if self.best.is_none_or(|b| z > b) {
                self.best = Some(z);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ties_go_to_the_lowest_triangle_and_contacts_are_collected() {
        // Two flat squares side by side at the same height, a flat end over their
        // common edge: every triangle touching gives z = 1.
        let p = |x: f64, y: f64| Point3::new(x, y, 1.0);
        let mesh = TriMesh::from_triangles(&[
            [p(0.0, 0.0), p(10.0, 0.0), p(10.0, 10.0)],
            [p(0.0, 0.0), p(10.0, 10.0), p(0.0, 10.0)],
            [p(10.0, 0.0), p(20.0, 0.0), p(20.0, 10.0)],
            [p(10.0, 0.0), p(20.0, 10.0), p(10.0, 10.0)],
        ]);
        let d = MeshDropper::new(&mesh, &"flat:d=4".parse().unwrap());
        let mut s = DropScratch::default();
        let r = d.drop(10.0, 5.0, &mut s).unwrap();
        assert_eq!((r.z, r.tri), (1.0, 0));
        let mut contacts = Vec::new();
        let r2 = d
            .drop_with_contacts(10.0, 5.0, 1e-6, &mut s, &mut contacts)
            .unwrap();
        assert_eq!(r2, r);
        // Triangles 1 and 2 lie beyond the diagonals, more than 2 mm away.
        assert_eq!(
            contacts.iter().map(|c| c.tri).collect::<Vec<_>>(),
            vec![0, 3]
        );
        assert!(d.drop(f64::NAN, 5.0, &mut s).is_none());
        assert_eq!(d.len(), 4);
        assert_eq!(d.surface_z(10.0, 5.0), Some(1.0));
        assert_eq!(d.surface_z(-1.0, 5.0), None);
    }
}
