//! The dexel stock: one column of material per grid cell, from `-inf` up to the
//! cell's height (thesis 000 §2.4, the Z-map; thesis 002 §2.2.3, "dexine" / G-buffer).
//!
//! A 3-axis cut only ever lowers a column's top, so one height per cell is the whole
//! state; material removal is `height = min(height, lowest tool point over the cell
//! centre)`. Heights are `f64`: the closed-form checks compare cell centres to 1e-9 mm,
//! beyond `f32`'s reach on a 200 mm part (an `f32` ulp there is ~4e-6 mm). A cell with
//! no material at all (outside a mesh stock, or off the part for an offset stock) is
//! `-inf`. Beside each height the stock keeps the index of the motion that last
//! lowered it ([`NO_MOTION`] when none did), which is how a gouge is traced back to
//! its program line.

use crate::error::SimError;
use crate::grid::Grid;
use rayon::prelude::*;

/// Last-motion value of a cell that no motion has lowered.
pub const NO_MOTION: u32 = u32::MAX;

/// How a stock starts.
#[derive(Debug, Clone, Copy)]
pub enum StockInit<'a> {
    /// A block whose top is at `top` (mm) over the whole grid.
    Box {
        /// Height of the block's top, mm.
        top: f64,
    },
    /// The design raised by `allowance` (mm): `design[c] + allowance` where the design
    /// is defined (finite), no material elsewhere. `design` is row-major over the grid.
    Offset {
        /// Design heights per cell (NaN or `-inf` off the part).
        design: &'a [f64],
        /// Stock allowance above the design, mm (>= 0).
        allowance: f64,
    },
    /// Heights given per cell (e.g. a mesh's upper envelope); NaN means no material.
    Heights(&'a [f64]),
}

/// A Z-map stock over a grid.
#[derive(Debug, Clone)]
pub struct Dexel {
    grid: Grid,
    heights: Vec<f64>,
    last: Vec<u32>,
}

impl Dexel {
    /// A stock over `grid` initialised by `init`.
    ///
    /// # Units
    /// mm.
    ///
    /// # Errors
    /// [`SimError::InvalidParameter`] for a non-finite box top, a negative or
    /// non-finite allowance, or per-cell arrays whose length is not the grid's.
    ///
    /// # Example
    /// ```
    /// use swarf_sim::{Dexel, Grid, StockInit};
    /// let g = Grid::covering([0.0, 0.0], [2.0, 1.0], 0.5, 1 << 20).unwrap();
    /// let d = Dexel::new(g, StockInit::Box { top: 3.0 }).unwrap();
    /// assert_eq!(d.height(1, 1), 3.0);
    /// ```
    pub fn new(grid: Grid, init: StockInit<'_>) -> Result<Dexel, SimError> {
        let n = grid.len();
        let heights = match init {
            StockInit::Box { top } => {
                if !top.is_finite() {
                    return Err(SimError::InvalidParameter {
                        name: "stock top".into(),
                        value: top,
                        expected: "a finite height in mm".into(),
                    });
                }
                vec![top; n]
            }
            StockInit::Offset { design, allowance } => {
                SimError::check_non_negative("stock allowance", allowance)?;
                check_len("design heights", design.len(), n)?;
                design
                    .par_iter()
                    .map(|&z| {
                        if z.is_finite() {
                            z + allowance
                        } else {
                            f64::NEG_INFINITY
                        }
                    })
                    .collect()
            }
            StockInit::Heights(h) => {
                check_len("stock heights", h.len(), n)?;
                h.par_iter()
                    .map(|&z| if z.is_nan() { f64::NEG_INFINITY } else { z })
                    .collect()
            }
        };
        Ok(Dexel {
            grid,
            heights,
            last: vec![NO_MOTION; n],
        })
    }

    /// The grid.
    pub fn grid(&self) -> &Grid {
        &self.grid
    }

    /// Heights, row-major (`-inf`: no material).
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// Per cell, the index of the motion that last lowered it ([`NO_MOTION`]: none).
    pub fn last_motion(&self) -> &[u32] {
        &self.last
    }

    /// Height of cell `(i, j)`, mm.
    ///
    /// # Panics
    /// When `(i, j)` is off the grid.
    pub fn height(&self, i: usize, j: usize) -> f64 {
        self.heights[j * self.grid.nx + i]
    }

    /// Heights and last-motion indices as mutable row bands of `rows` rows each
    /// (the last band may be shorter), for parallel updates.
    pub(crate) fn bands_mut(
        &mut self,
        rows: usize,
    ) -> impl IndexedParallelIterator<Item = (usize, (&mut [f64], &mut [u32]))> {
        let chunk = rows.max(1) * self.grid.nx.max(1);
        self.heights
            .par_chunks_mut(chunk)
            .zip(self.last.par_chunks_mut(chunk))
            .enumerate()
    }
}

fn check_len(what: &str, got: usize, want: usize) -> Result<(), SimError> {
    if got == want {
        Ok(())
    } else {
        Err(SimError::InvalidParameter {
            name: what.into(),
            value: got as f64,
            expected: format!("one value per grid cell ({want})"),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn initialisations() {
        let g = Grid::covering([0.0, 0.0], [2.0, 1.0], 0.5, 1 << 20).unwrap();
        assert!(Dexel::new(g, StockInit::Box { top: f64::NAN }).is_err());
        let mut design = vec![1.0; g.len()];
        design[3] = f64::NAN;
        let d = Dexel::new(
            g,
            StockInit::Offset {
                design: &design,
                allowance: 0.5,
            },
        )
        .unwrap();
        assert_eq!(d.heights()[0], 1.5);
        assert_eq!(d.heights()[3], f64::NEG_INFINITY);
        assert!(d.last_motion().iter().all(|&m| m == NO_MOTION));
        let bad = Dexel::new(
            g,
            StockInit::Offset {
                design: &design,
                allowance: -1.0,
            },
        );
        assert!(bad.is_err());
        assert!(Dexel::new(g, StockInit::Heights(&design[1..])).is_err());
        let h = Dexel::new(g, StockInit::Heights(&design)).unwrap();
        assert_eq!((h.height(3, 0), h.height(0, 1)), (f64::NEG_INFINITY, 1.0));
    }

    #[test]
    fn bands_cover_the_grid_in_order() {
        let g = Grid::covering([0.0, 0.0], [2.0, 2.5], 0.5, 1 << 20).unwrap();
        let mut d = Dexel::new(g, StockInit::Box { top: 0.0 }).unwrap();
        let sizes: Vec<(usize, usize)> = d.bands_mut(2).map(|(k, (h, _))| (k, h.len())).collect();
        assert_eq!(sizes, vec![(0, 8), (1, 8), (2, 4)]);
    }
}
