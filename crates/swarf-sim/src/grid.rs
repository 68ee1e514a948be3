//! The Z-map grid: square cells over a rectangle of the XY plane, one height per cell
//! sampled at the cell centre (thesis 000 §2.4 "Z-map"; thesis 002 §2.2.3 "dexel" /
//! G-buffer).
//!
//! Cell `(i, j)` (column `i` along x, row `j` along y) has its centre at
//! `origin + ((i + 1/2) c, (j + 1/2) c)`; storage is row-major, index `j * nx + i`, so a
//! band of rows is one contiguous slice and row bands can be handed to threads.
//! Everything the verifier keeps per cell (stock height, design height, the motion
//! that last lowered the cell) is counted in [`BYTES_PER_CELL`], so a grid that would
//! not fit is refused before anything is allocated.

use crate::error::SimError;
use serde::Serialize;

/// Bytes the verifier holds per cell: stock height (f64), design height (f64),
/// last-motion index (u32), and deviation work space (f64).
pub const BYTES_PER_CELL: u64 = 8 + 8 + 4 + 8;

/// Default memory limit for a grid, bytes (4 GiB).
pub const DEFAULT_MAX_BYTES: u64 = 4 << 30;

/// A uniform grid of square cells over a rectangle, mm.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Grid {
    /// Lower-left corner of cell (0, 0), mm.
    pub origin: [f64; 2],
    /// Cell side, mm.
    pub cell: f64,
    /// Cells along x.
    pub nx: usize,
    /// Cells along y.
    pub ny: usize,
}

impl Grid {
    /// The grid of cells of side `cell` covering the rectangle `[min, max]` (the last
    /// row and column may reach past `max` by less than a cell), refused when it would
    /// need more than `max_bytes` (see [`BYTES_PER_CELL`]).
    ///
    /// # Units
    /// mm; `max_bytes` in bytes.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] for a cell that is not finite and > 0,
    /// [`SimError::Empty`] for a rectangle that is empty or not finite,
    /// [`SimError::GridTooLarge`] with the memory needed and a cell size that fits.
    ///
    /// # Example
    /// ```
    /// use swarf_sim::Grid;
    /// let g = Grid::covering([0.0, 0.0], [10.0, 5.0], 0.5, 1 << 30).unwrap();
    /// assert_eq!((g.nx, g.ny), (20, 10));
    /// assert_eq!(g.centre(0, 0), [0.25, 0.25]);
    /// assert!(Grid::covering([0.0, 0.0], [10.0, 5.0], 0.0, 1 << 30).is_err());
    /// ```
    pub fn covering(
        min: [f64; 2],
        max: [f64; 2],
        cell: f64,
        max_bytes: u64,
    ) -> Result<Grid, SimError> {
        SimError::check_positive("cell size", cell)?;
        let ok = (0..2).all(|k| min[k].is_finite() && max[k].is_finite() && max[k] > min[k]);
        if !ok {
            return Err(SimError::Empty(format!(
                "cannot build a grid over [{:?}, {:?}]: expected a rectangle of positive size",
                min, max
            )));
        }
        let counts = [0, 1].map(|k| ((max[k] - min[k]) / cell).ceil().max(1.0));
        let cells_f = counts[0] * counts[1];
        let needed_f = cells_f * BYTES_PER_CELL as f64;
        if needed_f > max_bytes as f64 || counts.iter().any(|&n| n > u32::MAX as f64) {
            let area = (max[0] - min[0]) * (max[1] - min[1]);
            let fits = (area * BYTES_PER_CELL as f64 / max_bytes.max(1) as f64).sqrt();
            return Err(SimError::GridTooLarge {
                nx: counts[0].min(usize::MAX as f64) as usize,
                ny: counts[1].min(usize::MAX as f64) as usize,
                cells: cells_f.min(usize::MAX as f64) as usize,
                cell,
                needed: needed_f.min(u64::MAX as f64) as u64,
                limit: max_bytes,
                suggested: fits * 1.01,
            });
        }
        // Ask the system for the memory before anything is built, so that a limit
        // above what the machine can give is a refusal, not an abort.
        let mut probe: Vec<u8> = Vec::new();
        if probe.try_reserve_exact(needed_f as usize).is_err() {
            return Err(SimError::NoMemory {
                needed: needed_f as u64,
                cell,
            });
        }
        drop(probe);
        Ok(Grid {
            origin: min,
            cell,
            nx: counts[0] as usize,
            ny: counts[1] as usize,
        })
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// True when the grid has no cell.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Bytes the verifier needs for this grid ([`BYTES_PER_CELL`] per cell).
    pub fn bytes_needed(&self) -> u64 {
        self.len() as u64 * BYTES_PER_CELL
    }

    /// Centre of cell `(i, j)`, mm.
    pub fn centre(&self, i: usize, j: usize) -> [f64; 2] {
        [self.x(i), self.y(j)]
    }

    /// x of the centres of column `i`, mm.
    #[inline]
    pub fn x(&self, i: usize) -> f64 {
        self.origin[0] + (i as f64 + 0.5) * self.cell
    }

    /// y of the centres of row `j`, mm.
    #[inline]
    pub fn y(&self, j: usize) -> f64 {
        self.origin[1] + (j as f64 + 0.5) * self.cell
    }

    /// Upper corner of the grid, mm.
    pub fn max(&self) -> [f64; 2] {
        [
            self.origin[0] + self.nx as f64 * self.cell,
            self.origin[1] + self.ny as f64 * self.cell,
        ]
    }

    /// Columns whose centres lie in `[lo, hi]` (mm), clamped to the grid; `None` when
    /// there is none.
    #[inline]
    pub fn columns(&self, lo: f64, hi: f64) -> Option<(usize, usize)> {
        span(lo, hi, self.origin[0], self.cell, self.nx)
    }

    /// Rows whose centres lie in `[lo, hi]` (mm), clamped to the grid; `None` when
    /// there is none.
    #[inline]
    pub fn rows(&self, lo: f64, hi: f64) -> Option<(usize, usize)> {
        span(lo, hi, self.origin[1], self.cell, self.ny)
    }

    /// The cell whose square holds `(x, y)`, if it is on the grid.
    pub fn cell_of(&self, x: f64, y: f64) -> Option<(usize, usize)> {
        let i = ((x - self.origin[0]) / self.cell).floor();
        let j = ((y - self.origin[1]) / self.cell).floor();
        (i >= 0.0 && j >= 0.0 && (i as usize) < self.nx && (j as usize) < self.ny)
            .then_some((i as usize, j as usize))
    }
}

/// Indices `k` in `0..n` with `origin + (k + 1/2) c` in `[lo, hi]`.
#[inline]
fn span(lo: f64, hi: f64, origin: f64, c: f64, n: usize) -> Option<(usize, usize)> {
    if lo.is_nan() || hi.is_nan() || lo > hi || n == 0 {
        return None;
    }
    let a = ((lo - origin) / c - 0.5).ceil();
    let b = ((hi - origin) / c - 0.5).floor();
    if b < 0.0 || a > (n - 1) as f64 || a > b {
        return None;
    }
    Some((a.max(0.0) as usize, (b as usize).min(n - 1)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spans_hold_exactly_the_centres_inside() {
        let g = Grid::covering([-1.0, 2.0], [1.0, 3.0], 0.25, 1 << 20).unwrap();
        assert_eq!((g.nx, g.ny), (8, 4));
        assert_eq!(g.columns(-1.0, 1.0), Some((0, 7)));
        assert_eq!(g.columns(-0.875, -0.875), Some((0, 0)));
        assert_eq!(g.columns(-0.87, -0.63), None);
        assert_eq!(g.columns(-0.87, -0.62), Some((1, 1)));
        assert_eq!(g.columns(5.0, 6.0), None);
        assert_eq!(g.columns(-9.0, -2.0), None);
        assert_eq!(g.columns(f64::NAN, 1.0), None);
        assert_eq!(g.rows(2.0, 2.2), Some((0, 0)));
        assert_eq!(g.cell_of(0.1, 2.9), Some((4, 3)));
        assert_eq!(g.cell_of(1.1, 2.9), None);
        assert_eq!(g.max(), [1.0, 3.0]);
        for i in 0..g.nx {
            let x = g.x(i);
            assert_eq!(g.columns(x, x), Some((i, i)));
        }
    }

    #[test]
    fn refuses_huge_grids_with_the_size_needed() {
        let e = Grid::covering([0.0, 0.0], [1000.0, 1000.0], 0.001, 4 << 30).unwrap_err();
        let SimError::GridTooLarge {
            cells,
            needed,
            suggested,
            ..
        } = e
        else {
            panic!("{e}");
        };
        assert_eq!(cells, 1_000_000_000_000);
        assert_eq!(needed, 1_000_000_000_000 * BYTES_PER_CELL);
        let g = Grid::covering([0.0, 0.0], [1000.0, 1000.0], suggested, 4 << 30).unwrap();
        assert!(g.bytes_needed() <= 4 << 30);
        assert!(Grid::covering([0.0, 0.0], [0.0, 1.0], 0.1, 1 << 30).is_err());
        assert!(Grid::covering([0.0, 0.0], [1.0, 1.0], -0.1, 1 << 30).is_err());
    }
}
