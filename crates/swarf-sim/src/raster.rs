//! Vertical ray casting at cell centres by scan conversion: the cells whose centres a
//! triangle's XY projection holds, with the barycentric weights there.
//!
//! Casting one vertical ray per cell and asking an XY index for the triangles under
//! it gives the same answer as visiting, for each triangle the index returns for a
//! band of rows, the cell centres inside its projection; the second is what this file
//! does (the [`swarf_geom::XyIndex`] query is per band, see [`crate::design`]). The
//! inside test is closed (weights `>= -INSIDE_EPS`), so a centre on an edge shared by
//! two triangles is reported for both and no ray slips between them; callers keep the
//! highest hit (the upper envelope, as the part-file convention asks). Triangles
//! whose projection has no area (vertical walls) hold no centre and are skipped; their
//! neighbours carry the wall's top and bottom edges.

use crate::grid::Grid;

/// Barycentric weights down to this (relative) still count as inside.
pub const INSIDE_EPS: f64 = 1e-12;

/// Calls `hit(index_in_band, weights)` for every cell of rows `j0..=j1` whose centre
/// lies in the XY projection of `tri`; `index_in_band = (j - j0) * nx + i`.
pub fn cover(
    grid: &Grid,
    j0: usize,
    j1: usize,
    tri: &[[f64; 3]; 3],
    mut hit: impl FnMut(usize, [f64; 3]),
) {
    let [a, b, c] = tri;
    let area = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]);
    if !area.is_finite() || area.abs() <= f64::MIN_POSITIVE {
        return;
    }
    let inv = 1.0 / area;
    let xlo = a[0].min(b[0]).min(c[0]);
    let xhi = a[0].max(b[0]).max(c[0]);
    let ylo = a[1].min(b[1]).min(c[1]);
    let yhi = a[1].max(b[1]).max(c[1]);
    let (Some((i0, i1)), Some((r0, r1))) = (grid.columns(xlo, xhi), grid.rows(ylo, yhi)) else {
        return;
    };
    let edge = |p: &[f64; 3], q: &[f64; 3], x: f64, y: f64| {
        ((q[0] - x) * (p[1] - y) - (q[1] - y) * (p[0] - x)) * -inv
    };
    for j in r0.max(j0)..=r1.min(j1) {
        let y = grid.y(j);
        let base = (j - j0) * grid.nx;
        for i in i0..=i1 {
            let x = grid.x(i);
            let wa = edge(b, c, x, y);
            let wb = edge(c, a, x, y);
            let wc = 1.0 - wa - wb;
            if wa >= -INSIDE_EPS && wb >= -INSIDE_EPS && wc >= -INSIDE_EPS {
                hit(base + i, [wa, wb, wc]);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn covers_the_centres_inside_with_exact_plane_heights() {
        let g = Grid::covering([0.0, 0.0], [4.0, 4.0], 0.5, 1 << 20).unwrap();
        let tri = [[0.0, 0.0, 1.0], [4.0, 0.0, 3.0], [0.0, 4.0, 5.0]];
        let mut z = vec![f64::NAN; g.len()];
        cover(&g, 0, g.ny - 1, &tri, |k, w| {
            z[k] = w[0] * tri[0][2] + w[1] * tri[1][2] + w[2] * tri[2][2];
        });
        for j in 0..g.ny {
            for i in 0..g.nx {
                let [x, y] = g.centre(i, j);
                let inside = x + y <= 4.0;
                let k = j * g.nx + i;
                assert_eq!(z[k].is_finite(), inside, "{x} {y}");
                if inside {
                    assert!((z[k] - (1.0 + 0.5 * x + y)).abs() < 1e-12);
                }
            }
        }
        // The other half: a centre on the shared diagonal is covered by both.
        let other = [[4.0, 0.0, 3.0], [4.0, 4.0, 0.0], [0.0, 4.0, 5.0]];
        let mut n = 0;
        cover(&g, 0, g.ny - 1, &other, |k, _| {
            n += 1;
            assert!(
                z[k].is_nan() || {
                    let (i, j) = (k % g.nx, k / g.nx);
                    let [x, y] = g.centre(i, j);
                    (x + y - 4.0).abs() < 1e-12
                }
            );
        });
        assert_eq!(n, 36);
    }

    #[test]
    fn band_offsets_and_vertical_triangles() {
        let g = Grid::covering([0.0, 0.0], [2.0, 2.0], 0.5, 1 << 20).unwrap();
        let tri = [[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [0.0, 2.0, 0.0]];
        let mut seen = Vec::new();
        cover(&g, 2, 3, &tri, |k, _| seen.push(k));
        assert_eq!(seen, vec![0, 1, 4]);
        let wall = [[0.0, 0.0, 0.0], [2.0, 2.0, 0.0], [1.0, 1.0, 5.0]];
        cover(&g, 0, 3, &wall, |_, _| {
            panic!("a vertical triangle covers nothing")
        });
    }
}
