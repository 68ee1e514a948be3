//! The map's place in a picture: a world rectangle of the XY plane drawn at one scale
//! (pixels per mm, the largest that fits [`MAP_MAX`]), y up, and the grid cells under
//! each of its pixels, so that a pixel covering several cells can show the most
//! extreme of them.

use super::text::Rect;

/// A regular lattice of square cells in the XY plane, as a map shows it: the cells
/// under each pixel are found by index arithmetic (swarf-sim's dexel grid is one).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cells {
    /// Lower-left corner of cell `(0, 0)`, mm.
    pub origin: [f64; 2],
    /// Cell size, mm.
    pub cell: f64,
    /// Columns.
    pub nx: usize,
    /// Rows.
    pub ny: usize,
}

/// Largest map size, px.
const MAP_MAX: [f64; 2] = [1000.0, 700.0];

/// The map: the world rectangle `rect` (`[xmin, ymin, xmax, ymax]`, mm) drawn at
/// `ppmm` pixels per mm, `w x h` pixels from `(left, top)`.
pub(crate) struct Map {
    grid: Cells,
    /// World rectangle, mm.
    pub rect: [f64; 4],
    /// Picture column of the map's left edge.
    pub left: i64,
    /// Picture row of the map's top edge.
    pub top: i64,
    /// Pixels per mm.
    pub ppmm: f64,
    /// Map width, px.
    pub w: i64,
    /// Map height, px.
    pub h: i64,
}

impl Map {
    /// The map of `rect` over `grid` at the largest scale that fits, placed at the
    /// origin until the page sets `left` and `top`.
    pub(crate) fn new(grid: &Cells, rect: [f64; 4]) -> Map {
        let (sx, sy) = ((rect[2] - rect[0]).max(1e-9), (rect[3] - rect[1]).max(1e-9));
        let ppmm = (MAP_MAX[0] / sx).min(MAP_MAX[1] / sy);
        Map {
            grid: *grid,
            rect,
            left: 0,
            top: 0,
            ppmm,
            w: (sx * ppmm).round().max(1.0) as i64,
            h: (sy * ppmm).round().max(1.0) as i64,
        }
    }

    /// The map's pixels.
    pub(crate) fn inside(&self) -> Rect {
        [self.left, self.top, self.left + self.w, self.top + self.h]
    }

    /// Picture coordinates of a point of the XY plane.
    pub(crate) fn px(&self, x: f64, y: f64) -> [f64; 2] {
        [
            self.left as f64 + (x - self.rect[0]) * self.ppmm,
            (self.top + self.h) as f64 - (y - self.rect[1]) * self.ppmm,
        ]
    }

    /// Cells under map pixel `(u, v)` (from the map's top-left): column and row
    /// ranges, `None` off the grid.
    pub(crate) fn cells(&self, u: i64, v: i64) -> Option<([usize; 2], [usize; 2])> {
        let g = &self.grid;
        let span = |a0: f64, a1: f64, origin: f64, n: usize| {
            let lo = ((a0 - origin) / g.cell).floor();
            let hi = ((a1 - origin) / g.cell).ceil();
            if hi <= 0.0 || lo >= n as f64 {
                return None;
            }
            let lo = lo.max(0.0) as usize;
            Some([lo, (hi as usize).clamp(lo + 1, n)])
        };
        let x0 = self.rect[0] + u as f64 / self.ppmm;
        let y0 = self.rect[1] + (self.h - 1 - v) as f64 / self.ppmm;
        let i = span(x0, x0 + 1.0 / self.ppmm, g.origin[0], g.nx)?;
        let j = span(y0, y0 + 1.0 / self.ppmm, g.origin[1], g.ny)?;
        Some((i, j))
    }
}
