//! Parametric curves: B-spline and NURBS of any degree, in 3D (a curve in a patch's
//! parameter plane keeps `z = 0`).
//!
//! Evaluation is de Boor by basis functions ([`crate::patch::basis`], NURBS Book A2.2
//! and A4.1): `C(t) = sum N_i(t) w_i P_i / sum N_i(t) w_i`. The knot vector need not be
//! clamped: the curve is defined on `[U_p, U_n]` (`n` control points), which is how
//! STEP and IGES write periodic curves. [`NurbsCurve::polyline`] samples the curve
//! within a chordal tolerance by bisection: a piece is accepted when the curve point at
//! its middle and at its quarters lie within `tol` of the chord; pieces smaller than
//! [`MIN_PIECES`] per knot span are never accepted, so a curve whose middle point
//! happens to lie on the chord is still followed.

use crate::error::GeomError;
use crate::math::{Point3, point_segment_distance};
use crate::patch::MAX_DEGREE;
use crate::patch::basis::{basis_funs, find_span};

/// Every knot span is cut into at least this many pieces by [`NurbsCurve::polyline`].
pub const MIN_PIECES: usize = 4;
/// Most points [`NurbsCurve::polyline`] returns; a smaller tolerance is refused.
pub const MAX_POLYLINE_POINTS: usize = 1 << 20;

/// A B-spline or NURBS curve. Build it with [`NurbsCurve::new`], which validates.
#[derive(Debug, Clone, PartialEq)]
pub struct NurbsCurve {
    degree: usize,
    knots: Vec<f64>,
    points: Vec<Point3>,
    weights: Option<Vec<f64>>,
}

impl NurbsCurve {
    /// A curve of `degree` with `knots` (non-decreasing, `points.len() + degree + 1`
    /// of them, clamped or not) and optional `weights` (one per point, > 0).
    ///
    /// # Units
    /// Points in mm (or parameter units for a curve in a patch's plane).
    ///
    /// # Errors
    /// [`GeomError::InvalidPatch`] naming `degree`, `knots`, `points` or `weights`.
    pub fn new(
        degree: usize,
        knots: Vec<f64>,
        points: Vec<Point3>,
        weights: Option<Vec<f64>>,
    ) -> Result<NurbsCurve, GeomError> {
        if degree == 0 || degree > MAX_DEGREE {
            return Err(GeomError::patch(
                "degree",
                format!("{degree}: expected 1 to {MAX_DEGREE}"),
            ));
        }
        if points.len() < degree + 1 {
            return Err(GeomError::patch(
                "points",
                format!(
                    "{} control points: degree {degree} needs at least {}",
                    points.len(),
                    degree + 1
                ),
            ));
        }
        if let Some(k) = points
            .iter()
            .position(|p| !p.coords.iter().all(|c| c.is_finite()))
        {
            return Err(GeomError::patch(format!("points[{k}]"), "not finite"));
        }
        if knots.len() != points.len() + degree + 1 {
            return Err(GeomError::patch(
                "knots",
                format!(
                    "{} knots: expected {} (control points + degree + 1)",
                    knots.len(),
                    points.len() + degree + 1
                ),
            ));
        }
        if knots.iter().any(|k| !k.is_finite()) || knots.windows(2).any(|w| w[1] < w[0]) {
            return Err(GeomError::patch(
                "knots",
                "expected finite, non-decreasing knots",
            ));
        }
        let n = points.len();
        if knots[n] <= knots[degree] {
            return Err(GeomError::patch("knots", "the curve's knot range is empty"));
        }
        if let Some(w) = &weights {
            if w.len() != n {
                return Err(GeomError::patch(
                    "weights",
                    format!("{} weights for {n} control points", w.len()),
                ));
            }
            if let Some(k) = w.iter().position(|w| !(w.is_finite() && *w > 0.0)) {
                return Err(GeomError::patch(
                    format!("weights[{k}]"),
                    "expected a finite weight > 0",
                ));
            }
        }
        Ok(NurbsCurve {
            degree,
            knots,
            points,
            weights,
        })
    }

    /// The curve's degree.
    pub fn degree(&self) -> usize {
        self.degree
    }

    /// The parameter range `[U_p, U_n]`.
    pub fn domain(&self) -> [f64; 2] {
        [self.knots[self.degree], self.knots[self.points.len()]]
    }

    /// The point at `t` (clamped into the domain).
    pub fn eval(&self, t: f64) -> Point3 {
        let [a, b] = self.domain();
        let t = t.clamp(a, b);
        let p = self.degree;
        let span = find_span(&self.knots[..=self.points.len() + p], p, t);
        let n = basis_funs(&self.knots, p, span, t);
        let (mut acc, mut wsum) = (nalgebra::Vector3::zeros(), 0.0);
        for (r, nr) in n.iter().enumerate().take(p + 1) {
            let i = span - p + r;
            let w = self.weights.as_ref().map_or(1.0, |w| w[i]);
            acc += self.points[i].coords * (nr * w);
            wsum += nr * w;
        }
        Point3::from(acc / wsum)
    }

    /// Points `(t, C(t))` from `t0` to `t1` (either order, clamped into the domain)
    /// whose chords lie within `tol` of the curve (module doc); both ends included.
    ///
    /// # Units
    /// `tol` in the points' units.
    ///
    /// # Errors
    /// [`GeomError::InvalidParameter`] naming `tol` when it is not finite and > 0, or
    /// so small that more than [`MAX_POLYLINE_POINTS`] points would be needed.
    pub fn polyline(&self, t0: f64, t1: f64, tol: f64) -> Result<Vec<(f64, Point3)>, GeomError> {
        GeomError::check_positive("tol", tol)?;
        let [a, b] = self.domain();
        let (t0, t1) = (t0.clamp(a, b), t1.clamp(a, b));
        let mut breaks = vec![t0];
        let (lo, hi) = (t0.min(t1), t0.max(t1));
        let mut inner: Vec<f64> = self.knots[self.degree..=self.points.len()]
            .iter()
            .copied()
            .filter(|k| *k > lo && *k < hi)
            .collect();
        inner.dedup();
        if t1 < t0 {
            inner.reverse();
        }
        breaks.extend(inner);
        breaks.push(t1);
        let mut out = vec![(t0, self.eval(t0))];
        for w in breaks.windows(2) {
            for k in 0..MIN_PIECES {
                let s = w[0] + (w[1] - w[0]) * k as f64 / MIN_PIECES as f64;
                let e = w[0] + (w[1] - w[0]) * (k + 1) as f64 / MIN_PIECES as f64;
                self.bisect(s, e, tol, &mut out)?;
            }
        }
        Ok(out)
    }

    /// Appends the points after `(s, C(s))` up to `(e, C(e))`, bisecting until each
    /// chord is within `tol`.
    fn bisect(
        &self,
        s: f64,
        e: f64,
        tol: f64,
        out: &mut Vec<(f64, Point3)>,
    ) -> Result<(), GeomError> {
        let mut stack = vec![(s, e)];
        while let Some((s, e)) = stack.pop() {
            let (ps, pe) = (self.eval(s), self.eval(e));
            let flat = [0.25, 0.5, 0.75].iter().all(|f| {
                let q = self.eval(s + (e - s) * f);
                point_segment_distance(&q, &ps, &pe) <= tol
            });
            if flat || (e - s).abs() <= f64::EPSILON * (s.abs() + e.abs()) {
                out.push((e, pe));
                if out.len() > MAX_POLYLINE_POINTS {
                    return Err(GeomError::InvalidParameter {
                        name: "tol".into(),
                        value: tol,
                        expected: format!(
                            "a tolerance that needs at most {MAX_POLYLINE_POINTS} points on the curve"
                        ),
                    });
                }
            } else {
                let m = 0.5 * (s + e);
                stack.push((m, e));
                stack.push((s, m));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A full circle of radius 2 as a 9-point rational quadratic (NURBS Book ex. 7.1).
    fn circle() -> NurbsCurve {
        let h = std::f64::consts::FRAC_1_SQRT_2;
        let pts = [
            (2.0, 0.0),
            (2.0, 2.0),
            (0.0, 2.0),
            (-2.0, 2.0),
            (-2.0, 0.0),
            (-2.0, -2.0),
            (0.0, -2.0),
            (2.0, -2.0),
            (2.0, 0.0),
        ]
        .map(|(x, y)| Point3::new(x, y, 0.0));
        let w = vec![1.0, h, 1.0, h, 1.0, h, 1.0, h, 1.0];
        let k = vec![0., 0., 0., 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1., 1., 1.];
        NurbsCurve::new(2, k, pts.to_vec(), Some(w)).unwrap()
    }

    #[test]
    fn rational_circle_is_exact() {
        let c = circle();
        for k in 0..=100 {
            let p = c.eval(k as f64 / 100.0);
            assert!((p.coords.norm() - 2.0).abs() < 1e-14, "{p}");
        }
    }

    #[test]
    fn polyline_meets_its_tolerance_against_the_closed_form() {
        let c = circle();
        for tol in [1e-2, 1e-4, 1e-6] {
            let pl = c.polyline(0.0, 1.0, tol).unwrap();
            // Sagitta of each chord of a circle of radius 2, from its length.
            for w in pl.windows(2) {
                let half = 0.5 * (w[1].1 - w[0].1).norm();
                let sag = 2.0 - (4.0 - half * half).sqrt();
                assert!(sag <= tol * 1.0001, "{sag} > {tol}");
            }
            let n = pl.len();
            let ideal = std::f64::consts::PI / (tol / 2.0 * 2.0).sqrt().asin().max(1e-300);
            assert!((n as f64) < 4.0 * ideal + 20.0, "{n} points for tol {tol}");
            assert_eq!(pl[0].0, 0.0);
            assert_eq!(pl[n - 1].0, 1.0);
        }
        let back = c.polyline(1.0, 0.5, 1e-3).unwrap();
        assert!(back.windows(2).all(|w| w[1].0 < w[0].0));
    }

    #[test]
    fn unclamped_knots_evaluate_on_their_inner_range() {
        // Uniform cubic B-spline: on [U_3, U_4] the curve is the classic blend.
        let pts: Vec<Point3> = (0..4)
            .map(|i| Point3::new(i as f64, (i * i) as f64, 0.0))
            .collect();
        let c = NurbsCurve::new(3, (0..8).map(f64::from).collect(), pts, None).unwrap();
        assert_eq!(c.domain(), [3.0, 4.0]);
        let p = c.eval(3.0);
        // (P0 + 4 P1 + P2) / 6
        assert!(
            (p.x - 1.0).abs() < 1e-14 && (p.y - 4.0 / 3.0).abs() < 1e-14,
            "{p}"
        );
    }

    #[test]
    fn bad_definitions_name_their_field() {
        let p = vec![Point3::origin(); 3];
        let e = |r: Result<NurbsCurve, GeomError>| r.unwrap_err().to_string();
        assert!(e(NurbsCurve::new(0, vec![0.0; 4], p.clone(), None)).starts_with("degree"));
        assert!(e(NurbsCurve::new(2, vec![0.0; 5], p.clone(), None)).starts_with("knots"));
        assert!(e(NurbsCurve::new(2, vec![0.0; 6], p.clone(), None)).contains("empty"));
        let k = vec![0., 0., 0., 1., 1., 1.];
        assert!(
            e(NurbsCurve::new(
                2,
                k.clone(),
                p.clone(),
                Some(vec![1.0, -1.0, 1.0])
            ))
            .starts_with("weights[1]")
        );
        let mut bad = p.clone();
        bad[2].x = f64::NAN;
        assert!(e(NurbsCurve::new(2, k.clone(), bad, None)).starts_with("points[2]"));
        assert!(
            NurbsCurve::new(2, k, p, None)
                .unwrap()
                .polyline(0.0, 1.0, 0.0)
                .is_err()
        );
    }
}
