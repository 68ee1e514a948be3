//! Building an indexed mesh from triangle soup by welding exactly equal vertices.
//!
//! STL stores every triangle with its own three corners; an indexed [`TriMesh`] shares
//! them. Two corners are the same vertex when their coordinates are bit-for-bit equal
//! after mapping `-0.0` to `0.0` (`x + 0.0` does that and leaves every other value,
//! NaN included, unchanged). No tolerance is applied: welding nearby-but-different
//! points would move geometry, which is a repair, not a read.
//!
//! The table is open addressing with linear probing over `u32` vertex ids (4 bytes
//! a slot, load at most 1/2), and compares keys by looking the candidate vertex up in
//! the output vertex list, so the only per-vertex memory besides the output is the
//! table itself: about 8 to 16 bytes a vertex against roughly 40 for a
//! `std::collections::HashMap<[u64; 3], u32>` with its key copies, and a
//! multiply-rotate hash instead of SipHash. For a 10-million-triangle STL
//! (about 5 million distinct vertices) that is 32 to 64 MB of table next to the
//! 240 MB of output.

use super::TriMesh;
use crate::error::GeomError;
use crate::math::Point3;

/// Marks an empty table slot; therefore also one more than the largest vertex id.
const EMPTY: u32 = u32::MAX;
/// log2 of the smallest table.
const MIN_TABLE_BITS: u32 = 4;

/// Incremental builder of a [`TriMesh`] that welds exactly equal vertices.
///
/// # Example
/// ```
/// use swarf_geom::{MeshBuilder, Point3};
/// let mut b = MeshBuilder::new();
/// let a = b.vertex(Point3::new(1.0, 2.0, 3.0)).unwrap();
/// assert_eq!(b.vertex(Point3::new(1.0, 2.0, 3.0)).unwrap(), a);
/// assert_eq!(b.vertex(Point3::new(1.0, 2.0, 3.5)).unwrap(), a + 1);
/// ```
#[derive(Debug, Clone)]
pub struct MeshBuilder {
    vertices: Vec<Point3>,
    triangles: Vec<[u32; 3]>,
    table: Vec<u32>,
    bits: u32,
}

impl Default for MeshBuilder {
    fn default() -> Self {
        MeshBuilder::new()
    }
}

impl MeshBuilder {
    /// An empty builder.
    pub fn new() -> MeshBuilder {
        MeshBuilder::with_capacity(0, 0)
    }

    /// An empty builder with room for about `vertices` distinct vertices and
    /// `triangles` triangles (hints only; both grow as needed).
    pub fn with_capacity(vertices: usize, triangles: usize) -> MeshBuilder {
        let bits = table_bits(vertices);
        MeshBuilder {
            vertices: Vec::with_capacity(vertices),
            triangles: Vec::with_capacity(triangles),
            table: vec![EMPTY; 1 << bits],
            bits,
        }
    }

    /// The id of the vertex at `p`, adding it when no exactly equal vertex exists.
    ///
    /// # Errors
    /// [`GeomError::InvalidMesh`] when a new vertex would need an id beyond
    /// `u32::MAX - 1`.
    pub fn vertex(&mut self, p: Point3) -> Result<u32, GeomError> {
        let key = canonical(p);
        let mask = self.table.len() - 1;
        let mut slot = self.slot_of(&key);
        loop {
            let id = self.table[slot];
            if id == EMPTY {
                break;
            }
            if bits_of(&self.vertices[id as usize]) == bits_of(&key) {
                return Ok(id);
            }
            slot = (slot + 1) & mask;
        }
        let id = u32::try_from(self.vertices.len())
            .ok()
            .filter(|&id| id != EMPTY)
            .ok_or_else(|| {
                GeomError::InvalidMesh(format!(
                    "more than {} distinct vertices; the mesh index is 32-bit",
                    EMPTY - 1
                ))
            })?;
        self.vertices.push(key);
        self.table[slot] = id;
        if self.vertices.len() * 2 > self.table.len() {
            self.grow();
        }
        Ok(id)
    }

    /// Adds a triangle given by its corners, welding them into the vertex list.
    ///
    /// # Errors
    /// As [`MeshBuilder::vertex`].
    pub fn push_triangle(&mut self, corners: [Point3; 3]) -> Result<(), GeomError> {
        let t = [
            self.vertex(corners[0])?,
            self.vertex(corners[1])?,
            self.vertex(corners[2])?,
        ];
        self.triangles.push(t);
        Ok(())
    }

    /// Number of distinct vertices so far.
    pub fn vertex_count(&self) -> usize {
        self.vertices.len()
    }

    /// Number of triangles so far.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The mesh built so far. The welding table is dropped first, then the lists are
    /// shrunk to their lengths (large blocks shrink in place with the system
    /// allocator, so this does not copy).
    pub fn finish(self) -> TriMesh {
        let MeshBuilder {
            mut vertices,
            mut triangles,
            table,
            ..
        } = self;
        drop(table);
        vertices.shrink_to_fit();
        triangles.shrink_to_fit();
        TriMesh {
            vertices,
            triangles,
        }
    }

    fn slot_of(&self, p: &Point3) -> usize {
        (hash(p) >> (64 - self.bits)) as usize
    }

    /// Doubles the table and re-inserts every vertex (all distinct: no comparisons).
    fn grow(&mut self) {
        self.bits += 1;
        self.table = vec![EMPTY; 1 << self.bits];
        let mask = self.table.len() - 1;
        for (id, p) in self.vertices.iter().enumerate() {
            let mut slot = self.slot_of(p);
            while self.table[slot] != EMPTY {
                slot = (slot + 1) & mask;
            }
            self.table[slot] = id as u32;
        }
    }
}

/// Smallest table (log2) that holds `n` vertices at load at most 1/2.
fn table_bits(n: usize) -> u32 {
    let want = n.saturating_mul(2).max(1 << MIN_TABLE_BITS);
    want.next_power_of_two().trailing_zeros()
}

/// `p` with `-0.0` replaced by `0.0` in every coordinate.
fn canonical(p: Point3) -> Point3 {
    p.map(|c| c + 0.0)
}

fn bits_of(p: &Point3) -> [u64; 3] {
    [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()]
}

/// Multiply-rotate mix of the three coordinates' bits; the table uses the top bits.
fn hash(p: &Point3) -> u64 {
    let [x, y, z] = bits_of(p);
    let mut h = x.wrapping_mul(0x9E37_79B9_7F4A_7C15);
    h = (h.rotate_left(29) ^ y).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
    h = (h.rotate_left(31) ^ z).wrapping_mul(0x1656_67B1_9E37_79F9);
    h ^ (h >> 29)
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use std::collections::HashMap;

    #[test]
    fn nan_and_signed_zero() {
        let mut b = MeshBuilder::new();
        let z = b.vertex(Point3::new(0.0, -0.0, 0.0)).unwrap();
        assert_eq!(b.vertex(Point3::new(-0.0, 0.0, -0.0)).unwrap(), z);
        let n = b.vertex(Point3::new(f64::NAN, 1.0, 2.0)).unwrap();
        assert_eq!(b.vertex(Point3::new(f64::NAN, 1.0, 2.0)).unwrap(), n);
        assert_ne!(n, z);
        assert_eq!(b.vertex_count(), 2);
        let m = b.finish();
        assert!(m.vertices[0].x.is_sign_positive() && m.vertices[0].y.is_sign_positive());
    }

    #[test]
    fn grows_past_many_vertices() {
        let mut b = MeshBuilder::with_capacity(3, 0);
        for round in 0..2 {
            for i in 0..5000u32 {
                let p = Point3::new(f64::from(i % 71), f64::from(i / 71), 0.5);
                assert_eq!(b.vertex(p).unwrap(), i, "round {round}");
            }
        }
        assert_eq!(b.vertex_count(), 5000);
        assert!(b.table.len() >= 10_000 && b.table.len().is_power_of_two());
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Against a std HashMap on the canonical bit patterns.
        #[test]
        fn welds_like_a_hash_map(coords in prop::collection::vec((0u8..6, 0u8..6, 0u8..3), 3..300)) {
            let pts: Vec<Point3> = coords
                .iter()
                .map(|&(x, y, z)| Point3::new(f64::from(x) - 2.0, f64::from(y) * 0.5, -f64::from(z)))
                .collect();
            let tris: Vec<[Point3; 3]> = pts.chunks_exact(3).map(|c| [c[0], c[1], c[2]]).collect();
            let m = TriMesh::from_triangles(&tris);
            let mut oracle: HashMap<[u64; 3], u32> = HashMap::new();
            let mut ids = Vec::new();
            for p in tris.iter().flatten() {
                let n = oracle.len() as u32;
                ids.push(*oracle.entry(bits_of(&canonical(*p))).or_insert(n));
            }
            prop_assert_eq!(m.vertices.len(), oracle.len());
            let flat: Vec<u32> = m.triangles.iter().flatten().copied().collect();
            prop_assert_eq!(flat, ids);
            for (i, t) in tris.iter().enumerate() {
                prop_assert_eq!(m.triangle(i), *t);
            }
        }
    }
}
