//! Building an [`XyIndex`]: bounds, base cell size, levels, anchor cells, and the
//! counting sort into the CSR layout (see the parent module's doc).
//!
//! Steps over triangles run in parallel with rayon and collect in order; the sort is
//! a sequential stable counting sort. The result is therefore the same on any number
//! of threads. Peak memory while building is about 24 bytes a triangle (keys and
//! entries) plus the offsets.

use super::layout::{
    EXTENT_SAMPLES, Level, capped_cell, counting_sort, levels, median_or_area, round_down, round_up,
};
use super::{Entry, XyIndex};
use crate::math::Aabb;
use crate::mesh::TriMesh;
use rayon::prelude::*;

/// Level-0 cell side over the median triangle XY extent. Bench `mesh_index` (disc
/// radius 4.5 mm over 0.7 mm triangles) measured 1x, 2x and 4x: 2x was fastest, 1x
/// pays a row overhead on twice the rows, 4x scans twice the area.
const CELL_PER_MEDIAN: f64 = 2.0;
/// Smallest chunk of triangles a rayon task handles while building.
const PAR_CHUNK: usize = 4096;

impl XyIndex {
    /// Builds the index with the base cell size taken from the median triangle XY
    /// extent. Deterministic; parallel over triangles.
    ///
    /// # Panics
    /// When the mesh has more than `u32::MAX` triangles or a vertex index is out of
    /// range.
    pub fn build(mesh: &TriMesh) -> XyIndex {
        XyIndex::build_with_cell_size(mesh, None)
    }

    /// As [`XyIndex::build`] with an explicit level-0 cell side `cell` (mm) when
    /// `Some` (non-positive or non-finite values fall back to the median extent).
    /// Results are the same for any cell size; only speed and memory change. The
    /// number of level-0 cells stays within about two per triangle whatever `cell` is.
    ///
    /// # Panics
    /// As [`XyIndex::build`].
    pub fn build_with_cell_size(mesh: &TriMesh, cell: Option<f64>) -> XyIndex {
        assert!(
            u32::try_from(mesh.triangles.len()).is_ok(),
            "XyIndex: more than u32::MAX triangles"
        );
        let bounds = finite_bounds(mesh);
        let origin = [bounds.min.x, bounds.min.y];
        let extent = if bounds.is_empty() {
            [0.0, 0.0]
        } else {
            [bounds.max.x - origin[0], bounds.max.y - origin[1]]
        };
        let indexed = count_finite(mesh);
        let c0 = cell
            .filter(|c| c.is_finite() && *c > 0.0)
            .unwrap_or_else(|| CELL_PER_MEDIAN * median_extent(mesh, origin, extent));
        let c0 = capped_cell(c0, extent, indexed);
        let (keys, levels, cells) = anchor_keys(mesh, origin, extent, c0);
        let (offsets, order) = counting_sort(&keys, cells);
        drop(keys);
        let entries = order
            .par_iter()
            .with_min_len(PAR_CHUNK)
            .map(|&t| Entry {
                bbox: stored_box(mesh, origin, t as usize).unwrap_or([0.0; 4]),
                id: t,
            })
            .collect();
        XyIndex {
            origin,
            bounds,
            levels,
            offsets,
            entries,
        }
    }
}

/// Box of the corners of the triangles whose corners are all finite.
fn finite_bounds(mesh: &TriMesh) -> Aabb {
    mesh.triangles
        .par_iter()
        .with_min_len(PAR_CHUNK)
        .enumerate()
        .fold(Aabb::empty, |mut b, (i, t)| {
            if mesh.usable(i) {
                t.iter().for_each(|&k| b.grow(&mesh.vertices[k as usize]));
            }
            b
        })
        .reduce(Aabb::empty, |a, b| a.union(&b))
}

fn count_finite(mesh: &TriMesh) -> usize {
    mesh.triangles
        .par_iter()
        .with_min_len(PAR_CHUNK)
        .enumerate()
        .filter(|&(i, _)| mesh.usable(i))
        .count()
}

/// Outward-rounded relative XY box of triangle `t`, `None` when a corner is not finite.
pub(super) fn stored_box(mesh: &TriMesh, origin: [f64; 2], t: usize) -> Option<[f32; 4]> {
    if !mesh.usable(t) {
        return None;
    }
    let c = mesh.triangles[t].map(|k| mesh.vertices[k as usize]);
    let lo = |a: usize| c.iter().map(|p| p[a]).fold(f64::INFINITY, f64::min) - origin[a];
    let hi = |a: usize| c.iter().map(|p| p[a]).fold(f64::NEG_INFINITY, f64::max) - origin[a];
    Some([
        round_down(lo(0)),
        round_down(lo(1)),
        round_up(hi(0)),
        round_up(hi(1)),
    ])
}

/// Median of `max(dx, dy)` over an evenly strided sample of the finite triangles, or
/// a cell from the area per triangle when that median is zero (or nothing is finite).
fn median_extent(mesh: &TriMesh, origin: [f64; 2], extent: [f64; 2]) -> f64 {
    let stride = mesh.triangles.len().div_ceil(EXTENT_SAMPLES).max(1);
    let sizes: Vec<f64> = (0..mesh.triangles.len())
        .step_by(stride)
        .filter_map(|t| stored_box(mesh, origin, t))
        .map(|b| f64::from((b[2] - b[0]).max(b[3] - b[1])))
        .collect();
    median_or_area(sizes, extent, mesh.triangles.len())
}

/// The levels (coarsest: every box fits) and each triangle's global anchor cell
/// (`u32::MAX` for a non-finite triangle); returns the total cell count too.
fn anchor_keys(
    mesh: &TriMesh,
    origin: [f64; 2],
    extent: [f64; 2],
    c0: f64,
) -> (Vec<u32>, Vec<Level>, usize) {
    let mut levels = levels(c0, extent);
    let total = levels.last().map_or(0, Level::end);
    assert!(total < u32::MAX as usize, "XyIndex: too many cells");
    let keys: Vec<u32> = (0..mesh.triangles.len())
        .into_par_iter()
        .with_min_len(PAR_CHUNK)
        .map(|t| match stored_box(mesh, origin, t) {
            Some(b) => levels
                .iter()
                .find(|l| l.fits(&b))
                .map_or(u32::MAX, |l| l.anchor(&b) as u32),
            None => u32::MAX,
        })
        .collect();
    let used = keys
        .par_iter()
        .filter(|&&k| k != u32::MAX)
        .map(|&k| levels.partition_point(|l| l.base <= k as usize))
        .max()
        .unwrap_or(0);
    levels.truncate(used.max(1));
    let cells = levels.last().map_or(0, Level::end);
    (keys, levels, cells)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Same index on one thread and on four, for a mesh spanning many rayon chunks.
    #[test]
    fn build_is_deterministic_across_thread_counts() {
        use crate::math::Point3;
        let p = |i: usize, j: usize| {
            let (x, y) = (i as f64 * 0.37, j as f64 * 0.41);
            Point3::new(x + (y * 3.0).sin(), y, x.cos())
        };
        let soup: Vec<[Point3; 3]> = (0..120 * 120)
            .flat_map(|k| {
                let (i, j) = (k % 120, k / 120);
                [
                    [p(i, j), p(i + 1, j), p(i, j + 1)],
                    [p(i + 1, j), p(i + 1, j + 1), p(i, j + 1)],
                ]
            })
            .collect();
        let mesh = TriMesh::from_triangles(&soup);
        let on = |n: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap();
            pool.install(|| XyIndex::build(&mesh))
        };
        let (a, b) = (on(1), on(4));
        assert_eq!(a.len(), mesh.len());
        assert_eq!(
            (a.offsets, a.entries, a.bounds),
            (b.offsets, b.entries, b.bounds)
        );
        assert_eq!(a.levels.len(), b.levels.len());
    }
}
