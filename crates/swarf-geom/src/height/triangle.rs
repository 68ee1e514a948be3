//! One triangle seen along +z: its barycentric weights at `(x, y)`, its height there
//! (the vertical hit), and the cell centres of a regular lattice that its XY projection
//! holds (scan conversion of the same test, for grids of queries).
//!
//! With `A = (b - a) x (c - a) . z` (twice the signed XY area), the weight of `a` at
//! `q` is `w_a = ((c - q) x (b - q) . z) / -A`, likewise `w_b` (edge `c a`), and
//! `w_c = 1 - w_a - w_b`; the height of the triangle's plane is `sum w_k z_k`. The
//! inside test is closed (every weight `>= -`[`INSIDE_EPS`]), so a point on an edge
//! shared by two triangles belongs to both and no ray slips between them; callers
//! keep the highest (or lowest) hit. A triangle whose projection has no area (a
//! vertical wall) holds no point; its neighbours carry the wall's top and bottom.

use crate::math::Point3;

/// Barycentric weights down to this (negative, dimensionless) still count as inside.
pub const INSIDE_EPS: f64 = 1e-12;

/// Half-width of the rectangle around a query point that the XY index is asked for,
/// mm: the closed inside test reaches [`INSIDE_EPS`] of a triangle's size past its
/// edges, where the index's stored boxes (exact near the index origin) may not reach;
/// 1e-9 mm covers that for triangles up to 1000 mm.
pub const QUERY_SLACK: f64 = 1e-9;

/// The rectangle `[min, max]` to ask the XY index for around `(x, y)`.
#[inline]
pub(super) fn query_rect(x: f64, y: f64) -> ([f64; 2], [f64; 2]) {
    (
        [x - QUERY_SLACK, y - QUERY_SLACK],
        [x + QUERY_SLACK, y + QUERY_SLACK],
    )
}

/// A regular lattice of query points (e.g. the cell centres of a Z-map): column `i`
/// at `x(i)`, row `j` at `y(j)`, both increasing, stored row-major.
pub trait Lattice {
    /// Points per row.
    fn nx(&self) -> usize;
    /// x of column `i`, mm.
    fn x(&self, i: usize) -> f64;
    /// y of row `j`, mm.
    fn y(&self, j: usize) -> f64;
    /// Columns whose x lies in `[lo, hi]` (mm), clamped; `None` when there is none.
    fn columns(&self, lo: f64, hi: f64) -> Option<(usize, usize)>;
    /// Rows whose y lies in `[lo, hi]` (mm), clamped; `None` when there is none.
    fn rows(&self, lo: f64, hi: f64) -> Option<(usize, usize)>;
}

/// `1 / A`, or `None` for a projection without area (or not finite).
#[inline]
fn inverse_area(tri: &[[f64; 3]; 3]) -> Option<f64> {
    let [a, b, c] = tri;
    let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    (area.is_finite() && area.abs() > f64::MIN_POSITIVE).then(|| 1.0 / area)
}

/// The weights at `(x, y)` when inside (module doc), from `inv = 1 / A`.
#[inline]
fn inside(tri: &[[f64; 3]; 3], inv: f64, x: f64, y: f64) -> Option<[f64; 3]> {
    let [a, b, c] = tri;
    let edge =
        |p: &[f64; 3], q: &[f64; 3]| ((q[0] - x) * (p[1] - y) - (q[1] - y) * (p[0] - x)) * -inv;
    let wa = edge(b, c);
    let wb = edge(c, a);
    let wc = 1.0 - wa - wb;
    (wa >= -INSIDE_EPS && wb >= -INSIDE_EPS && wc >= -INSIDE_EPS).then_some([wa, wb, wc])
}

/// The barycentric weights of `(x, y)` in the XY projection of `tri`, when inside.
///
/// # Units
/// `tri` and `(x, y)` in mm; the weights are dimensionless.
pub fn barycentric(tri: &[[f64; 3]; 3], x: f64, y: f64) -> Option<[f64; 3]> {
    inside(tri, inverse_area(tri)?, x, y)
}

/// The height of `tri` above (or below) `(x, y)`: the vertical hit of the ray through
/// that point, when it lies in the triangle's XY projection; `None` outside or for a
/// triangle seen edge-on.
///
/// # Units
/// mm.
///
/// # Example
/// ```
/// use swarf_geom::{Point3, height::vertical_hit};
/// let t = [Point3::new(0.0, 0.0, 1.0), Point3::new(10.0, 0.0, 3.0), Point3::new(0.0, 10.0, 1.0)];
/// assert!((vertical_hit(&t, 5.0, 2.0).unwrap() - 2.0).abs() < 1e-12);
/// assert!(vertical_hit(&t, 8.0, 8.0).is_none());
/// ```
pub fn vertical_hit(tri: &[Point3; 3], x: f64, y: f64) -> Option<f64> {
    let p = tri.map(|q| [q.x, q.y, q.z]);
    barycentric(&p, x, y).map(|w| w[0] * p[0][2] + w[1] * p[1][2] + w[2] * p[2][2])
}

/// Calls `hit(index_in_band, weights)` for every point of rows `j0..=j1` of `grid`
/// that lies in the XY projection of `tri`, by the same closed test as
/// [`barycentric`]; `index_in_band = (j - j0) * nx + i`.
///
/// # Units
/// mm.
pub fn cover(
    grid: &impl Lattice,
    j0: usize,
    j1: usize,
    tri: &[[f64; 3]; 3],
    mut hit: impl FnMut(usize, [f64; 3]),
) {
    let Some(inv) = inverse_area(tri) else {
        return;
    };
    let [a, b, c] = tri;
    let xlo = a[0].min(b[0]).min(c[0]);
    let xhi = a[0].max(b[0]).max(c[0]);
    let ylo = a[1].min(b[1]).min(c[1]);
    let yhi = a[1].max(b[1]).max(c[1]);
    // The inside test reaches a hair past the exact box (module doc): scan its
    // neighbourhood too, so a grid point gets the same answer as a point query.
    let (lo, _) = query_rect(xlo, ylo);
    let (_, hi) = query_rect(xhi, yhi);
    let (Some((i0, i1)), Some((r0, r1))) = (grid.columns(lo[0], hi[0]), grid.rows(lo[1], hi[1]))
    else {
        return;
    };
    let nx = grid.nx();
    for j in r0.max(j0)..=r1.min(j1) {
        let y = grid.y(j);
        let base = (j - j0) * nx;
        for i in i0..=i1 {
            if let Some(w) = inside(tri, inv, grid.x(i), y) {
                hit(base + i, w);
            }
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// Centres `(i + 1/2) cell` from 0, `n` a side: the lattice of a Z-map.
    pub(crate) struct Square {
        pub(crate) cell: f64,
        pub(crate) n: usize,
    }

    impl Square {
        fn span(&self, lo: f64, hi: f64) -> Option<(usize, usize)> {
            let a = (lo / self.cell - 0.5).ceil().max(0.0);
            let b = (hi / self.cell - 0.5).floor().min(self.n as f64 - 1.0);
            (a <= b).then_some((a as usize, b as usize))
        }
    }

    impl Lattice for Square {
        fn nx(&self) -> usize {
            self.n
        }
        fn x(&self, i: usize) -> f64 {
            (i as f64 + 0.5) * self.cell
        }
        fn y(&self, j: usize) -> f64 {
            (j as f64 + 0.5) * self.cell
        }
        fn columns(&self, lo: f64, hi: f64) -> Option<(usize, usize)> {
            self.span(lo, hi)
        }
        fn rows(&self, lo: f64, hi: f64) -> Option<(usize, usize)> {
            self.span(lo, hi)
        }
    }

    #[test]
    fn covers_the_centres_inside_with_exact_plane_heights() {
        let g = Square { cell: 0.5, n: 8 };
        let tri = [[0.0, 0.0, 1.0], [4.0, 0.0, 3.0], [0.0, 4.0, 5.0]];
        let mut z = vec![f64::NAN; 64];
        cover(&g, 0, 7, &tri, |k, w| {
            z[k] = w[0] * tri[0][2] + w[1] * tri[1][2] + w[2] * tri[2][2];
        });
        for j in 0..8 {
            for i in 0..8 {
                let (x, y) = (g.x(i), g.y(j));
                let inside = x + y <= 4.0;
                let k = j * 8 + i;
                assert_eq!(z[k].is_finite(), inside, "{x} {y}");
                if inside {
                    assert!((z[k] - (1.0 + 0.5 * x + y)).abs() < 1e-12);
                    let pts = tri.map(|p| Point3::new(p[0], p[1], p[2]));
                    assert_eq!(vertical_hit(&pts, x, y), Some(z[k]));
                }
            }
        }
        // The other half: a centre on the shared diagonal is covered by both.
        let other = [[4.0, 0.0, 3.0], [4.0, 4.0, 0.0], [0.0, 4.0, 5.0]];
        let mut n = 0;
        cover(&g, 0, 7, &other, |k, _| {
            n += 1;
            let (x, y) = (g.x(k % 8), g.y(k / 8));
            assert!(z[k].is_nan() || (x + y - 4.0).abs() < 1e-12);
        });
        assert_eq!(n, 36);
    }

    #[test]
    fn band_offsets_edge_on_triangles_and_corners() {
        let g = Square { cell: 0.5, n: 4 };
        let tri = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
        let mut seen = Vec::new();
        cover(&g, 2, 3, &tri, |k, _| seen.push(k));
        assert_eq!(seen, vec![0, 1, 4]);
        let wall = [[0.0, 0.0, 0.0], [2.0, 2.0, 0.0], [1.0, 1.0, 5.0]];
        cover(&g, 0, 3, &wall, |_, _| {
            panic!("a vertical triangle covers nothing")
        });
        let p = |x: f64, y: f64, z: f64| Point3::new(x, y, z);
        let wall = [p(0.0, 0.0, 0.0), p(1.0, 0.0, 0.0), p(0.5, 0.0, 9.0)];
        assert!(vertical_hit(&wall, 0.5, 0.0).is_none());
        let high = [p(0.0, 0.0, 1.0), p(10.0, 0.0, 3.0), p(0.0, 10.0, 1.0)];
        assert_eq!(vertical_hit(&high, 10.0, 0.0), Some(3.0));
        assert!(vertical_hit(&high, f64::NAN, 0.0).is_none());
    }
}
