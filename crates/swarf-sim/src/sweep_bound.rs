//! How finely a tilted motion must be sampled: a second-order bound for rounded
//! tools below the stock's reach, the first-order bound otherwise.
//!
//! # The bound
//!
//! A five-axis motion moves the tool rigidly: the tip `p(t)` along the motion's path
//! and the axis turned about the fixed normal of its end axes at the constant rate
//! `alpha` (the one slerp), so a tool point at offset `w` from the tip follows
//! `g(t) = p(t) + R(t) w` with `|g'| <= |p'| + alpha |w|` and
//! `|g''| <= |p''| + alpha^2 |w|`. The simulator cuts the union `U` of the tool at
//! `t_k = k / n`, which lies inside the true swept solid `S`.
//!
//! Ball and bull cutters (corner radius `r > 0`, `R` for a ball) are, below their flat
//! top, unions of balls of radius `rho = min(r, L - r)` (`L` the flute length): the
//! tool is the eroded core `C` (a bull of radius `R - rho` and corner `r - rho`
//! raised by `rho` and cut at `L - rho`, which holds its corner when
//! `r + rho <= L`; points within `B_c = sqrt((R - rho)^2 + (L - rho)^2)` of the
//! tip) grown by the ball, except in the slab within `rho` of the top, where the rim
//! is sharp. Take a point `q` of `S` that is not in that slab: it lies in a ball
//! `B(g_c(t), rho)` for some core point `c` and `t` between two samples. The chord
//! between `g_c(t_k)` and `g_c(t_k+1)` passes within `e = h^2 / 8 * max |g''|`
//! (`h = 1 / n`, the interpolation error of a vector function) of `g_c(t)`, so `q` is
//! within `rho + e` of that chord, and the capsule of radius `rho` about a chord of
//! length `l <= h max |g'|` lies within `sqrt(rho^2 + l^2 / 4) - rho <= l^2 / (8 rho)`
//! of its two end balls, which are in `U`. Hence every such point of `S` is within
//!
//! ```text
//! delta_2 = (A + V^2 / rho) / (8 n^2),   V = S + alpha B_c,   A = P + alpha^2 B_c
//! ```
//!
//! of `U` (3D distance), `S` the tip path's length bound and `P` the bound of `|p''|`
//! (0 for straight motions, `M Theta^2` for arcs, [`crate::sweep`]): `n` grows as
//! `1 / sqrt(sample_tol)`.
//!
//! The slab is sharp, and the first-order bound `delta_1 = (S + alpha B) / (2 n)`
//! (`B` the reach of the whole tool) holds there. It matters only where the slab can
//! reach material. At every sample the slab's lowest point and XY box are computed;
//! between samples every slab point moves by at most `delta_1`, so when at each sample
//! the slab's lowest point less `delta_1` stands above the highest stock in its box
//! grown by `delta_1` ([`StockCeiling`]: the stock only falls during a simulation, so
//! its initial heights bound it), the slab never touches the stock and `delta_2`
//! bounds the cut. Otherwise (and for flat, conical, tapered and general APT tools,
//! whose edges are sharp) the motion is sampled to `delta_1`.

use crate::grid::Grid;
use crate::sweep_tilted::ToolInstance;
use swarf_tool::{Cutter, Pose};

/// Side of the tiles whose highest initial stock bounds the stock, mm (about).
pub const TILE_MM: f64 = 2.0;

/// An upper bound of the stock's height over XY boxes.
#[derive(Debug, Clone, PartialEq)]
pub enum StockCeiling {
    /// No stock is higher than this anywhere, mm.
    Level(f64),
    /// The highest initial height of each square tile of `cells` x `cells` cells
    /// (about [`TILE_MM`] wide).
    Tiles {
        /// The stock's grid.
        grid: Grid,
        /// Cells per tile side.
        cells: usize,
        /// Tiles per row.
        tiles_x: usize,
        /// Highest height per tile (row-major), mm (`-inf`: no stock).
        max: Vec<f64>,
    },
}

impl StockCeiling {
    /// The tiles of stock `heights` on `grid` (row-major, one per cell).
    pub fn of(grid: &Grid, heights: &[f64]) -> StockCeiling {
        let cells = ((TILE_MM / grid.cell).ceil() as usize).clamp(1, 256);
        let tiles_x = grid.nx.div_ceil(cells);
        let tiles_y = grid.ny.div_ceil(cells);
        let mut max = vec![f64::NEG_INFINITY; tiles_x * tiles_y];
        for (j, row) in heights.chunks(grid.nx.max(1)).enumerate() {
            let base = (j / cells) * tiles_x;
            for (i, &h) in row.iter().enumerate() {
                let m = &mut max[base + i / cells];
                *m = m.max(h);
            }
        }
        StockCeiling::Tiles {
            grid: *grid,
            cells,
            tiles_x,
            max,
        }
    }

    /// True when, over every tile (or the whole plane, for a level) meeting the box
    /// `[xmin, ymin, xmax, ymax]`, `low` of the tile's rectangle (a lower bound of
    /// something over it) stands above the stock's bound there.
    pub fn clears(&self, b: [f64; 4], low: impl Fn([f64; 4]) -> f64) -> bool {
        match self {
            StockCeiling::Level(z) => low(b) > *z,
            StockCeiling::Tiles {
                grid,
                cells,
                tiles_x,
                max,
            } => {
                let side = *cells as f64 * grid.cell;
                let span = |lo: f64, hi: f64, origin: f64, n: usize| {
                    let count = n.div_ceil(*cells) as f64;
                    let a = ((lo - origin) / side).floor().max(0.0);
                    let b = ((hi - origin) / side).floor().min(count - 1.0);
                    (a <= b).then_some((a as usize, b as usize))
                };
                let (Some((i0, i1)), Some((j0, j1))) = (
                    span(b[0], b[2], grid.origin[0], grid.nx),
                    span(b[1], b[3], grid.origin[1], grid.ny),
                ) else {
                    return true;
                };
                (j0..=j1).all(|j| {
                    (i0..=i1).all(|i| {
                        let top = max[j * tiles_x + i];
                        let x0 = grid.origin[0] + i as f64 * side;
                        let y0 = grid.origin[1] + j as f64 * side;
                        top == f64::NEG_INFINITY || low([x0, y0, x0 + side, y0 + side]) > top
                    })
                })
            }
        }
    }
}

/// The rolling radius `rho = min(r, L - r)` of a cutter with corner radius `r` and
/// flute length `L = length`: ball and bull cutters are unions of balls of that
/// radius below the slab within `rho` of their top (see the module doc); 0 for the
/// others and for a flute no longer than the corner.
pub fn rolling_radius(cutter: &Cutter, length: f64) -> f64 {
    let r = match *cutter {
        Cutter::Ball { radius, .. } => radius,
        Cutter::Bull { corner, .. } => corner,
        _ => 0.0,
    };
    let rho = r.min(length - r);
    if rho > 0.0 { rho } else { 0.0 }
}

/// What the bound needs of the tool: radius `R`, flute length `L`, rolling radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rounding {
    /// Radius, mm.
    pub radius: f64,
    /// Flute length, mm.
    pub length: f64,
    /// Rolling radius, mm (0: sharp edges below the top).
    pub rho: f64,
}

/// The motion's kinematics for the bound: tip path length `S`, bound of `|p''|`
/// (`P`), turn `alpha`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// Tip path length bound, mm.
    pub path: f64,
    /// Bound of the tip's second derivative in the motion parameter, mm.
    pub bend: f64,
    /// Angle between the end axes, radians.
    pub turn: f64,
}

impl Rounding {
    /// Reach of any tool point from the tip, mm.
    fn reach(&self) -> f64 {
        self.radius.hypot(self.length)
    }

    /// Reach of the core's points from the tip, mm.
    fn core_reach(&self) -> f64 {
        (self.radius - self.rho)
            .max(0.0)
            .hypot(self.length - self.rho)
    }

    /// `n * delta_1`: the first-order bound times the sample count, mm.
    pub fn first_order(&self, k: &Kinematics) -> f64 {
        0.5 * (k.path + self.reach() * k.turn)
    }

    /// `n^2 * delta_2`: the second-order bound times the squared sample count, mm;
    /// `None` for a tool with sharp edges.
    pub fn second_order(&self, k: &Kinematics) -> Option<f64> {
        if self.rho <= 0.0 {
            return None;
        }
        let bc = self.core_reach();
        let v = k.path + k.turn * bc;
        let a = k.bend + k.turn * k.turn * bc;
        Some((a + v * v / self.rho) / 8.0)
    }

    /// True when the top slab (axial height at least `L - rho`) of the tool at each of
    /// `poses`, lowered and widened by `margin` (the first-order bound: how far a slab
    /// point moves to the nearest sample), stands above `ceiling`. Over each tile the
    /// slab's lowest point is bounded by its box's bottom and, for an axis above the
    /// horizontal, by the plane of the slab's bottom face (every slab point lies
    /// above it; `margin` lowers it by `margin / a_z`), least at a tile corner.
    pub fn slab_clear(
        &self,
        poses: impl IntoIterator<Item = Pose>,
        margin: f64,
        ceiling: &StockCeiling,
    ) -> bool {
        let bottom = self.length - self.rho;
        poses.into_iter().all(|pose| {
            let Some(a) = pose.axis.try_normalize(1e-12) else {
                return false;
            };
            // The slab is the cylinder of the tool's radius and length rho from `lo`.
            let lo = pose.cl + a * bottom;
            let slab = ToolInstance::new(Pose { cl: lo, axis: a }, self.radius, self.rho);
            let [x0, y0, x1, y1] = slab.bounds();
            let b = [x0 - margin, y0 - margin, x1 + margin, y1 + margin];
            let box_low = slab.zlo() - margin;
            let (gx, gy) = (-a.x / a.z, -a.y / a.z);
            let plane = |x: f64, y: f64| lo.z + gx * (x - lo.x) + gy * (y - lo.y) - margin / a.z;
            ceiling.clears(b, |t| {
                if a.z < PLANE_MIN_COS {
                    return box_low;
                }
                let x = if gx >= 0.0 { t[0] } else { t[2] };
                let y = if gy >= 0.0 { t[1] } else { t[3] };
                box_low.max(plane(x, y))
            })
        })
    }
}

/// Below this axis height (about 87 degrees of tilt) the slab's plane bound is not
/// used (it grows without bound as the axis nears the horizontal).
const PLANE_MIN_COS: f64 = 0.05;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rolling_radius_of_the_family() {
        let rho = |spec: &str| {
            let c: Cutter = spec.parse().unwrap();
            rolling_radius(&c, c.length())
        };
        assert_eq!(rho("ball:d=8,length=20"), 4.0);
        assert_eq!(rho("bull:d=10,r=2,length=20"), 2.0);
        // A flute shorter than twice the ball's radius: the balls that fit below the
        // top are smaller.
        assert_eq!(rho("ball:d=8,length=6"), 2.0);
        assert_eq!(rho("flat:d=8"), 0.0);
        assert_eq!(rho("cone:d=6,angle=60"), 0.0);
    }

    #[test]
    fn tiles_bound_every_cell_they_cover() {
        let g = Grid::covering([0.0, 0.0], [9.3, 7.1], 0.1, 1 << 30).unwrap();
        let heights: Vec<f64> = (0..g.len())
            .map(|k| ((k * 7919) % 1000) as f64 / 100.0 - 3.0)
            .collect();
        let c = StockCeiling::of(&g, &heights);
        for b in [
            [1.0, 1.0, 2.0, 1.5],
            [-5.0, -5.0, 0.3, 0.2],
            [8.9, 6.0, 20.0, 20.0],
            [3.33, 2.22, 3.34, 2.23],
        ] {
            let highest = (0..g.ny)
                .flat_map(|j| (0..g.nx).map(move |i| (i, j)))
                .filter(|&(i, j)| {
                    let [x, y] = g.centre(i, j);
                    x >= b[0] && x <= b[2] && y >= b[1] && y <= b[3]
                })
                .map(|(i, j)| heights[j * g.nx + i])
                .fold(f64::NEG_INFINITY, f64::max);
            // Clear just above the highest tile, never below the highest cell.
            assert!(!c.clears(b, |_| highest - 1e-9), "{b:?}");
            assert!(c.clears(b, |_| 7.0 + 1e-9), "{b:?}");
        }
        assert!(c.clears([50.0, 50.0, 60.0, 60.0], |_| f64::NEG_INFINITY));
    }
}
