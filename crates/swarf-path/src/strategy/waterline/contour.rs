//! One level's contour: marching squares on the drop field, exact crossings.
//!
//! Each grid node is inside (drop height above the level) or outside. A cell edge
//! whose ends differ holds one crossing, found exactly by [`Probe::root`]. Within a
//! cell the crossings pair up by the marching-squares table; each pair is oriented so
//! that the inside lies to the right of travel (the cell's boundary walked
//! counter-clockwise meets an outside-to-inside edge, then the inside-to-outside edge
//! that closes the same corner region). A saddle cell (diagonal corners inside) is
//! settled by the drop at its centre. Every crossing then has one successor, and the
//! loops are followed from the lowest crossing index up, so the result is
//! deterministic. Crossings and chord refinement run in parallel and are collected in
//! order.

use super::field::DropField;
use super::probe::{ContourPoint, Probe, Z_EPS};
use rayon::prelude::*;
use swarf_tool::drop::DropScratch;

/// A closed contour loop: points in travel order with the inside on the right (the
/// first point is not repeated).
pub(crate) type Loop = Vec<ContourPoint>;

/// Edge ids: horizontal edge `(i, j) - (i + 1, j)` is `j nx + i`, vertical edge
/// `(i, j) - (i, j + 1)` is `nx ny + j nx + i`.
struct Edges<'a> {
    field: &'a DropField,
    inside: Vec<bool>,
    /// Crossing edges, ascending.
    ids: Vec<u64>,
}

impl Edges<'_> {
    fn node_inside(&self, i: usize, j: usize) -> bool {
        self.inside[j * self.field.nx + i]
    }

    fn h(&self, i: usize, j: usize) -> u64 {
        (j * self.field.nx + i) as u64
    }

    fn v(&self, i: usize, j: usize) -> u64 {
        (self.field.nx * self.field.ny + j * self.field.nx + i) as u64
    }

    /// The nodes at the ends of edge `id`.
    fn ends(&self, id: u64) -> ([usize; 2], [usize; 2]) {
        let (nx, ny) = (self.field.nx as u64, self.field.ny as u64);
        let (k, vertical) = if id >= nx * ny {
            (id - nx * ny, true)
        } else {
            (id, false)
        };
        let (i, j) = ((k % nx) as usize, (k / nx) as usize);
        if vertical {
            ([i, j], [i, j + 1])
        } else {
            ([i, j], [i + 1, j])
        }
    }

    fn index(&self, id: u64) -> usize {
        self.ids.binary_search(&id).unwrap_or(usize::MAX)
    }
}

/// The closed loops of `probe`'s level over `field`, refined to `tol` (mm) at chord
/// midpoints, inside on the right.
pub(crate) fn level_loops(field: &DropField, probe: &Probe, tol: f64) -> Vec<Loop> {
    let (nx, ny) = (field.nx, field.ny);
    let inside: Vec<bool> = (0..nx * ny)
        .map(|k| field.height(k % nx, k / nx) > probe.z + Z_EPS)
        .collect();
    let mut edges = Edges {
        field,
        inside,
        ids: Vec::new(),
    };
    for j in 0..ny {
        for i in 0..nx - 1 {
            if edges.node_inside(i, j) != edges.node_inside(i + 1, j) {
                edges.ids.push(edges.h(i, j));
            }
        }
    }
    for j in 0..ny - 1 {
        for i in 0..nx {
            if edges.node_inside(i, j) != edges.node_inside(i, j + 1) {
                edges.ids.push(edges.v(i, j));
            }
        }
    }
    if edges.ids.is_empty() {
        return Vec::new();
    }
    let crossings: Vec<Option<ContourPoint>> = edges
        .ids
        .par_iter()
        .map_init(DropScratch::default, |s, &id| {
            let (p, q) = edges.ends(id);
            let (a, b) = if edges.node_inside(p[0], p[1]) {
                (p, q)
            } else {
                (q, p)
            };
            probe.root(field.xy(a[0], a[1]), field.xy(b[0], b[1]), s)
        })
        .collect();
    let next = successors(&edges, probe);
    let loops = follow(&next, &crossings);
    loops
        .par_iter()
        .map_init(DropScratch::default, |s, lp| {
            let mut out = Vec::with_capacity(lp.len());
            for k in 0..lp.len() {
                out.push(lp[k]);
                probe.refine(lp[k], lp[(k + 1) % lp.len()], tol, true, s, &mut out, 0);
            }
            out
        })
        .collect()
}

/// The successor crossing of each crossing (`usize::MAX` where none).
fn successors(edges: &Edges, probe: &Probe) -> Vec<usize> {
    let field = edges.field;
    let mut cells: Vec<(usize, usize)> = Vec::new();
    for &id in &edges.ids {
        let ([i, j], [i1, j1]) = edges.ends(id);
        // The (up to two) cells beside this edge.
        if j1 > j {
            if i > 0 {
                cells.push((i - 1, j));
            }
            if i + 1 < field.nx {
                cells.push((i, j));
            }
        } else {
            if j > 0 {
                cells.push((i, j - 1));
            }
            if j + 1 < field.ny {
                cells.push((i1 - 1, j));
            }
        }
    }
    cells.sort_unstable();
    cells.dedup();
    let pairs: Vec<[(u64, u64); 2]> = cells
        .par_iter()
        .map_init(DropScratch::default, |s, &(i, j)| {
            cell_segments(edges, probe, i, j, s)
        })
        .collect();
    let mut next = vec![usize::MAX; edges.ids.len()];
    for (from, to) in pairs.into_iter().flatten() {
        if from != u64::MAX {
            next[edges.index(from)] = edges.index(to);
        }
    }
    next
}

/// The oriented segments (edge id pairs) of cell `(i, j)`; unused slots hold
/// `u64::MAX`.
fn cell_segments(
    edges: &Edges,
    probe: &Probe,
    i: usize,
    j: usize,
    s: &mut DropScratch,
) -> [(u64, u64); 2] {
    let b = [
        edges.node_inside(i, j),
        edges.node_inside(i + 1, j),
        edges.node_inside(i + 1, j + 1),
        edges.node_inside(i, j + 1),
    ];
    let e = [
        edges.h(i, j),
        edges.v(i + 1, j),
        edges.h(i, j + 1),
        edges.v(i, j),
    ];
    let none = (u64::MAX, u64::MAX);
    let out_in: Vec<usize> = (0..4).filter(|&k| !b[k] && b[(k + 1) % 4]).collect();
    let in_out: Vec<usize> = (0..4).filter(|&k| b[k] && !b[(k + 1) % 4]).collect();
    match (out_in.as_slice(), in_out.as_slice()) {
        ([a], [z]) => [(e[*a], e[*z]), none],
        ([a0, a1], [_, _]) => {
            let f = edges.field;
            let c = [
                f.origin[0] + f.step * (i as f64 + 0.5),
                f.origin[1] + f.step * (j as f64 + 0.5),
            ];
            // Centre inside: each outside-to-inside edge pairs with the inside-to-
            // outside edge before it (clockwise); outside: with the one after it.
            let shift = if probe.inside(c, s) { 3 } else { 1 };
            [(e[*a0], e[(a0 + shift) % 4]), (e[*a1], e[(a1 + shift) % 4])]
        }
        _ => [none, none],
    }
}

/// Loops of crossing points following `next`, each started at its lowest index.
fn follow(next: &[usize], crossings: &[Option<ContourPoint>]) -> Vec<Loop> {
    let mut seen = vec![false; next.len()];
    let mut loops = Vec::new();
    for start in 0..next.len() {
        if seen[start] {
            continue;
        }
        let mut lp = Vec::new();
        let mut k = start;
        while k < next.len() && !seen[k] {
            seen[k] = true;
            if let Some(p) = crossings[k] {
                lp.push(p);
            }
            k = next[k];
        }
        if lp.len() >= 3 {
            loops.push(lp);
        }
    }
    loops
}
