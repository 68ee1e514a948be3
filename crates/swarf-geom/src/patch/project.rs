//! Closest point on a patch (point projection).
//!
//! Minimise `f(u, v) = |S(u, v) - P|^2 / 2` over the parameter box. With the residual
//! `r = S - P` the gradient is `g = (r.S_u, r.S_v)` and the exact Hessian
//! `H = [[S_u.S_u + r.S_uu, S_u.S_v + r.S_uv], [., S_v.S_v + r.S_vv]]` (Piegl & Tiller,
//! The NURBS Book sec. 6.1, written as a minimisation). Each iteration:
//!
//! 1. Active set: a parameter on its bound whose gradient pushes it outward is frozen;
//!    Newton then runs on the free ones only, i.e. 1-D Newton along the edge curve, or
//!    nothing at a corner (projected Newton, Bertsekas 1982).
//! 2. The Newton direction on the free parameters; where `H` is not positive definite
//!    (far from the surface on its concave side), the Gauss-Newton direction of the
//!    metric `[[E, F], [F, G]]`, which always descends.
//! 3. Backtracking (Armijo) on the step clamped into the box, so `f` never increases;
//!    once the predicted decrease is below the rounding of `f`, the full Newton step is
//!    taken (the gradient still converges quadratically where `f` cannot show it).
//!
//! Convergence: every free component of `r` along its tangent is below
//! [`ORTHOGONALITY_COS`] `|r|` or [`SOLVER_LENGTH`]. Starts: the nodes of a sample grid
//! (density from the knot spans and degrees) that are local minima of the distance, best
//! first, and the nearest nodes (which catch a second minimum on another edge next to a
//! corner); the best converged answer wins.

use super::Patch;
use super::eval::SurfaceDerivs;
use crate::math::{Point3, Vec3};
use crate::solve::{ORTHOGONALITY_COS, SolveStatus};
use crate::tol::{MAX_NEWTON_ITERATIONS, SOLVER_LENGTH, SOLVER_PARAM};

/// Local minima of the sample grid tried as starts, and as many of its nearest nodes.
const MAX_STARTS: usize = 4;
/// Armijo sufficient-decrease constant (dimensionless).
const ARMIJO: f64 = 1e-4;
/// A full step whose predicted decrease is below this times `f` is taken without the
/// Armijo test: `f` cannot resolve it in floating point, the gradient still can.
const ROUNDING_REL: f64 = 1e-10;
/// Smallest line-search step fraction before the iteration counts as stalled.
const MIN_STEP_FRACTION: f64 = 1e-12;

/// The closest point of a patch to a query point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// Parameter u of the closest point.
    pub u: f64,
    /// Parameter v of the closest point.
    pub v: f64,
    /// The closest point, mm.
    pub point: Point3,
    /// Its distance from the query point, mm.
    pub distance: f64,
    /// How the solver ended (on the boundary = the answer lies on a patch edge).
    pub status: SolveStatus,
}

/// One iterate: parameters, derivatives there and the objective.
struct Iterate {
    u: [f64; 2],
    d: SurfaceDerivs,
    f: f64,
}

impl Patch {
    /// The closest point of the patch to `p`: the global minimum over a few starts
    /// chosen on a sample grid, each refined by constrained Newton.
    ///
    /// # Units
    /// mm.
    ///
    /// # Example
    /// ```
    /// use swarf_geom::{Patch, Point3, SolveStatus};
    /// let flat = Patch::bezier([1, 1], vec![
    ///     Point3::new(0.0, 0.0, 0.0), Point3::new(0.0, 4.0, 0.0),
    ///     Point3::new(4.0, 0.0, 0.0), Point3::new(4.0, 4.0, 0.0),
    /// ]).unwrap();
    /// let pr = flat.project(&Point3::new(1.0, 3.0, 2.0));
    /// assert!((pr.u - 0.25).abs() < 1e-12 && (pr.v - 0.75).abs() < 1e-12);
    /// assert!((pr.distance - 2.0).abs() < 1e-12 && pr.status == SolveStatus::Converged);
    /// let edge = flat.project(&Point3::new(6.0, 2.0, 0.0));
    /// assert_eq!(edge.status, SolveStatus::OnBoundary);
    /// ```
    pub fn project(&self, p: &Point3) -> Projection {
        let mut best: Option<Projection> = None;
        for (u, v) in self.projection_starts(p) {
            let pr = self.project_from(p, u, v);
            let better = best.is_none_or(|b| {
                (pr.status.converged() && !b.status.converged())
                    || (pr.status.converged() == b.status.converged() && pr.distance < b.distance)
            });
            if better {
                best = Some(pr);
            }
        }
        best.unwrap_or_else(|| self.project_from(p, self.domain()[0][0], self.domain()[1][0]))
    }

    /// The local closest point of the patch to `p`, by constrained Newton from `(u, v)`
    /// (clamped into the domain). Use it to track a moving query point cheaply; use
    /// [`Patch::project`] for the global answer.
    ///
    /// # Units
    /// mm.
    pub fn project_from(&self, p: &Point3, u: f64, v: f64) -> Projection {
        let (u, v) = self.clamp_params(u, v);
        let mut it = self.iterate(p, [u, v]);
        for _ in 0..MAX_NEWTON_ITERATIONS {
            let (g, fixed) = self.active_set(&it, p);
            if let Some(status) = converged(&it, p, &g, fixed) {
                return finish(&it, status);
            }
            let step = newton_step(&it, p, &g, fixed);
            match self.line_search(p, &it, &step, &g) {
                Some(next) => it = next,
                None => {
                    let status = if fixed.iter().any(|x| *x) {
                        SolveStatus::OnBoundary
                    } else {
                        SolveStatus::Converged
                    };
                    let loose = loosely_converged(&it, p, &g, fixed);
                    return finish(
                        &it,
                        if loose {
                            status
                        } else {
                            SolveStatus::MaxIterations
                        },
                    );
                }
            }
        }
        finish(&it, SolveStatus::MaxIterations)
    }

    fn iterate(&self, p: &Point3, u: [f64; 2]) -> Iterate {
        let d = self.derivs(u[0], u[1]);
        let f = 0.5 * (d.point - p).norm_squared();
        Iterate { u, d, f }
    }

    /// The gradient and which parameters are frozen on a bound.
    fn active_set(&self, it: &Iterate, p: &Point3) -> ([f64; 2], [bool; 2]) {
        let r = it.d.point - p;
        let g = [r.dot(&it.d.du), r.dot(&it.d.dv)];
        let dom = self.domain();
        let fixed = [0, 1]
            .map(|k| (it.u[k] <= dom[k][0] && g[k] > 0.0) || (it.u[k] >= dom[k][1] && g[k] < 0.0));
        (g, fixed)
    }

    /// Backtracking along the clamped step; `None` when no step decreases `f`.
    fn line_search(
        &self,
        p: &Point3,
        it: &Iterate,
        step: &[f64; 2],
        g: &[f64; 2],
    ) -> Option<Iterate> {
        let slope = g[0] * step[0] + g[1] * step[1];
        let mut t = 1.0;
        while t >= MIN_STEP_FRACTION {
            let (u, v) = self.clamp_params(it.u[0] + t * step[0], it.u[1] + t * step[1]);
            if u == it.u[0] && v == it.u[1] {
                return None;
            }
            let next = self.iterate(p, [u, v]);
            let moved = (u - it.u[0]) * g[0] + (v - it.u[1]) * g[1];
            let below_rounding = t == 1.0 && -moved <= ROUNDING_REL * it.f;
            if below_rounding || next.f <= it.f + ARMIJO * moved.min(t * slope).min(0.0) {
                return Some(next);
            }
            t *= 0.5;
        }
        None
    }

    /// Nodes of a sample grid that are local minima of the distance to `p`, best first.
    fn projection_starts(&self, p: &Point3) -> Vec<(f64, f64)> {
        let [ru, rv] = self.sample_params();
        let nv = rv.len();
        let dist: Vec<f64> = ru
            .iter()
            .flat_map(|u| rv.iter().map(move |v| (*u, *v)))
            .map(|(u, v)| (self.eval(u, v) - p).norm_squared())
            .collect();
        let mut minima: Vec<(f64, usize)> = (0..dist.len())
            .filter(|&k| {
                let (i, j) = (k / nv, k % nv);
                neighbours(i, j, ru.len(), nv).all(|m| dist[k] <= dist[m])
            })
            .map(|k| (dist[k], k))
            .collect();
        minima.sort_by(|a, b| a.0.total_cmp(&b.0));
        minima.truncate(MAX_STARTS);
        let mut nearest: Vec<(f64, usize)> = dist.iter().copied().zip(0..).collect();
        let extra = MAX_STARTS.min(nearest.len());
        nearest.select_nth_unstable_by(extra - 1, |a, b| a.0.total_cmp(&b.0));
        for node in &nearest[..extra] {
            if !minima.iter().any(|m| m.1 == node.1) {
                minima.push(*node);
            }
        }
        minima
            .iter()
            .map(|&(_, k)| (ru[k / nv], rv[k % nv]))
            .collect()
    }

    /// Sample parameters per direction: `2 (degree + 1)` intervals per knot span, at
    /// least 6 and at most 64 in all.
    pub(crate) fn sample_params(&self) -> [Vec<f64>; 2] {
        [0, 1].map(|dir| {
            let k = &self.knots[dir];
            let p = self.degree[dir];
            let spans: Vec<[f64; 2]> = k[p..k.len() - p]
                .windows(2)
                .filter(|w| w[1] > w[0])
                .map(|w| [w[0], w[1]])
                .collect();
            let per = (2 * (p + 1))
                .max(6usize.div_ceil(spans.len()))
                .min((64 / spans.len()).max(1));
            let mut out = vec![spans[0][0]];
            for [a, b] in spans {
                out.extend((1..=per).map(|s| a + (b - a) * s as f64 / per as f64));
            }
            out
        })
    }
}

/// Indices of the up to 8 grid neighbours of node `(i, j)`.
fn neighbours(i: usize, j: usize, nu: usize, nv: usize) -> impl Iterator<Item = usize> {
    (i.saturating_sub(1)..=(i + 1).min(nu - 1))
        .flat_map(move |a| (j.saturating_sub(1)..=(j + 1).min(nv - 1)).map(move |b| (a, b)))
        .filter(move |&(a, b)| (a, b) != (i, j))
        .map(move |(a, b)| a * nv + b)
}

/// `Some(status)` when every free tangential residual is negligible.
fn converged(it: &Iterate, p: &Point3, g: &[f64; 2], fixed: [bool; 2]) -> Option<SolveStatus> {
    let r = (it.d.point - p).norm();
    let tangents = [it.d.du.norm(), it.d.dv.norm()];
    let small = (0..2).all(|k| {
        fixed[k] || g[k].abs() <= tangents[k] * (ORTHOGONALITY_COS * r).max(SOLVER_LENGTH)
    });
    small.then_some(if fixed.iter().any(|x| *x) {
        SolveStatus::OnBoundary
    } else {
        SolveStatus::Converged
    })
}

/// The convergence test a thousand times looser, for a stalled line search (the
/// objective cannot decrease in floating point any more).
fn loosely_converged(it: &Iterate, p: &Point3, g: &[f64; 2], fixed: [bool; 2]) -> bool {
    let r = (it.d.point - p).norm();
    let tangents = [it.d.du.norm(), it.d.dv.norm()];
    (0..2).all(|k| {
        fixed[k] || g[k].abs() <= 1e3 * tangents[k] * (ORTHOGONALITY_COS * r).max(SOLVER_LENGTH)
    })
}

/// Newton (or Gauss-Newton) step on the free parameters; zero on the frozen ones.
fn newton_step(it: &Iterate, p: &Point3, g: &[f64; 2], fixed: [bool; 2]) -> [f64; 2] {
    let d = &it.d;
    let r: Vec3 = d.point - p;
    let metric = [d.du.dot(&d.du), d.du.dot(&d.dv), d.dv.dot(&d.dv)];
    let hessian = [
        metric[0] + r.dot(&d.duu),
        metric[1] + r.dot(&d.duv),
        metric[2] + r.dot(&d.dvv),
    ];
    solve_free(&hessian, g, fixed)
        .or_else(|| solve_free(&metric, g, fixed))
        .unwrap_or_else(|| {
            let scale = metric[0].max(metric[2]).max(SOLVER_PARAM);
            [0, 1].map(|k| if fixed[k] { 0.0 } else { -g[k] / scale })
        })
}

/// `-A^-1 g` on the free components of the symmetric `A = [[a, b], [b, c]]`, when `A`
/// restricted to them is positive definite.
fn solve_free(a: &[f64; 3], g: &[f64; 2], fixed: [bool; 2]) -> Option<[f64; 2]> {
    let [a11, a12, a22] = *a;
    match fixed {
        [true, true] => Some([0.0, 0.0]),
        [true, false] => (a22 > 0.0).then(|| [0.0, -g[1] / a22]),
        [false, true] => (a11 > 0.0).then(|| [-g[0] / a11, 0.0]),
        [false, false] => {
            let det = a11 * a22 - a12 * a12;
            (a11 > 0.0 && det > 1e-14 * a11 * a22).then(|| {
                [
                    -(a22 * g[0] - a12 * g[1]) / det,
                    -(a11 * g[1] - a12 * g[0]) / det,
                ]
            })
        }
    }
}

fn finish(it: &Iterate, status: SolveStatus) -> Projection {
    Projection {
        u: it.u[0],
        v: it.u[1],
        point: it.d.point,
        distance: (2.0 * it.f).sqrt(),
        status,
    }
}

#[cfg(test)]
mod tests {
    use super::super::fixtures::{die, nurbs_spline, sphere_octant, wave};
    use super::*;
    use proptest::prelude::*;

    /// Smallest distance over a dense grid of the domain: the brute-force oracle.
    fn brute_force(patch: &Patch, p: &Point3, n: u32) -> f64 {
        let [[u0, u1], [v0, v1]] = patch.domain();
        let mut best = f64::INFINITY;
        for i in 0..=n {
            for j in 0..=n {
                let u = u0 + (u1 - u0) * f64::from(i) / f64::from(n);
                let v = v0 + (v1 - v0) * f64::from(j) / f64::from(n);
                best = best.min((patch.eval(u, v) - p).norm());
            }
        }
        best
    }

    /// The first-order optimality conditions of the constrained minimum.
    fn check_optimal(patch: &Patch, p: &Point3, pr: &Projection) -> Result<(), TestCaseError> {
        prop_assert!(pr.status.converged(), "{pr:?}");
        let d = patch.derivs(pr.u, pr.v);
        prop_assert!((d.point - pr.point).norm() == 0.0);
        let r = d.point - p;
        prop_assert!((r.norm() - pr.distance).abs() < 1e-12);
        if r.norm() < 1e-6 {
            return Ok(());
        }
        let dom = patch.domain();
        let mut on_bound = false;
        for (k, t) in [d.du, d.dv].iter().enumerate() {
            let cos = r.dot(t) / (r.norm() * t.norm());
            let at = [pr.u, pr.v][k];
            if at == dom[k][0] && cos > 0.0 || at == dom[k][1] && cos < 0.0 {
                on_bound = true;
            } else {
                prop_assert!(cos.abs() < 1e-9, "dir {k}: cos {cos} at {pr:?}");
            }
        }
        prop_assert_eq!(on_bound, pr.status == SolveStatus::OnBoundary, "{:?}", pr);
        Ok(())
    }

    fn near_surface(patch: Patch) -> impl Strategy<Value = (Patch, Point3)> {
        (-0.1..1.1f64, -0.1..1.1f64, -40.0..40.0f64, -3.0..3.0f64).prop_map(move |(u, v, h, t)| {
            let d = patch.derivs(u, v);
            let n = d.normal().unwrap_or_else(Vec3::z);
            let (cu, cv) = patch.clamp_params(u, v);
            let out = d.du * (u - cu) + d.dv * (v - cv);
            let p = d.point + out + n * h + d.du.normalize() * t;
            (patch.clone(), p)
        })
    }

    fn in_box(patch: Patch) -> impl Strategy<Value = (Patch, Point3)> {
        let b = patch.control_box().inflated(30.0);
        (b.min.x..b.max.x, b.min.y..b.max.y, b.min.z..b.max.z)
            .prop_map(move |(x, y, z)| (patch.clone(), Point3::new(x, y, z)))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(40))]

        #[test]
        fn projections_are_optimal_and_global(
            (patch, p) in prop_oneof![
                near_surface(die()), near_surface(wave()), in_box(die()), in_box(wave()),
            ],
        ) {
            let pr = patch.project(&p);
            check_optimal(&patch, &p, &pr)?;
            let brute = brute_force(&patch, &p, 150);
            prop_assert!(pr.distance <= brute + 1e-9, "{} vs brute {brute}", pr.distance);
        }

        #[test]
        fn rational_and_multi_span_projections(
            (patch, p) in prop_oneof![near_surface(nurbs_spline()), in_box(nurbs_spline())],
        ) {
            let pr = patch.project(&p);
            check_optimal(&patch, &p, &pr)?;
            let br = brute_force(&patch, &p, 150); prop_assert!(pr.distance <= br + 1e-9, "{p:?} {pr:?} {br} {:?}", patch.projection_starts(&p));
        }
    }

    #[test]
    fn sphere_projection_is_radial() {
        let s = sphere_octant(5.0);
        for q in [
            Point3::new(1.0, 2.0, 3.0),
            Point3::new(10.0, 1.0, 0.5),
            Point3::new(0.01, 0.02, 0.03),
        ] {
            let pr = s.project(&q);
            assert!(
                (pr.distance - (5.0 - q.coords.norm()).abs()).abs() < 1e-10,
                "{pr:?}"
            );
            assert!((pr.point.coords.normalize() - q.coords.normalize()).norm() < 1e-9);
        }
        let corner = s.project(&Point3::new(-3.0, -4.0, -1.0));
        assert_eq!(corner.status, SolveStatus::OnBoundary);
    }

    #[test]
    fn points_on_the_surface_project_to_themselves() {
        let w = wave();
        for (u, v) in [(0.2, 0.3), (0.77, 0.5), (0.0, 0.6), (1.0, 1.0)] {
            let pr = w.project(&w.eval(u, v));
            assert!(pr.distance < 1e-9, "{pr:?}");
            assert!((pr.u - u).abs() < 1e-8 && (pr.v - v).abs() < 1e-8, "{pr:?}");
        }
    }

    #[test]
    fn non_finite_queries_do_not_panic() {
        let pr = die().project(&Point3::new(f64::NAN, 0.0, 0.0));
        assert!(pr.distance.is_nan() || pr.status == SolveStatus::MaxIterations);
    }
}
