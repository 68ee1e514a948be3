//! The Go board (thesis 002 §6.1.1-6.1.2): the triangles' classes and XY
//! footprints, the cells each footprint meets, and the cells' classes.

use super::{ClassGrid, ClassifyParams, MAX_CELLS, MAX_INCIDENCES, SurfaceClass};
use crate::error::PathError;
use rayon::prelude::*;
use swarf_geom::TriMesh;

/// A facet is vertical (its XY footprint a segment, no area) when its unit normal's
/// z is within this of 0.
pub(super) const VERTICAL_NZ: f64 = 1e-9;

/// A footprint meets a cell when it covers more than this fraction of the cell's
/// area (or, for a vertical facet, runs more than this fraction of its side in it):
/// touching along an edge or at a corner is not meeting.
const MEET_REL: f64 = 1e-9;

/// A triangle as the board sees it.
#[derive(Debug, Clone)]
pub(super) struct Facet {
    /// Its class; `None` for a degenerate triangle or one facing down (hidden from
    /// a tool coming from above).
    pub class: Option<SurfaceClass>,
    /// 3D area, mm².
    pub area: f64,
    /// Corners projected on XY, mm.
    pub xy: [[f64; 2]; 3],
    /// Whether the footprint is a segment (see [`VERTICAL_NZ`]).
    pub vertical: bool,
    /// Whether the triangle has no normal (zero area, non-finite, or a corner outside
    /// the coordinate domain).
    pub degenerate: bool,
}

impl Facet {
    /// Triangle `i` of `mesh`, classified by `params`.
    pub fn new(mesh: &TriMesh, i: usize, params: &ClassifyParams) -> Facet {
        let [a, b, c] = mesh.triangle(i);
        // A triangle outside the coordinate domain is skipped, as by every mesh
        // consumer: it counts as degenerate.
        let normal = mesh.normal(i).filter(|_| mesh.usable(i));
        let vertical = normal.is_some_and(|n| n.z.abs() <= VERTICAL_NZ);
        let class = normal
            .filter(|n| vertical || n.z > 0.0)
            .map(|n| params.class_of(&n));
        Facet {
            class,
            area: if normal.is_some() {
                (b - a).cross(&(c - a)).norm() / 2.0
            } else {
                0.0
            },
            xy: [a, b, c].map(|p| [p.x, p.y]),
            vertical,
            degenerate: normal.is_none(),
        }
    }
}

/// The board's lattice: `nx` by `ny` square cells of side `cell` from `origin`.
#[derive(Debug, Clone, Copy)]
pub(super) struct Board {
    pub origin: [f64; 2],
    /// Upper corner of the classified facets' XY box (the board may reach past it).
    pub max: [f64; 2],
    pub cell: f64,
    pub nx: usize,
    pub ny: usize,
}

impl Board {
    /// The board over the XY box of the classified facets, `None` when there is none.
    ///
    /// # Errors
    /// [`PathError::InvalidParameter`] on `classify.cell` when the board would have
    /// more than [`MAX_CELLS`] cells or the facets' boxes more than
    /// [`MAX_INCIDENCES`] cells in all (counted before anything is allocated).
    pub fn new(tris: &[Facet], cell: f64) -> Result<Option<Board>, PathError> {
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for p in tris.iter().filter(|t| t.class.is_some()).flat_map(|t| t.xy) {
            for k in 0..2 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        if lo[0] > hi[0] {
            return Ok(None);
        }
        let count = |k: usize| ((hi[k] - lo[k]) / cell).ceil().max(1.0);
        let (nx, ny) = (count(0), count(1));
        let too_many = |what: &str, n: f64, limit: usize| {
            Err(PathError::InvalidParameter {
                field: "classify.cell".into(),
                message: format!(
                    "{cell} mm gives {n:.3e} {what} over the part's {:.3} x {:.3} mm box, \
                     more than the limit {limit}: expected a larger cell",
                    hi[0] - lo[0],
                    hi[1] - lo[1]
                ),
            })
        };
        if nx * ny > MAX_CELLS as f64 {
            return too_many("cells", nx * ny, MAX_CELLS);
        }
        let board = Board {
            origin: lo,
            max: hi,
            cell,
            nx: nx as usize,
            ny: ny as usize,
        };
        let pairs: f64 = tris
            .iter()
            .filter(|t| t.class.is_some())
            .map(|t| {
                let ([i0, i1], [j0, j1]) = board.span(t);
                ((i1 - i0 + 1) * (j1 - j0 + 1)) as f64
            })
            .sum();
        if pairs > MAX_INCIDENCES as f64 {
            return too_many("(triangle, cell) pairs", pairs, MAX_INCIDENCES);
        }
        Ok(Some(board))
    }

    /// `[x0, y0, x1, y1]` of cell `k` (index `j * nx + i`); every use computes the
    /// corners the same way, so neighbouring pieces share their edges exactly.
    pub fn rect(&self, k: usize) -> [f64; 4] {
        let (i, j) = ((k % self.nx) as f64, (k / self.nx) as f64);
        let [ox, oy] = self.origin;
        [
            ox + i * self.cell,
            oy + j * self.cell,
            ox + (i + 1.0) * self.cell,
            oy + (j + 1.0) * self.cell,
        ]
    }

    /// Inclusive ranges of cell columns and rows under `t`'s XY box, one more on
    /// each side for a vertical facet (its segment may lie on a cell line, in both
    /// cells beside it).
    fn span(&self, t: &Facet) -> ([usize; 2], [usize; 2]) {
        let pad = if t.vertical { 1.0 } else { 0.0 };
        let index = |v: f64, o: f64, n: usize, side: f64| {
            let f = ((v - o) / self.cell).floor() + side * pad;
            if f <= 0.0 { 0 } else { (f as usize).min(n - 1) }
        };
        let range = |k: usize, o: f64, n: usize| {
            let lo = t.xy.iter().map(|p| p[k]).fold(f64::INFINITY, f64::min);
            let hi = t.xy.iter().map(|p| p[k]).fold(f64::NEG_INFINITY, f64::max);
            [index(lo, o, n, -1.0), index(hi, o, n, 1.0)]
        };
        (
            range(0, self.origin[0], self.nx),
            range(1, self.origin[1], self.ny),
        )
    }

    /// `t`'s footprint clipped to cell `k` (possibly empty or degenerate).
    pub fn clip(&self, t: &Facet, k: usize) -> Vec<[f64; 2]> {
        clip_to_rect(&t.xy, self.rect(k))
    }

    /// Whether `t`'s footprint meets cell `k` (see [`MEET_REL`]).
    fn meets(&self, t: &Facet, k: usize) -> bool {
        let piece = self.clip(t, k);
        if t.vertical {
            let far = piece
                .iter()
                .flat_map(|p| piece.iter().map(move |q| (p[0] - q[0]).hypot(p[1] - q[1])))
                .fold(0.0, f64::max);
            far > MEET_REL * self.cell
        } else {
            ring_area(&piece).abs() > MEET_REL * self.cell * self.cell
        }
    }

    /// The cells each facet meets, in facet order (none for a facet without class).
    pub fn bin(&self, tris: &[Facet]) -> Vec<Vec<usize>> {
        tris.par_iter()
            .map(|t| {
                if t.class.is_none() {
                    return Vec::new();
                }
                let ([i0, i1], [j0, j1]) = self.span(t);
                (j0..=j1)
                    .flat_map(|j| (i0..=i1).map(move |i| j * self.nx + i))
                    .filter(|&k| self.meets(t, k))
                    .collect()
            })
            .collect()
    }

    /// Each cell's class: the strongest of the facets meeting it.
    pub fn classes(&self, tris: &[Facet], cells: &[Vec<usize>]) -> ClassGrid {
        let mut classes = vec![None; self.nx * self.ny];
        for (t, met) in tris.iter().zip(cells) {
            for &k in met {
                classes[k] = classes[k].max(t.class);
            }
        }
        ClassGrid {
            origin: self.origin,
            cell: self.cell,
            nx: self.nx,
            ny: self.ny,
            classes,
        }
    }
}

/// The signed area of the closed ring `ring` (counter-clockwise
/// positive), mm².
pub(super) fn ring_area(ring: &[[f64; 2]]) -> f64 {
    let n = ring.len();
    (0..n)
        .map(|k| {
            let (p, q) = (ring[k], ring[(k + 1) % n]);
            p[0] * q[1] - q[0] * p[1]
        })
        .sum::<f64>()
        / 2.0
}

/// The convex polygon `poly` clipped to the rectangle `[x0, y0, x1, y1]`
/// (Sutherland-Hodgman, one half-plane per side; points on a side are set exactly
/// on it).
fn clip_to_rect(poly: &[[f64; 2]], rect: [f64; 4]) -> Vec<[f64; 2]> {
    let mut out = poly.to_vec();
    for (axis, bound, keep_above) in [
        (0, rect[0], true),
        (0, rect[2], false),
        (1, rect[1], true),
        (1, rect[3], false),
    ] {
        let inside = |p: &[f64; 2]| {
            if keep_above {
                p[axis] >= bound
            } else {
                p[axis] <= bound
            }
        };
        let cut = |p: [f64; 2], q: [f64; 2]| {
            let t = (bound - p[axis]) / (q[axis] - p[axis]);
            let mut r = [p[0] + t * (q[0] - p[0]), p[1] + t * (q[1] - p[1])];
            r[axis] = bound;
            r
        };
        let input = std::mem::take(&mut out);
        for k in 0..input.len() {
            let (p, q) = (input[k], input[(k + 1) % input.len()]);
            match (inside(&p), inside(&q)) {
                (true, true) => out.push(q),
                (true, false) => out.push(cut(p, q)),
                (false, true) => out.extend([cut(p, q), q]),
                (false, false) => {}
            }
        }
        if out.is_empty() {
            break;
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clipping_a_triangle_to_a_square() {
        let tri = [[0.0, 0.0], [4.0, 0.0], [0.0, 4.0]];
        let piece = clip_to_rect(&tri, [1.0, 1.0, 2.0, 2.0]);
        assert!((ring_area(&piece) - 1.0).abs() < 1e-12, "{piece:?}");
        let corner = clip_to_rect(&tri, [1.0, 2.0, 3.0, 4.0]);
        assert!((ring_area(&corner) - 0.5).abs() < 1e-12, "{corner:?}");
        assert!(clip_to_rect(&tri, [3.0, 3.0, 4.0, 4.0]).is_empty());
        let touching = clip_to_rect(&tri, [4.0, -1.0, 5.0, 0.0]);
        assert!(ring_area(&touching).abs() < 1e-12);
    }
}
