//! A surface point on two planes, or on one plane along a patch edge.
//!
//! The side step of iso-planar and iso-scallop paths moves a CC point `P` across its
//! path inside the cross-section plane normal to the path tangent `T`: the point sought
//! is on the surface, on that plane (`T . S = T . P`) and on a second plane (the next
//! drive plane `M . S = m`, or `B . S = B . P + w` for a side offset `w`). Both
//! conditions are linear in `S`, so Newton on `(u, v)` uses the Jacobian
//! `[[a . S_u, a . S_v], [b . S_u, b . S_v]]` (Lo 2000 solves the same 2x2 system for
//! the parameter increment of the next iso-planar path). Iterates are kept in the
//! domain; a solution outside it shows as iterates pinned to a bound, reported as an
//! exit through that edge. Along an edge (one parameter fixed) one plane condition is
//! solved by 1-D Newton on the free parameter.

use swarf_geom::tol::{MAX_NEWTON_ITERATIONS, SOLVER_LENGTH};
use swarf_geom::{Patch, SurfaceDerivs, Vec3};

/// Consecutive iterates pinned to a bound before the solution counts as outside.
const PINNED_EXIT: usize = 3;
/// Largest Newton step as a fraction of the parameter range (damping).
const MAX_STEP_FRACTION: f64 = 0.25;

/// A plane `normal . x = offset` (normal not necessarily unit).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneEq {
    /// Normal.
    pub normal: Vec3,
    /// Offset.
    pub offset: f64,
}

impl PlaneEq {
    fn residual(&self, d: &SurfaceDerivs) -> f64 {
        self.normal.dot(&d.point.coords) - self.offset
    }
}

/// A patch edge: which parameter is fixed (0 = u, 1 = v) and at which end (0 = low,
/// 1 = high).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Edge {
    /// The fixed parameter.
    pub dir: usize,
    /// Its end.
    pub end: usize,
}

/// Outcome of a solve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Solved {
    /// Converged inside the domain (or on its boundary).
    Inside {
        /// Parameters.
        uv: [f64; 2],
        /// Derivatives there.
        d: SurfaceDerivs,
    },
    /// The solution lies beyond `edge`; `uv` is the last (clamped) iterate.
    Exit {
        /// Last iterate.
        uv: [f64; 2],
        /// The edge it is pinned to.
        edge: Edge,
    },
    /// No convergence (a singular Jacobian or too many iterations).
    Failed,
}

/// The point of `patch` on planes `a` and `b`, by Newton from `uv`.
pub fn two_planes(patch: &Patch, uv: [f64; 2], a: &PlaneEq, b: &PlaneEq) -> Solved {
    let dom = patch.domain();
    let range = [dom[0][1] - dom[0][0], dom[1][1] - dom[1][0]];
    let scale = a.normal.norm().max(b.normal.norm());
    let mut uv = clamp(patch, uv);
    let mut pinned = 0;
    for _ in 0..MAX_NEWTON_ITERATIONS {
        let d = patch.derivs(uv[0], uv[1]);
        let f = [a.residual(&d), b.residual(&d)];
        if f[0].abs().max(f[1].abs()) <= SOLVER_LENGTH * scale {
            return Solved::Inside { uv, d };
        }
        let j = [
            [a.normal.dot(&d.du), a.normal.dot(&d.dv)],
            [b.normal.dot(&d.du), b.normal.dot(&d.dv)],
        ];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        if det == 0.0 || !det.is_finite() {
            return Solved::Failed;
        }
        let mut step = [
            -(f[0] * j[1][1] - f[1] * j[0][1]) / det,
            -(j[0][0] * f[1] - j[1][0] * f[0]) / det,
        ];
        let limit = (0..2)
            .map(|k| step[k].abs() / (MAX_STEP_FRACTION * range[k]))
            .fold(1.0, f64::max);
        step = step.map(|s| s / limit);
        let want = [uv[0] + step[0], uv[1] + step[1]];
        let next = clamp(patch, want);
        if next != want {
            pinned += 1;
            if pinned >= PINNED_EXIT {
                return Solved::Exit {
                    uv: next,
                    edge: pinned_edge(&dom, &want),
                };
            }
        } else {
            pinned = 0;
        }
        uv = next;
    }
    Solved::Failed
}

/// The point of `edge` on plane `a`, by 1-D Newton on the free parameter from `t`;
/// `None` when it does not converge inside the edge.
pub fn on_edge(
    patch: &Patch,
    edge: Edge,
    t: f64,
    a: &PlaneEq,
) -> Option<([f64; 2], SurfaceDerivs)> {
    let dom = patch.domain();
    let free = 1 - edge.dir;
    let fixed = dom[edge.dir][edge.end];
    let at = |t: f64| {
        let mut uv = [0.0; 2];
        uv[edge.dir] = fixed;
        uv[free] = t.clamp(dom[free][0], dom[free][1]);
        uv
    };
    let mut t = t.clamp(dom[free][0], dom[free][1]);
    let mut pinned = 0;
    for _ in 0..MAX_NEWTON_ITERATIONS {
        let uv = at(t);
        let d = patch.derivs(uv[0], uv[1]);
        let f = a.residual(&d);
        if f.abs() <= SOLVER_LENGTH * a.normal.norm() {
            return Some((uv, d));
        }
        let slope = a.normal.dot(if free == 0 { &d.du } else { &d.dv });
        if slope == 0.0 || !slope.is_finite() {
            return None;
        }
        let range = dom[free][1] - dom[free][0];
        let step = (-f / slope).clamp(-MAX_STEP_FRACTION * range, MAX_STEP_FRACTION * range);
        let want = t + step;
        let next = want.clamp(dom[free][0], dom[free][1]);
        pinned = if next != want { pinned + 1 } else { 0 };
        if pinned >= PINNED_EXIT {
            return None;
        }
        t = next;
    }
    None
}

fn clamp(patch: &Patch, uv: [f64; 2]) -> [f64; 2] {
    let (u, v) = patch.clamp_params(uv[0], uv[1]);
    [u, v]
}

/// The bound `want` violates most (relative to the range).
fn pinned_edge(dom: &[[f64; 2]; 2], want: &[f64; 2]) -> Edge {
    let mut best = (0.0, Edge { dir: 0, end: 0 });
    for dir in 0..2 {
        let range = dom[dir][1] - dom[dir][0];
        let below = (dom[dir][0] - want[dir]) / range;
        let above = (want[dir] - dom[dir][1]) / range;
        if below > best.0 {
            best = (below, Edge { dir, end: 0 });
        }
        if above > best.0 {
            best = (above, Edge { dir, end: 1 });
        }
    }
    best.1
}

#[cfg(test)]
mod tests {
    use super::*;
    use swarf_geom::Point3;

    /// The paraboloid-like bicubic bump of `cl_curve`'s tests, in the usual order.
    fn bump() -> Patch {
        let c = [-2.5, 5.0 / 6.0, 5.0 / 6.0, -2.5];
        let mut pts = Vec::new();
        for i in 0..4 {
            for j in 0..4 {
                let (x, y) = (-10.0 + 20.0 * i as f64 / 3.0, -10.0 + 20.0 * j as f64 / 3.0);
                pts.push(Point3::new(x, y, 10.0 + c[i] + c[j]));
            }
        }
        Patch::bezier([3, 3], pts).unwrap()
    }

    #[test]
    fn point_on_two_planes_and_exits() {
        let p = bump();
        // x = 3 and y = -2: u = (3 + 10) / 20, v = 8 / 20.
        let a = PlaneEq {
            normal: Vec3::x(),
            offset: 3.0,
        };
        let b = PlaneEq {
            normal: Vec3::y(),
            offset: -2.0,
        };
        match two_planes(&p, [0.5, 0.5], &a, &b) {
            Solved::Inside { uv, d } => {
                assert!((uv[0] - 0.65).abs() < 1e-12 && (uv[1] - 0.4).abs() < 1e-12);
                assert!((d.point.z - (10.0 - (9.0 + 4.0) / 40.0)).abs() < 1e-9);
            }
            other => panic!("{other:?}"),
        }
        // x = 13 is beyond the u = 1 edge.
        let far = PlaneEq {
            normal: Vec3::x(),
            offset: 13.0,
        };
        match two_planes(&p, [0.5, 0.5], &far, &b) {
            Solved::Exit { uv, edge } => {
                assert_eq!(edge, Edge { dir: 0, end: 1 });
                assert_eq!(uv[0], 1.0);
            }
            other => panic!("{other:?}"),
        }
        // Along the edge u = 1, the plane y = -2 is met at v = 0.4.
        let (uv, d) = on_edge(&p, Edge { dir: 0, end: 1 }, 0.9, &b).unwrap();
        assert!((uv[1] - 0.4).abs() < 1e-12 && d.point.x == 10.0);
        let off = PlaneEq {
            normal: Vec3::y(),
            offset: 20.0,
        };
        assert!(on_edge(&p, Edge { dir: 0, end: 1 }, 0.5, &off).is_none());
    }
}
