//! Exact removal by a straight move of a vertical tool (3-axis `G0`/`G1`, and each
//! chord of a sampled arc).
//!
//! The move's swept solid is the union of the tool's positions along the segment. Over
//! a cell centre its lowest point is `A_z + min_w (m (s + w) + h(sqrt(w^2 + d^2)))`,
//! solved per profile piece in closed form (or by a bracketed 1-D root for a torus) in
//! [`crate::swept_min`]. Only cells whose centres lie within the tool radius of the
//! move's XY segment (the "stadium": the segment's XY projection grown by the radius)
//! are visited: each row meets the stadium in one interval, the union of the two end
//! discs' chords and the band's, computed per row.
//!
//! A ball end mill, the common finishing tool, takes a two-square-root fast path
//! (the capsule formula of the swept-minimum module, specialised); the tests check it
//! against the general path.

use crate::grid::Grid;
use crate::swept_min::{swept_min, swept_min_below};
use swarf_geom::Point3;
use swarf_geom::tol::LENGTH_EPS;
use swarf_tool::drop::Envelope;
use swarf_tool::drop::envelope::Piece;

/// One straight move of a vertical tool, ready to cut rows.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LinearSweep {
    /// Start of the move's XY segment (tip), and the tip height there.
    a: [f64; 3],
    /// Unit XY direction (`(1, 0)` for a vertical move).
    e: [f64; 2],
    /// XY length, mm.
    len: f64,
    /// Slope `dz / len` (0 for a vertical move, whose start is its lower end).
    m: f64,
    /// Lowest tip height over the move, mm.
    zmin: f64,
    /// Tool radius, mm.
    radius: f64,
}

/// Cells per lane group of the ball's row loop.
const LANES: usize = 8;

/// What a row cut did: cells visited, cells lowered and the deepest lowering.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RowCut {
    /// Cells whose centres the tool could reach.
    pub visited: u64,
    /// Cells lowered.
    pub lowered: u64,
    /// Largest amount a cell was lowered by, mm (0 when none).
    pub depth: f64,
}

impl LinearSweep {
    /// The move of the tool tip from `a` to `b` for a tool of radius `radius`.
    pub fn new(a: &Point3, b: &Point3, radius: f64) -> LinearSweep {
        let (dx, dy, dz) = (b.x - a.x, b.y - a.y, b.z - a.z);
        let len = dx.hypot(dy);
        if len <= LENGTH_EPS {
            let zmin = a.z.min(b.z);
            return LinearSweep {
                a: [a.x, a.y, zmin],
                e: [1.0, 0.0],
                len: 0.0,
                m: 0.0,
                zmin,
                radius,
            };
        }
        LinearSweep {
            a: [a.x, a.y, a.z],
            e: [dx / len, dy / len],
            len,
            m: dz / len,
            zmin: a.z.min(b.z),
            radius,
        }
    }

    /// XY box of the cells the move may lower: `[xmin, ymin, xmax, ymax]`, mm.
    pub fn bounds(&self) -> [f64; 4] {
        let b = [
            self.a[0] + self.len * self.e[0],
            self.a[1] + self.len * self.e[1],
        ];
        let r = self.radius;
        [
            self.a[0].min(b[0]) - r,
            self.a[1].min(b[1]) - r,
            self.a[0].max(b[0]) + r,
            self.a[1].max(b[1]) + r,
        ]
    }

    /// The x-interval where the row at `y` meets the stadium, if any.
    pub fn row_span(&self, y: f64) -> Option<(f64, f64)> {
        let r = self.radius;
        let mut lo = f64::INFINITY;
        let mut hi = f64::NEG_INFINITY;
        let b = [
            self.a[0] + self.len * self.e[0],
            self.a[1] + self.len * self.e[1],
        ];
        for p in [[self.a[0], self.a[1]], b] {
            let dy = y - p[1];
            if dy.abs() <= r {
                let h = (r * r - dy * dy).sqrt();
                lo = lo.min(p[0] - h);
                hi = hi.max(p[0] + h);
            }
        }
        if self.len > 0.0
            && let Some((l, h)) = self.band_span(y)
        {
            lo = lo.min(l);
            hi = hi.max(h);
        }
        (lo <= hi).then_some((lo, hi))
    }

    /// Where the row meets the band `0 <= s <= len`, `|d| <= radius`.
    fn band_span(&self, y: f64) -> Option<(f64, f64)> {
        let [ex, ey] = self.e;
        let ty = y - self.a[1];
        // s(x) = (x - ax) ex + ty ey,  d(x) = -(x - ax) ey + ty ex.
        let mut lo = f64::NEG_INFINITY;
        let mut hi = f64::INFINITY;
        let mut clip = |coef: f64, c0: f64, vmin: f64, vmax: f64| {
            if coef.abs() <= 1e-15 {
                if c0 < vmin || c0 > vmax {
                    lo = f64::INFINITY;
                }
                return;
            }
            let (t0, t1) = ((vmin - c0) / coef, (vmax - c0) / coef);
            lo = lo.max(t0.min(t1));
            hi = hi.min(t0.max(t1));
        };
        clip(ex, ty * ey, 0.0, self.len);
        clip(-ey, ty * ex, -self.radius, self.radius);
        (lo <= hi).then_some((self.a[0] + lo, self.a[0] + hi))
    }

    /// Lowest point of the swept tool over `(x, y)`; `+inf` when it does not reach.
    #[inline]
    pub fn lowest(&self, env: &Envelope, x: f64, y: f64) -> f64 {
        let (tx, ty) = (x - self.a[0], y - self.a[1]);
        let s = tx * self.e[0] + ty * self.e[1];
        let d = (ty * self.e[0] - tx * self.e[1]).abs();
        self.a[2] + swept_min(env, s, d, self.len, self.m)
    }

    /// Lowers the cells of row `j` (`heights`, `last` are that row's slices) to the
    /// swept tool, recording `motion` in `last` for every cell lowered.
    pub fn cut_row(
        &self,
        env: &Envelope,
        grid: &Grid,
        j: usize,
        heights: &mut [f64],
        last: &mut [u32],
        motion: u32,
    ) -> RowCut {
        let y = grid.y(j);
        let Some((x0, x1)) = self.row_span(y) else {
            return RowCut::default();
        };
        let Some((i0, i1)) = grid.columns(x0, x1) else {
            return RowCut::default();
        };
        if let Some(r) = ball_radius(env) {
            return self.cut_row_ball(r, grid, y, (i0, i1), heights, last, motion);
        }
        let mut out = RowCut {
            visited: (i1 - i0 + 1) as u64,
            ..RowCut::default()
        };
        let ty = y - self.a[1];
        for i in i0..=i1 {
            let h = heights[i];
            if h <= self.zmin {
                continue;
            }
            let tx = grid.x(i) - self.a[0];
            let s = tx * self.e[0] + ty * self.e[1];
            let d = (ty * self.e[0] - tx * self.e[1]).abs();
            // The tool is never nearer the cell than d, so never below zmin + h(d).
            if h <= self.zmin + env.lowest_at(d) {
                continue;
            }
            let z = self.a[2] + swept_min_below(env, s, d, self.len, self.m, h - self.a[2]);
            if z < h {
                heights[i] = z;
                last[i] = motion;
                out.lowered += 1;
                out.depth = out.depth.max(h - z);
            }
        }
        out
    }

    /// The ball's row loop: the capsule formula over lanes of [`LANES`] cells at a
    /// time, without branches, so that the compiler can use vector square roots.
    #[allow(clippy::too_many_arguments)]
    fn cut_row_ball(
        &self,
        r: f64,
        grid: &Grid,
        y: f64,
        (i0, i1): (usize, usize),
        heights: &mut [f64],
        last: &mut [u32],
        motion: u32,
    ) -> RowCut {
        let mut out = RowCut {
            visited: (i1 - i0 + 1) as u64,
            ..RowCut::default()
        };
        let (ex, ey) = (self.e[0], self.e[1]);
        let ty = y - self.a[1];
        let k = -self.m / (1.0 + self.m * self.m).sqrt();
        let (r2, len, m, top) = (r * r, self.len, self.m, self.a[2] + r);
        let mut i = i0;
        while i <= i1 {
            let n = (i1 + 1 - i).min(LANES);
            let mut h = [f64::NEG_INFINITY; LANES];
            h[..n].copy_from_slice(&heights[i..i + n]);
            let tx0 = grid.x(i) - self.a[0];
            // Per lane: the capsule's lowest point is t - sqrt(rem); whether it lies
            // below the cell is decided without that second square root.
            let mut t = [0.0f64; LANES];
            let mut rem = [0.0f64; LANES];
            let mut low = [false; LANES];
            for lane in 0..LANES {
                let tx = tx0 + (lane as i32) as f64 * grid.cell;
                let s = tx * ex + ty * ey;
                let d = ty * ex - tx * ey;
                let q = r2 - d * d;
                let wr = q.max(0.0).sqrt();
                let lo = (-s).max(-wr);
                let hi = (len - s).min(wr);
                let w = (k * wr).min(hi).max(lo);
                let tl = top + m * (s + w);
                let rl = (q - w * w).max(0.0);
                let b = tl - h[lane];
                t[lane] = tl;
                rem[lane] = rl;
                low[lane] = q >= 0.0 && lo <= hi && (b < 0.0 || b * b < rl);
            }
            if low.iter().any(|&l| l) {
                for lane in 0..n {
                    let z = t[lane] - rem[lane].sqrt();
                    if low[lane] && z < h[lane] {
                        heights[i + lane] = z;
                        last[i + lane] = motion;
                        out.lowered += 1;
                        out.depth = out.depth.max(h[lane] - z);
                    }
                }
            }
            i += n;
        }
        out
    }
}

/// The radius when the envelope is a single ball (sphere centred on the axis).
#[inline]
fn ball_radius(env: &Envelope) -> Option<f64> {
    match env.pieces() {
        [
            Piece::Arc {
                rho0, rho1, ce, r, ..
            },
        ] if *ce == 0.0 && *rho0 == 0.0 && *rho1 == *r => Some(*r),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use swarf_tool::Cutter;

    fn env(spec: &str) -> Envelope {
        Envelope::new(&spec.parse::<Cutter>().unwrap().profile())
    }

    #[test]
    fn row_span_is_the_stadium() {
        let r = 2.0;
        let sw = LinearSweep::new(&Point3::new(0.0, 0.0, 0.0), &Point3::new(6.0, 3.0, 1.0), r);
        let grid = Grid::covering([-5.0, -5.0], [12.0, 9.0], 0.05, 1 << 30).unwrap();
        for j in (0..grid.ny).step_by(7) {
            let y = grid.y(j);
            let span = sw.row_span(y);
            for i in 0..grid.nx {
                let x = grid.x(i);
                // distance from (x, y) to the segment
                let (px, py) = (x, y);
                let t = ((px * 6.0 + py * 3.0) / 45.0).clamp(0.0, 1.0);
                let dist = (px - 6.0 * t).hypot(py - 3.0 * t);
                let inside = span.is_some_and(|(a, b)| x >= a && x <= b);
                if (dist - r).abs() > 1e-9 {
                    assert_eq!(inside, dist < r, "x {x} y {y} dist {dist}");
                }
            }
        }
        let b = sw.bounds();
        assert_eq!(b, [-2.0, -2.0, 8.0, 5.0]);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        #[test]
        fn ball_fast_path_equals_general_path(
            ax in -3.0..3.0f64, ay in -3.0..3.0f64, az in -2.0..2.0f64,
            bx in -3.0..3.0f64, by in -3.0..3.0f64, bz in -2.0..2.0f64,
        ) {
            let e = env("ball:d=8");
            let sw = LinearSweep::new(&Point3::new(ax, ay, az), &Point3::new(bx, by, bz), 4.0);
            let grid = Grid::covering([-8.0, -8.0], [8.0, 8.0], 0.4, 1 << 30).unwrap();
            for j in 0..grid.ny {
                let mut h = vec![100.0; grid.nx];
                let mut last = vec![0; grid.nx];
                sw.cut_row(&e, &grid, j, &mut h, &mut last, 1);
                for (i, &hz) in h.iter().enumerate() {
                    let want = sw.lowest(&e, grid.x(i), grid.y(j)).min(100.0);
                    prop_assert!((hz - want).abs() < 1e-12, "{hz} {want}");
                }
            }
        }
    }

    #[test]
    fn ball_and_only_ball_takes_the_fast_path() {
        assert_eq!(ball_radius(&env("ball:d=8")), Some(4.0));
        assert_eq!(ball_radius(&env("bull:d=8,r=2")), None);
        assert_eq!(ball_radius(&env("flat:d=8")), None);
    }

    #[test]
    fn vertical_plunge_uses_the_lower_end() {
        let e = env("flat:d=4");
        let sw = LinearSweep::new(
            &Point3::new(1.0, 1.0, 5.0),
            &Point3::new(1.0, 1.0, -1.0),
            2.0,
        );
        assert_eq!(sw.lowest(&e, 2.0, 1.5), -1.0);
        assert_eq!(sw.lowest(&e, 3.1, 1.0), f64::INFINITY);
        assert_eq!(sw.row_span(1.0), Some((-1.0, 3.0)));
    }
}
