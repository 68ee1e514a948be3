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
