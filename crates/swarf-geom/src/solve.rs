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
