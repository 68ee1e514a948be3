//! Tensor-product parametric patches: Bezier, B-spline and NURBS of any degree.
//!
//! One representation serves all three: a patch holds clamped knot vectors in u and v
//! (a Bezier direction has the knots `[0; p+1] ++ [1; p+1]`) and optional weights
//! (absent = polynomial). Control points are row-major, index `i * n_v + j`, `i` along u.
//! The algorithms live in one file each beside this one.

mod area;
pub mod basis;
mod curvature_range;
mod diffgeo;
mod elementary;
mod eval;
#[cfg(test)]
pub(crate) mod fixtures;
mod knot_insert;
mod power;
mod project;
mod section;
mod section_seed;
mod section_trace;
mod stitch;
mod surface_box;
mod tessellate;
mod tessellate_trimmed;

pub use basis::MAX_DEGREE;
pub use curvature_range::CurvatureRange;
pub use diffgeo::{Curvature, FundamentalForms};
pub use elementary::{Frame, arc_parameter};
pub use eval::SurfaceDerivs;
pub use power::PowerPatch;
pub use project::Projection;
pub use section::{SectionCurve, SurfaceSample};
pub use surface_box::SurfaceBox;

use crate::error::GeomError;
use crate::math::{Aabb, Point3};
use crate::tol::MIN_PATCH_EXTENT;
use serde::{Deserialize, Serialize};

/// Which family a patch belongs to (for reports; the algorithms treat all alike).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum PatchKind {
    /// One polynomial span in each direction, all weights 1.
    Bezier,
    /// Polynomial spline (several spans in at least one direction), all weights 1.
    BSpline,
    /// Rational: weights given and not all equal.
    Nurbs,
}

/// A tensor-product patch. Build it with [`Patch::new`] or [`Patch::bezier`], which
/// validate everything; the fields are private so a `Patch` is always valid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Patch {
    degree: [usize; 2],
    count: [usize; 2],
    knots: [Vec<f64>; 2],
    points: Vec<Point3>,
    weights: Option<Vec<f64>>,
}

const DIR_NAMES: [&str; 2] = ["u", "v"];

impl Patch {
    /// A Bezier patch of the given `[degree_u, degree_v]`, with
    /// `(degree_u+1)*(degree_v+1)` row-major control points.
    ///
    /// # Errors
    /// [`GeomError::InvalidPatch`] when a degree is 0 or the point count is wrong.
    pub fn bezier(degree: [usize; 2], points: Vec<Point3>) -> Result<Patch, GeomError> {
        Patch::new(degree, points, [None, None], None)
    }

    /// A patch from its degrees, row-major control points, optional clamped knot
    /// vectors (`None` in a direction = Bezier in that direction) and optional weights.
    ///
    /// # Units
    /// Points in mm; knots and weights are dimensionless.
    ///
    /// # Errors
    /// [`GeomError::InvalidPatch`] naming the field (`degree`, `knots_u`, `knots_v`,
    /// `points`, `weights`) when a degree is 0 or above [`MAX_DEGREE`], a knot vector is not finite,
    /// decreasing, unclamped, of the wrong length or has an empty range, the number of
    /// points does not match, a point is not finite, the points span less than
    /// [`MIN_PATCH_EXTENT`] (1e-6 mm), or a weight is not finite and > 0.
    pub fn new(
        degree: [usize; 2],
        points: Vec<Point3>,
        knots: [Option<Vec<f64>>; 2],
        weights: Option<Vec<f64>>,
    ) -> Result<Patch, GeomError> {
        let [ku, kv] = knots;
        let ku = checked_knots(0, degree[0], ku)?;
        let kv = checked_knots(1, degree[1], kv)?;
        let count = [ku.len() - degree[0] - 1, kv.len() - degree[1] - 1];
        let expected = count[0] * count[1];
        if points.len() != expected {
            return Err(GeomError::patch(
                "points",
                format!(
                    "expected {expected} control points ({} along u x {} along v) for degree \
                     [{}, {}]{}, found {}",
                    count[0],
                    count[1],
                    degree[0],
                    degree[1],
                    if expected == (degree[0] + 1) * (degree[1] + 1) {
                        ""
                    } else {
                        " and the given knots"
                    },
                    points.len()
                ),
            ));
        }
        if let Some(i) = points
            .iter()
            .position(|p| !p.coords.iter().all(|c| c.is_finite()))
        {
            return Err(GeomError::patch(
                format!("points[{i}]"),
                "expected three finite coordinates",
            ));
        }
        let extent = Aabb::from_points(&points).size().amax();
        if extent < MIN_PATCH_EXTENT {
            return Err(GeomError::patch(
                "points",
                format!(
                    "expected control points spanning at least {MIN_PATCH_EXTENT:e} mm (the \
                     longest side of their box; smaller patches have no computable normal or \
                     curvature), found {extent:.1e} mm"
                ),
            ));
        }
        if let Some(w) = &weights {
            if w.len() != expected {
                return Err(GeomError::patch(
                    "weights",
                    format!(
                        "expected {expected} weights, one per control point, found {}",
                        w.len()
                    ),
                ));
            }
            if let Some(i) = w.iter().position(|x| !(x.is_finite() && *x > 0.0)) {
                return Err(GeomError::patch(
                    format!("weights[{i}]"),
                    format!("expected a finite weight > 0, found {}", w[i]),
                ));
            }
        }
        let weights = weights.filter(|w| w.iter().any(|x| *x != w[0]));
        let weights = weights.map(|w| w.into_iter().collect::<Vec<_>>());
        Ok(Patch {
            degree,
            count,
            knots: [ku, kv],
            points,
            weights,
        })
    }

    /// `[degree_u, degree_v]`.
    pub fn degree(&self) -> [usize; 2] {
        self.degree
    }

    /// Number of control points `[n_u, n_v]`.
    pub fn count(&self) -> [usize; 2] {
        self.count
    }

    /// The clamped knot vector in direction `dir` (0 = u, 1 = v).
    pub fn knots(&self, dir: usize) -> &[f64] {
        &self.knots[dir]
    }

    /// Control points, row-major (`i * n_v + j`).
    pub fn points(&self) -> &[Point3] {
        &self.points
    }

    /// Weights in the order of the points; `None` for a polynomial patch (all 1).
    /// Weights that are all equal are dropped at construction (the surface is the same).
    pub fn weights(&self) -> Option<&[f64]> {
        self.weights.as_deref()
    }

    /// Control point `(i, j)`.
    pub fn point(&self, i: usize, j: usize) -> Point3 {
        self.points[i * self.count[1] + j]
    }

    /// Weight of control point `(i, j)` (1 for a polynomial patch).
    pub fn weight(&self, i: usize, j: usize) -> f64 {
        self.weights
            .as_ref()
            .map_or(1.0, |w| w[i * self.count[1] + j])
    }

    /// Bezier, B-spline or NURBS.
    pub fn kind(&self) -> PatchKind {
        if self.weights.is_some() {
            PatchKind::Nurbs
        } else if self.count[0] == self.degree[0] + 1 && self.count[1] == self.degree[1] + 1 {
            PatchKind::Bezier
        } else {
            PatchKind::BSpline
        }
    }

    /// Parameter ranges `[[u0, u1], [v0, v1]]`.
    pub fn domain(&self) -> [[f64; 2]; 2] {
        [0, 1].map(|d| {
            let k = &self.knots[d];
            [k[0], k[k.len() - 1]]
        })
    }

    /// Box around the control points, which holds the whole patch (convex hull
    /// property; weights are positive).
    pub fn control_box(&self) -> Aabb {
        Aabb::from_points(&self.points)
    }
}

/// Validates (or, when absent, makes Bezier) knots for direction `dir`.
fn checked_knots(dir: usize, p: usize, knots: Option<Vec<f64>>) -> Result<Vec<f64>, GeomError> {
    let field = format!("knots_{}", DIR_NAMES[dir]);
    checked_degree(dir, p)?;
    let Some(k) = knots else {
        let mut k = vec![0.0; p + 1];
        k.extend(std::iter::repeat_n(1.0, p + 1));
        return Ok(k);
    };
    if k.len() < 2 * (p + 1) {
        return Err(GeomError::patch(
            field,
            format!(
                "expected at least {} knots for degree {p} (n + degree + 1 with n >= degree + 1), found {}",
                2 * (p + 1),
                k.len()
            ),
        ));
    }
    if let Some(i) = k.iter().position(|x| !x.is_finite()) {
        return Err(GeomError::patch(
            format!("{field}[{i}]"),
            "expected a finite knot",
        ));
    }
    if let Some(i) = k.windows(2).position(|w| w[1] < w[0]) {
        return Err(GeomError::patch(
            format!("{field}[{}]", i + 1),
            format!("knots must not decrease, found {} after {}", k[i + 1], k[i]),
        ));
    }
    let n = k.len();
    if k[..=p].iter().any(|x| *x != k[0]) || k[n - p - 1..].iter().any(|x| *x != k[n - 1]) {
        return Err(GeomError::patch(
            field,
            format!(
                "expected a clamped knot vector: the first {} and the last {} knots equal",
                p + 1,
                p + 1
            ),
        ));
    }
    if k[0] >= k[n - 1] {
        return Err(GeomError::patch(
            field,
            "expected a non-empty parameter range",
        ));
    }
    if k[p + 1] == k[0] || k[n - p - 2] == k[n - 1] {
        return Err(GeomError::patch(
            field,
            format!(
                "an end knot is repeated more than {} times (degree + 1)",
                p + 1
            ),
        ));
    }
    checked_interior(&field, p, &k)?;
    Ok(k)
}

/// Degree `p` of direction `dir` is within 1..=[`MAX_DEGREE`].
fn checked_degree(dir: usize, p: usize) -> Result<(), GeomError> {
    if p == 0 {
        return Err(GeomError::patch(
            "degree",
            format!("degree_{} must be at least 1, found 0", DIR_NAMES[dir]),
        ));
    }
    if p > MAX_DEGREE {
        return Err(GeomError::patch(
            "degree",
            format!(
                "degree_{} must be at most {MAX_DEGREE}, found {p}",
                DIR_NAMES[dir]
            ),
        ));
    }
    Ok(())
}

/// No interior knot of the clamped vector `k` (degree `p`) is repeated more than `p`
/// times.
fn checked_interior(field: &str, p: usize, k: &[f64]) -> Result<(), GeomError> {
    let n = k.len();
    let mut i = p + 1;
    while i < n - p - 1 {
        let m = k[i..n - p - 1].iter().take_while(|x| **x == k[i]).count();
        if m > p {
            return Err(GeomError::patch(
                format!("{field}[{i}]"),
                format!(
                    "interior knot {} repeated {m} times; at most the degree {p} allowed",
                    k[i]
                ),
            ));
        }
        i += m;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(nu: usize, nv: usize) -> Vec<Point3> {
        (0..nu * nv)
            .map(|k| Point3::new((k / nv) as f64, (k % nv) as f64, 0.0))
            .collect()
    }

    #[test]
    fn bezier_counts_and_kind() {
        let p = Patch::bezier([2, 3], grid(3, 4)).unwrap();
        assert_eq!(p.count(), [3, 4]);
        assert_eq!(p.kind(), PatchKind::Bezier);
        assert_eq!(p.domain(), [[0.0, 1.0], [0.0, 1.0]]);
        let e = Patch::bezier([2, 3], grid(3, 3)).unwrap_err();
        assert!(e.to_string().contains("expected 12 control points"), "{e}");
    }

    #[test]
    fn bad_knots_are_named() {
        let k = |v: Vec<f64>| [Some(v), None];
        let bad = [
            (vec![0.0, 0.0, 1.0, 0.5, 1.0, 1.0], "must not decrease"),
            (vec![0.0, 0.1, 0.0, 1.0, 1.0, 1.0], "must not decrease"),
            (vec![0.0, 0.2, 0.5, 1.0, 1.0, 1.0], "clamped"),
            (vec![0.0, 0.0, 0.0, 1.0, 1.0], "at least 6 knots"),
            (vec![0.0, 0.0, 0.0, f64::NAN, 1.0, 1.0, 1.0], "finite"),
            (vec![0.0, 0.0, 0.0, 0.0, 0.0, 0.0], "non-empty"),
            (
                vec![0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0],
                "repeated 3 times",
            ),
        ];
        for (knots, want) in bad {
            let n = knots.len().saturating_sub(3).max(1);
            let e = Patch::new([2, 2], grid(n, 3), k(knots.clone()), None).unwrap_err();
            assert!(e.to_string().contains("knots_u"), "{knots:?}: {e}");
            assert!(e.to_string().contains(want), "{knots:?}: {e}");
        }
    }

    #[test]
    fn bad_weights_and_points_are_named() {
        let e = Patch::new(
            [1, 1],
            grid(2, 2),
            [None, None],
            Some(vec![1.0, -1.0, 1.0, 1.0]),
        )
        .unwrap_err();
        assert!(e.to_string().starts_with("weights[1]"), "{e}");
        let e = Patch::new([1, 1], grid(2, 2), [None, None], Some(vec![1.0; 3])).unwrap_err();
        assert!(e.to_string().contains("expected 4 weights"), "{e}");
        let mut pts = grid(2, 2);
        pts[2].z = f64::INFINITY;
        let e = Patch::bezier([1, 1], pts).unwrap_err();
        assert!(e.to_string().starts_with("points[2]"), "{e}");
        let e = Patch::bezier([0, 1], grid(1, 2)).unwrap_err();
        assert!(e.to_string().starts_with("degree"), "{e}");
    }

    #[test]
    fn patches_below_the_smallest_extent_are_refused() {
        let scaled = |s: f64| grid(2, 2).into_iter().map(|p| p * s).collect::<Vec<_>>();
        let e = Patch::bezier([1, 1], scaled(1e-200)).unwrap_err();
        assert_eq!(
            e.to_string(),
            "points: expected control points spanning at least 1e-6 mm (the longest side \
             of their box; smaller patches have no computable normal or curvature), found \
             1.0e-200 mm"
        );
        let e = Patch::bezier([1, 1], vec![Point3::new(5.0, 5.0, 5.0); 4]).unwrap_err();
        assert!(e.to_string().contains("found 0.0e0 mm"), "{e}");
        assert!(Patch::bezier([1, 1], scaled(0.99e-6)).is_err());
        let p = Patch::bezier([1, 1], scaled(1e-6)).unwrap();
        let c = p.derivs(0.5, 0.5);
        assert!(
            c.normal().is_some(),
            "the smallest patch still has a normal"
        );
    }

    #[test]
    fn degree_cap_and_end_multiplicity_are_checked() {
        let e = Patch::bezier([16, 1], grid(17, 2)).unwrap_err();
        assert!(e.to_string().contains("at most 15"), "{e}");
        assert!(Patch::bezier([15, 1], grid(16, 2)).is_ok());
        let k = vec![0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
        let e = Patch::new([2, 1], grid(4, 2), [Some(k), None], None).unwrap_err();
        assert!(e.to_string().contains("repeated more than 3"), "{e}");
        let k = vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0];
        let e = Patch::new([2, 1], grid(4, 2), [Some(k), None], None).unwrap_err();
        assert!(e.to_string().contains("repeated more than 3"), "{e}");
    }

    #[test]
    fn uniform_weights_are_polynomial() {
        let p = Patch::new([1, 1], grid(2, 2), [None, None], Some(vec![2.0; 4])).unwrap();
        assert_eq!(p.kind(), PatchKind::Bezier);
        let p = Patch::new(
            [1, 1],
            grid(2, 2),
            [None, None],
            Some(vec![1.0, 2.0, 1.0, 1.0]),
        )
        .unwrap();
        assert_eq!(p.kind(), PatchKind::Nurbs);
        assert_eq!(p.weight(0, 1), 2.0);
    }
}
