//! Triangle meshes: an indexed vertex/triangle list, its validation and an XY index.
//!
//! A [`TriMesh`] is the plain indexed form every mesh format reduces to: shared vertex
//! positions and triangles as three indices into them. Vertices are `u32`-indexed,
//! which halves the triangle list against `usize` and still allows four billion
//! vertices; meshes of ten million triangles (a 500 MB binary STL) are the design
//! size. The algorithms live in one file each beside this one:
//!
//! - [`weld`]: building a mesh from triangle soup, merging exactly equal vertices;
//! - [`validate`]: non-finite, degenerate and duplicate triangles;
//! - [`index`]: the uniform-grid XY index that drop-cutter and the dexel
//!   simulation query millions of times.

pub mod index;
pub mod validate;
pub mod weld;

use crate::error::GeomError;
use crate::math::{Aabb, Point3, Vec3};
use serde::{Deserialize, Serialize};

pub use index::XyIndex;
pub use validate::{DEGENERATE_AREA_REL, MeshReport};
pub use weld::MeshBuilder;

/// An indexed triangle mesh, mm.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct TriMesh {
    /// Vertex positions.
    pub vertices: Vec<Point3>,
    /// Triangles as indices into `vertices`, counter-clockwise seen from outside.
    pub triangles: Vec<[u32; 3]>,
}

impl TriMesh {
    /// A mesh from vertices and triangles, checking that every index is in range.
    ///
    /// # Units
    /// Vertex positions in mm.
    ///
    /// # Errors
    /// [`GeomError::InvalidMesh`] naming the first triangle with an index out of range.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Point3, TriMesh};
    /// let v = vec![Point3::origin(), Point3::new(1.0, 0.0, 0.0), Point3::new(0.0, 1.0, 0.0)];
    /// assert_eq!(TriMesh::new(v.clone(), vec![[0, 1, 2]]).unwrap().len(), 1);
    /// assert!(TriMesh::new(v, vec![[0, 1, 3]]).is_err());
    /// ```
    pub fn new(vertices: Vec<Point3>, triangles: Vec<[u32; 3]>) -> Result<TriMesh, GeomError> {
        let n = vertices.len();
        if let Some(i) = triangles
            .iter()
            .position(|t| t.iter().any(|&k| k as usize >= n))
        {
            return Err(GeomError::InvalidMesh(format!(
                "triangle {i} has vertex indices {:?}, expected each below the vertex count {n}",
                triangles[i]
            )));
        }
        Ok(TriMesh {
            vertices,
            triangles,
        })
    }

    /// A mesh from a triangle soup, welding vertices whose coordinates are exactly
    /// equal (`-0.0` counts as `0.0`); see [`MeshBuilder`].
    ///
    /// # Panics
    /// When the soup holds more than `u32::MAX - 1` distinct vertices (over 100 GB of
    /// input); use [`MeshBuilder`] directly to get an error instead.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Point3, TriMesh};
    /// let [a, b, c, d] = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]
    ///     .map(|[x, y]| Point3::new(x, y, 0.0));
    /// let m = TriMesh::from_triangles(&[[a, b, c], [a, c, d]]);
    /// assert_eq!((m.vertices.len(), m.triangles[1]), (4, [0, 2, 3]));
    /// ```
    pub fn from_triangles(triangles: &[[Point3; 3]]) -> TriMesh {
        let mut builder = MeshBuilder::with_capacity(triangles.len(), triangles.len());
        for t in triangles {
            if let Err(e) = builder.push_triangle(*t) {
                panic!("{e}");
            }
        }
        builder.finish()
    }

    /// The corners of triangle `i`.
    ///
    /// # Panics
    /// When `i >= self.len()` (or the mesh was built with out-of-range indices by
    /// writing the public fields directly).
    pub fn triangle(&self, i: usize) -> [Point3; 3] {
        self.triangles[i].map(|k| self.vertices[k as usize])
    }

    /// Number of triangles.
    pub fn len(&self) -> usize {
        self.triangles.len()
    }

    /// Whether triangle `t`'s corners are all usable: finite and within the coordinate
    /// domain ([`crate::domain::usable_point`]). Every consumer skips the others.
    pub fn usable(&self, t: usize) -> bool {
        self.triangles[t]
            .iter()
            .all(|&k| crate::domain::usable_point(&self.vertices[k as usize]))
    }

    /// True when the mesh has no triangle.
    pub fn is_empty(&self) -> bool {
        self.triangles.is_empty()
    }

    /// Box around the corners of the usable triangles ([`TriMesh::usable`]; empty
    /// when there is none).
    pub fn aabb(&self) -> Aabb {
        let mut b = Aabb::empty();
        for (i, t) in self.triangles.iter().enumerate() {
            if self.usable(i) {
                t.iter().for_each(|&k| b.grow(&self.vertices[k as usize]));
            }
        }
        b
    }

    /// Unit normal of triangle `i` by the right-hand rule over its corner order, or
    /// `None` when the triangle has no well-defined normal (zero area within
    /// [`DEGENERATE_AREA_REL`], or non-finite).
    ///
    /// # Panics
    /// When `i >= self.len()`.
    pub fn normal(&self, i: usize) -> Option<Vec3> {
        let [a, b, c] = self.triangle(i);
        let n = (b - a).cross(&(c - a));
        let longest = (b - a)
            .norm_squared()
            .max((c - b).norm_squared())
            .max((a - c).norm_squared());
        let twice_area = n.norm();
        if !twice_area.is_finite() || twice_area <= DEGENERATE_AREA_REL * longest {
            return None;
        }
        Some(n.normalize())
    }

    /// Appends `other`'s vertices and triangles (indices shifted). Vertices are not
    /// welded across the two.
    ///
    /// # Panics
    /// When the result would hold more than `u32::MAX` vertices.
    pub fn append(&mut self, other: &TriMesh) {
        let total = self.vertices.len() + other.vertices.len();
        assert!(
            total <= u32::MAX as usize,
            "TriMesh::append: {total} vertices, more than u32::MAX"
        );
        let shift = self.vertices.len() as u32;
        self.vertices.extend_from_slice(&other.vertices);
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|k| k + shift)));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(x: f64, y: f64, z: f64) -> Point3 {
        Point3::new(x, y, z)
    }

    #[test]
    fn new_rejects_out_of_range_and_names_triangle() {
        let v = vec![p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)];
        let e = TriMesh::new(v, vec![[0, 1, 2], [2, 1, 0], [0, 3, 1]]).unwrap_err();
        let s = e.to_string();
        assert!(s.contains("triangle 2") && s.contains("[0, 3, 1]"), "{s}");
    }

    #[test]
    fn from_triangles_welds_exact_equals_only() {
        let a = p(0.0, 0.0, 0.0);
        let a_neg = p(-0.0, 0.0, -0.0);
        let b = p(1.0, 0.0, 0.0);
        let b_near = p(1.0 + f64::EPSILON, 0.0, 0.0);
        let c = p(0.0, 1.0, 0.0);
        let m = TriMesh::from_triangles(&[[a, b, c], [a_neg, c, b_near]]);
        assert_eq!(m.vertices.len(), 4);
        assert_eq!(m.triangles, vec![[0, 1, 2], [0, 2, 3]]);
        assert_eq!(m.triangle(1), [a, c, b_near]);
        assert_eq!(m.len(), 2);
        assert!(!m.is_empty() && TriMesh::default().is_empty());
    }

    #[test]
    fn aabb_and_normal() {
        let m = TriMesh::from_triangles(&[
            [p(0.0, 0.0, 1.0), p(2.0, 0.0, 1.0), p(0.0, 3.0, 1.0)],
            [p(0.0, 0.0, 0.0), p(1.0, 1.0, 1.0), p(2.0, 2.0, 2.0)],
            [p(f64::NAN, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)],
        ]);
        let b = m.aabb();
        assert_eq!((b.min, b.max), (p(0.0, 0.0, 0.0), p(2.0, 3.0, 2.0)));
        assert_eq!(m.normal(0), Some(Vec3::z()));
        assert_eq!(m.normal(1), None);
        assert_eq!(m.normal(2), None);
        let flipped = TriMesh::new(m.vertices.clone(), vec![[0, 2, 1]]).unwrap();
        assert_eq!(flipped.normal(0), Some(-Vec3::z()));
        assert!(TriMesh::default().aabb().is_empty());
    }

    #[test]
    fn append_shifts_indices() {
        let t = [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)];
        let mut m = TriMesh::from_triangles(&[t]);
        let other = TriMesh::from_triangles(&[t.map(|q| q + Vec3::z())]);
        m.append(&other);
        assert_eq!(m.triangles, vec![[0, 1, 2], [3, 4, 5]]);
        assert_eq!(m.triangle(1)[2], p(0.0, 1.0, 1.0));
    }
}
