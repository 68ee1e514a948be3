//! The height query on a triangle mesh: the vertical hits of the triangles that the
//! [`XyIndex`] returns around the query point, the highest (upper envelope) or the
//! lowest (lower envelope) kept.

use super::triangle::{Lattice, cover, query_rect, vertical_hit};
use crate::math::{Point3, Vec3};
use crate::mesh::{TriMesh, XyIndex};
use rayon::prelude::*;
use std::borrow::Cow;

/// A triangle mesh prepared for height queries.
#[derive(Debug, Clone)]
pub struct MeshHeights<'a> {
    mesh: Cow<'a, TriMesh>,
    index: XyIndex,
}

impl<'a> MeshHeights<'a> {
    /// Indexes a borrowed `mesh` in XY.
    pub fn new(mesh: &'a TriMesh) -> MeshHeights<'a> {
        MeshHeights {
            index: XyIndex::build(mesh),
            mesh: Cow::Borrowed(mesh),
        }
    }

    /// Indexes an owned `mesh` in XY.
    pub fn owned(mesh: TriMesh) -> MeshHeights<'static> {
        MeshHeights {
            index: XyIndex::build(&mesh),
            mesh: Cow::Owned(mesh),
        }
    }

    /// The mesh.
    pub fn mesh(&self) -> &TriMesh {
        &self.mesh
    }

    /// The heights of every triangle above or below `(x, y)`, reduced by `pick`.
    fn reduce(&self, x: f64, y: f64, pick: fn(f64, f64) -> f64) -> Option<f64> {
        let mut best: Option<f64> = None;
        let (lo, hi) = query_rect(x, y);
        self.index.for_each_in_rect(lo, hi, |t| {
            if let Some(z) = vertical_hit(&self.mesh.triangle(t as usize), x, y) {
                best = Some(best.map_or(z, |b| pick(b, z)));
            }
        });
        best
    }

    /// The upper envelope at `(x, y)`: the highest triangle point above it; `None`
    /// outside the mesh's XY shadow.
    ///
    /// # Units
    /// mm.
    pub fn upper(&self, x: f64, y: f64) -> Option<f64> {
        self.reduce(x, y, f64::max)
    }

    /// The lower envelope at `(x, y)`: the lowest triangle point above or below it;
    /// `None` outside the mesh's XY shadow.
    ///
    /// # Units
    /// mm.
    pub fn lower(&self, x: f64, y: f64) -> Option<f64> {
        self.reduce(x, y, f64::min)
    }

    /// [`MeshHeights::upper`] for every point, in parallel, answers in order.
    ///
    /// # Units
    /// mm.
    pub fn upper_points(&self, points: &[[f64; 2]]) -> Vec<Option<f64>> {
        points.par_iter().map(|&[x, y]| self.upper(x, y)).collect()
    }

    /// The upper envelope at every point of rows `j0..=j1` of `grid`: calls
    /// `put(index_in_band, z, unit upward normal)` where the mesh has a height,
    /// `index_in_band = (j - j0) nx + i`; the triangles are scan-converted over the
    /// band (one index query per band).
    ///
    /// # Units
    /// mm.
    pub fn fill_rows(
        &self,
        grid: &impl Lattice,
        j0: usize,
        j1: usize,
        mut put: impl FnMut(usize, f64, Vec3),
    ) {
        let nx = grid.nx();
        if nx == 0 || j1 < j0 {
            return;
        }
        let mut best = vec![(f64::NAN, u32::MAX); (j1 - j0 + 1) * nx];
        let (lo, _) = query_rect(grid.x(0), grid.y(j0));
        let (_, hi) = query_rect(grid.x(nx - 1), grid.y(j1));
        self.index.for_each_in_rect(lo, hi, |t| {
            let tri = self.mesh.triangle(t as usize);
            let p = tri.map(|q| [q.x, q.y, q.z]);
            cover(grid, j0, j1, &p, |k, w| {
                let z = w[0] * p[0][2] + w[1] * p[1][2] + w[2] * p[2][2];
                if best[k].0.is_nan() || z > best[k].0 {
                    best[k] = (z, t);
                }
            });
        });
        for (k, &(z, t)) in best.iter().enumerate() {
            if t != u32::MAX {
                put(k, z, upward(&self.mesh.triangle(t as usize)));
            }
        }
    }
}

/// Unit normal of a triangle, turned upward (`+z` for one without area).
fn upward(t: &[Point3; 3]) -> Vec3 {
    let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
    let n = if n.z < 0.0 { -n } else { n };
    n.try_normalize(0.0).unwrap_or(Vec3::z())
}
