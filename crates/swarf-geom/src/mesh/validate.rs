//! Mesh validation: non-finite, degenerate and duplicate triangles.
//!
//! - *Non-finite*: a corner has a NaN or infinite coordinate. Such triangles are not
//!   checked further.
//! - *Degenerate*: two corners share a vertex index or a position, or the area is
//!   zero relative to the triangle's size: `|(b - a) x (c - a)| <= eps * l^2` with `l`
//!   the longest edge and `eps` = [`DEGENERATE_AREA_REL`]. The cross product's length
//!   is twice the area and `l^2 / 2` bounds the area of a triangle with longest edge
//!   `l` up to a constant, so the test is scale-free: it flags needles and caps whose
//!   height is below about `eps * l`, which carry no usable normal.
//! - *Duplicate*: the same three positions as an earlier triangle, in any order and
//!   either winding. Positions are compared exactly (after welding, `-0.0 == 0.0`),
//!   by sorting the triangles on their sorted canonical vertex ids, which costs
//!   16 bytes a triangle instead of a hash map of 72-byte keys.

use super::TriMesh;
use super::weld::MeshBuilder;
use std::fmt;

/// Relative area below which a triangle counts as degenerate (dimensionless):
/// `|(b - a) x (c - a)| <= DEGENERATE_AREA_REL * longest_edge^2`.
pub const DEGENERATE_AREA_REL: f64 = 1e-12;

/// How many entries of each kind [`MeshReport`]'s `Display` lists before "and N more".
const SHOWN: usize = 20;

/// What [`TriMesh::validate`] found; all entries are triangle indices, ascending.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct MeshReport {
    /// Triangles with a corner coordinate that is NaN, infinite or outside the
    /// coordinate domain ([`crate::domain::usable_point`]).
    pub non_finite: Vec<usize>,
    /// Triangles of zero area (repeated vertex index or position, or relative area
    /// within [`DEGENERATE_AREA_REL`]).
    pub degenerate: Vec<usize>,
    /// `(first, duplicate)`: triangle `duplicate` has the same three corner positions
    /// as the earlier triangle `first`. Sorted by `duplicate`.
    pub duplicate: Vec<(usize, usize)>,
}

impl MeshReport {
    /// True when nothing was found.
    pub fn is_clean(&self) -> bool {
        self.non_finite.is_empty() && self.degenerate.is_empty() && self.duplicate.is_empty()
    }
}

impl fmt::Display for MeshReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_clean() {
            return write!(f, "mesh is clean");
        }
        let mut first = true;
        let mut section = |f: &mut fmt::Formatter<'_>, what: &str, items: Vec<String>| {
            if items.is_empty() {
                return Ok(());
            }
            if !first {
                writeln!(f)?;
            }
            first = false;
            write!(f, "{} {what} triangle(s): ", items.len())?;
            write!(f, "{}", items[..items.len().min(SHOWN)].join(", "))?;
            if items.len() > SHOWN {
                write!(f, ", and {} more", items.len() - SHOWN)?;
            }
            Ok(())
        };
        let list = |v: &[usize]| v.iter().map(ToString::to_string).collect();
        section(f, "non-finite or out-of-range", list(&self.non_finite))?;
        section(f, "degenerate", list(&self.degenerate))?;
        let dups = self
            .duplicate
            .iter()
            .map(|(a, b)| format!("{b} (same as {a})"))
            .collect();
        section(f, "duplicate", dups)
    }
}

impl TriMesh {
    /// Lists the non-finite, degenerate and duplicate triangles (see the module doc).
    ///
    /// # Panics
    /// When a triangle's vertex index is out of range (impossible for meshes made by
    /// [`TriMesh::new`] or [`TriMesh::from_triangles`]).
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Point3, TriMesh};
    /// let [a, b, c] = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]].map(|[x, y]| Point3::new(x, y, 0.0));
    /// let m = TriMesh::from_triangles(&[[a, b, c], [b, a, c], [a, a, b]]);
    /// let r = m.validate();
    /// assert_eq!((r.degenerate, r.duplicate), (vec![2], vec![(0, 1)]));
    /// ```
    pub fn validate(&self) -> MeshReport {
        let mut report = MeshReport::default();
        for i in 0..self.len() {
            if !self.usable(i) {
                report.non_finite.push(i);
            } else if self.is_degenerate(i) {
                report.degenerate.push(i);
            }
        }
        report.duplicate = self.duplicates();
        report
    }

    fn is_degenerate(&self, i: usize) -> bool {
        let [ia, ib, ic] = self.triangles[i];
        if ia == ib || ib == ic || ia == ic {
            return true;
        }
        let [a, b, c] = self.triangle(i);
        if a == b || b == c || a == c {
            return true;
        }
        let longest = (b - a)
            .norm_squared()
            .max((c - b).norm_squared())
            .max((a - c).norm_squared());
        (b - a).cross(&(c - a)).norm() <= DEGENERATE_AREA_REL * longest
    }

    /// `(first, duplicate)` pairs among the finite triangles, sorted by `duplicate`.
    fn duplicates(&self) -> Vec<(usize, usize)> {
        let mut welder = MeshBuilder::with_capacity(self.vertices.len(), 0);
        let mut ids = Vec::with_capacity(self.vertices.len());
        for p in &self.vertices {
            match welder.vertex(*p) {
                Ok(id) => ids.push(id),
                Err(_) => return Vec::new(),
            }
        }
        drop(welder);
        let mut keyed: Vec<([u32; 3], u32)> = self
            .triangles
            .iter()
            .enumerate()
            .filter(|&(i, _)| self.usable(i))
            .map(|(i, t)| {
                let mut key = t.map(|k| ids[k as usize]);
                key.sort_unstable();
                (key, i as u32)
            })
            .collect();
        keyed.sort_unstable();
        let mut pairs = Vec::new();
        for run in keyed.chunk_by(|a, b| a.0 == b.0) {
            let first = run[0].1 as usize;
            pairs.extend(run[1..].iter().map(|&(_, i)| (first, i as usize)));
        }
        pairs.sort_unstable_by_key(|&(_, d)| d);
        pairs
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Point3;
    use proptest::prelude::*;

    fn p(x: f64, y: f64, z: f64) -> Point3 {
        Point3::new(x, y, z)
    }

    #[test]
    fn finds_each_kind() {
        let (a, b, c, d) = (
            p(0.0, 0.0, 0.0),
            p(1.0, 0.0, 0.0),
            p(0.0, 1.0, 0.0),
            p(1.0, 1.0, 0.0),
        );
        let needle = p(2.0, 1e-13, 0.0);
        let m = TriMesh::from_triangles(&[
            [a, b, c],
            [b, d, c],
            [c, b, a],
            [a, b, needle],
            [p(f64::NAN, 0.0, 0.0), b, c],
            [b, c, a],
            [a, b, p(0.5, 1e-6, 0.0)],
            [a, b, p(0.5, 2e6, 0.0)],
        ]);
        let r = m.validate();
        assert_eq!(r.non_finite, vec![4, 7]);
        assert_eq!(r.degenerate, vec![3]);
        assert_eq!(r.duplicate, vec![(0, 2), (0, 5)]);
        assert!(!r.is_clean());
        let s = r.to_string();
        assert!(
            s.contains("2 non-finite or out-of-range triangle(s): 4, 7"),
            "{s}"
        );
        assert!(s.contains("2 (same as 0), 5 (same as 0)"), "{s}");
    }

    #[test]
    fn repeated_index_and_unwelded_position_are_degenerate() {
        let v = vec![p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 0.0, 0.0)];
        let m = TriMesh::new(v, vec![[0, 0, 1], [0, 1, 2]]).unwrap();
        assert_eq!(m.validate().degenerate, vec![0, 1]);
    }

    #[test]
    fn display_truncates_and_clean_mesh() {
        let r = MeshReport {
            non_finite: (0..25).collect(),
            ..MeshReport::default()
        };
        let s = r.to_string();
        assert!(s.ends_with("19, and 5 more"), "{s}");
        assert!(!s.contains("20,"), "{s}");
        let clean =
            TriMesh::from_triangles(&[[p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.0, 1.0, 0.0)]]);
        assert!(clean.validate().is_clean());
        assert_eq!(clean.validate().to_string(), "mesh is clean");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Duplicates against an O(n^2) comparison of sorted corner lists.
        #[test]
        fn duplicates_match_brute_force(
            tris in prop::collection::vec(prop::array::uniform3((0u8..3, 0u8..3)), 1..40),
            perm in 0usize..6,
        ) {
            let pt = |(x, y): (u8, u8)| p(f64::from(x), f64::from(y), f64::from(x) * 0.25);
            let order = [[0, 1, 2], [1, 2, 0], [2, 0, 1], [0, 2, 1], [2, 1, 0], [1, 0, 2]][perm];
            let soup: Vec<[Point3; 3]> = tris
                .iter()
                .enumerate()
                .map(|(i, t)| if i % 2 == 1 { order.map(|k| pt(t[k])) } else { t.map(pt) })
                .collect();
            let m = TriMesh::from_triangles(&soup);
            let sorted = |t: &[Point3; 3]| {
                let mut k: Vec<(u64, u64, u64)> =
                    t.iter().map(|q| (q.x.to_bits(), q.y.to_bits(), q.z.to_bits())).collect();
                k.sort_unstable();
                k
            };
            let mut want = Vec::new();
            for j in 0..soup.len() {
                if let Some(i) = (0..j).find(|&i| sorted(&soup[i]) == sorted(&soup[j])) {
                    want.push((i, j));
                }
            }
            let r = m.validate();
            prop_assert_eq!(r.duplicate, want);
            for (i, t) in soup.iter().enumerate() {
                let flat = t[0] == t[1] || t[1] == t[2] || t[0] == t[2]
                    || (t[1] - t[0]).cross(&(t[2] - t[0])).norm() == 0.0;
                prop_assert_eq!(r.degenerate.contains(&i), flat);
            }
        }
    }
}
