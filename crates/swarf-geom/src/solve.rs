//! What the iterative geometric solvers report, and the thresholds they share.
//!
//! A solver returns its best answer together with a [`SolveStatus`] rather than
//! asserting convergence (house style): callers decide whether an unconverged answer is
//! good enough for them.

use serde::{Deserialize, Serialize};

/// How an iterative solver ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum SolveStatus {
    /// Converged to an interior solution.
    Converged,
    /// Converged to a solution with at least one parameter on the domain boundary (a
    /// constrained optimum: e.g. the nearest point lies on a patch edge or corner).
    OnBoundary,
    /// Ran out of iterations; the answer is the best iterate found.
    MaxIterations,
}

impl SolveStatus {
    /// True for [`SolveStatus::Converged`] and [`SolveStatus::OnBoundary`].
    pub fn converged(self) -> bool {
        !matches!(self, SolveStatus::MaxIterations)
    }
}

/// A normal `du x dv` shorter than this times `|du|^2 + |dv|^2` is degenerate: the
/// parametrisation has collapsed (a pole) or `du` and `dv` are parallel
/// (dimensionless).
pub const DEGENERATE_NORMAL_REL: f64 = 1e-12;

/// Principal curvatures closer than this, relative to the larger magnitude, make an
/// umbilic point, where the principal directions are taken along `du` (dimensionless).
pub const UMBILIC_REL: f64 = 1e-10;

/// Cosine between a projection's residual vector and a surface tangent below which the
/// residual counts as normal to the surface (dimensionless).
pub const ORTHOGONALITY_COS: f64 = 1e-13;

/// The golden-section ratio `(sqrt(5) - 1) / 2`.
pub const GOLDEN: f64 = 0.618_033_988_749_894_8;

/// What [`golden_max`] found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GoldenMax {
    /// The final bracket `[a, b]`.
    pub bracket: [f64; 2],
    /// The best evaluated point and its value (the first of equal values); `None`
    /// after zero steps.
    pub best: Option<(f64, f64)>,
}

/// Golden-section search for a maximum of a unimodal `f` on `[a, b]`: `steps`
/// reductions of the bracket by [`GOLDEN`], each keeping the side of the larger of
/// the two interior values (the left side on a tie). `f` is evaluated twice a step.
///
/// ```
/// use swarf_geom::solve::golden_max;
/// let g = golden_max(|x| -(x - 0.3) * (x - 0.3), 0.0, 1.0, 40);
/// assert!((g.bracket[0] - 0.3).abs() < 1e-6 && (g.best.unwrap().0 - 0.3).abs() < 1e-6);
/// ```
pub fn golden_max(f: impl Fn(f64) -> f64, mut a: f64, mut b: f64, steps: usize) -> GoldenMax {
    let mut best: Option<(f64, f64)> = None;
    for _ in 0..steps {
        let (c, d) = (b - GOLDEN * (b - a), a + GOLDEN * (b - a));
        let (fc, fd) = (f(c), f(d));
        for (x, v) in [(c, fc), (d, fd)] {
            if best.is_none_or(|(_, bv)| v > bv) {
                best = Some((x, v));
            }
        }
        if fc >= fd {
            b = d;
        } else {
            a = c;
        }
    }
    GoldenMax {
        bracket: [a, b],
        best,
    }
}

/// The bracket [`illinois`] ends with: each end and its value, the first end keeping
/// the sign of `f(a)`.
pub type Bracket = [(f64, f64); 2];

/// A root of a continuous `f` between `a` and `b`, where `fa = f(a)` and `fb = f(b)`
/// have opposite signs (or one is 0): the Illinois variant of regula falsi (the
/// retained end's value halved when the same end is kept twice), with a bisection
/// step whenever a step shrinks the bracket by less than half. Stops when the
/// bracket is `tol` wide, `f` is exactly 0, or after `max_steps` evaluations.
///
/// ```
/// use swarf_geom::solve::illinois;
/// let f = |x: f64| x * x - 2.0;
/// let [lo, hi] = illinois(f, 0.0, 2.0, f(0.0), f(2.0), 1e-12, 200);
/// assert!((lo.0 - 2f64.sqrt()).abs() < 1e-12 && lo.1 <= 0.0 && hi.1 >= 0.0);
/// ```
pub fn illinois(
    mut f: impl FnMut(f64) -> f64,
    a: f64,
    b: f64,
    fa: f64,
    fb: f64,
    tol: f64,
    max_steps: usize,
) -> Bracket {
    let (mut lo, mut hi) = ((a, fa), (b, fb));
    if fa == 0.0 {
        return [lo, lo];
    }
    if fb == 0.0 {
        return [hi, hi];
    }
    let (mut wa, mut wb) = (fa, fb);
    let mut side = 0i8;
    for _ in 0..max_steps {
        let width = (hi.0 - lo.0).abs();
        if width <= tol {
            break;
        }
        let mut x = hi.0 - wb * (hi.0 - lo.0) / (wb - wa);
        let (near, far) = (lo.0.min(hi.0), lo.0.max(hi.0));
        if !(x > near && x < far) {
            x = 0.5 * (lo.0 + hi.0);
        }
        let fx = f(x);
        if fx == 0.0 {
            return [(x, fx), (x, fx)];
        }
        let old = width;
        if (fx < 0.0) == (fa < 0.0) {
            lo = (x, fx);
            wa = fx;
            if side == -1 {
                wb *= 0.5;
            }
            side = -1;
        } else {
            hi = (x, fx);
            wb = fx;
            if side == 1 {
                wa *= 0.5;
            }
            side = 1;
        }
        if (hi.0 - lo.0).abs() > 0.5 * old {
            // A slow step: bisect once.
            let m = 0.5 * (lo.0 + hi.0);
            let fm = f(m);
            if fm == 0.0 {
                return [(m, fm), (m, fm)];
            }
            if (fm < 0.0) == (fa < 0.0) {
                lo = (m, fm);
                wa = fm;
            } else {
                hi = (m, fm);
                wb = fm;
            }
            side = 0;
        }
    }
    [lo, hi]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn converged_statuses() {
        assert!(SolveStatus::Converged.converged());
        assert!(SolveStatus::OnBoundary.converged());
        assert!(!SolveStatus::MaxIterations.converged());
    }
}
