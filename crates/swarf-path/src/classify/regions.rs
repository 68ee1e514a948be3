//! The regions of the three classes from the Go board (thesis 002 §6.1.2): whole
//! cells inside, the triangles' footprints clipped to the boundary cells.

use super::board::{Board, Facet, ring_area};
use super::{ClassGrid, SurfaceClass};
use geo::{BooleanOps, Coord, LineString, MultiPolygon, Polygon, unary_union};
use rayon::prelude::*;

/// Index of `class` in the `[steep, horizontal, other]` arrays.
fn slot(class: SurfaceClass) -> usize {
    match class {
        SurfaceClass::Steep => 0,
        SurfaceClass::Horizontal => 1,
        SurfaceClass::Other => 2,
    }
}

/// The `[steep, horizontal, other]` regions, disjoint (module doc of
/// [`super`]).
pub(super) fn regions(
    board: &Board,
    grid: &ClassGrid,
    tris: &[Facet],
    cells: &[Vec<usize>],
) -> [MultiPolygon<f64>; 3] {
    let whole = whole_cells(grid, tris, cells);
    let mut parts: [Vec<Polygon<f64>>; 3] = Default::default();
    for (rect, class) in whole_runs(board, &whole) {
        parts[slot(class)].push(rect);
    }
    let pieces: Vec<Vec<(usize, Polygon<f64>)>> = tris
        .par_iter()
        .zip(cells)
        .map(|(t, met)| {
            let Some(class) = t.class else {
                return Vec::new();
            };
            met.iter()
                .filter(|&&k| whole[k].is_none())
                .filter_map(|&k| polygon(board.clip(t, k)).map(|p| (slot(class), p)))
                .collect()
        })
        .collect();
    for (s, p) in pieces.into_iter().flatten() {
        parts[s].push(p);
    }
    let [steep, horizontal, other] = parts.map(|p| unary_union(p.iter()));
    let horizontal = horizontal.difference(&steep);
    let other = other.difference(&steep).difference(&horizontal);
    [steep, horizontal, other]
}

/// The class each cell gives whole to its region, `None` where the cell is cut
/// into pieces: interior cells (all eight neighbours exist and share the class)
/// and the cells a vertical steep facet meets (steep).
fn whole_cells(
    grid: &ClassGrid,
    tris: &[Facet],
    cells: &[Vec<usize>],
) -> Vec<Option<SurfaceClass>> {
    let (nx, ny) = (grid.nx, grid.ny);
    let interior = |i: usize, j: usize| {
        let c = grid.classes[j * nx + i];
        c.is_some()
            && i > 0
            && j > 0
            && i + 1 < nx
            && j + 1 < ny
            && (j - 1..=j + 1).all(|jj| (i - 1..=i + 1).all(|ii| grid.classes[jj * nx + ii] == c))
    };
    let mut whole: Vec<Option<SurfaceClass>> = (0..nx * ny)
        .map(|k| {
            if interior(k % nx, k / nx) {
                grid.classes[k]
            } else {
                None
            }
        })
        .collect();
    for (t, met) in tris.iter().zip(cells) {
        if t.vertical && t.class == Some(SurfaceClass::Steep) {
            for &k in met {
                whole[k] = Some(SurfaceClass::Steep);
            }
        }
    }
    whole
}

/// Runs of whole cells of one class along each row, as rectangles with their class,
/// cut back to the facets' XY box where the last cells reach past it.
fn whole_runs(board: &Board, whole: &[Option<SurfaceClass>]) -> Vec<(Polygon<f64>, SurfaceClass)> {
    let nx = board.nx;
    let mut out = Vec::new();
    for j in 0..board.ny {
        let row = &whole[j * nx..(j + 1) * nx];
        let mut i = 0;
        while i < nx {
            let Some(class) = row[i] else {
                i += 1;
                continue;
            };
            let start = i;
            while i < nx && row[i] == Some(class) {
                i += 1;
            }
            let [x0, y0, ..] = board.rect(j * nx + start);
            let [.., x1, y1] = board.rect(j * nx + i - 1);
            let [x1, y1] = [x1.min(board.max[0]), y1.min(board.max[1])];
            let ring = vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
            if let Some(p) = polygon(ring) {
                out.push((p, class));
            }
        }
    }
    out
}

/// The ring as a counter-clockwise polygon, `None` when it has no area.
fn polygon(mut ring: Vec<[f64; 2]>) -> Option<Polygon<f64>> {
    ring.dedup();
    let area = ring_area(&ring);
    if ring.len() < 3 || area == 0.0 {
        return None;
    }
    if area < 0.0 {
        ring.reverse();
    }
    let coords: Vec<Coord<f64>> = ring.iter().map(|p| Coord { x: p[0], y: p[1] }).collect();
    Some(Polygon::new(LineString::new(coords), Vec::new()))
}
