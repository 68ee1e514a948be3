//! The machined surface of a vertical flat, ball or bull end mill along a tool path,
//! independent of the planners' models: the tool's bottom in closed form, swept
//! exactly along each straight move (the lowest bottom over the move at a point, a
//! convex minimisation), the machined height the lowest over all moves, and the
//! material left at a surface point where the ray along its normal first reaches that
//! height.

use rayon::prelude::*;
use swarf_geom::{Point3, Vec3};
use swarf_path::Plan;
use swarf_tool::Cutter;

use super::moves::Moves;

/// Golden-section steps minimising the tool bottom over one move.
const GOLDEN_STEPS: usize = 32;
const GOLDEN: f64 = 0.618_033_988_749_894_8;
/// Points this far beyond a tool's radius still touch its rim (rounding of the CL
/// points), mm.
const REACH_EPS: f64 = 1e-9;
/// Least first bracket of the ray's root, mm.
const RAY_START: f64 = 1e-4;
/// Root of the ray's height gap, mm.
const RAY_TOL: f64 = 1e-7;

/// The bottom of a vertical end mill above its tip at distance `rho` from the axis.
#[derive(Debug, Clone, Copy)]
pub enum Bottom {
    /// Flat end, radius.
    Flat(f64),
    /// Ball end, radius.
    Ball(f64),
    /// Bull nose: radius, corner radius.
    Bull(f64, f64),
}

impl Bottom {
    /// The closed form of `cutter` (flat, ball or bull).
    pub fn of(cutter: &Cutter) -> Bottom {
        match *cutter {
            Cutter::Flat { radius, .. } => Bottom::Flat(radius),
            Cutter::Ball { radius, .. } => Bottom::Ball(radius),
            Cutter::Bull { radius, corner, .. } => Bottom::Bull(radius, corner),
            ref other => panic!("no closed form for {other:?}"),
        }
    }

    /// Tool radius, mm.
    pub fn radius(&self) -> f64 {
        match *self {
            Bottom::Flat(r) | Bottom::Ball(r) | Bottom::Bull(r, _) => r,
        }
    }

    /// Height above the tip at `rho` (infinite beyond the radius).
    pub fn at(&self, rho: f64) -> f64 {
        let r = self.radius();
        if rho > r + REACH_EPS {
            return f64::INFINITY;
        }
        let rho = rho.min(r);
        match *self {
            Bottom::Flat(_) => 0.0,
            Bottom::Ball(r) => r - (r * r - rho * rho).max(0.0).sqrt(),
            Bottom::Bull(r, c) => {
                let x = rho - (r - c);
                if x <= 0.0 {
                    0.0
                } else {
                    c - (c * c - x * x).max(0.0).sqrt()
                }
            }
        }
    }
}

thread_local! {
    /// Lower bounds of the moves within reach of a point, reused between calls.
    static LOWER: std::cell::RefCell<Vec<(f64, usize)>> = const { std::cell::RefCell::new(Vec::new()) };
}

/// The straight moves of a tool path (CL points), bucketed on an XY grid.
pub struct Swept {
    bottom: Bottom,
    moves: Moves,
}

impl Swept {
    /// The cutting moves of `plan` for `cutter`.
    pub fn new(plan: &Plan, cutter: &Cutter) -> Swept {
        Swept {
            bottom: Bottom::of(cutter),
            moves: Moves::new(plan, 0.0),
        }
    }

    /// Height of the machined surface at `(x, y)`: the lowest tool bottom over all
    /// moves; infinite where no tool passes.
    pub fn height(&self, x: f64, y: f64) -> f64 {
        let r = self.bottom.radius();
        LOWER.with(|lower| {
            let mut lower = lower.borrow_mut();
            lower.clear();
            self.moves
                .for_each_near([x, y], [x, y], r + 2.0 * REACH_EPS, &mut |k| {
                    let (a, b) = self.moves.segs[k];
                    let d = xy_distance(x, y, &a, &b);
                    if d <= r + REACH_EPS {
                        lower.push((a.z.min(b.z) + self.bottom.at(d), k));
                    }
                });
            lower.sort_unstable_by(|p, q| p.0.total_cmp(&q.0));
            let mut best = f64::INFINITY;
            for &(bound, k) in lower.iter() {
                if bound >= best {
                    break;
                }
                let (a, b) = self.moves.segs[k];
                best = best.min(self.move_height(x, y, &a, &b));
            }
            best
        })
    }

    /// Lowest tool bottom at `(x, y)` over the move from `a` to `b` (CL points): with
    /// `tau` the distance along the move's XY projection, `tau * slope + bottom(rho)`
    /// is convex in `tau` (the bottom is a convex function of the XY offset), so a
    /// golden-section search over the stretch within reach finds it.
    fn move_height(&self, x: f64, y: f64, a: &Point3, b: &Point3) -> f64 {
        let (ex, ey) = (b.x - a.x, b.y - a.y);
        let len = ex.hypot(ey);
        let (qx, qy) = (x - a.x, y - a.y);
        let r = self.bottom.radius();
        if len < 1e-12 {
            return a.z + self.bottom.at(qx.hypot(qy));
        }
        let (ux, uy) = (ex / len, ey / len);
        let xi = qx * ux + qy * uy;
        let eta = (qx * uy - qy * ux).abs();
        if eta > r + REACH_EPS {
            return f64::INFINITY;
        }
        let half = (r * r - eta * eta).max(0.0).sqrt() + REACH_EPS;
        let (lo, hi) = ((xi - half).max(0.0), (xi + half).min(len));
        if lo > hi {
            return f64::INFINITY;
        }
        let slope = (b.z - a.z) / len;
        let f = |tau: f64| a.z + tau * slope + self.bottom.at((xi - tau).hypot(eta).min(r));
        let (p, q) = golden_min(&f, lo, hi, GOLDEN_STEPS);
        f(0.5 * (p + q)).min(f(lo)).min(f(hi))
    }

    /// Material left above the surface point `p` along its unit normal `n` (toward the
    /// tool): the first `t >= 0` where `p + t n` reaches the machined height (0 where
    /// `p` is already cut; infinite where no tool passes above it).
    pub fn residual(&self, p: &Point3, n: &Vec3) -> f64 {
        let gap = |t: f64| {
            let q = p + t * n;
            q.z - self.height(q.x, q.y)
        };
        let g0 = gap(0.0);
        if g0 >= 0.0 {
            return 0.0;
        }
        if !g0.is_finite() {
            return f64::INFINITY;
        }
        let r = self.bottom.radius();
        let (mut lo, mut flo) = (0.0, g0);
        let mut hi = (-g0 * n.z).max(RAY_START);
        let mut fhi = gap(hi);
        while fhi < 0.0 {
            (lo, flo) = (hi, fhi);
            hi *= 2.0;
            if hi > 2.0 * r {
                return f64::INFINITY;
            }
            fhi = gap(hi);
        }
        let mut side = 0;
        while hi - lo > RAY_TOL {
            let mut t = lo - flo * (hi - lo) / (fhi - flo);
            if !(t > lo && t < hi) {
                t = 0.5 * (lo + hi);
            }
            let ft = gap(t);
            if ft < 0.0 {
                (lo, flo) = (t, ft);
                if side == -1 {
                    fhi *= 0.5;
                }
                side = -1;
            } else {
                (hi, fhi) = (t, ft);
                if side == 1 {
                    flo *= 0.5;
                }
                side = 1;
            }
        }
        hi
    }
}

/// Golden-section search for the least of a convex `f` on `[a, b]`, one evaluation
/// per step: the final bracket.
pub fn golden_min(f: &impl Fn(f64) -> f64, mut a: f64, mut b: f64, steps: usize) -> (f64, f64) {
    let (mut c, mut d) = (b - GOLDEN * (b - a), a + GOLDEN * (b - a));
    let (mut fc, mut fd) = (f(c), f(d));
    for _ in 0..steps {
        if fc <= fd {
            (b, d, fd) = (d, c, fc);
            c = b - GOLDEN * (b - a);
            fc = f(c);
        } else {
            (a, c, fc) = (c, d, fd);
            d = a + GOLDEN * (b - a);
            fd = f(d);
        }
    }
    (a, b)
}

/// XY distance from `(x, y)` to the XY projection of segment `ab`.
fn xy_distance(x: f64, y: f64, a: &Point3, b: &Point3) -> f64 {
    let (ex, ey) = (b.x - a.x, b.y - a.y);
    let ee = ex * ex + ey * ey;
    let t = if ee > 0.0 {
        (((x - a.x) * ex + (y - a.y) * ey) / ee).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (x - a.x - t * ex).hypot(y - a.y - t * ey)
}

/// Residuals at many points at once (rayon).
pub fn residuals(swept: &Swept, frames: &[(Point3, Vec3)]) -> Vec<f64> {
    frames
        .par_iter()
        .map(|(p, n)| swept.residual(p, n))
        .collect()
}
