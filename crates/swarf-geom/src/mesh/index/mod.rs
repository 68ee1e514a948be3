//! XY index of a triangle mesh: which triangles' XY bounding boxes meet a disc or a
//! rectangle.
//!
//! Drop-cutter asks this millions of times per tool path (a disc of the tool radius,
//! typically 4-5 mm, over ~1 mm triangles, meshes up to 10 million triangles), and so
//! does the dexel simulation; the answer must be exact, deterministic and cheap.
//!
//! # Structure: a hierarchical uniform grid with one anchor cell per triangle
//!
//! Level `k` is a uniform grid of square cells of side `c_k = c_0 * 2^k` over the
//! mesh's XY bounds; `c_0` is the median triangle XY extent (`max(dx, dy)`, from a
//! fixed sample). A triangle is stored once, in the lowest level where its box spans
//! at most two cells in x and in y, in the cell holding its box's lower-left corner
//! (its *anchor*). With `cell(v) = clamp(floor(v / c_k))`, which is monotone, a box
//! `[a, b]` meets the query interval `[q0, q1]` only if `a <= q1` and `b >= q0`, hence
//! `cell(a) <= cell(q1)` and `cell(a) >= cell(b) - 1 >= cell(q0) - 1`: a query scans
//! the anchor cells `cell(q0) - 1 ..= cell(q1)` of each level and tests the stored
//! boxes. The argument is on cell indices, so it holds exactly under rounding.
//! Triangles much larger than the median (long CAD slivers, a ground plane) rise to
//! coarse levels, where a query touches a handful of cells, instead of being copied
//! into hundreds of fine cells; no triangle is ever stored twice, so no query needs
//! de-duplication (this is the hierarchical grid of Ericson, *Real-Time Collision
//! Detection*, sec. 7.2, and a refinement of thesis 002's "2D spatial directory",
//! sec. 5.2.1, a grid whose cells point at the items anchored in them).
//!
//! Storage is CSR: one offsets array over all cells of all levels, and the entries
//! (triangle id, box) in cell order, cells row-major, so the cells of one grid row
//! within a query are one contiguous run of memory. Boxes are `f32`, relative to the
//! lower-left corner of the bounds and rounded outward (strictly, so the stored box
//! contains the exact `f64` box); an answer is therefore a superset of the exact
//! `f64` answer by at most a few `f32` ulps of the part size (about 1e-5 mm on a
//! 100 mm part), which a drop-cutter or dexel test discards. Memory: 20 bytes a
//! triangle plus 4 bytes a cell (level 0 holds about one cell per triangle, all
//! levels at most 4/3 of that): about 24 to 26 bytes a triangle (see the bench).
//!
//! Why not a BVH: the boxes are small and uniform, the query is a fixed-size disc,
//! and a grid reaches the right cells with two multiplications and scans them
//! linearly, where a BVH descends ~log2(n) levels with a branch miss per node; the
//! bench `mesh_index` measures both (the BVH as a peer) on the same mesh.
//!
//! Triangles with a non-finite corner are not indexed and never returned.

use super::TriMesh;
use crate::math::Aabb;
use rayon::prelude::*;

/// At most this many level-0 cells per indexed triangle (plus [`MIN_CELLS`]); keeps a
/// mesh of tiny triangles spread over a huge area from allocating a huge grid.
const MAX_CELLS_PER_TRIANGLE: f64 = 2.0;
/// Level-0 cell budget floor, so that small meshes still get a useful grid.
const MIN_CELLS: f64 = 64.0;
/// Largest number of sampled triangles for the median extent.
const EXTENT_SAMPLES: usize = 65_536;
/// Smallest chunk of triangles a rayon task handles while building.
const PAR_CHUNK: usize = 4096;

/// One grid level: square cells of side `cell`, `dims` cells in x and y, whose cell
/// `(i, j)` is global cell `base + j * dims[0] + i`.
#[derive(Debug, Clone)]
struct Level {
    inv_cell: f64,
    dims: [usize; 2],
    base: usize,
}

impl Level {
    /// Cell column (`axis` 0) or row (1) holding relative coordinate `v` (clamped).
    fn cell(&self, axis: usize, v: f64) -> usize {
        let c = (v * self.inv_cell).floor();
        if c >= 1.0 {
            (c as usize).min(self.dims[axis] - 1)
        } else {
            0
        }
    }

    /// True when `b` spans at most two cells in x and in y on this level.
    fn fits(&self, b: &[f32; 4]) -> bool {
        (0..2).all(|a| self.cell(a, f64::from(b[a + 2])) <= self.cell(a, f64::from(b[a])) + 1)
    }

    /// Global id of the anchor cell of `b`.
    fn anchor(&self, b: &[f32; 4]) -> usize {
        let [i, j] = [0, 1].map(|a| self.cell(a, f64::from(b[a])));
        self.base + j * self.dims[0] + i
    }
}

/// Spatial index over the XY bounding boxes of a mesh's triangles.
///
/// # Example
/// ```
/// use swarf_geom::{Point3, TriMesh, XyIndex};
/// let t = |x: f64| [Point3::new(x, 0.0, 0.0), Point3::new(x + 1.0, 0.0, 0.0), Point3::new(x, 1.0, 0.0)];
/// let mesh = TriMesh::from_triangles(&[t(0.0), t(10.0), t(20.0)]);
/// let index = XyIndex::build(&mesh);
/// let mut out = Vec::new();
/// index.query_disc([11.5, 0.5], 1.0, &mut out);
/// assert_eq!(out, vec![1]);
/// index.query_rect([0.5, 0.0], [20.0, 0.0], &mut out);
/// assert_eq!(out, vec![0, 1, 2]);
/// ```
#[derive(Debug, Clone)]
pub struct XyIndex {
    origin: [f64; 2],
    bounds: Aabb,
    levels: Vec<Level>,
    /// Entry range of global cell `g`: `offsets[g]..offsets[g + 1]`.
    offsets: Vec<u32>,
    /// Triangle ids in entry order.
    ids: Vec<u32>,
    /// `[min_x, min_y, max_x, max_y]` relative to `origin`, rounded outward, in entry
    /// order.
    boxes: Vec<[f32; 4]>,
}

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
            .unwrap_or_else(|| median_extent(mesh, origin, extent));
        let c0 = capped_cell(c0, extent, indexed);
        let (keys, levels, cells) = anchor_keys(mesh, origin, extent, c0);
        let (offsets, ids) = counting_sort(&keys, cells);
        drop(keys);
        let boxes = ids
            .par_iter()
            .with_min_len(PAR_CHUNK)
            .map(|&t| stored_box(mesh, origin, t as usize).unwrap_or([0.0; 4]))
            .collect();
        XyIndex {
            origin,
            bounds,
            levels,
            offsets,
            ids,
            boxes,
        }
    }

    /// Box around the indexed triangles (all of them but those with a non-finite
    /// corner), mm; empty when none is indexed.
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// Number of indexed triangles.
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// True when no triangle is indexed.
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// Heap bytes held by the index.
    pub fn memory_bytes(&self) -> usize {
        self.offsets.capacity() * 4
            + self.ids.capacity() * 4
            + self.boxes.capacity() * 16
            + self.levels.capacity() * std::mem::size_of::<Level>()
    }

    /// Replaces `out` with the ids, ascending, of the triangles whose XY bounding box
    /// meets the closed rectangle `[min, max]` (empty when `min > max` or NaN).
    ///
    /// # Units
    /// mm.
    pub fn query_rect(&self, min: [f64; 2], max: [f64; 2], out: &mut Vec<u32>) {
        out.clear();
        if !(min[0] <= max[0] && min[1] <= max[1]) {
            return;
        }
        let q0 = [min[0] - self.origin[0], min[1] - self.origin[1]];
        let q1 = [max[0] - self.origin[0], max[1] - self.origin[1]];
        self.scan(q0, q1, out, |b| {
            f64::from(b[0]) <= q1[0]
                && f64::from(b[1]) <= q1[1]
                && f64::from(b[2]) >= q0[0]
                && f64::from(b[3]) >= q0[1]
        });
    }

    /// Replaces `out` with the ids, ascending, of the triangles whose XY bounding box
    /// meets the closed disc of `radius` about `center` (empty when `radius < 0` or
    /// NaN).
    ///
    /// # Units
    /// mm.
    pub fn query_disc(&self, center: [f64; 2], radius: f64, out: &mut Vec<u32>) {
        out.clear();
        if radius.is_nan() || radius < 0.0 || center.iter().any(|c| c.is_nan()) {
            return;
        }
        let c = [center[0] - self.origin[0], center[1] - self.origin[1]];
        let r2 = radius * radius;
        let q0 = [c[0] - radius, c[1] - radius];
        let q1 = [c[0] + radius, c[1] + radius];
        self.scan(q0, q1, out, |b| {
            let dx = (f64::from(b[0]) - c[0])
                .max(c[0] - f64::from(b[2]))
                .max(0.0);
            let dy = (f64::from(b[1]) - c[1])
                .max(c[1] - f64::from(b[3]))
                .max(0.0);
            dx * dx + dy * dy <= r2
        });
    }

    /// Pushes the ids of the entries anchored in the cells that can meet the relative
    /// rectangle `[q0, q1]` and pass `hit`, then sorts them.
    fn scan(
        &self,
        q0: [f64; 2],
        q1: [f64; 2],
        out: &mut Vec<u32>,
        hit: impl Fn(&[f32; 4]) -> bool,
    ) {
        if self.ids.is_empty() {
            return;
        }
        for level in &self.levels {
            let cx = [level.cell(0, q0[0]).saturating_sub(1), level.cell(0, q1[0])];
            let cy = [level.cell(1, q0[1]).saturating_sub(1), level.cell(1, q1[1])];
            for j in cy[0]..=cy[1] {
                let row = level.base + j * level.dims[0];
                let run =
                    self.offsets[row + cx[0]] as usize..self.offsets[row + cx[1] + 1] as usize;
                for (id, b) in self.ids[run.clone()].iter().zip(&self.boxes[run]) {
                    if hit(b) {
                        out.push(*id);
                    }
                }
            }
        }
        out.sort_unstable();
    }
}

/// Box of the corners of the triangles whose corners are all finite.
fn finite_bounds(mesh: &TriMesh) -> Aabb {
    mesh.triangles
        .par_iter()
        .with_min_len(PAR_CHUNK)
        .fold(Aabb::empty, |mut b, t| {
            let c = t.map(|k| mesh.vertices[k as usize]);
            if c.iter().all(|p| p.coords.iter().all(|v| v.is_finite())) {
                c.iter().for_each(|p| b.grow(p));
            }
            b
        })
        .reduce(Aabb::empty, |a, b| a.union(&b))
}

fn count_finite(mesh: &TriMesh) -> usize {
    mesh.triangles
        .par_iter()
        .with_min_len(PAR_CHUNK)
        .filter(|t| {
            t.iter().all(|&k| {
                mesh.vertices[k as usize]
                    .coords
                    .iter()
                    .all(|v| v.is_finite())
            })
        })
        .count()
}

/// `f32` at or below `v`, strictly below when `v` is representable (so that the
/// rounding of the `f64` subtraction that produced `v` is covered too).
fn round_down(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) >= v { f.next_down() } else { f }
}

/// `f32` strictly above `v` (see [`round_down`]).
fn round_up(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) <= v { f.next_up() } else { f }
}

/// Outward-rounded relative XY box of triangle `t`, `None` when a corner is not finite.
fn stored_box(mesh: &TriMesh, origin: [f64; 2], t: usize) -> Option<[f32; 4]> {
    let c = mesh.triangles[t].map(|k| mesh.vertices[k as usize]);
    if !c.iter().all(|p| p.coords.iter().all(|v| v.is_finite())) {
        return None;
    }
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
    let mut sizes: Vec<f64> = (0..mesh.triangles.len())
        .step_by(stride)
        .filter_map(|t| stored_box(mesh, origin, t))
        .map(|b| f64::from((b[2] - b[0]).max(b[3] - b[1])))
        .collect();
    let mid = sizes.len() / 2;
    let median = if sizes.is_empty() {
        0.0
    } else {
        *sizes.select_nth_unstable_by(mid, f64::total_cmp).1
    };
    if median > 0.0 {
        median
    } else {
        let area = extent[0].max(f64::MIN_POSITIVE) * extent[1].max(f64::MIN_POSITIVE);
        (area / mesh.triangles.len().max(1) as f64)
            .sqrt()
            .max(f64::MIN_POSITIVE)
    }
}

/// Grows `c0` until level 0 has at most [`MAX_CELLS_PER_TRIANGLE`] cells a triangle.
fn capped_cell(mut c0: f64, extent: [f64; 2], indexed: usize) -> f64 {
    let budget = MAX_CELLS_PER_TRIANGLE * indexed as f64 + MIN_CELLS;
    let cells = |c: f64| (extent[0] / c + 1.0) * (extent[1] / c + 1.0);
    while cells(c0) > budget {
        let ideal = ((extent[0] * extent[1]) / budget).sqrt();
        c0 = (c0 * 1.25).max(ideal);
    }
    c0
}

/// The levels (coarsest: every box fits) and each triangle's global anchor cell
/// (`u32::MAX` for a non-finite triangle); returns the total cell count too.
fn anchor_keys(
    mesh: &TriMesh,
    origin: [f64; 2],
    extent: [f64; 2],
    c0: f64,
) -> (Vec<u32>, Vec<Level>, usize) {
    let mut levels: Vec<Level> = Vec::new();
    let mut base = 0;
    let mut cell = c0;
    loop {
        let dims = extent.map(|e| (e / cell).floor() as usize + 1);
        levels.push(Level {
            inv_cell: 1.0 / cell,
            dims,
            base,
        });
        base += dims[0] * dims[1];
        if dims[0] <= 2 && dims[1] <= 2 {
            break;
        }
        cell *= 2.0;
    }
    assert!(base < u32::MAX as usize, "XyIndex: too many cells");
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
    let cells = levels.last().map_or(0, |l| l.base + l.dims[0] * l.dims[1]);
    (keys, levels, cells)
}

/// Stable counting sort of triangle ids by key: CSR offsets and ids, ascending in
/// each cell; keys `u32::MAX` are dropped.
fn counting_sort(keys: &[u32], cells: usize) -> (Vec<u32>, Vec<u32>) {
    let mut offsets = vec![0u32; cells + 1];
    for &k in keys.iter().filter(|&&k| k != u32::MAX) {
        offsets[k as usize + 1] += 1;
    }
    for g in 0..cells {
        offsets[g + 1] += offsets[g];
    }
    let mut cursor = offsets.clone();
    let mut ids = vec![0u32; offsets[cells] as usize];
    for (t, &k) in keys.iter().enumerate() {
        if k != u32::MAX {
            ids[cursor[k as usize] as usize] = t as u32;
            cursor[k as usize] += 1;
        }
    }
    (offsets, ids)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::math::Point3;
    use proptest::prelude::*;

    /// Oracle: every triangle's stored box against the query, by closest point.
    fn brute_disc(mesh: &TriMesh, origin: [f64; 2], c: [f64; 2], r: f64) -> Vec<u32> {
        let c = [c[0] - origin[0], c[1] - origin[1]];
        (0..mesh.len())
            .filter(|&t| {
                stored_box(mesh, origin, t).is_some_and(|b| {
                    let px = c[0].clamp(f64::from(b[0]), f64::from(b[2]));
                    let py = c[1].clamp(f64::from(b[1]), f64::from(b[3]));
                    (px - c[0]).powi(2) + (py - c[1]).powi(2) <= r * r
                })
            })
            .map(|t| t as u32)
            .collect()
    }

    fn brute_rect(mesh: &TriMesh, origin: [f64; 2], lo: [f64; 2], hi: [f64; 2]) -> Vec<u32> {
        (0..mesh.len())
            .filter(|&t| {
                stored_box(mesh, origin, t).is_some_and(|b| {
                    (0..2).all(|a| {
                        f64::from(b[a]) <= hi[a] - origin[a]
                            && f64::from(b[a + 2]) >= lo[a] - origin[a]
                    })
                })
            })
            .map(|t| t as u32)
            .collect()
    }

    /// Triangles of sizes spread over three decades, a few with NaN corners.
    fn soup() -> impl Strategy<Value = TriMesh> {
        let tri = (
            -50.0..50.0f64,
            -30.0..30.0f64,
            -3.0..1.5f64,
            prop::array::uniform4(0.0..1.0f64),
            0u8..40,
        );
        prop::collection::vec(tri, 1..300).prop_map(|ts| {
            let soup: Vec<[Point3; 3]> = ts
                .iter()
                .map(|&(x, y, log_size, [a, b, c, d], nan)| {
                    let s = 10f64.powf(log_size);
                    let x0 = if nan == 0 { f64::NAN } else { x };
                    [
                        Point3::new(x0, y, 0.0),
                        Point3::new(x + s * a, y + s * b * 0.3, 1.0),
                        Point3::new(x + s * c * 0.5, y + s * d, -1.0),
                    ]
                })
                .collect();
            TriMesh::from_triangles(&soup)
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        #[test]
        fn queries_match_brute_force(
            mesh in soup(),
            cell in prop::option::of(0.001..100.0f64),
            queries in prop::collection::vec((-70.0..70.0f64, -40.0..40.0f64, 0.0..20.0f64, 0.0..20.0f64), 1..12),
        ) {
            let index = XyIndex::build_with_cell_size(&mesh, cell);
            let mut out = Vec::new();
            for &(x, y, r, h) in &queries {
                index.query_disc([x, y], r, &mut out);
                prop_assert_eq!(&out, &brute_disc(&mesh, index.origin, [x, y], r));
                let (lo, hi) = ([x, y], [x + r, y + h]);
                index.query_rect(lo, hi, &mut out);
                prop_assert_eq!(&out, &brute_rect(&mesh, index.origin, lo, hi));
            }
        }

        /// The answer holds every triangle whose exact f64 box meets the disc.
        #[test]
        fn holds_exact_f64_answer(mesh in soup(), x in -60.0..60.0f64, y in -35.0..35.0f64, r in 0.0..10.0f64) {
            let index = XyIndex::build(&mesh);
            let mut out = Vec::new();
            index.query_disc([x, y], r, &mut out);
            for t in 0..mesh.len() {
                let c = mesh.triangle(t);
                if c.iter().any(|p| !p.x.is_finite()) {
                    prop_assert!(!out.contains(&(t as u32)));
                    continue;
                }
                let (x0, x1) = (c.iter().map(|p| p.x).fold(f64::MAX, f64::min), c.iter().map(|p| p.x).fold(f64::MIN, f64::max));
                let (y0, y1) = (c.iter().map(|p| p.y).fold(f64::MAX, f64::min), c.iter().map(|p| p.y).fold(f64::MIN, f64::max));
                let d2 = (x.clamp(x0, x1) - x).powi(2) + (y.clamp(y0, y1) - y).powi(2);
                if d2 <= r * r {
                    prop_assert!(out.binary_search(&(t as u32)).is_ok(), "triangle {} missing", t);
                } else if d2.sqrt() > r + 1e-4 {
                    prop_assert!(out.binary_search(&(t as u32)).is_err(), "triangle {} extra", t);
                }
            }
        }
    }

    #[test]
    fn rounding_is_strictly_outward() {
        for v in [0.0, 1.0, 0.1, -0.1, 1e-30, 123456.789, -3.0e10, 16777217.0] {
            assert!(f64::from(round_down(v)) < v, "{v}");
            assert!(f64::from(round_up(v)) > v, "{v}");
        }
    }

    #[test]
    fn empty_nan_and_degenerate_inputs() {
        let mut out = vec![7];
        let empty = XyIndex::build(&TriMesh::default());
        empty.query_disc([0.0, 0.0], 1.0, &mut out);
        assert!(out.is_empty() && empty.is_empty() && empty.bounds().is_empty());
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        let mesh = TriMesh::from_triangles(&[
            [p(0.0, 0.0), p(0.0, 0.0), p(0.0, 0.0)],
            [p(0.0, 0.0), p(0.0, 0.0), p(0.0, 0.0)],
            [p(f64::INFINITY, 0.0), p(1.0, 0.0), p(0.0, 1.0)],
        ]);
        let index = XyIndex::build(&mesh);
        assert_eq!(index.len(), 2);
        index.query_disc([0.0, 0.0], 0.0, &mut out);
        assert_eq!(out, vec![0, 1]);
        index.query_disc([f64::NAN, 0.0], 1.0, &mut out);
        assert!(out.is_empty());
        index.query_disc([0.0, 0.0], -1.0, &mut out);
        assert!(out.is_empty());
        index.query_rect([1.0, 0.0], [0.0, 1.0], &mut out);
        assert!(out.is_empty());
        index.query_rect([f64::NEG_INFINITY; 2], [f64::INFINITY; 2], &mut out);
        assert_eq!(out, vec![0, 1]);
        index.query_disc([1e300, 0.0], f64::INFINITY, &mut out);
        assert_eq!(out, vec![0, 1]);
    }

    #[test]
    fn big_triangles_rise_to_coarse_levels() {
        let p = |x: f64, y: f64| Point3::new(x, y, 0.0);
        let mut soup: Vec<[Point3; 3]> = (0..400)
            .map(|i| {
                let (x, y) = (f64::from(i % 20), f64::from(i / 20));
                [p(x, y), p(x + 1.0, y), p(x, y + 1.0)]
            })
            .collect();
        soup.push([p(-5.0, -5.0), p(25.0, -5.0), p(-5.0, 25.0)]);
        let mesh = TriMesh::from_triangles(&soup);
        let index = XyIndex::build(&mesh);
        assert!(index.levels.len() >= 4, "{}", index.levels.len());
        let mut out = Vec::new();
        index.query_disc([10.5, 10.5], 0.2, &mut out);
        assert_eq!(out, brute_disc(&mesh, index.origin, [10.5, 10.5], 0.2));
        assert!(out.contains(&400) && out.len() < 10, "{out:?}");
        assert!(index.memory_bytes() < 401 * 40, "{}", index.memory_bytes());
    }
}
