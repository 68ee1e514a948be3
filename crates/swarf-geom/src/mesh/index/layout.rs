//! The anchor-grid layout of [`super::XyIndex`] (its outward rounding of boxes to
//! `f32` is also swarf-tool's drop tree's): levels of square cells, the anchor cell of a box, the anchor cells a query scans,
//! the row narrowing of disc queries, outward rounding of boxes to `f32`, the base
//! cell size and the counting sort into CSR order. The correctness argument (on cell
//! indices, so exact under rounding) is in the parent module's doc.

/// Relative slack of the row narrowing of disc queries: far above the rounding of
/// the band and half-width computations (~1e-16 relative), far below a cell.
pub const ROW_SLACK: f64 = 1e-9;
/// At most this many level-0 cells per stored triangle (plus [`MIN_CELLS`]); keeps a
/// mesh of tiny triangles spread over a huge area from allocating a huge grid.
pub const MAX_CELLS_PER_TRIANGLE: f64 = 2.0;
/// Level-0 cell budget floor, so that small meshes still get a useful grid.
pub const MIN_CELLS: f64 = 64.0;
/// Largest number of sampled triangles for the median extent.
pub const EXTENT_SAMPLES: usize = 65_536;

/// One grid level: square cells of side `cell_size`, `dims` cells in x and y, whose
/// cell `(i, j)` is global cell `base + j * dims[0] + i`.
#[derive(Debug, Clone)]
pub struct Level {
    /// Cell side, mm.
    pub cell_size: f64,
    inv_cell: f64,
    /// Cells in x and in y.
    pub dims: [usize; 2],
    /// Global id of the level's first cell.
    pub base: usize,
}

impl Level {
    /// Cell column (`axis` 0) or row (1) holding relative coordinate `v` (clamped).
    /// The cast truncates, which is the floor for the values >= 1 it sees; NaN and
    /// everything below 1 give cell 0. Monotone in `v`, as the argument requires.
    #[inline]
    pub fn cell(&self, axis: usize, v: f64) -> usize {
        let c = v * self.inv_cell;
        if c >= 1.0 {
            (c as usize).min(self.dims[axis] - 1)
        } else {
            0
        }
    }

    /// True when box `b` (`[x0, y0, x1, y1]`) spans at most two cells in x and in y.
    #[inline]
    pub fn fits(&self, b: &[f32; 4]) -> bool {
        (0..2).all(|a| self.cell(a, f64::from(b[a + 2])) <= self.cell(a, f64::from(b[a])) + 1)
    }

    /// Anchor cells `[first, last]` along `axis` that can hold a box meeting the
    /// interval `[lo, hi]` (a box spans at most two cells).
    #[inline]
    pub fn span(&self, axis: usize, lo: f64, hi: f64) -> [usize; 2] {
        [self.cell(axis, lo).saturating_sub(1), self.cell(axis, hi)]
    }

    /// Half-width in x of the disc of radius `r` about y = `cy` over the band of y that
    /// boxes anchored in row `j` can occupy (`[j c, (j + 2) c)`, unbounded at the edge
    /// rows where coordinates are clamped), widened by [`ROW_SLACK`]; `None` when the
    /// disc misses the band.
    #[inline]
    pub fn row_half_width(&self, j: usize, cy: f64, r: f64) -> Option<f64> {
        let c = self.cell_size;
        let slack = ROW_SLACK * (cy.abs() + r + (j + 3) as f64 * c);
        let lo = if j == 0 {
            f64::NEG_INFINITY
        } else {
            j as f64 * c - slack
        };
        let hi = if j + 2 >= self.dims[1] {
            f64::INFINITY
        } else {
            (j + 2) as f64 * c + slack
        };
        let dy = (lo - cy).max(cy - hi).max(0.0);
        (dy <= r).then(|| (r * r - dy * dy).max(0.0).sqrt() + slack)
    }

    /// Global id of the anchor cell of box `b`.
    #[inline]
    pub fn anchor(&self, b: &[f32; 4]) -> usize {
        let [i, j] = [0, 1].map(|a| self.cell(a, f64::from(b[a])));
        self.base + j * self.dims[0] + i
    }

    /// Global id one past the level's last cell.
    pub fn end(&self) -> usize {
        self.base + self.dims[0] * self.dims[1]
    }
}

/// The levels over `extent` (mm, from the grid origin), from cells of side `c0` up to
/// the first level of at most 2 x 2 cells, where every box fits.
pub fn levels(c0: f64, extent: [f64; 2]) -> Vec<Level> {
    let mut levels = Vec::new();
    let (mut base, mut cell) = (0, c0);
    loop {
        let dims = extent.map(|e| (e / cell).floor() as usize + 1);
        levels.push(Level {
            cell_size: cell,
            inv_cell: 1.0 / cell,
            dims,
            base,
        });
        base += dims[0] * dims[1];
        if dims[0] <= 2 && dims[1] <= 2 {
            return levels;
        }
        cell *= 2.0;
    }
}

/// The median of `sizes` (box extents of a sample of the triangles, mm), or the side
/// of the area of `extent` per triangle (`count` of them) when that median is zero
/// or there is no sample.
pub fn median_or_area(mut sizes: Vec<f64>, extent: [f64; 2], count: usize) -> f64 {
    let mid = sizes.len() / 2;
    let median = if sizes.is_empty() {
        0.0
    } else {
        *sizes.select_nth_unstable_by(mid, f64::total_cmp).1
    };
    if median > 0.0 {
        median
    } else {
        (area(extent) / count.max(1) as f64)
            .sqrt()
            .max(f64::MIN_POSITIVE)
    }
}

/// Grows `c0` until level 0 has at most [`MAX_CELLS_PER_TRIANGLE`] cells for each of
/// `count` triangles (plus [`MIN_CELLS`]).
pub fn capped_cell(mut c0: f64, extent: [f64; 2], count: usize) -> f64 {
    let budget = MAX_CELLS_PER_TRIANGLE * count as f64 + MIN_CELLS;
    let cells = |c: f64| (extent[0] / c + 1.0) * (extent[1] / c + 1.0);
    while cells(c0) > budget {
        c0 = (c0 * 1.25).max((area(extent) / budget).sqrt());
    }
    c0
}

/// Area of `extent`, each side at least the smallest positive `f64`.
fn area(extent: [f64; 2]) -> f64 {
    extent[0].max(f64::MIN_POSITIVE) * extent[1].max(f64::MIN_POSITIVE)
}

/// `f32` at or below `v`, strictly below when `v` is representable (so that the
/// rounding of the `f64` subtraction that produced `v` is covered too).
#[inline]
pub fn round_down(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) >= v { f.next_down() } else { f }
}

/// `f32` strictly above `v` (see [`round_down`]).
#[inline]
pub fn round_up(v: f64) -> f32 {
    let f = v as f32;
    if f64::from(f) <= v { f.next_up() } else { f }
}

/// Stable counting sort by cell: CSR offsets over `cells` cells and the permutation
/// of the items into cell order; items whose key is `u32::MAX` are left out.
pub fn counting_sort(keys: &[u32], cells: usize) -> (Vec<u32>, Vec<u32>) {
    let mut offsets = vec![0u32; cells + 1];
    for &k in keys.iter().filter(|&&k| k != u32::MAX) {
        offsets[k as usize + 1] += 1;
    }
    for g in 0..cells {
        offsets[g + 1] += offsets[g];
    }
    let mut cursor = offsets.clone();
    let mut order = vec![0u32; offsets[cells] as usize];
    for (i, &k) in keys.iter().enumerate() {
        if k != u32::MAX {
            order[cursor[k as usize] as usize] = i as u32;
            cursor[k as usize] += 1;
        }
    }
    (offsets, order)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rounding_is_strictly_outward() {
        for v in [0.0, 1.0, 0.1, -0.1, 1e-30, 123456.789, -3.0e10, 16777217.0] {
            assert!(f64::from(round_down(v)) < v, "{v}");
            assert!(f64::from(round_up(v)) > v, "{v}");
        }
    }

    #[test]
    fn counting_sort_is_stable_and_drops_the_unkeyed() {
        let (offsets, order) = counting_sort(&[2, 0, u32::MAX, 2, 1, 0], 3);
        assert_eq!(offsets, vec![0, 2, 3, 5]);
        assert_eq!(order, vec![1, 5, 4, 0, 3]);
    }

    #[test]
    fn levels_end_where_every_box_fits() {
        let ls = levels(1.0, [10.0, 3.0]);
        assert_eq!(ls[0].dims, [11, 4]);
        let last = ls.last().unwrap();
        assert!(last.dims[0] <= 2 && last.dims[1] <= 2);
        assert!(last.fits(&[0.0, 0.0, 10.0, 3.0]));
        assert_eq!(ls[1].base, ls[0].end());
    }
}
