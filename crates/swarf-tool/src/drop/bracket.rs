//! A bracketed, safeguarded Newton root finder for one sign change.
//!
//! Given `f` with `f(lo) > 0 >= f(hi)` (one sign change in `[lo, hi]`, as the
//! derivative of a concave function has), each step tries Newton from the current
//! iterate and falls back to bisection when the Newton point leaves the bracket or
//! the step does not at least halve the previous one (Numerical Recipes' `rtsafe`).
//! The bracket shrinks every step, so the method converges whatever `f` looks like
//! between the ends; near a simple root it converges quadratically. Iterations are
//! capped; bisection alone reaches the f64 resolution of any bracket in about 60
//! steps, so the cap of [`MAX_ITERATIONS`] is reached only for NaN input.

use swarf_geom::SolveStatus;

/// Largest number of steps.
pub const MAX_ITERATIONS: usize = 100;

/// The root of `f` in `[lo, hi]` to within `tol` (absolute, in `x`), given
/// `f(lo) > 0 >= f(hi)`. `f` returns the value and the derivative.
///
/// Returns the root and [`SolveStatus::Converged`], or the bracket midpoint and
/// [`SolveStatus::MaxIterations`] (also when `f` gives NaN).
pub fn root_decreasing(
    f: impl Fn(f64) -> (f64, f64),
    mut lo: f64,
    mut hi: f64,
    tol: f64,
) -> (f64, SolveStatus) {
    let mut x = 0.5 * (lo + hi);
    let mut step_old = (hi - lo).abs();
    let mut step = step_old;
    let (mut fx, mut dfx) = f(x);
    for _ in 0..MAX_ITERATIONS {
        if fx.is_nan() {
            break;
        }
        if fx > 0.0 {
            lo = x;
        } else {
            hi = x;
        }
        let newton_out = dfx == 0.0
            || !{
                let xn = x - fx / dfx;
                (xn - lo) * (xn - hi) <= 0.0
            };
        if newton_out || (2.0 * fx).abs() > (step_old * dfx).abs() {
            step_old = step;
            step = 0.5 * (hi - lo);
            x = lo + step;
        } else {
            step_old = step;
            step = fx / dfx;
            x -= step;
        }
        if step.abs() < tol || (hi - lo).abs() < tol {
            return (x.clamp(lo.min(hi), lo.max(hi)), SolveStatus::Converged);
        }
        (fx, dfx) = f(x);
        if fx == 0.0 {
            return (x, SolveStatus::Converged);
        }
    }
    (0.5 * (lo + hi), SolveStatus::MaxIterations)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_roots_of_smooth_and_nasty_functions() {
        let (x, s) = root_decreasing(|x| (2.0 - x * x, -2.0 * x), 0.0, 2.0, 1e-15);
        assert_eq!(s, SolveStatus::Converged);
        assert!((x - 2f64.sqrt()).abs() < 1e-15);
        // A step function: Newton is useless, bisection still converges.
        let (x, s) = root_decreasing(|x| (if x < 0.3 { 1.0 } else { -1.0 }, 0.0), 0.0, 1.0, 1e-14);
        assert_eq!(s, SolveStatus::Converged);
        assert!((x - 0.3).abs() < 1e-13);
        // Infinite slope at the root (like a torus equator).
        let (x, _) = root_decreasing(
            |x: f64| {
                let v = 0.5 - x;
                (v.cbrt(), -1.0 / (3.0 * v.abs().cbrt().powi(2)).max(1e-300))
            },
            0.0,
            1.0,
            1e-14,
        );
        assert!((x - 0.5).abs() < 1e-13);
        let (_, s) = root_decreasing(|_| (f64::NAN, f64::NAN), 0.0, 1.0, 1e-14);
        assert_eq!(s, SolveStatus::MaxIterations);
    }
}
