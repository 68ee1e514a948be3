//! Rest from the in-process stock (thesis 002 ch. 4): the IOPM after the parent
//! program(s) minus the design.
//!
//! The in-process model is the dexel stock the parent programs leave (swarf-sim);
//! the rest is where it stands above the design by more than a threshold. Cells over
//! the threshold are grouped into 8-connected sets (as the verification groups its
//! gouge and excess cells, [`swarf_sim::deviation::regions`]); each set is a raw
//! piece shaped as the union of its cells (one rectangle per run of cells in a
//! row, united with geo's booleans), its depth the largest excess in it.

use crate::pair::RestKind;
use crate::region::RawPiece;
use geo::{LineString, Polygon, unary_union};
use swarf_geom::Point3;
use swarf_sim::Grid;
use swarf_sim::deviation::regions;

/// The raw pieces where `excess` (per cell, row-major over `grid`, NaN where not
/// measured) is above `threshold`; `design` gives the heights of the deepest points.
///
/// # Units
/// mm.
pub fn pieces_from_excess(
    grid: &Grid,
    excess: &[f64],
    design: &[f64],
    threshold: f64,
) -> Vec<RawPiece> {
    regions(grid, excess, |v| v > threshold)
        .into_iter()
        .map(|mut cells| {
            cells.sort_unstable();
            piece(grid, excess, design, &cells)
        })
        .collect()
}

/// The piece of a set of cells (ascending indices).
fn piece(grid: &Grid, excess: &[f64], design: &[f64], cells: &[usize]) -> RawPiece {
    let nx = grid.nx;
    let mut rects = Vec::new();
    let mut k = 0;
    while k < cells.len() {
        let mut e = k;
        while e + 1 < cells.len()
            && cells[e + 1] == cells[e] + 1
            && !cells[e + 1].is_multiple_of(nx)
        {
            e += 1;
        }
        let (i0, i1, j) = (cells[k] % nx, cells[e] % nx, cells[k] / nx);
        let (x0, x1) = (
            grid.origin[0] + i0 as f64 * grid.cell,
            grid.origin[0] + (i1 + 1) as f64 * grid.cell,
        );
        let (y0, y1) = (
            grid.origin[1] + j as f64 * grid.cell,
            grid.origin[1] + (j + 1) as f64 * grid.cell,
        );
        rects.push(Polygon::new(
            LineString::from(vec![(x0, y0), (x1, y0), (x1, y1), (x0, y1)]),
            vec![],
        ));
        k = e + 1;
    }
    let worst = cells
        .iter()
        .copied()
        .fold(cells[0], |m, c| if excess[c] > excess[m] { c } else { m });
    let [x, y] = grid.centre(worst % nx, worst / nx);
    RawPiece {
        kinds: vec![RestKind::Stock],
        shape: unary_union(rects.iter()),
        depth: excess[worst],
        deepest: Point3::new(x, y, design.get(worst).copied().unwrap_or(f64::NAN)),
        pairs: Vec::new(),
        chains: Vec::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geo::Area;

    #[test]
    fn cells_over_the_threshold_make_pieces() {
        let grid = Grid {
            origin: [0.0, 0.0],
            cell: 0.5,
            nx: 6,
            ny: 4,
        };
        let mut excess = vec![0.0; 24];
        // An L of three cells, a diagonal neighbour of it, and a separate cell.
        for k in [0, 1, 6, 13, 5] {
            excess[k] = 0.2;
        }
        excess[13] = 0.7;
        excess[23] = f64::NAN;
        let design = vec![1.0; 24];
        let p = pieces_from_excess(&grid, &excess, &design, 0.1);
        assert_eq!(p.len(), 2);
        assert!((p[0].shape.unsigned_area() - 4.0 * 0.25).abs() < 1e-12);
        assert_eq!(p[0].depth, 0.7);
        assert_eq!(p[0].deepest, Point3::new(0.75, 1.25, 1.0));
        assert!((p[1].shape.unsigned_area() - 0.25).abs() < 1e-12);
        assert!(pieces_from_excess(&grid, &excess, &design, 1.0).is_empty());
    }
}
