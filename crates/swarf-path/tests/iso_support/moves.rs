//! The straight cutting moves of a tool path, bucketed on an XY grid so that the
//! oracles visit only the moves within reach of a point.

use swarf_geom::{Point3, Vec3};
use swarf_path::Plan;

/// Moves (segments between consecutive points of each pass, a lone point as a zero
/// segment) and the grid cells each one reaches within `reach` in XY.
pub struct MoveGrid {
    /// The moves.
    pub segs: Vec<(Point3, Point3)>,
    origin: [f64; 2],
    cell: f64,
    dims: [usize; 2],
    cells: Vec<Vec<u32>>,
}

impl MoveGrid {
    /// The cutting moves of `plan`, each CL point raised by `lift` along z, on cells
    /// of size `cell`, each move listed in every cell within `reach` of it.
    pub fn new(plan: &Plan, lift: f64, reach: f64, cell: f64) -> MoveGrid {
        let mut segs = Vec::new();
        for pass in &plan.toolpath.passes {
            let c: Vec<Point3> = pass
                .points
                .iter()
                .map(|p| p.pose.cl + lift * Vec3::z())
                .collect();
            if c.len() == 1 {
                segs.push((c[0], c[0]));
            }
            segs.extend(c.windows(2).map(|w| (w[0], w[1])));
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for (a, b) in &segs {
            for p in [a, b] {
                lo = [lo[0].min(p.x), lo[1].min(p.y)];
                hi = [hi[0].max(p.x), hi[1].max(p.y)];
            }
        }
        let origin = [lo[0] - reach, lo[1] - reach];
        let dims = [0, 1].map(|k| ((hi[k] - lo[k] + 2.0 * reach) / cell).ceil() as usize + 1);
        let mut grid = MoveGrid {
            segs,
            origin,
            cell,
            dims,
            cells: vec![Vec::new(); dims[0] * dims[1]],
        };
        for k in 0..grid.segs.len() {
            let (a, b) = grid.segs[k];
            let (x0, x1) = (
                grid.ix(a.x.min(b.x) - reach, 0),
                grid.ix(a.x.max(b.x) + reach, 0),
            );
            let (y0, y1) = (
                grid.ix(a.y.min(b.y) - reach, 1),
                grid.ix(a.y.max(b.y) + reach, 1),
            );
            for j in y0..=y1 {
                for i in x0..=x1 {
                    grid.cells[j * dims[0] + i].push(k as u32);
                }
            }
        }
        grid
    }

    fn ix(&self, v: f64, ax: usize) -> usize {
        (((v - self.origin[ax]) / self.cell).floor().max(0.0) as usize).min(self.dims[ax] - 1)
    }

    /// Indices (into [`MoveGrid::segs`]) of the moves listed in the cell of `(x, y)`:
    /// every move within `reach` of the point, and maybe a few more.
    pub fn near(&self, x: f64, y: f64) -> &[u32] {
        &self.cells[self.ix(y, 1) * self.dims[0] + self.ix(x, 0)]
    }
}
